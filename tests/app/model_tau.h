/* A frame's transmittance against a CPU fog_model, pixel by pixel: exp(-fog_model_optical_
 * depth) along each pixel's ray (camera_ray, rows top first) to the frame's depth, to
 * infinity where the depth is the far plane's (the sky); and a config's frame against its
 * render session's twin. Header-only. */
#ifndef FOGPIPE_TESTS_APP_MODEL_TAU_H
#define FOGPIPE_TESTS_APP_MODEL_TAU_H

#include <math.h>
#include <stdlib.h>

#include "app/config.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "render/render.h"
#include "test_util.h"

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

/* The config `text`, written to `path`, rendered at width x height through a render
 * session (`render`'s frame path) and compared with the session's own CPU twin
 * (render_fog_model). 0 with *e set; 1 with err set. */
static inline int model_tau_of_config(const char *path, const char *text, int width,
                                      int height, model_tau_error *e, fog_error *err) {
  scene_config cfg;
  if (!test_write_text(path, text)) return fog_fail(err, FOG_ERR_FILE_ACCESS, "cannot write %s", path);
  if (scene_config_load(path, &cfg, err)) return 1;
  render_session *s = render_session_create(&cfg, width, height, err);
  if (!s) return 1;
  float *tau = malloc(sizeof(float) * (size_t)width * height),
        *depth = malloc(sizeof(float) * (size_t)width * height);
  int status = !tau || !depth ? fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory")
               : render_session_frame(s, &(frame_pixels){.transmittance = tau, .depth = depth},
                                      err);
  if (!status) {
    const fog_model m = render_fog_model(render_session_fog(s));
    camera cam;
    scene_config_camera(&cfg, &cam);
    *e = model_tau_compare(&m, &cam, tau, depth, width, height);
  }
  free(tau), free(depth);
  render_session_destroy(s);
  return status;
}

#endif
