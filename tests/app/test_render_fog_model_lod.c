/* The product's CPU twin of a fogmap at LOD (render_fog_model of a render session: what
 * `fit` measures every rung against) agrees with the GL fog pass of the same session, for
 * both LOD methods at mu < 1: each pixel's transmittance against exp(-fog_model_optical_
 * depth) along the pixel's ray to the frame's depth, max |dtau| <= 2e-4. The twin passed
 * the pyramid's unused detail slot as D_1 (an empty grid): the sum of details walked it to
 * NaN (found by the sanitizers in fit's "fogmap as given" rung). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>

#include "app/config.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "model_tau.h"
#include "render/render.h"
#include "test_util.h"

enum { W = 64, H = 36 };

static void check(const char *dir, const char *lod) {
  char path[300], text[800];
  snprintf(path, sizeof path, "%s/%s.ini", dir, lod);
  snprintf(text, sizeof text,
           "[camera]\nposition = 0 40 300\nlook_at = 0 25 -200\nfov = 55\n"
           "[fog]\nfogmap = %s/data/fogmap_sample.png\ndensity_scale = 0.02\nlevels = 2\n"
           "lod = %s\nmu = 0.6\nprofile = exponential\nfog_height = 50\nscale_height = 25\n"
           "albedo = 0\n[box]\norigin = -512 -512\ncell_size = 4\n",
           FOGPIPE_SOURCE_DIR, lod);
  model_tau_error e;
  fog_error err = {0};
  if (model_tau_of_config(path, text, W, H, &e, &err)) {
    CHECK(0, "%s: %s", lod, err.message);
    return;
  }
  const double worst = e.worst, lowest = e.lowest;
  printf("lod %s, mu 0.6: max |dtau| %.2e (tau down to %.3f)\n", lod, worst, lowest);
  CHECK(worst <= 2e-4 && lowest < 0.9, "lod %s: max |dtau| %g against the GL, tau down to %g",
        lod, worst, lowest);
}

int main(void) {
  char dir[] = "/tmp/fogpipe_fog_model_lod_XXXXXX";
  if (!test_scratch_folder(dir)) return 1;
  check(dir, "sum");
  check(dir, "switch");
  test_remove_tree(dir);
  return test_finish("test_render_fog_model_lod");
}
