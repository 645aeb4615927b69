/* The exponential profile with a scale height far below the box's height: the GL walk
 * breaks every H/2 above y0 (its moments' series needs it), and a ray across the box
 * crossed 2e5 such breaks, past the walk's 65536 steps: the fog vanished (tau 1 where the
 * C twin says 0.4). The walk now breaks at y0 alone below it and not past 105 scale
 * heights above it (e^{-105} is below float's least). Each pixel's transmittance against
 * the CPU twin (render_fog_model, exact in double) along its ray to the frame's depth, for
 * H from 1 down to 1e-4 (the config's least), max |dtau| <= 2e-4, and the fog in view;
 * seen from above the box, from inside the fog below y0 looking up, and from y0 itself. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>

#include "app/config.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "model_tau.h"
#include "render/render.h"
#include "test_util.h"

enum { W = 48, H = 27 };

static void check(const char *dir, double scale_height, const char *view) {
  char path[300], text[900];
  snprintf(path, sizeof path, "%s/steep.ini", dir);
  snprintf(text, sizeof text,
           "[camera]\n%s\nfov = 60\n"
           "[terrain]\nheight = 0.000001\n"
           "[fog]\nfogmap = %s/data/fogmap_sample.png\ndensity_scale = 0.08\nlevels = 0\n"
           "profile = exponential\nfog_height = 10\nscale_height = %.17g\nalbedo = 0\n"
           "[box]\norigin = -512 -512\ncell_size = 4\nfloor = -1\ntop = 100\n",
           view, FOGPIPE_SOURCE_DIR, scale_height);
  model_tau_error e;
  fog_error err = {0};
  if (model_tau_of_config(path, text, W, H, &e, &err)) {
    CHECK(0, "H %g: %s", scale_height, err.message);
    return;
  }
  printf("%s, scale height %g: max |dtau| %.2e, tau from %.3f to %.3f\n", view, scale_height,
         e.worst, e.lowest, e.highest);
  CHECK(e.worst <= 2e-4 && e.lowest < 0.8, "%s, scale height %g: max |dtau| %g against the CPU "
        "twin, tau down to %g", view, scale_height, e.worst, e.lowest);
}

int main(void) {
  char dir[] = "/tmp/fogpipe-steep-XXXXXX";
  if (!test_scratch_folder(dir)) return 1;
  /* from above (every ray comes down through the breaks), from inside the fog below y0
   * looking up (rays rise through y0 and past the last break), and from y0 itself */
  const char *const views[3] = {"position = 13.7 300.3 40.1\nlook_at = 0 0 -60",
                                "position = 13.7 4.3 40.1\nlook_at = 0 60 -200",
                                "position = 13.7 10 40.1\nlook_at = 0 20 -200"};
  const double heights[] = {1.0, 0.01, 0.001, 1e-4};
  for (int v = 0; v < 3; v++)
    for (int i = 0; i < 4; i++) check(dir, heights[i], views[v]);
  test_remove_tree(dir);
  return test_finish("test_render_steep_profile");
}
