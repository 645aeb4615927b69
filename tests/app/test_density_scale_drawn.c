/* scene_config_draws_density_scale (what the window's density slider is shown for) against
 * the pixels: render_frame of a scene at [fog] density_scale D and at 3 D gives the same
 * transmittance exactly where the predicate says density_scale draws nothing. Linear fog
 * reads fog_start and fog_end alone (the slider did nothing on classic_fog.ini); exp2,
 * homogeneous, height and quadric fog read it. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/config.h"
#include "app/render_frame.h"
#include "test_util.h"

enum { W = 48, H = 27 };

static const char *const scenes[][2] = {
    {"linear", "[fog]\nmodel = linear\nfog_start = 20\nfog_end = 600\n"},
    {"quadric", "[fog]\nmodel = quadric\nquadric = sphere 0 40 -150 60 1 0.5\n"},
    {"height beside a quadric",
     "[fog]\nmodel = height\nfog_height = 0\nscale_height = 40\n"
     "quadric = sphere 0 40 -150 60 1 0.5\n"},
    {"exp2", "[fog]\nmodel = exp2\n"},
    {"homogeneous", "[fog]\nmodel = homogeneous\n"},
    {"height", "[fog]\nmodel = height\nfog_height = 0\nscale_height = 40\n"},
};

/* Max |delta transmittance| between density_scale 0.004 and 0.012; -1 on failure. */
static double change(const char *folder, const char *label, const char *fog, bool *draws) {
  double largest = -1.0;
  float *tau[2] = {malloc(sizeof(float) * W * H), malloc(sizeof(float) * W * H)};
  for (int k = 0; k < 2; k++) {
    char path[600], text[1024];
    snprintf(path, sizeof path, "%s/scene%d.ini", folder, k);
    snprintf(text, sizeof text,
             "[camera]\nposition = 0 40 200\nlook_at = 0 30 -200\n%sdensity_scale = %g\n", fog,
             k ? 0.012 : 0.004);
    if (!test_write_text(path, text)) goto done;
    scene_config cfg;
    fog_error err;
    if (scene_config_load(path, &cfg, &err)) {
      CHECK(0, "%s: %s", label, err.message);
      goto done;
    }
    *draws = scene_config_draws_density_scale(&cfg);
    render_frame_info info;
    if (render_frame(&cfg, W, H, &(frame_pixels){.transmittance = tau[k]}, &info, &err)) {
      CHECK(0, "%s: render_frame: %s", label, err.message);
      goto done;
    }
  }
  largest = 0.0;
  for (int i = 0; i < W * H; i++) {
    double d = tau[1][i] - tau[0][i];
    if (d < 0) d = -d;
    if (d > largest) largest = d;
  }
done:
  free(tau[0]), free(tau[1]);
  return largest;
}

int main(void) {
  char folder[] = "/tmp/fogpipe-density-drawn-XXXXXX";
  if (!test_scratch_folder(folder)) return 1;
  for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
    bool draws = false;
    const double d = change(folder, scenes[i][0], scenes[i][1], &draws);
    printf("%-24s draws density_scale: %-5s max |delta tau| x3: %.3g\n", scenes[i][0],
           draws ? "yes" : "no", d);
    if (d < 0) continue;
    CHECK(draws == (d > 1e-4), "%s: the predicate says %s, the pixels changed by %g",
          scenes[i][0], draws ? "it draws" : "it draws nothing", d);
    CHECK(draws || d == 0.0, "%s: density_scale moved pixels by %g", scenes[i][0], d);
  }
  /* [render] skip_below bounds the fog before density_scale: the fogmap's cells are that,
   * the volume's voxels are uploaded scaled, so its walk's threshold is scaled too (it was
   * compared with the scaled voxels as given: 10 x past the stated bound at 0.1) */
  char cwd[400];
  if (!getcwd(cwd, sizeof cwd)) cwd[0] = '\0';
  const char *const walks[][2] = {
      {"volume", "[fog]\nmodel = volume\nvdb = %s/../shared/data/vdb/plume/data/"
                 "fluid_data_0048.vdb\ndensity_scale = 0.1\n[render]\nskip_below = 0.02\n"},
      {"fogmap", "[fog]\nfogmap = %s/data/fogmap_sample.png\ndensity_scale = 0.1\n"
                 "[render]\nskip_below = 0.02\n"}};
  for (int w = 0; w < 2; w++) {
    char path[600], text[1200];
    snprintf(path, sizeof path, "%s/walk.ini", folder);
    snprintf(text, sizeof text, walks[w][1], cwd);
    scene_config cfg;
    fog_error err;
    if (!test_write_text(path, text)) continue;
    if (scene_config_load(path, &cfg, &err)) {
      CHECK(0, "%s: %s", walks[w][0], err.message);
      continue;
    }
    const fog_walk_settings walk = scene_config_walk(&cfg);
    const float expected = w == 0 ? 0.02f * 0.1f : 0.02f;
    CHECK(walk.skip == FOG_SKIP_BELOW && fabsf(walk.skip_below - expected) <= 1e-9f,
          "%s: the walk skips below %g, expected %g", walks[w][0], walk.skip_below, expected);
  }
  test_remove_tree(folder);
  return test_finish("test_density_scale_drawn");
}
