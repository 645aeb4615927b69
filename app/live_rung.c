/* The live demo's model selector (app/live_rung.h). */
#include "app/live_rung.h"

#include <math.h>

#include "app/fit_density.h"

const char *const live_rung_names[LIVE_RUNG_COUNT] = {
    "simulated fogmap (exact)", "homogeneous, fitted live", "height fog, fitted live"};

void live_rung_fit(const fog_model *fogmap, live_rung_kind kind, live_rung *out) {
  *out = (live_rung){.kind = kind, .max_error = NAN, .mean_error = NAN};
  double lo[3], hi[3];
  fit_samples s;
  /* 24 x 24 across, 16 layers: a ground fog is thin beside its footprint */
  if (kind == LIVE_RUNG_FOGMAP || !fog_model_bounds(fogmap, lo, hi) ||
      fit_samples_create_grid(&s, fogmap, lo, hi, (const int[3]){24, 16, 24}))
    return;
  double k = fit_homogeneous(&s), y0 = 0.0, scale_height = 1.0;
  out->fitted = k > 0.0;
  if (kind == LIVE_RUNG_HEIGHT && fit_height(&s, &k, &y0, &scale_height))
    out->model = (fog_model){.kind = FOG_MODEL_HEIGHT, .extinction = k, .y0 = y0,
                             .scale_height = scale_height};
  else
    out->model = (fog_model){.kind = FOG_MODEL_HOMOGENEOUS, .extinction = k};
  fit_samples_destroy(&s);
}

void live_rung_measure(const fog_model *fogmap, const camera *cam, int width, int height,
                       const float *depth, live_rung *out) {
  double worst = 0.0, sum = 0.0;
  int rays = 0;
  for (int j = 0; j < LIVE_RUNG_ROWS; j++)
    for (int i = 0; i < LIVE_RUNG_COLUMNS; i++) {
      const int px = (int)((i + 0.5) * width / LIVE_RUNG_COLUMNS);
      const int py = (int)((j + 0.5) * height / LIVE_RUNG_ROWS);
      double o[3], d[3];
      camera_ray(cam, px, py, width, height, o, d);
      const float t = depth[(size_t)py * width + px];
      const double length = t < 1e29f ? t : HUGE_VAL;
      double e = fabs(exp(-fog_model_optical_depth(&out->model, o, d, length)) -
                      exp(-fog_model_optical_depth(fogmap, o, d, length)));
      worst = fmax(worst, e), sum += e, rays++;
    }
  out->max_error = worst;
  out->mean_error = sum / rays;
  out->rays = rays;
}
