/* Surfaces up to the far plane are drawn, not the sky: down a tall column over a flat
 * ground toward the horizon, every row whose ray meets the ground before 0.998 far reads the
 * ground's distance (exact: 100 / |dir.y| from a camera 100 above it). The projection's
 * finite far put window depths within float rounding of 1 (the sky's) over the last few
 * per cent of far: the sky took them (on llvmpipe, ground lost from 0.975 far at near/far
 * 1e-6 and from 0.55 far at 1e-7: 5 and 169 of this column's 1845 ground rows). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "app/config.h"
#include "app/player.h"
#include "render/camera.h"
#include "tests/test_util.h"

enum { W = 4, H = 3600 };

static void check_column(const char *dir, double near_plane) {
  char path[300], text[600];
  snprintf(path, sizeof path, "%s/far.ini", dir);
  snprintf(text, sizeof text,
           "[camera]\nposition = 0 100 0\nyaw = 0\npitch = -0.07\nfov = 1\nnear = %g\n"
           "far = 100000\n[terrain]\norigin = -200000 0 -200000\nsize = 400000 400000\n"
           "height = 0\nresolution = 2\n",
           near_plane);
  if (!test_write_text(path, text)) return;
  scene_config cfg;
  fog_error err = {0};
  CHECK(scene_config_load(path, &cfg, &err) == 0, "%s", err.message);
  static float depth[W * H];
  player *p = player_create(&(player_desc){.config = &cfg, .width = W, .height = H, .fps = 24},
                            &err);
  CHECK(p && player_frame(p, 1, &(frame_pixels){.depth = depth}, &err) == 0, "%s", err.message);
  player_destroy(p);
  camera cam;
  scene_config_camera(&cfg, &cam);
  /* the rows' exact distances (row 0 at the top), and which way the frame's rows run */
  static double exact[H];
  for (int y = 0; y < H; y++) {
    double o[3], d[3];
    camera_ray(&cam, W / 2, y, W, H, o, d);
    exact[y] = d[1] < 0 ? o[1] / -d[1] : INFINITY;
  }
  int agree_down = 0, agree_up = 0;
  for (int y = 0; y < H; y++)
    if (exact[y] < 0.5 * cam.far_plane) {
      agree_down += fabs(depth[y * W + W / 2] - exact[y]) < 1e-3 * exact[y];
      agree_up += fabs(depth[(H - 1 - y) * W + W / 2] - exact[y]) < 1e-3 * exact[y];
    }
  const bool flipped = agree_up > agree_down;
  int lost = 0, checked = 0;
  double nearest_lost = INFINITY;
  for (int y = 0; y < H; y++) {
    if (!(exact[y] < 0.998 * cam.far_plane)) continue;
    const double got = depth[(flipped ? H - 1 - y : y) * W + W / 2];
    checked++;
    if (!(fabs(got - exact[y]) < 2e-3 * exact[y])) {
      lost++;
      nearest_lost = fmin(nearest_lost, exact[y]);
    }
  }
  CHECK(checked > 1000, "near %g: only %d rows on the ground", near_plane, checked);
  CHECK(lost == 0, "near %g (near/far %g): %d of %d ground rows read another distance, from "
        "%.4f far on (the sky's?)", near_plane, near_plane / cam.far_plane, lost, checked,
        nearest_lost / cam.far_plane);
}

int main(void) {
  char dir[] = "/tmp/fogpipe_far_XXXXXX";
  if (!mkdtemp(dir)) return 1;
  check_column(dir, 0.1);  /* near/far 1e-6, the default ratio */
  check_column(dir, 0.01); /* 1e-7, the least a config takes */
  test_remove_tree(dir);
  return test_finish("test_far_surfaces");
}
