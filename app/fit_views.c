/* The views of a fit and the rungs' errors on them (app/fit_views.h). */
#include "app/fit_views.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846

void fit_view_pose(const double lo[3], const double hi[3], int index, double position[3],
                   double target[3]) {
  double c[3], s[3];
  for (int a = 0; a < 3; a++) c[a] = 0.5 * (lo[a] + hi[a]), s[a] = hi[a] - lo[a];
  const double reach = 0.5 * hypot(s[0], s[2]);
  for (int a = 0; a < 3; a++) position[a] = c[a], target[a] = c[a];
  if (index < 4) { /* around, at mid height, 1.3 half-diagonals out */
    double az = (30.0 + 90.0 * index) * PI / 180.0;
    position[0] = c[0] + 1.3 * reach * sin(az), position[2] = c[2] + 1.3 * reach * cos(az);
  } else if (index < 6) { /* above, looking down at the centre */
    double az = (75.0 + 180.0 * (index - 4)) * PI / 180.0;
    position[0] = c[0] + reach * sin(az), position[2] = c[2] + reach * cos(az);
    position[1] = hi[1] + fmax(s[1], 0.5 * reach);
  } else if (index < 8) { /* inside, looking across */
    target[index == 6 ? 0 : 2] += reach;
  } else { /* inside, from near the floor looking up at 30 degrees */
    position[1] = lo[1] + 0.05 * s[1];
    target[1] = position[1] + 0.5 * reach * tan(PI / 6.0);
    target[2] -= 0.5 * reach;
  }
}

/* The ray's parameter where it leaves the box, or -1 where it misses it. */
static double box_exit(const double o[3], const double d[3], const double lo[3],
                       const double hi[3]) {
  double t0 = 0.0, t1 = HUGE_VAL;
  for (int a = 0; a < 3; a++) {
    if (d[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return -1.0;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    t0 = fmax(t0, fmin(ta, tb)), t1 = fmin(t1, fmax(ta, tb));
  }
  return t1 > t0 ? t1 : -1.0;
}

void fit_views_destroy(fit_views *v) {
  free(v->origin), free(v->dir), free(v->length), free(v->reference);
  *v = (fit_views){0};
}

int fit_views_create(fit_views *v, const fog_model *reference, const double lo[3],
                     const double hi[3], int rays_per_side) {
  *v = (fit_views){0};
  const size_t most = (size_t)FIT_VIEW_COUNT * rays_per_side * rays_per_side;
  v->origin = malloc(most * sizeof *v->origin);
  v->dir = malloc(most * sizeof *v->dir);
  v->length = malloc(most * sizeof *v->length);
  v->reference = malloc(most * sizeof *v->reference);
  if (!v->origin || !v->dir || !v->length || !v->reference) {
    fit_views_destroy(v);
    return 1;
  }
  const double half = tan(PI / 6.0); /* 60 degrees across */
  for (int view = 0; view < FIT_VIEW_COUNT; view++) {
    double o[3], target[3], f[3], r[3], u[3];
    fit_view_pose(lo, hi, view, o, target);
    for (int a = 0; a < 3; a++) f[a] = target[a] - o[a];
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int a = 0; a < 3; a++) f[a] /= fl;
    /* right = forward x up(0, 1, 0); up = right x forward */
    r[0] = -f[2], r[1] = 0.0, r[2] = f[0];
    double rl = hypot(r[0], r[2]);
    if (!(rl > 1e-9)) r[0] = 1.0, r[2] = 0.0, rl = 1.0;
    for (int a = 0; a < 3; a++) r[a] /= rl;
    u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2],
    u[2] = r[0] * f[1] - r[1] * f[0];
    for (int py = 0; py < rays_per_side; py++)
      for (int px = 0; px < rays_per_side; px++) {
        double x = (2.0 * (px + 0.5) / rays_per_side - 1.0) * half;
        double y = (1.0 - 2.0 * (py + 0.5) / rays_per_side) * half, d[3];
        for (int a = 0; a < 3; a++) d[a] = f[a] + x * r[a] + y * u[a];
        double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int a = 0; a < 3; a++) d[a] /= dl;
        double exit = box_exit(o, d, lo, hi);
        if (!(exit > 0.0)) continue;
        int k = v->count++;
        for (int a = 0; a < 3; a++) v->origin[k][a] = o[a], v->dir[k][a] = d[a];
        v->length[k] = exit;
        v->reference[k] = exp(-fog_model_optical_depth(reference, o, d, exit));
      }
  }
  return 0;
}

void fit_views_measure(const fit_views *v, const fog_model *rung, double *max_error,
                       double *mean_error) {
  double worst = 0.0, sum = 0.0;
  for (int k = 0; k < v->count; k++) {
    double tau = exp(-fog_model_optical_depth(rung, v->origin[k], v->dir[k], v->length[k]));
    double e = fabs(tau - v->reference[k]);
    if (!(e <= worst)) worst = e; /* NaN sticks */
    sum += e;
  }
  *max_error = worst;
  *mean_error = v->count ? sum / v->count : 0.0;
}
