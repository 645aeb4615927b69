/* A frame's transmittance against a CPU fog_model, pixel by pixel: exp(-fog_model_optical_
 * depth) along each pixel's ray (camera_ray, rows top first) to the frame's depth, to
 * infinity where the depth is the far plane's (the sky). Header-only. */
#ifndef FOGPIPE_TESTS_APP_MODEL_TAU_H
#define FOGPIPE_TESTS_APP_MODEL_TAU_H

#include <math.h>

#include "render/render.h"

typedef struct model_tau_error {
  double worst;          /* max |tau_model - tau_frame|; NaN if any pixel is NaN */
  double lowest, highest; /* the model's tau over the frame */
} model_tau_error;

static inline model_tau_error model_tau_compare(const fog_model *m, const camera *cam,
                                                const float *tau, const float *depth, int width,
                                                int height) {
  model_tau_error r = {.worst = 0.0, .lowest = 1.0, .highest = 0.0};
  for (int py = 0; py < height; py++)
    for (int px = 0; px < width; px++) {
      double o[3], d[3];
      camera_ray(cam, px, py, width, height, o, d);
      const double t = depth[py * width + px];
      const double length = t >= 0.999 * cam->far_plane ? HUGE_VAL : t;
      const double want = fog_transmittance(fog_model_optical_depth(m, o, d, length));
      const double e = fabs(want - tau[py * width + px]);
      if (!(e <= r.worst)) r.worst = e; /* NaN sticks */
      r.lowest = fmin(r.lowest, want), r.highest = fmax(r.highest, want);
    }
  return r;
}

#endif
