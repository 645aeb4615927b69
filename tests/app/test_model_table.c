/* The fog-model table (render/fog_models.def) drives everything that names a model: the
 * enum, the lookup by name, the config's choices and keys, the CPU dispatch and the GLSL
 * the fog pass compiles (constants and dispatch, render/fog_shader_text.h). Each row is
 * checked against the others: a row whose keys the config does not know, a name the
 * config does not accept, a kind the GLSL disagrees on or a model missing from the
 * generated dispatch fails here. The GL tests (test_render_fog_models, test_gpu_*) draw
 * every model with the generated text. */
#define _XOPEN_SOURCE 700
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/config.h"
#include "render/fog_models.h"
#include "render/fog_shader_text.h"
#include "test_util.h"

/* Loads a config of `[fog] model = name` plus what that model requires; the kind read. */
static int config_model(const char *name, const char *folder, int *kind) {
  char path[600], vdb[1200] = "";
  snprintf(path, sizeof path, "%s/model_%s.ini", folder, name);
  FILE *f = fopen(path, "w");
  if (!f) return 1;
  char *data = realpath("../shared/data/vdb/plume/data", NULL);
  if (data) snprintf(vdb, sizeof vdb, "vdb = %s/fluid_data_####.vdb\n", data);
  free(data);
  fprintf(f, "[fog]\nmodel = %s\n%s%s%s", name,
          !strcmp(name, "rbf") ? "rbf = 0 1 0 2 0.5\n" : "",
          !strcmp(name, "quadric") ? "quadric = sphere 0 1 0 2 0.5\n" : "",
          !strcmp(name, "volume") ? vdb : "");
  fclose(f);
  scene_config cfg;
  fog_error err;
  int failed = scene_config_load(path, &cfg, &err);
  CHECK(!failed, "model = %s: %s", name, err.message);
  remove(path);
  *kind = failed ? -1 : (int)cfg.fog.model;
  return failed;
}

int main(void) {
  char folder[] = "/tmp/fogpipe-model-table-XXXXXX";
  CHECK(mkdtemp(folder) != NULL, "mkdtemp");
  char constants[FOG_SHADER_GENERATED_MAX], dispatch[FOG_SHADER_GENERATED_MAX];
  int nc = fog_shader_generated("fog_constants.glsl", constants, sizeof constants);
  int nd = fog_shader_generated("fog_model_table.glsl", dispatch, sizeof dispatch);
  CHECK(nc > 0 && nd > 0, "generated GLSL: %d and %d bytes", nc, nd);
  CHECK(fog_shader_generated("fog_integral.glsl", constants, sizeof constants) == -1,
        "an embedded file's name is not generated");
  char small[16];
  CHECK(fog_shader_generated("fog_constants.glsl", small, sizeof small) == -2,
        "a buffer too small is refused");
  nc = fog_shader_generated("fog_constants.glsl", constants, sizeof constants);

  /* The enum's names, from the same rows: what the GLSL must call each kind. */
  static const char *const kinds[] = {
#define FOG_MODEL_ROW(KIND, id, label, keys, pyramid) #KIND,
#include "render/fog_models.def"
#undef FOG_MODEL_ROW
  };
  CHECK(sizeof kinds / sizeof kinds[0] == FOG_MODEL_COUNT, "rows and FOG_MODEL_COUNT");
  for (int k = 0; k < FOG_MODEL_COUNT; k++) {
    const fog_model_info *row = &fog_model_table[k];
    CHECK(row->kind == (fog_model_kind)k, "row %d holds kind %d", k, (int)row->kind);
    CHECK(row->name && row->name[0] && row->label && row->label[0] && row->optical_depth,
          "row %d is incomplete", k);
    CHECK(fog_model_find(row->name) == row, "fog_model_find(%s)", row->name);
    for (int j = 0; j < k; j++)
      CHECK(strcmp(fog_model_table[j].name, row->name), "two rows are called %s", row->name);

    /* Its keys are keys the config reads. */
    char keys[256];
    snprintf(keys, sizeof keys, "%s", row->keys);
    for (char *save = NULL, *key = strtok_r(keys, " ", &save); key;
         key = strtok_r(NULL, " ", &save))
      CHECK(scene_config_knows_key("fog", key), "%s lists [fog] %s, which configs lack",
            row->name, key);

    /* The config takes its name and reads it as its kind. */
    int kind = -1;
    if (!config_model(row->name, folder, &kind))
      CHECK(kind == k, "model = %s read as kind %d, not %d", row->name, kind, k);

    /* The GLSL agrees on its value and dispatches to both of its twins. */
    char line[128];
    snprintf(line, sizeof line, "#define FOG_MODEL_%s %d\n", kinds[k], k);
    CHECK(strstr(constants, line) != NULL, "fog_constants.glsl lacks '%.*s'",
          (int)strlen(line) - 1, line);
    snprintf(line, sizeof line, "FOG_MODEL_KIND == FOG_MODEL_%s\n", kinds[k]);
    const char *branch = strstr(dispatch, line);
    CHECK(branch != NULL, "fog_model_table.glsl has no branch for %s", kinds[k]);
    char depth[96], march[96];
    snprintf(depth, sizeof depth, "return fog_model_depth_%s(ray);", row->name);
    snprintf(march, sizeof march, "return fog_model_march_%s(ray);", row->name);
    if (branch) {
      const char *next = strstr(branch + strlen(line), "FOG_MODEL_KIND ==");
      const char *d = strstr(branch, depth), *m = strstr(branch, march);
      CHECK(d && m && (!next || (d < next && m < next)),
            "the %s branch does not call its twins %s / %s", kinds[k], depth, march);
    }
  }
  CHECK(fog_model_find("fog") == NULL && fog_model_find("") == NULL, "unknown names");
  fog_model bad = {.kind = FOG_MODEL_COUNT};
  double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
  CHECK(isnan(fog_model_optical_depth(&bad, o, d, 1.0)), "a kind past the table is NaN");
  /* An unknown model name is a config error naming the choices from the table. */
  char path[600];
  snprintf(path, sizeof path, "%s/bad.ini", folder);
  FILE *f = fopen(path, "w");
  if (f) {
    fputs("[fog]\nmodel = fogg\n", f);
    fclose(f);
    scene_config cfg;
    fog_error err;
    CHECK(scene_config_load(path, &cfg, &err) != 0 && strstr(err.message, fog_model_table[
          FOG_MODEL_COUNT - 1].name) && strstr(err.message, "bad.ini:2"),
          "model = fogg: %s", err.message);
    remove(path);
  }
  rmdir(folder);
  return test_finish("test_model_table");
}
