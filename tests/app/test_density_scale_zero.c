/* `[fog] density_scale = 0` is no fog: every pixel's transmittance is exactly 1, for every
 * model and every shipped config (it used to mean "1 per world unit", so a user turning
 * the fog off got thick fog: mean tau 0.28 on the default scene). Each config is also
 * rendered as shipped, so that the test sees fog there and cannot pass on an empty view. */
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

/* min and mean transmittance of cfg's frame; 0 on success. */
static int render_tau(const scene_config *cfg, double *min_tau, double *mean_tau) {
  float *tau = malloc(sizeof(float) * W * H);
  render_frame_info info;
  fog_error err = {0};
  int failed = render_frame(cfg, W, H, &(frame_pixels){.transmittance = tau}, &info, &err);
  CHECK(!failed, "render: %s", err.message);
  *min_tau = 1.0, *mean_tau = 0.0;
  for (int i = 0; !failed && i < W * H; i++) {
    *min_tau = fmin(*min_tau, tau[i]);
    *mean_tau += tau[i] / (W * H);
  }
  free(tau);
  return failed;
}

static void check_config(const char *path) {
  scene_config cfg;
  fog_error cerr;
  if (scene_config_load(path, &cfg, &cerr)) {
    CHECK(0, "%s", cerr.message);
    return;
  }
  double min_tau, mean_tau;
  if (!render_tau(&cfg, &min_tau, &mean_tau))
    CHECK(min_tau < 0.95, "%s as shipped: min tau %.4f, expected fog in view", path, min_tau);
  cfg.fog.density_scale = 0.0;
  cfg.fog.rbf_base = 0.0; /* model = rbf: K = rbf_base + density_scale sum of Gaussians */
  if (!render_tau(&cfg, &min_tau, &mean_tau))
    CHECK(min_tau == 1.0, "%s with density_scale = 0: min tau %.6f mean %.6f, expected 1",
          path, min_tau, mean_tau);
  printf("%s: density_scale = 0 gives min tau %.6f\n", path, min_tau);
}

int main(void) {
  char dir[] = "/tmp/fogpipe_density_zero_XXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  static const char *const inline_models[2][2] = {
      {"homogeneous", "[fog]\nmodel = homogeneous\ndensity_scale = 0.003\n"},
      {"height", "[fog]\nmodel = height\ndensity_scale = 0.02\nfog_height = 30\n"
                 "scale_height = 25\n"}};
  for (int k = 0; k < 2; k++) {
    char path[256];
    snprintf(path, sizeof path, "%s/%s.ini", dir, inline_models[k][0]);
    FILE *f = fopen(path, "w");
    fputs("[camera]\nposition = 0 120 400\nlook_at = 0 20 -100\n[terrain]\nresolution = 65\n",
          f);
    fputs(inline_models[k][1], f);
    fclose(f);
    check_config(path);
    unlink(path);
  }
  static const char *const shipped[] = {"configs/default.ini", "configs/heightmap.ini",
                                        "configs/rbf_fog_banks.ini", "configs/vdb_groundfog.ini",
                                        "configs/vdb_plume_volume.ini",
                                        "configs/quadric_volumes.ini"};
  for (size_t i = 0; i < sizeof shipped / sizeof shipped[0]; i++) check_config(shipped[i]);
  rmdir(dir);
  return test_finish("test_density_scale_zero");
}
