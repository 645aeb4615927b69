/* Lamps that move and flicker ([light] lamp_path, lamp_flicker; docs/config.md) in the
 * frames of `record`'s frame path (app/player.h): frame n shows the lamps at scene time
 * (n - 1) / fps, so it equals bit for bit the same frame of a config whose lamps stand
 * still where and as bright as scene_config_fog_lamps_at puts them then. For both frame
 * paths: a render session (homogeneous fog) and the simulating pipeline (a fogmap). Also:
 * the path's keys are met exactly and held past the ends, and the frames differ (the lamp
 * really moves). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/config.h"
#include "app/player.h"
#include "test_util.h"

enum { W = 48, H = 27 };

/* Frame n of cfg through the player (after frames 1..n-1). */
static int frame_of(const scene_config *cfg, double fps, int n, float *rgba) {
  fog_error err = {0};
  player *p = player_create(&(player_desc){.config = cfg, .width = W, .height = H, .fps = fps,
                                           .play = true, .synchronous = true},
                            &err);
  CHECK(p != NULL, "player: %s", err.message);
  if (!p) return 1;
  int status = 0;
  for (int k = 1; k <= n && !status; k++)
    status = player_frame(p, k, &(frame_pixels){.rgba = rgba}, &err);
  CHECK(status == 0, "frame %d: %s", n, err.message);
  player_destroy(p);
  return status;
}

/* cfg with every lamp standing where and as bright as it is at `time`. */
static scene_config still_at(const scene_config *cfg, double time) {
  scene_config still = *cfg;
  fog_lamps at = scene_config_fog_lamps_at(cfg, time);
  for (int i = 0; i < cfg->lamp_count; i++) {
    scene_lamp_config *l = &still.lamps[i];
    for (int a = 0; a < 3; a++) l->position[a] = at.lamp[i].position[a], l->colour[a] = at.lamp[i].intensity[a];
    l->key_count = 0;
    l->flicker_amount = 0;
  }
  return still;
}

static void check_path(const char *name, const scene_config *cfg, double fps, int frames) {
  static float moving[4 * W * H], still[4 * W * H], first[4 * W * H];
  int differ = 0;
  for (int n = 1; n <= frames; n++) {
    if (frame_of(cfg, fps, n, moving)) return;
    scene_config s = still_at(cfg, (n - 1) / fps);
    if (frame_of(&s, fps, n, still)) return;
    CHECK(!memcmp(moving, still, sizeof moving),
          "%s frame %d: differs from the lamps standing still at t = %g", name, n, (n - 1) / fps);
    if (n == 1) memcpy(first, moving, sizeof first);
    else differ += memcmp(first, moving, sizeof first) != 0;
  }
  CHECK(differ == frames - 1, "%s: only %d of %d frames differ from the first: the lamps do not move",
        name, differ, frames - 1);
  printf("%s: %d frames equal to the lamps standing still at their times\n", name, frames);
}

int main(void) {
  const char *ini = "/tmp/fogpipe_lamp_animation.ini";
  test_write_text(ini,
             "[camera]\nposition = 0 20 120\nlook_at = 0 10 0\nfov = 60\n"
             "[fog]\nmodel = homogeneous\ndensity_scale = 0.01\nalbedo = 0.9\nphase_g = 0.3\n"
             "colour = 0 0 0\n"
             "[light]\nsun_colour = 0.01 0.01 0.01\n"
             "lamp = -40 10 0 3000 2500 2000\n"
             "spot = 0 40 0 20000 20000 20000 0 -1 0 10 25\n"
             "lamp_path = 1 0 -40 10 0\nlamp_path = 1 1 40 10 0\nlamp_path = 1 2 40 30 20\n"
             "lamp_flicker = 2 0.6 3 7\n");
  scene_config cfg;
  fog_error err = {0};
  CHECK(scene_config_load(ini, &cfg, &err) == 0, "%s", err.message);
  CHECK(scene_config_lamps_animated(&cfg), "the lamps should animate");
  /* the keys exactly, linear between, held past the ends; the flicker within its amount */
  fog_lamps a = scene_config_fog_lamps_at(&cfg, 0.5), b = scene_config_fog_lamps_at(&cfg, 2.0),
            c = scene_config_fog_lamps_at(&cfg, 7.0), z = scene_config_fog_lamps_at(&cfg, -3.0);
  CHECK(a.lamp[0].position[0] == 0.0 && a.lamp[0].position[1] == 10.0, "t 0.5: x %g", a.lamp[0].position[0]);
  CHECK(b.lamp[0].position[0] == 40 && b.lamp[0].position[1] == 30 && b.lamp[0].position[2] == 20 &&
            c.lamp[0].position[1] == 30 && z.lamp[0].position[0] == -40,
        "keys and ends: (%g %g %g), held %g, before %g", b.lamp[0].position[0], b.lamp[0].position[1],
        b.lamp[0].position[2], c.lamp[0].position[1], z.lamp[0].position[0]);
  double lo = 1e30, hi = 0;
  for (int k = 0; k < 200; k++) {
    double v = scene_config_fog_lamps_at(&cfg, 0.05 * k).lamp[1].intensity[0] / 20000.0;
    lo = fmin(lo, v), hi = fmax(hi, v);
  }
  CHECK(lo >= 0.4 - 1e-12 && hi <= 1.0 && hi - lo > 0.2, "flicker factor %g..%g, expected in [0.4, 1]", lo, hi);
  check_path("render session (homogeneous)", &cfg, 2.0, 3);

  /* The pipeline: the ground fog simulated (the tests run from the source tree). */
  char cwd[512], text[2048];
  CHECK(getcwd(cwd, sizeof cwd) != NULL, "getcwd");
  snprintf(text, sizeof text,
             "[camera]\nposition = 0 60 200\nlook_at = 0 10 0\nfov = 60\n"
             "[fog]\nfogmap = %s/data/fogmap_groundfog.exr\ndensity_scale = 0.05\n"
             "albedo = 0.9\nphase_g = 0.3\ncolour = 0 0 0\nlevels = 1\n"
             "[box]\norigin = -64 -64\ncell_size = 1\nfloor = 0\ntop = 40\n"
             "[light]\nsun_colour = 0.01 0.01 0.01\n"
             "lamp = -30 10 0 3000 2500 2000\nlamp_path = 1 0 -30 10 0\nlamp_path = 1 1 30 10 0\n",
             cwd);
  test_write_text(ini, text);
  CHECK(scene_config_load(ini, &cfg, &err) == 0, "%s", err.message);
  /* at 24 fps, where the pipeline's (n - 1) x (1/fps) and (n - 1) / fps differ in their
   * last bit from frame 6 on (the frames still agree: the lamps reach the GPU as floats) */
  check_path("pipeline (fogmap)", &cfg, 24.0, 7);
  remove(ini);
  return test_finish("test_lamp_animation");
}
