/* The views of a fit and the rungs' errors on them (app/fit_views.h). */
#include "app/fit_views.h"

#include "render/fog_sun_shadow.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
  free(v->origin), free(v->dir), free(v->length), free(v->reference), free(v->light);
  *v = (fit_views){0};
}

int fit_views_create(fit_views *v, const fog_model *reference, const double lo[3],
                     const double hi[3], int rays_per_side, fog_error *err) {
  *v = (fit_views){0};
  const size_t most = (size_t)FIT_VIEW_COUNT * rays_per_side * rays_per_side;
  v->origin = malloc(most * sizeof *v->origin);
  v->dir = malloc(most * sizeof *v->dir);
  v->length = malloc(most * sizeof *v->length);
  v->reference = malloc(most * sizeof *v->reference);
  if (!v->origin || !v->dir || !v->length || !v->reference) {
    fit_views_destroy(v);
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for %zu rays of the fit's views",
                    most);
  }
  const double half = tan(PI / 6.0); /* 60 degrees across */
  fog_model ref = *reference; /* a classic factor's eye: each view's camera */
  for (int view = 0; view < FIT_VIEW_COUNT; view++) {
    double o[3], target[3], f[3], r[3], u[3];
    fit_view_pose(lo, hi, view, o, target);
    memcpy(ref.eye, o, sizeof ref.eye);
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
        v->reference[k] = exp(-fog_model_optical_depth(&ref, o, d, exit));
      }
  }
  return 0;
}

void fit_views_measure(const fit_views *v, const fog_model *rung, double *max_error,
                       double *mean_error) {
  double worst = 0.0, sum = 0.0;
  fog_model m = *rung;
  const bool radial = fog_model_about_eye(&m);
  for (int k = 0; k < v->count; k++) {
    if (radial) memcpy(m.eye, v->origin[k], sizeof m.eye); /* the view's camera */
    double tau = exp(-fog_model_optical_depth(&m, v->origin[k], v->dir[k], v->length[k]));
    double e = fabs(tau - v->reference[k]);
    /* NaN sticks (a NaN worst is not <= e either: the next ray overwrote it) */
    if (!isnan(worst) && !(e <= worst)) worst = e;
    sum += e;
  }
  *max_error = worst;
  *mean_error = v->count ? sum / v->count : 0.0;
}

/* The worst |delta tau| of a classic factor f(L) over the views' rays (from their cameras). */
static double classic_error(const fit_views *v, int count, bool linear, double p, double q) {
  double worst = 0.0;
  for (int f = 0; f < count; f++)
    for (int k = 0; k < v[f].count; k++) {
      double L = v[f].length[k], tau;
      if (linear)
        tau = L <= p ? 1.0 : (L >= q ? 0.0 : (q - L) / (q - p));
      else
        tau = exp(-(p * L) * (p * L));
      worst = fmax(worst, fabs(tau - v[f].reference[k]));
    }
  return worst;
}

double fit_views_exp2(const fit_views *v, int count) {
  /* least squares of (a L)^2 on the depth (capped at 20: e^-20 is opaque) */
  double dl2 = 0.0, l4 = 0.0;
  for (int f = 0; f < count; f++)
    for (int k = 0; k < v[f].count; k++) {
      double L = v[f].length[k], D = fmin(-log(fmax(v[f].reference[k], 1e-300)), 20.0);
      dl2 += D * L * L, l4 += L * L * L * L;
    }
  if (!(dl2 > 0.0 && l4 > 0.0)) return 0.0;
  double a0 = sqrt(dl2 / l4), best = a0, best_error = HUGE_VAL;
  for (int i = -100; i <= 100; i++) { /* a0 x 10^(i/100): a decade either way */
    double a = a0 * pow(10.0, i / 100.0), e = classic_error(v, count, false, a, 0.0);
    if (e < best_error) best_error = e, best = a;
  }
  return best;
}

void fit_views_linear(const fit_views *v, int count, double *start, double *end) {
  double longest = 0.0;
  for (int f = 0; f < count; f++)
    for (int k = 0; k < v[f].count; k++) longest = fmax(longest, v[f].length[k]);
  double best_error = HUGE_VAL;
  *start = 0.0, *end = 2.0 * longest;
  for (int i = 0; i < 48; i++) {
    double s = longest * i / 48.0;
    for (int j = -40; j <= 24; j++) { /* end - start from longest/32 to 8 longest */
      double e = s + longest * pow(2.0, j / 8.0), error = classic_error(v, count, true, s, e);
      if (error < best_error) best_error = error, *start = s, *end = e;
    }
  }
  /* then a pattern search from the grid's best: each step tried both ways on each of the
   * two, halved when neither helps */
  double step[2] = {longest / 48.0, (*end - *start) * (pow(2.0, 1.0 / 8.0) - 1.0)};
  for (int round = 0; round < 200 && (step[0] > 1e-9 * longest || step[1] > 1e-9 * longest);
       round++) {
    bool moved = false;
    for (int which = 0; which < 2; which++)
      for (int sign = -1; sign <= 1; sign += 2) {
        double s = *start + (which == 0 ? sign * step[0] : 0.0);
        double e = *end + (which == 1 ? sign * step[1] : 0.0);
        if (!(s >= 0.0 && e > s)) continue;
        double error = classic_error(v, count, true, s, e);
        if (error < best_error) best_error = error, *start = s, *end = e, moved = true;
      }
    if (!moved) step[0] *= 0.5, step[1] *= 0.5;
  }
}

