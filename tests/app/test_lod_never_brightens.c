/* Fog never makes what is behind it brighter, at any LOD: the ground fog fogmap (sharp
 * edges, 0 outside) at mu = 0.5 and 0, linear and quadratic bases, both LOD methods, through
 * render_frame (the GL fog pass): every pixel's transmittance <= 1 and every colour >= 0.
 * The bases' coarse levels dip below zero next to the edges (-0.18 of the peak at J = 3),
 * and a ray through those dips used to leave with tau up to 12 and negative colours;
 * the renderer's pyramid clamps them (transform_density_pyramid). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>

enum { W = 64, H = 36 };
#include "frame_util.h"
#include "test_util.h"

static char dir[] = "/tmp/fogpipe_lod_brightens_XXXXXX";

static void check(const char *basis, const char *lod, const char *mu) {
  char path[300], text[1400], label[80];
  snprintf(label, sizeof label, "%s, lod %s, mu %s", basis, lod, mu);
  snprintf(path, sizeof path, "%s/scene.ini", dir);
  snprintf(text, sizeof text,
           "[camera]\nposition = 0 40 140\nlook_at = 0 0 0\nfov = 60\n"
           "[terrain]\norigin = -200 0 -200\nsize = 400 400\nheight = 0.000001\n"
           "[light]\nsun_elevation = 30\n"
           "[fog]\nfogmap = %s/data/fogmap_groundfog.exr\ndensity_scale = 0.5\n"
           "basis = %s\nlevels = 3\nlod = %s\nmu = %s\nprofile = slab\nfog_height = 20\n"
           "albedo = 0\n"
           "[box]\norigin = -64 -64\ncell_size = 1\nfloor = 0\n",
           FOGPIPE_SOURCE_DIR, basis, lod, mu);
  scene_config cfg;
  fog_error err = {0};
  if (!test_write_text(path, text)) return;
  if (scene_config_load(path, &cfg, &err)) {
    CHECK(0, "%s: %s", label, err.message);
    return;
  }
  static frame f;
  if (render(&cfg, &f, label)) return;
  double tau_max = 0.0, rgb_min = 0.0, tau_min = 1.0;
  for (int k = 0; k < W * H; k++) {
    tau_max = fmax(tau_max, f.tau[k]), tau_min = fmin(tau_min, f.tau[k]);
    for (int c = 0; c < 3; c++) rgb_min = fmin(rgb_min, f.rgba[4 * k + c]);
  }
  CHECK(tau_min < 0.9, "%s: no fog in view (tau >= %g): nothing tested", label, tau_min);
  CHECK(tau_max <= 1.0 + 1e-6, "%s: transmittance %.6g > 1", label, tau_max);
  CHECK(rgb_min >= 0.0, "%s: a colour of %.6g", label, rgb_min);
}

int main(void) {
  if (!mkdtemp(dir)) {
    perror(dir);
    return 1;
  }
  check("linear", "switch", "0.5");
  check("linear", "sum", "0.5");
  check("linear", "switch", "0");
  check("quadratic", "switch", "0.5");
  check("quadratic", "sum", "0.5");
  test_remove_tree(dir);
  return test_finish("lod_never_brightens");
}
