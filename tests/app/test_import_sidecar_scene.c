/* `fogpipe import`'s sidecar says its [box] and [fog] are scene config sections: copied into
 * a scene with `fogmap = NAME.FRAME.exr` added to [fog], they load (scene_config_load) and
 * hold every profile coefficient the sidecar lists. The plume's frame 48 has a
 * profile of 64 coefficients, a line of ~600 bytes where a config line holds 199: the
 * sidecar wraps it over indented lines. */
#include "tests/app/record_util.h" /* first: it sets _POSIX_C_SOURCE */
#include "tests/test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"

int main(void) {
  char root[] = "/tmp/fogpipe-sidecar-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char command[2048], log[600], sidecar[600], scene[600];
  snprintf(log, sizeof log, "%s/import.log", root);
  snprintf(command, sizeof command,
           "'%s' import ../shared/data/vdb/plume/data/fluid_data_0048.vdb --out '%s/imp' "
           "> '%s' 2>&1", record_bin(), root, log);
  int status = system(command);
  CHECK(status == 0, "import failed");
  if (status) record_print_log(log);
  snprintf(sidecar, sizeof sidecar, "%s/imp/fog.ini", root);
  snprintf(scene, sizeof scene, "%s/imp/scene.ini", root);

  /* The scene: the sidecar's lines from [box] on (its [box] and [fog]), with the fogmap. */
  FILE *in = fopen(sidecar, "r"), *out = fopen(scene, "w");
  CHECK(in && out, "cannot read %s or write %s", sidecar, scene);
  char line[4096];
  bool copying = false;
  int coefficients = 0;
  double sum = 0;
  while (in && out && fgets(line, sizeof line, in)) {
    if (!strncmp(line, "[box]", 5)) copying = true;
    if (!copying) continue;
    fputs(line, out);
    if (!strncmp(line, "[fog]", 5)) fputs("fogmap = fog.0048.exr\n", out);
    /* the coefficients as the sidecar lists them: its key's line and the indented ones */
    const char *numbers = NULL;
    if (!strncmp(line, "profile_coefficients =", 22)) numbers = line + 22;
    else if (line[0] == ' ' && coefficients > 0) numbers = line;
    for (char *p = (char *)numbers, *end; numbers; p = end) {
      double v = strtod(p, &end);
      if (end == p) break;
      coefficients++, sum += v;
    }
  }
  if (in) fclose(in);
  if (out) fclose(out);
  CHECK(coefficients > 32, "%d profile coefficients in %s", coefficients, sidecar);

  scene_config cfg;
  fog_error err = {0};
  status = scene_config_load(scene, &cfg, &err);
  CHECK(status == 0, "the sidecar's [box] and [fog] do not load as a scene: %s", err.message);
  if (!status) {
    CHECK(cfg.fog.profile_count == coefficients, "the scene has %d coefficients, the sidecar %d",
          cfg.fog.profile_count, coefficients);
    double loaded = 0;
    for (int k = 0; k < cfg.fog.profile_count; k++) loaded += cfg.fog.profile_coefficients[k];
    CHECK(fabs(loaded - sum) <= 1e-12 * fmax(1.0, sum), "coefficients sum %.17g, sidecar %.17g",
          loaded, sum);
  }
  test_remove_tree(root);
  return test_finish("test_import_sidecar_scene");
}
