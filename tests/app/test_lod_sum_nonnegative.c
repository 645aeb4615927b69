/* Under `lod = sum` the signed detail bands of a sharp-edged map, summed in float, can
 * add up to a negative optical depth on rays that miss its fog (at mu 1 the bands cancel to
 * A_J, less rounding of their large terms); extinction is never negative, so the pass takes
 * the sum as 0 there (GL and its CPU twin alike). It used to draw a transmittance above 1
 * (1.002 at a density of 1e3, 1.28 at 1e5) and NaN at 1e8, which `render` then refused to
 * write. A 4 x 4 map, its top half dense, from above and from the side (FOGPIPE_BIN). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "exr_channel_util.h"
#include "test_bin.h"

enum { W = 96, H = 54 };

int main(void) {
  char dir[] = "/tmp/fogpipe_lod_sum_XXXXXX";
  const char *bin = test_bin_and_folder(dir);
  if (!bin) return test_finish("test_lod_sum_nonnegative");
  static const double densities[3] = {1e3, 1e5, 1e8};
  static const char *const views[2] = {"position = 0 200 0\nlook_at = 0 0 0.01",
                                       "position = -30 120 -30\nlook_at = 20 0 20"};
  for (int q = 0; q < 2; q++)
    for (int k = 0; k < 3; k++) {
    char map_path[300], ini[300], exr[300], text[1200], cmd[2400];
    snprintf(map_path, sizeof map_path, "%s/map.exr", dir);
    snprintf(ini, sizeof ini, "%s/scene.ini", dir);
    snprintf(exr, sizeof exr, "%s/frame.exr", dir);
    fogmap map;
    fog_error err;
    CHECK(!fogmap_create(&map, 4, 4, &err), "%s", err.message);
    for (int i = 0; i < 16; i++) map.density[i] = i < 8 ? (float)densities[k] : 0.0f;
    CHECK(!fogmap_save_exr(map_path, &map, &err), "%s", err.message);
    fogmap_destroy(&map);
    snprintf(text, sizeof text,
             "[camera]\n%s\n"
             "[terrain]\nheight = 0\n"
             "[box]\norigin = 0 0\ncell_size = 10\nfloor = 0\ntop = 50\n"
             "[fog]\nfogmap = map.exr\ndensity_scale = 1\nlod = sum\nmu = 1\n", views[q]);
    test_write_text(ini, text);
    snprintf(cmd, sizeof cmd, "'%s' render '%s' --size %dx%d --out '%s' > /dev/null", bin, ini, W,
             H, exr);
    CHECK(system(cmd) == 0, "density %g: %s failed", densities[k], cmd);
    float *tau = load_exr_channel(exr, "transmittance", W, H);
    double most = 0.0, least = 1.0;
    int nonfinite = 0;
    for (int i = 0; tau && i < W * H; i++) {
      if (!isfinite(tau[i])) nonfinite++;
      else most = fmax(most, tau[i]), least = fmin(least, tau[i]);
    }
    printf("density %g: transmittance %g .. %g, %d non-finite\n", densities[k], least, most,
           nonfinite);
    CHECK(tau && nonfinite == 0 && most <= 1.0 && least < 0.5,
          "density %g: transmittance %g .. %g, %d non-finite", densities[k], least, most,
          nonfinite);
    free(tau);
    remove(exr), remove(map_path), remove(ini);
  }
  test_remove_tree(dir);
  return test_finish("test_lod_sum_nonnegative");
}
