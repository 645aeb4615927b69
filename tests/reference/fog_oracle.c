/* The independent reference for the exact integrator: adaptive Gauss-Kronrod (G7K15) on
 * the extinction evaluated pointwise by brute-force B-spline sums. It shares nothing with
 * fog_integral_cpu.c but the struct definitions: no knot cells, no DDA, no cell weights;
 * B-splines come from the truncated-power formula, the box from its own slab test, the
 * split points from enumerating the B-spline supports' ends in world coordinates (adaptive
 * quadrature alone cannot be trusted across a jump or kink that falls between its nodes:
 * it then reports a tiny error and is wrong by 1e-4; measured). */
#include <math.h>
#include <stdlib.h>

#include "reference/fog_oracle.h"

/* Centred B-spline of degree d: phi_d(x) = 1/d! sum_{k=0}^{d+1} (-1)^k C(d+1,k)
 * (x + (d+1)/2 - k)_+^d (de Boor, A Practical Guide to Splines, ch. IX). */
static double oracle_bspline(int d, double x) {
  static const double binom[5][5] = {
      {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};
  static const double factorial[4] = {1, 1, 2, 6};
  if (fabs(x) >= 0.5 * (d + 1)) return 0.0;
  double sum = 0.0;
  for (int k = 0; k <= d + 1; k++) {
    double y = x + 0.5 * (d + 1) - k;
    if (y <= 0.0) continue;
    double power = 1.0; /* y^d by products: pow() was most of the oracle's time */
    for (int e = 0; e < d; e++) power *= y;
    sum += ((k % 2) ? -1.0 : 1.0) * binom[d + 1][k] * power;
  }
  return sum / factorial[d];
}

/* f(u, v) = sum_ij c_ij phi_d((u - origin_u)/spacing - i) phi_d((v - origin_v)/spacing - j),
 * summed over every coefficient within the support radius. */
static double oracle_grid_value(const transform_grid *g, double u, double v) {
  double x = (u - g->origin_u) / g->spacing, z = (v - g->origin_v) / g->spacing;
  double r = 0.5 * (g->degree + 1);
  int i_lo = (int)ceil(x - r), i_hi = (int)floor(x + r);
  int j_lo = (int)ceil(z - r), j_hi = (int)floor(z + r);
  double wx[5], sum = 0.0; /* at most d + 2 <= 5 columns: their weights once, not per row */
  for (int i = i_lo; i <= i_hi; i++) wx[i - i_lo] = oracle_bspline(g->degree, x - i);
  for (int j = j_lo; j <= j_hi; j++) {
    if (j < 0 || j >= g->height) continue;
    double wz = oracle_bspline(g->degree, z - j);
    for (int i = i_lo; i <= i_hi; i++) {
      if (i < 0 || i >= g->width) continue;
      sum += wz * wx[i - i_lo] * g->coefficients[(size_t)j * g->width + i];
    }
  }
  return sum;
}

static double oracle_profile_value(const fog_profile *p, double y) {
  switch (p->kind) {
    case FOG_PROFILE_SLAB:
      return (y >= p->y_floor && y <= p->y_top) ? 1.0 : 0.0;
    case FOG_PROFILE_EXPONENTIAL:
      if (y < p->y_floor || y > p->y_top) return 0.0;
      return y <= p->y0 ? 1.0 : exp(-(y - p->y0) / p->scale_height);
    default: {
      double x = (y - p->origin) / p->spacing, sum = 0.0;
      for (int k = 0; k < p->count; k++) sum += p->coefficients[k] * oracle_bspline(p->degree, x - k);
      return sum;
    }
  }
}

typedef struct oracle_ray {
  const fog_volume *volume;
  const transform_grid *grid;
  const double *camera, *dir;
  double h, box_lo[3], box_hi[3]; /* world box */
} oracle_ray;

/* K at parameter t; zero outside the box (the box edges are split points, so the value
 * exactly on an edge never matters). */
static double oracle_extinction(const oracle_ray *r, double t) {
  double p[3];
  for (int a = 0; a < 3; a++) {
    p[a] = r->camera[a] + t * r->dir[a];
    if (p[a] < r->box_lo[a] || p[a] > r->box_hi[a]) return 0.0;
  }
  double u = (p[0] - r->volume->origin_x) / r->h - 0.5;
  double v = (p[2] - r->volume->origin_z) / r->h - 0.5;
  double e = r->volume->extinction;
  return e * oracle_grid_value(r->grid, u, v) * oracle_profile_value(&r->volume->profile, p[1]);
}

#include "reference/gauss_kronrod.h"

static double oracle_gk15(const oracle_ray *r, double a, double b, double *err) {
  double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double fc = oracle_extinction(r, c);
  double k = wgk[7] * fc, g = wg[3] * fc;
  for (int i = 0; i < 7; i++) {
    double f1 = oracle_extinction(r, c - h * xgk[i]), f2 = oracle_extinction(r, c + h * xgk[i]);
    k += wgk[i] * (f1 + f2);
    if (i % 2 == 1) g += wg[i / 2] * (f1 + f2);
  }
  *err = fabs((k - g) * h);
  return k * h;
}

/* Recursive bisection with a tolerance proportional to the interval's length, down to a
 * floor of 1e-14 of the whole range (what is left there is a jump of a degree-0 grid, whose
 * error is then below tolerance-scale: extinction * 1e-14 * length). */
static double oracle_adapt(const oracle_ray *r, double a, double b, double whole, double tol,
                           double *err_sum, int depth) {
  double err, val = oracle_gk15(r, a, b, &err);
  if (err <= tol * (b - a) / whole || (b - a) <= 1e-14 * whole || depth > 200) {
    *err_sum += err;
    return val;
  }
  double m = 0.5 * (a + b);
  return oracle_adapt(r, a, m, whole, tol, err_sum, depth + 1) +
         oracle_adapt(r, m, b, whole, tol, err_sum, depth + 1);
}

static int oracle_compare(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Appends the parameters in (lo, hi) where coordinate c(t) = c0 + t dc crosses
 * base + step * (n + (degree+1)/2) for integer n: the ends of the B-spline supports
 * phi_d((c - base)/step - i), i.e. where the piecewise polynomial may break. Enumerated
 * directly from the support formula (not from knot cells). */
static int oracle_add_breaks(double **splits, int *count, int *capacity, double c0, double dc,
                             double base, double step, int degree, double lo, double hi) {
  if (dc == 0.0) return 0;
  double a = (c0 + lo * dc - base) / step - 0.5 * (degree + 1);
  double b = (c0 + hi * dc - base) / step - 0.5 * (degree + 1);
  if (a > b) {
    double s = a;
    a = b;
    b = s;
  }
  for (double n = ceil(a); n <= b; n += 1.0) {
    double t = (base + step * (n + 0.5 * (degree + 1)) - c0) / dc;
    if (!(t > lo && t < hi)) continue;
    if (*count == *capacity) {
      *capacity = 2 * *capacity + 16;
      double *grown = realloc(*splits, (size_t)*capacity * sizeof **splits);
      if (!grown) return 1;
      *splits = grown;
    }
    (*splits)[(*count)++] = t;
  }
  return 0;
}

/* The box from the placement (fog_field.h): x, z from the corner and W x H cells of
 * cell_size; y the profile's support. */
void fog_box_oracle(const fog_volume *volume, double box_lo[3], double box_hi[3]) {
  const fog_profile *p = &volume->profile;
  double h = volume->cell_size;
  box_lo[0] = volume->origin_x;
  box_hi[0] = volume->origin_x + volume->map_width * h;
  box_lo[2] = volume->origin_z;
  box_hi[2] = volume->origin_z + volume->map_height * h;
  if (p->kind == FOG_PROFILE_BSPLINE) {
    box_lo[1] = p->origin - 0.5 * (p->degree + 1) * p->spacing;
    box_hi[1] = p->origin + (p->count - 1 + 0.5 * (p->degree + 1)) * p->spacing;
  } else {
    box_lo[1] = p->y_floor;
    box_hi[1] = p->y_top;
  }
}

double fog_extinction_oracle(const fog_volume *volume, const transform_grid *grid,
                             const double p[3]) {
  double lo[3], hi[3];
  fog_box_oracle(volume, lo, hi);
  for (int a = 0; a < 3; a++)
    if (p[a] < lo[a] || p[a] > hi[a]) return 0.0;
  double u = (p[0] - volume->origin_x) / volume->cell_size - 0.5;
  double v = (p[2] - volume->origin_z) / volume->cell_size - 0.5;
  return volume->extinction * oracle_grid_value(grid, u, v) *
         oracle_profile_value(&volume->profile, p[1]);
}

double fog_optical_depth_oracle(const fog_volume *volume, const transform_grid *grid,
                                const double camera[3], const double dir[3], double t_start,
                                double t_stop, double tolerance, double *error_estimate) {
  oracle_ray r = {.volume = volume, .grid = grid, .camera = camera, .dir = dir,
                  .h = volume->cell_size};
  const fog_profile *p = &volume->profile;
  fog_box_oracle(volume, r.box_lo, r.box_hi);
  /* Split points: the box planes and the profile's discontinuities, within [start, stop]. */
  double lo = t_start, hi = t_stop;
  for (int a = 0; a < 3; a++) {
    if (dir[a] == 0.0) {
      if (camera[a] < r.box_lo[a] || camera[a] > r.box_hi[a]) lo = hi; /* misses */
      continue;
    }
    double ta = (r.box_lo[a] - camera[a]) / dir[a], tb = (r.box_hi[a] - camera[a]) / dir[a];
    if (ta > tb) {
      double s = ta;
      ta = tb;
      tb = s;
    }
    if (ta > lo) lo = ta;
    if (tb < hi) hi = tb;
  }
  if (error_estimate) *error_estimate = 0.0;
  if (!(lo < hi)) return 0.0;
  int n = 0, capacity = 64;
  double *splits = malloc((size_t)capacity * sizeof *splits);
  if (!splits) return NAN;
  splits[n++] = lo;
  splits[n++] = hi;
  if (p->kind == FOG_PROFILE_EXPONENTIAL && dir[1] != 0.0) {
    double t = (p->y0 - camera[1]) / dir[1];
    if (t > lo && t < hi) splits[n++] = t;
  }
  /* Where the pieces of f and of a B-spline profile join: u = (X - origin_x)/h - 1/2, so
   * X = origin_x + h (1/2 + origin_u + spacing * x). */
  int failed =
      oracle_add_breaks(&splits, &n, &capacity, camera[0], dir[0],
                        volume->origin_x + r.h * (0.5 + grid->origin_u), r.h * grid->spacing,
                        grid->degree, lo, hi) ||
      oracle_add_breaks(&splits, &n, &capacity, camera[2], dir[2],
                        volume->origin_z + r.h * (0.5 + grid->origin_v), r.h * grid->spacing,
                        grid->degree, lo, hi) ||
      (p->kind == FOG_PROFILE_BSPLINE &&
       oracle_add_breaks(&splits, &n, &capacity, camera[1], dir[1], p->origin, p->spacing,
                         p->degree, lo, hi));
  if (failed) {
    free(splits);
    return NAN;
  }
  qsort(splits, (size_t)n, sizeof *splits, oracle_compare);
  double sum = 0.0, err = 0.0, whole = hi - lo;
  for (int i = 0; i + 1 < n; i++)
    if (splits[i + 1] > splits[i])
      sum += oracle_adapt(&r, splits[i], splits[i + 1], whole, tolerance, &err, 0);
  free(splits);
  if (error_estimate) *error_estimate = err;
  return sum;
}
