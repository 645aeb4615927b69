/* A config without fog (no fogmap, VDB or sequence, the fogmap model) has none in every
 * command, as docs/config.md says of an empty file: `render` draws the scene alone, and
 * `record`, which simulates a fogmap scene, starts from clear air, so its frames have
 * transmittance 1 everywhere (with no emitters nothing makes fog), frame 1 as render's;
 * `bake` of it writes frames of density 0 (the demo runs the same pipeline). Quadric
 * volumes beside that model are fog (docs/config.md: beside every model): `render` draws
 * them as `record` does, frame 1's transmittance the same (render drew the scene alone). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "exr_channel_util.h"
#include "test_bin.h"
#include "test_util.h"

enum { W = 32, H = 18 };

static char dir[] = "/tmp/fogpipe_no_fog_XXXXXX";

/* The smallest transmittance of an EXR's pixels (2 after a failed check). */
static double least_transmittance(const char *path) {
  float *t = load_exr_channel(path, "transmittance", W, H);
  double least = t ? 1.0 : 2.0;
  for (int k = 0; t && k < W * H; k++) least = t[k] < least ? t[k] : least;
  free(t);
  return least;
}

int main(void) {
  const char *bin = test_bin_and_folder(dir);
  if (!bin) return test_finish("test_no_fog_config");
  char ini[300], line[1200], output[4096], path[400];
  snprintf(ini, sizeof ini, "%s/plain.ini", dir);
  test_write_text(ini, "[render]\nwidth = 32\nheight = 18\n[terrain]\nresolution = 17\n");
  snprintf(line, sizeof line, "'%s' render '%s' --out '%s/r.exr' 2>&1", bin, ini, dir);
  CHECK(test_run_output(line, output, sizeof output) == 0 && strstr(output, "no fog"),
        "render: %s", output);
  snprintf(path, sizeof path, "%s/r.exr", dir);
  CHECK(least_transmittance(path) == 1.0, "render drew fog: transmittance %g",
        least_transmittance(path));
  snprintf(line, sizeof line, "'%s' record '%s' --frames 3 --out '%s/rec' 2>&1", bin, ini, dir);
  CHECK(test_run_output(line, output, sizeof output) == 0, "record: %s", output);
  for (int f = 1; f <= 3; f++) {
    snprintf(path, sizeof path, "%s/rec/frame.%04d.exr", dir, f);
    const double least = least_transmittance(path);
    CHECK(least == 1.0, "record frame %d has fog: transmittance down to %g", f, least);
  }
  /* bake simulates the same clear air: every frame's density 0 */
  snprintf(line, sizeof line, "'%s' bake '%s' --frames 2 --out '%s/bake' 2>&1", bin, ini, dir);
  CHECK(test_run_output(line, output, sizeof output) == 0, "bake: %s", output);
  for (int f = 1; f <= 2; f++) {
    snprintf(path, sizeof path, "%s/bake/fog.%04d.exr", dir, f);
    fogmap map = {0};
    fog_error err = {0};
    double most = -1;
    if (fogmap_load(path, &(fogmap_load_desc){0}, &map, &err) == 0) {
      most = 0;
      for (int k = 0; k < map.width * map.height; k++)
        most = map.density[k] > most ? map.density[k] : most;
      fogmap_destroy(&map);
    }
    CHECK(most == 0.0, "bake frame %d: densest cell %g (%s)", f, most, err.message);
  }
  /* quadric volumes beside the fogmap model with no fogmap: render draws them as record */
  snprintf(ini, sizeof ini, "%s/quadric.ini", dir);
  test_write_text(ini, "[render]\nwidth = 32\nheight = 18\n[terrain]\nresolution = 17\n"
                       "[camera]\nposition = 0 60 -200\nlook_at = 0 40 -60\n"
                       "[fog]\nquadric = sphere 0 40 -60 40 0.5\n");
  snprintf(line, sizeof line, "'%s' render '%s' --out '%s/q.exr' 2>&1", bin, ini, dir);
  CHECK(test_run_output(line, output, sizeof output) == 0 && strstr(output, "scene + fog"),
        "render of quadrics beside the fogmap model: %s", output);
  snprintf(line, sizeof line, "'%s' record '%s' --frames 1 --out '%s/qrec' 2>&1", bin, ini, dir);
  CHECK(test_run_output(line, output, sizeof output) == 0, "record: %s", output);
  snprintf(path, sizeof path, "%s/q.exr", dir);
  float *rendered = load_exr_channel(path, "transmittance", W, H);
  snprintf(path, sizeof path, "%s/qrec/frame.0001.exr", dir);
  float *recorded = load_exr_channel(path, "transmittance", W, H);
  double least = 1.0, worst = 0.0;
  for (int k = 0; rendered && recorded && k < W * H; k++) {
    least = rendered[k] < least ? rendered[k] : least;
    const double d = rendered[k] - recorded[k];
    worst = fabs(d) > worst ? fabs(d) : worst;
  }
  CHECK(rendered && recorded && least < 0.5 && worst < 1e-5,
        "quadrics beside the fogmap model: render's transmittance down to %g, %g from "
        "record's frame 1", least, worst);
  free(rendered), free(recorded);
  test_remove_tree(dir);
  return test_finish("test_no_fog_config");
}