/* Each ray's in-scattered luminance (fit_light) for model m into out. */
static int inscatter(const fit_views *v, const fog_model *model, const fit_light *light,
                     double *out, fog_error *err) {
  const fog_sun *sun = &light->sun;
  fog_sun_shadow volume = {0};
  fog_sun_shadow_kind kind =
      light->self_shadow ? fog_sun_shadow_kind_of(model, sun->direction) : FOG_SUN_SHADOW_NONE;
  if (kind == FOG_SUN_SHADOW_VOLUME &&
      (fog_sun_shadow_create(&volume, &(fog_sun_shadow_desc){.across = light->resolution,
                                                             .along = light->resolution},
                             err) ||
       fog_sun_shadow_compute(&volume, model, sun->direction, 2, err))) {
    fog_sun_shadow_destroy(&volume);
    return 1;
  }
  if (kind == FOG_SUN_SHADOW_HEIGHT) volume.sun[0] = sun->direction[0],
      volume.sun[1] = sun->direction[1], volume.sun[2] = sun->direction[2];
  const double ambient = (light->ambient[0] + light->ambient[1] + light->ambient[2]) / 3.0;
  /* the renderer's L_sun: none from below the horizon */
  const double lsun = (sun->radiance[0] + sun->radiance[1] + sun->radiance[2]) / 3.0 *
                      fog_sun_above_horizon(sun->direction);
  fog_model m = *model;
  const bool radial = fog_model_about_eye(&m);
  for (int k = 0; k < v->count; k++) {
    if (radial) memcpy(m.eye, v->origin[k], sizeof m.eye);
    const double *d = v->dir[k];
    double tau = exp(-fog_model_optical_depth(&m, v->origin[k], d, v->length[k]));
    double mean = sun->albedo > 0.0
                      ? fog_sun_mean_transmittance(&m, kind, &volume, light->rule, 30.0,
                                                   v->origin[k], d, v->length[k])
                      : 1.0;
    double cos_theta = d[0] * sun->direction[0] + d[1] * sun->direction[1] +
                       d[2] * sun->direction[2];
    out[k] = (ambient + sun->albedo * lsun * fog_phase_hg(sun->phase_g, cos_theta) * mean) *
             (1.0 - tau);
  }
  fog_sun_shadow_destroy(&volume);
  return 0;
}

int fit_views_light(fit_views *v, const fog_model *reference, const fit_light *light,
                    fog_error *err) {
  free(v->light);
  if (!(v->light = malloc((size_t)(v->count > 0 ? v->count : 1) * sizeof *v->light))) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    return 1;
  }
  return inscatter(v, reference, light, v->light, err);
}

int fit_views_measure_light(const fit_views *v, const fog_model *rung, const fit_light *light,
                            double *relative_error, fog_error *err) {
  double *mine = malloc((size_t)(v->count > 0 ? v->count : 1) * sizeof *mine);
  if (!mine) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    return 1;
  }
  if (inscatter(v, rung, light, mine, err)) {
    free(mine);
    return 1;
  }
  double worst = 0.0, brightest = 0.0;
  for (int k = 0; k < v->count; k++) {
    double e = fabs(mine[k] - v->light[k]);
    if (!isnan(worst) && !(e <= worst)) worst = e; /* NaN sticks */
    brightest = fmax(brightest, v->light[k]);
  }
  free(mine);
  *relative_error = brightest > 0.0 ? worst / brightest : worst;
  return 0;
}

int fit_views_rbf_amplitudes(const fit_views *v, int count, fog_rbf *g, int n) {
  /* min sum_rays w (sum_i c_i D_i - D_ref)^2, c >= 0: D_i the optical depth of Gaussian i
   * (density 1) along the ray, D_ref the reference's (capped at 10: opaque is opaque), w =
   * max(tau_ref, 0.05)^2 (a depth error moves tau by tau times it). */
  double *a = calloc((size_t)n * n, sizeof *a), *b = calloc((size_t)n, sizeof *b);
  double *depth = malloc((size_t)n * sizeof *depth);
  if (!a || !b || !depth) {
    free(a), free(b), free(depth);
    return 1;
  }
  for (int f = 0; f < count; f++)
    for (int k = 0; k < v[f].count; k++) {
      double tau = v[f].reference[k], target = fmin(-log(fmax(tau, 1e-300)), 10.0);
      double w = fmax(tau, 0.05) * fmax(tau, 0.05);
      for (int i = 0; i < n; i++) {
        fog_rbf one = g[i];
        one.density = 1.0;
        depth[i] = fog_rbf_optical_depth(0.0, &one, 1, v[f].origin[k], v[f].dir[k],
                                         v[f].length[k]);
      }
      for (int i = 0; i < n; i++) {
        if (depth[i] == 0.0) continue;
        b[i] += w * depth[i] * target;
        for (int j = 0; j < n; j++) a[(size_t)i * n + j] += w * depth[i] * depth[j];
      }
    }
  /* A Gaussian the views hardly see (its depth ~1e-80 along every ray: small and away from
   * them) has a diagonal ~1e-160, and one step of the solve would give it an amplitude of
   * ~1e80 that no view checks (and no config holds): it keeps the moments' amplitude. */
  double largest = 0.0;
  for (int i = 0; i < n; i++) largest = fmax(largest, a[(size_t)i * n + i]);
  const double seen = 1e-12 * largest;
  for (int sweep = 0; sweep < 500; sweep++) { /* projected Gauss-Seidel from the moments */
    double change = 0.0, size = 0.0;
    for (int i = 0; i < n; i++) {
      double diag = a[(size_t)i * n + i];
      if (!(diag > seen)) continue;
      double r = b[i];
      for (int j = 0; j < n; j++) r -= a[(size_t)i * n + j] * g[j].density;
      double next = fmax(0.0, g[i].density + r / diag);
      change = fmax(change, fabs(next - g[i].density)), size = fmax(size, next);
      g[i].density = next;
    }
    if (change <= 1e-12 * size) break;
  }
  free(a), free(b), free(depth);
  return 0;
}
