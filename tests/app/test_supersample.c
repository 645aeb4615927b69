/* [render] supersample = k: a frame is the k x k block means of the same frame drawn at k
 * times the size (colour, alpha, transmittance, in-scatter), its depth each block's nearest
 * surface; the blocks are computed here in double from a player drawing one sample a pixel
 * at k x, for the static scene (a render session) and the simulated one (the per-frame
 * pipeline, as record draws it), k = 2 with every output and k = 3 with colour alone. The
 * sky (depth = the far plane) is a block's depth only where every sample is sky: with a far
 * plane of 400, surfaces at the frame's edge lie past it along their rays.
 * Silhouettes do get in-between values (anti-aliasing: blocks whose samples differ by more
 * than 0.1 in red). A size past 16384 a side, supersampled, is refused naming the key. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "app/player.h"
#include "tests/test_util.h"

enum { W = 48, H = 27, KMAX = 3 };

typedef struct frame {
  float rgba[4 * W * KMAX * H * KMAX], transmittance[W * KMAX * H * KMAX],
      depth[W * KMAX * H * KMAX], inscatter[3 * W * KMAX * H * KMAX];
} frame;

/* all: every output; otherwise colour alone (the others NULL, as `render` to a PNG asks) */
static int draw(const scene_config *cfg, int width, int height, bool play, bool all,
                frame *f) {
  fog_error err = {0};
  player *p = player_create(&(player_desc){.config = cfg, .width = width, .height = height,
                                           .fps = 24.0, .play = play},
                            &err);
  const frame_pixels out = {.rgba = f->rgba, .transmittance = all ? f->transmittance : NULL,
                            .depth = all ? f->depth : NULL,
                            .inscatter = all ? f->inscatter : NULL};
  int status = !p || player_frame(p, 1, &out, &err);
  CHECK(status == 0, "player at %dx%d: %s", width, height, err.message);
  player_destroy(p);
  return status;
}

/* far_cut: the config's far plane cuts the terrain, so that blocks hold sky samples beside
 * surfaces further along their rays than the far plane (a z-plane), which are not sky */
static void compare(const char *label, const scene_config *cfg, int k, bool play, bool all,
                    bool far_cut) {
  static frame fine, coarse;
  scene_config one = *cfg, many = *cfg;
  one.supersample = 1, many.supersample = k;
  if (draw(&one, W * k, H * k, play, true, &fine) || draw(&many, W, H, play, all, &coarse))
    return;
  const int channels = all ? 8 : 4;
  const float sky = (float)cfg->camera.far_plane; /* the depth the frames hold for the sky */
  double worst = 0.0;
  int depth_wrong = 0, edges = 0, sky_beside_far_surface = 0;
  for (int y = 0; y < H; y++)
    for (int x = 0; x < W; x++) {
      const int o = y * W + x;
      double mean[8] = {0}, nearest = INFINITY, lo = INFINITY, hi = -INFINITY;
      bool any_sky = false;
      for (int j = 0; j < k; j++)
        for (int i = 0; i < k; i++) {
          const int s = (y * k + j) * W * k + x * k + i;
          for (int c = 0; c < 4; c++) mean[c] += fine.rgba[4 * s + c] / (double)(k * k);
          mean[4] += fine.transmittance[s] / (double)(k * k);
          for (int c = 0; c < 3; c++) mean[5 + c] += fine.inscatter[3 * s + c] / (double)(k * k);
          if (fine.depth[s] == sky)
            any_sky = true;
          else
            nearest = fmin(nearest, fine.depth[s]);
          lo = fmin(lo, fine.rgba[4 * s]), hi = fmax(hi, fine.rgba[4 * s]);
        }
      const double got[8] = {coarse.rgba[4 * o], coarse.rgba[4 * o + 1], coarse.rgba[4 * o + 2],
                             coarse.rgba[4 * o + 3], coarse.transmittance[o],
                             coarse.inscatter[3 * o], coarse.inscatter[3 * o + 1],
                             coarse.inscatter[3 * o + 2]};
      for (int c = 0; c < channels; c++)
        worst = fmax(worst, fabs(got[c] - mean[c]) / fmax(1.0, fabs(mean[c])));
      if (nearest == INFINITY) nearest = sky; /* sky only where every sample is sky */
      if (all) depth_wrong += coarse.depth[o] != (float)nearest;
      sky_beside_far_surface += any_sky && nearest > sky;
      edges += hi - lo > 0.1;
    }
  printf("%s, k = %d%s: supersampled %dx%d against the block means of %dx%d: worst %.2e; %d "
         "edge blocks\n", label, k, all ? "" : ", colour alone", W, H, W * k, H * k, worst,
         edges);
  CHECK(worst < 1e-6, "%s, k = %d: a supersampled value is %.3e off its block's mean", label,
        k, worst);
  CHECK(depth_wrong == 0, "%s: %d depths are not their block's nearest", label, depth_wrong);
  CHECK(edges > 20, "%s: only %d blocks straddle an edge", label, edges);
  if (far_cut)
    CHECK(sky_beside_far_surface > 0, "%s: no block holds sky beside a surface past the far "
          "plane (the case the far-plane config is for)", label);
}

int main(void) {
  scene_config cfg;
  fog_error err = {0};
  if (scene_config_load("configs/default.ini", &cfg, &err)) {
    CHECK(0, "%s", err.message);
    return test_finish("test_supersample");
  }
  compare("default.ini as held (render session)", &cfg, 2, false, true, false);
  compare("default.ini simulated (pipeline)", &cfg, 2, true, true, false);
  compare("default.ini as held (render session)", &cfg, 3, false, false, false);
  scene_config near_far = cfg;
  near_far.camera.far_plane = 400.0;
  compare("default.ini, far plane 400 (render session)", &near_far, 2, false, true, true);
  compare("default.ini, far plane 400 (pipeline)", &near_far, 2, true, true, true);

  cfg.supersample = 4;
  player *p = player_create(&(player_desc){.config = &cfg, .width = 5000, .height = 100,
                                           .fps = 24.0},
                            &err);
  CHECK(!p && strstr(err.message, "[render] supersample = 4 draws 20000x400 pixels"),
        "5000 wide x 4: '%s'", err.message);
  player_destroy(p);
  return test_finish("test_supersample");
}
