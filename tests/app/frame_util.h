/* A W x H frame of `fogpipe render`'s frame path (app/render_frame.h) for the light tests:
 * colour, transmittance, depth and in-scatter, and render() to fill one from a config.
 * Header-only; include it after the test's `enum { W = ..., H = ... };`. */
#ifndef FOGPIPE_TESTS_APP_FRAME_UTIL_H
#define FOGPIPE_TESTS_APP_FRAME_UTIL_H

#include <math.h>

#include "app/config.h"
#include "app/render_frame.h"
#include "render/render.h"
#include "test_util.h"

typedef struct frame {
  float rgba[4 * W * H], tau[W * H], depth[W * H], inscatter[3 * W * H];
} frame;

/* Renders cfg into f, CHECKing the result (label names it); non-zero on failure. */
static inline int render(const scene_config *cfg, frame *f, const char *label) {
  render_frame_info info;
  fog_error err = {0};
  const frame_pixels out = {.rgba = f->rgba, .transmittance = f->tau, .depth = f->depth,
                            .inscatter = f->inscatter};
  const int failed = render_frame(cfg, W, H, &out, &info, &err);
  CHECK(!failed, "%s: %s", label, err.message);
  return failed;
}

/* Pixel (px, py)'s ray under cam (rows top first) and its surface distance in f: HUGE_VAL
 * where f's depth is the far plane's (the sky). */
static inline double frame_pixel_ray(const frame *f, const camera *cam, int px, int py,
                                     double o[3], double d[3]) {
  camera_ray(cam, px, py, W, H, o, d);
  const double t = f->depth[py * W + px];
  return t >= 0.999 * cam->far_plane ? HUGE_VAL : t;
}

#endif
