/* The sky (render/shaders/scene_sky_fs.glsl) is brightest at the horizon and smooth through
 * it: down one column of a frame of sky alone (the camera level, the terrain far behind
 * it), the brightness peaks at the horizon's row, and no row bends the profile more than a
 * smooth gradient does (the largest second difference). The old gradient, sqrt(up) above
 * and a linear darkening below, met at a kink that drew a bright line along every horizon:
 * its second difference there was 9.2e-3 at 720 rows (now 7.6e-5); the bound is 2e-3. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "app/config.h"
#include "app/player.h"
#include "tests/test_util.h"

enum { W = 8, H = 720 };

int main(void) {
  char dir[] = "/tmp/fogpipe_sky_XXXXXX", path[300];
  if (!mkdtemp(dir)) return 1;
  snprintf(path, sizeof path, "%s/sky.ini", dir);
  if (!test_write_text(path, "[camera]\nposition = 0 50 0\nlook_at = 0 50 -100\nfov = 60\n"
                             "[terrain]\norigin = 5000 0 5000\nsize = 10 10\nheight = 1\n"
                             "resolution = 2\n[light]\nsun_colour = 0 0 0\n"))
    return test_finish("test_sky_horizon");
  scene_config cfg;
  fog_error err = {0};
  CHECK(scene_config_load(path, &cfg, &err) == 0, "%s", err.message);
  static float rgba[4 * W * H];
  player *p = player_create(&(player_desc){.config = &cfg, .width = W, .height = H, .fps = 24},
                            &err);
  CHECK(p && player_frame(p, 1, &(frame_pixels){.rgba = rgba}, &err) == 0, "%s", err.message);
  player_destroy(p);
  double b[H];
  for (int y = 0; y < H; y++) {
    const float *c = rgba + 4 * (y * W + W / 2);
    b[y] = (c[0] + c[1] + c[2]) / 3.0;
  }
  int brightest = 0;
  double bend = 0.0;
  int bend_row = 0;
  for (int y = 0; y < H; y++) {
    if (b[y] > b[brightest]) brightest = y;
    if (y > 0 && y + 1 < H) {
      const double d2 = fabs(b[y - 1] - 2.0 * b[y] + b[y + 1]);
      if (d2 > bend) bend = d2, bend_row = y;
    }
  }
  printf("sky column: brightest at row %d of %d (the horizon at %d); largest second "
         "difference %.2e at row %d\n", brightest, H, H / 2, bend, bend_row);
  CHECK(abs(brightest - H / 2) <= 3, "the sky is brightest at row %d, not at the horizon (%d)",
        brightest, H / 2);
  CHECK(bend < 2e-3, "the sky bends by %.3e at row %d: a crease", bend, bend_row);
  unlink(path);
  rmdir(dir);
  return test_finish("test_sky_horizon");
}
