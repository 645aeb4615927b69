/* The live demo's model selector (app/live_rung.h). */
#include "app/live_rung.h"

#include <math.h>

#include "app/fit_density.h"

const char *const live_rung_names[LIVE_RUNG_COUNT] = {
    "simulated fogmap (exact)", "homogeneous, fitted live", "height fog, fitted live",
    "16 Gaussians, fitted live", "4 ellipsoids, fitted live"};

bool live_rung_bounded(live_rung_kind kind) {
  return kind == LIVE_RUNG_GAUSSIANS || kind == LIVE_RUNG_ELLIPSOIDS;
}

fog_model live_rung_model(const live_rung *r) {
  fog_model m = r->model;
  if (m.kind == FOG_MODEL_RBF) m.rbfs = r->rbfs;
  if (m.kind == FOG_MODEL_QUADRIC) m.quadrics = r->quadrics;
  return m;
}

fog_model live_rung_with_beside(const fog_model *rung, const fog_quadric *beside, int count,
                                fog_quadric out[FOG_MAX_QUADRICS]) {
  fog_model m = *rung;
  if (m.kind != FOG_MODEL_QUADRIC) return m;
  int n = 0;
  for (int i = 0; i < rung->quadric_count && n < FOG_MAX_QUADRICS; i++)
    out[n++] = rung->quadrics[i];
  for (int i = 0; i < count && n < FOG_MAX_QUADRICS; i++) out[n++] = beside[i];
  m.quadrics = out, m.quadric_count = n;
  return m;
}

/* Gaussians or ellipsoids; false: none fitted (no fog, or out of memory). */
static bool fit_shapes(const fit_samples *s, live_rung *out) {
  if (out->kind == LIVE_RUNG_GAUSSIANS) {
    const int n = fit_rbfs(s, LIVE_RUNG_GAUSSIAN_COUNT, out->rbfs);
    out->model = (fog_model){.kind = FOG_MODEL_RBF, .extinction = 0.0,
                             .rbf_count = n > 0 ? n : 0};
    return n > 0;
  }
  const int n = fit_ellipsoids(s, LIVE_RUNG_ELLIPSOID_COUNT, out->quadrics);
  out->model = (fog_model){.kind = FOG_MODEL_QUADRIC, .quadric_count = n > 0 ? n : 0};
  return n > 0;
}

void live_rung_fit(const fog_model *fogmap, live_rung_kind kind, live_rung *out) {
  *out = (live_rung){.kind = kind, .max_error = NAN, .mean_error = NAN};
  double lo[3], hi[3];
  fit_samples s;
  fog_error unused; /* out of memory leaves the rung unfitted, as its result says */
  /* 24 x 24 across, 16 layers: a ground fog is thin beside its footprint */
  if (kind == LIVE_RUNG_FOGMAP || !fog_model_bounds(fogmap, lo, hi) ||
      fit_samples_create_grid(&s, fogmap, lo, hi, (const int[3]){24, 16, 24}, &unused))
    return;
  if (live_rung_bounded(kind)) {
    out->fitted = fit_shapes(&s, out);
    fit_samples_destroy(&s);
    return;
  }
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
  const fog_model model = live_rung_model(out);
  for (int j = 0; j < LIVE_RUNG_ROWS; j++)
    for (int i = 0; i < LIVE_RUNG_COLUMNS; i++) {
      const int px = (int)((i + 0.5) * width / LIVE_RUNG_COLUMNS);
      const int py = (int)((j + 0.5) * height / LIVE_RUNG_ROWS);
      double o[3], d[3];
      camera_ray(cam, px, py, width, height, o, d);
      const float t = depth[(size_t)py * width + px];
      const double length = t < 1e29f ? t : HUGE_VAL;
      double e = fabs(exp(-fog_model_optical_depth(&model, o, d, length)) -
                      exp(-fog_model_optical_depth(fogmap, o, d, length)));
      worst = fmax(worst, e), sum += e, rays++;
    }
  out->max_error = worst;
  out->mean_error = sum / rays;
  out->rays = rays;
}
