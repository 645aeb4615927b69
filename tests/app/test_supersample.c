/* [render] supersample = 2: a frame is the 2 x 2 block means of the same frame drawn at twice
 * the size (colour, alpha, transmittance, in-scatter), its depth each block's nearest
 * surface; the blocks are computed here in double from a player drawing one sample a pixel
 * at 2x, for the static scene (a render session) and the simulated one (the per-frame
 * pipeline, as record draws it). Silhouettes do get in-between values (anti-aliasing:
 * blocks whose samples differ by more than 0.1 in red). A size past 16384 a side,
 * supersampled, is refused naming the key. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "app/player.h"
#include "tests/test_util.h"

enum { W = 48, H = 27, K = 2 };

typedef struct frame {
  float rgba[4 * W * K * H * K], transmittance[W * K * H * K], depth[W * K * H * K],
      inscatter[3 * W * K * H * K];
} frame;

static int draw(const scene_config *cfg, int width, int height, bool play, frame *f) {
  fog_error err = {0};
  player *p = player_create(&(player_desc){.config = cfg, .width = width, .height = height,
                                           .fps = 24.0, .play = play},
                            &err);
  int status = !p || player_frame(p, 1, &(frame_pixels){.rgba = f->rgba,
                                                         .transmittance = f->transmittance,
                                                         .depth = f->depth,
                                                         .inscatter = f->inscatter},
                                  &err);
  CHECK(status == 0, "player at %dx%d: %s", width, height, err.message);
  player_destroy(p);
  return status;
}

static void compare(const char *label, const scene_config *cfg, bool play) {
  static frame fine, coarse;
  scene_config one = *cfg, two = *cfg;
  one.supersample = 1, two.supersample = K;
  if (draw(&one, W * K, H * K, play, &fine) || draw(&two, W, H, play, &coarse)) return;
  double worst = 0.0;
  int depth_wrong = 0, edges = 0;
  for (int y = 0; y < H; y++)
    for (int x = 0; x < W; x++) {
      const int o = y * W + x;
      double mean[8] = {0}, nearest = INFINITY, lo = INFINITY, hi = -INFINITY;
      for (int j = 0; j < K; j++)
        for (int i = 0; i < K; i++) {
          const int s = (y * K + j) * W * K + x * K + i;
          for (int c = 0; c < 4; c++) mean[c] += fine.rgba[4 * s + c] / (double)(K * K);
          mean[4] += fine.transmittance[s] / (double)(K * K);
          for (int c = 0; c < 3; c++) mean[5 + c] += fine.inscatter[3 * s + c] / (double)(K * K);
          nearest = fmin(nearest, fine.depth[s]);
          lo = fmin(lo, fine.rgba[4 * s]), hi = fmax(hi, fine.rgba[4 * s]);
        }
      const double got[8] = {coarse.rgba[4 * o], coarse.rgba[4 * o + 1], coarse.rgba[4 * o + 2],
                             coarse.rgba[4 * o + 3], coarse.transmittance[o],
                             coarse.inscatter[3 * o], coarse.inscatter[3 * o + 1],
                             coarse.inscatter[3 * o + 2]};
      for (int c = 0; c < 8; c++)
        worst = fmax(worst, fabs(got[c] - mean[c]) / fmax(1.0, fabs(mean[c])));
      depth_wrong += coarse.depth[o] != (float)nearest;
      edges += hi - lo > 0.1;
    }
  printf("%s: supersampled %dx%d against the 2x2 block means of %dx%d: worst %.2e; %d edge "
         "blocks\n", label, W, H, W * K, H * K, worst, edges);
  CHECK(worst < 1e-6, "%s: a supersampled value is %.3e off its block's mean", label, worst);
  CHECK(depth_wrong == 0, "%s: %d depths are not their block's nearest", label, depth_wrong);
  CHECK(edges > 20, "%s: only %d blocks straddle an edge", label, edges);
}

int main(void) {
  scene_config cfg;
  fog_error err = {0};
  if (scene_config_load("configs/default.ini", &cfg, &err)) {
    CHECK(0, "%s", err.message);
    return test_finish("test_supersample");
  }
  compare("default.ini as held (render session)", &cfg, false);
  compare("default.ini simulated (pipeline)", &cfg, true);

  cfg.supersample = 4;
  player *p = player_create(&(player_desc){.config = &cfg, .width = 5000, .height = 100,
                                           .fps = 24.0},
                            &err);
  CHECK(!p && strstr(err.message, "[render] supersample = 4 draws 20000x400 pixels"),
        "5000 wide x 4: '%s'", err.message);
  player_destroy(p);
  return test_finish("test_supersample");
}
