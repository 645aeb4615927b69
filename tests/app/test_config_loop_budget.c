/* Every shipped config with lamps draws on llvmpipe: the lamps' and the view ray's loop bounds
 * (fog_pass_lamp_loop_bound with the lamps' shadow cubes and the surfaces' dimming counted in,
 * fog_pass_view_loop_bound with every Gaussian in one tile) stay below the renderer's cap less
 * the view ray's reserve, so the fog pass's guard (docs/platform.md, the loop cap) never
 * refuses them. So does the simulated fogmap with the most lamps the demo's lamp tool places
 * (FOG_MAX_LAMPS) at the config's default method: the lamp tool cannot trip the guard. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "app/render_fog.h"
#include "render/render.h"
#include "test_util.h"

/* llvmpipe's cap (test_gpu_lamp_loop_cap measures it): the budget on any renderer. */
#define LLVMPIPE_LOOP_CAP 65535.0

static const lamp_shadow_maps some_cubes = {.count = FOG_MAX_LAMPS}; /* cubes for all */

/* The lamps' bound and the view ray's (every Gaussian in one screen tile). */
static double worst_case_bound(const render_fog *fog, const fog_lamps *lamps) {
  fog_pass_params p = fog->params;
  p.lamps = *lamps;
  p.lamp_shadows = &some_cubes;
  p.surface_lamps = 1;
  return fog_pass_loop_bound(&p, p.model_rbf_count);
}

static void check_config(const char *path, bool all_lamps) {
  scene_config *cfg = malloc(sizeof *cfg);
  fog_error err = {0};
  CHECK(cfg && scene_config_load(path, cfg, &err) == 0, "%s: %s", path, err.message);
  if (!cfg || (cfg->lamp_count == 0 && !all_lamps)) {
    free(cfg);
    return;
  }
  render_fog fog;
  CHECK(render_fog_create(&fog, cfg, &err) == 0, "%s: %s", path, err.message);
  if (err.message[0]) {
    free(cfg);
    return;
  }
  fog_lamps lamps = scene_config_fog_lamps(cfg);
  if (all_lamps) { /* the lamp tool's most: copies of one lamp */
    lamps.lamp[0] = (fog_lamp){.kind = FOG_LAMP_POINT, .position = {0, 60, 0},
                               .intensity = {1000, 900, 800}, .radius = 0.5};
    for (int i = 1; i < FOG_MAX_LAMPS; i++) lamps.lamp[i] = lamps.lamp[0];
    lamps.count = FOG_MAX_LAMPS;
  }
  const double bound = worst_case_bound(&fog, &lamps);
  fog_lamps live = lamps;
  live.method = scene_live_lamp_method(lamps.method);
  const double live_bound = worst_case_bound(&fog, &live);
  printf("%s (%s, %d lamps): bound %.0f, at the live rule %.0f\n", path,
         fog_model_table[fog.params.model].name, lamps.count, bound, live_bound);
  CHECK(bound > 0 && bound <= LLVMPIPE_LOOP_CAP - FOG_PASS_LOOP_RESERVE,
        "%s: %d lamps bound at %.0f loop iterations: over llvmpipe's %.0f less the reserve %d",
        path, lamps.count, bound, LLVMPIPE_LOOP_CAP, FOG_PASS_LOOP_RESERVE);
  CHECK(live_bound > 0 && live_bound <= bound, "%s: the live rule's bound %.0f is not below "
        "the config's %.0f", path, live_bound, bound);
  render_fog_destroy(&fog);
  free(cfg);
}

int main(void) {
  fog_error err = {0};
  gl_context *ctx = gl_context_create(&(gl_context_desc){0}, &err);
  CHECK(ctx != NULL, "headless context: %s", err.message);
  if (!ctx) return test_finish("test_config_loop_budget");
  DIR *dir = opendir("configs");
  CHECK(dir != NULL, "configs/: cannot list it (run from the source tree)");
  int with_lamps = 0;
  for (struct dirent *e; dir && (e = readdir(dir));) {
    size_t n = strlen(e->d_name);
    if (n < 5 || strcmp(e->d_name + n - 4, ".ini")) continue;
    char path[512];
    snprintf(path, sizeof path, "configs/%s", e->d_name);
    scene_config *cfg = malloc(sizeof *cfg);
    if (cfg && scene_config_load(path, cfg, &err) == 0 && cfg->lamp_count > 0) {
      with_lamps++;
      check_config(path, false);
    }
    free(cfg);
  }
  if (dir) closedir(dir);
  CHECK(with_lamps >= 3, "%d shipped configs with lamps: expected night_lamps, lamp_shafts and "
        "rbf_lamp_tube at least", with_lamps);
  check_config("configs/default.ini", true);
  gl_context_destroy(ctx);
  return test_finish("test_config_loop_budget");
}
