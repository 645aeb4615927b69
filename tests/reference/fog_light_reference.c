/* Single scattering of sunlight, the test reference (fog_light_reference.h): adaptive G7K15
 * on the pointwise density, the ray cut first at the medium's box, cut and breaks.
 *
 * S = int tau(u) K(u) T_s(u) du is integrated piece by piece along the ray, in order,
 * carrying D(u) = int_0^u K: a piece is first halved until its optical depth is <= 1/2 (tau
 * then varies by at most e^{1/2} across it, so 15 nodes resolve it and the error estimate is
 * honest even on a 1e30-long ray through constant fog), then integrated adaptively; at each
 * outer node tau comes from D at the interval's start plus adaptive integrals between the
 * consecutive sorted nodes (no nested integral from 0: the increments are short and
 * break-free). The ray stops once tau < tol/1000: all the rest of S is at most tau.
 *
 * Tolerance budget of S (absolute tol): 0.8 tol for the outer quadrature, shared by the
 * pieces as 0.4 tol (their share of 1 - tau + their share of the length), whose sum is
 * <= 0.8 tol; 0.05 tol for the pieces' depths and 0.05 tol for the increments (an error
 * dD in tau's exponent moves S by <= dD * S1 <= dD); 0.05 tol on each sun ray's depth
 * (moves S by <= 0.05 tol S1); 0.001 tol for the stop. */
#include <math.h>
#include <stdlib.h>

#include "reference/fog_light_reference.h"
#include "reference/ref_slab.h"
#include "reference/fog_oracle.h"

enum { LR_MAX_DEPTH = 60 };
/* Density evaluations of one public call at most, sun rays included (~1 minute): a runaway
 * subdivision (a kink the breaks do not announce costs ~30 bisections per kink, each with
 * 15 sun rays) gives NAN instead of a hang. S on a 64 x 64 fogmap takes ~1e6. */
#define LR_WORK_LIMIT 500000000L
/* |K15 - G7| below this fraction of int |f| is roundoff, accepted whatever the tolerance. */
#define LR_ROUNDOFF 1e-14
/* Largest optical depth of one outer piece. */
#define LR_PIECE_DEPTH 0.5

#include "reference/gauss_kronrod.h"

/* The 15 Kronrod nodes on [a, b] in increasing order, with their Kronrod and Gauss weights
 * (the Gauss weight is 0 at the Kronrod-only nodes). */
static void lr_nodes(double a, double b, double t[15], double wk[15], double wgs[15]) {
  double c = 0.5 * (a + b), h = 0.5 * (b - a);
  for (int i = 0; i < 7; i++) {
    t[i] = c - h * xgk[i];
    t[14 - i] = c + h * xgk[i];
    wk[i] = wk[14 - i] = wgk[i];
    wgs[i] = wgs[14 - i] = (i % 2 == 1) ? wg[i / 2] : 0.0;
  }
  t[7] = c;
  wk[7] = wgk[7];
  wgs[7] = wg[3];
}

typedef struct lr_ray {
  const light_ref_medium *m;
  const double *o, *d;
  long *work; /* density evaluations of the public call so far */
} lr_ray;

static double lr_density(const lr_ray *r, double t) {
  double p[3] = {r->o[0] + t * r->d[0], r->o[1] + t * r->d[1], r->o[2] + t * r->d[2]};
  return r->m->density(r->m, p);
}

static int lr_too_short(double a, double b) {
  return !(b - a > 1e-15 * (fabs(a) + fabs(b)));
}

/* Adaptive G7K15 of K along the ray on [a, b] (break-free), tolerance halved on each
 * bisection (so proportional to length). */
static double lr_adapt_depth(lr_ray *r, double a, double b, double tol, int depth) {
  double t[15], wk[15], wgs[15], k = 0.0, g = 0.0, mag = 0.0, h = 0.5 * (b - a);
  if ((*r->work += 15) > LR_WORK_LIMIT) return NAN;
  lr_nodes(a, b, t, wk, wgs);
  for (int i = 0; i < 15; i++) {
    double f = lr_density(r, t[i]);
    k += wk[i] * f;
    g += wgs[i] * f;
    mag += wk[i] * fabs(f);
  }
  double val = k * h, err = fabs((k - g) * h);
  if (isnan(val)) return val;
  if (err <= tol || err <= LR_ROUNDOFF * mag * h || depth >= LR_MAX_DEPTH || lr_too_short(a, b))
    return val;
  double c = 0.5 * (a + b);
  return lr_adapt_depth(r, a, c, 0.5 * tol, depth + 1) +
         lr_adapt_depth(r, c, b, 0.5 * tol, depth + 1);
}

/* Ray against the box (slab test, zero direction components allowed): narrows [*lo, *hi]
 * to the box's part; 0 when nothing is left. */
static int lr_clip(const light_ref_medium *m, const double o[3], const double d[3], double *lo,
                   double *hi) {
  return ref_slab_clip(m->box_min, m->box_max, o, d, lo, hi);
}

static int lr_compare(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The ray's stretch in [t0, t1] clipped to the box and the cut, with the breaks inside it:
 * sorted distinct points s_0 = lo < ... < s_{n-1} = hi in a malloc'ed *points. Returns n
 * (0: nothing left; then *points is NULL) or -1 (out of memory, failing breaks). */
static int lr_ray_points(const light_ref_medium *m, const double o[3], const double d[3],
                         double t0, double t1, double **points) {
  double lo = t0, hi = t1;
  *points = NULL;
  if (!lr_clip(m, o, d, &lo, &hi)) return 0;
  if (m->cut) {
    double c = m->cut(m, o, d, lo, hi);
    if (c < hi) hi = c;
    if (!(lo < hi)) return 0;
  }
  int capacity = 64;
  for (int attempt = 0; attempt < 2; attempt++) {
    double *s = malloc((size_t)(capacity + 2) * sizeof *s);
    if (!s) return -1;
    int nb = m->breaks ? m->breaks(m, o, d, lo, hi, s + 1, capacity) : 0;
    if (nb < 0) {
      free(s);
      return -1;
    }
    if (nb > capacity) { /* room for all, once */
      free(s);
      capacity = nb;
      continue;
    }
    int n = 0;
    s[n++] = lo;
    for (int i = 1; i <= nb; i++)
      if (s[i] > lo && s[i] < hi) s[n++] = s[i];
    s[n++] = hi;
    qsort(s, (size_t)n, sizeof *s, lr_compare);
    int k = 1;
    for (int i = 1; i < n; i++)
      if (s[i] > s[k - 1]) s[k++] = s[i];
    *points = s;
    return k;
  }
  return -1;
}

static int lr_bad_medium(const light_ref_medium *m, double tol) {
  return !m || !m->density || !(tol > 0.0);
}

/* D on [t0, t1]: each break-free piece gets its length's share of tol. */
static double lr_depth(const light_ref_medium *m, const double o[3], const double d[3],
                       double t0, double t1, double tol, long *work) {
  double *s;
  int n = lr_ray_points(m, o, d, t0, t1, &s);
  if (n < 0) return NAN;
  double sum = 0.0;
  if (n >= 2) {
    lr_ray r = {.m = m, .o = o, .d = d, .work = work};
    double whole = s[n - 1] - s[0];
    for (int i = 0; i + 1 < n; i++)
      sum += lr_adapt_depth(&r, s[i], s[i + 1], tol * (s[i + 1] - s[i]) / whole, 0);
  }
  free(s);
  return sum;
}

double light_ref_optical_depth(const light_ref_medium *m, const double o[3], const double d[3],
                               double t0, double t1, double tol) {
  if (lr_bad_medium(m, tol) || !(t0 <= t1)) return NAN;
  long work = 0;
  return lr_depth(m, o, d, t0, t1, tol, &work);
}

double light_ref_sun_transmittance(const light_ref_medium *m, const double p[3],
                                   const double sun_dir[3], double tol) {
  return exp(-light_ref_optical_depth(m, p, sun_dir, 0.0, HUGE_VAL, tol));
}

/* ----------------------------------------------------------------------------------------
 * The in-scatter integral. */

typedef struct lr_scatter {
  lr_ray view;
  const double *sun; /* NULL: unshadowed */
  double tol;        /* the call's absolute tolerance */
  double length;     /* the clipped stretch's length: the tolerances' per-length shares */
  int failed;
} lr_scatter;

/* Tolerance of a depth integral of length len: 0.05 tol per the whole stretch. */
static double lr_depth_tol(const lr_scatter *c, double len) {
  return 0.05 * c->tol * len / c->length;
}

/* tau(u) K(u) T_s(u) at the 15 nodes of [a, b] given D(a); D(b) to *d_b. */
static double lr_gk15_scatter(lr_scatter *c, double a, double b, double d_a, double *err,
                              double *mag, double *d_b) {
  double t[15], wk[15], wgs[15], k = 0.0, g = 0.0, h = 0.5 * (b - a), depth = d_a, prev = a;
  lr_nodes(a, b, t, wk, wgs);
  *mag = 0.0;
  for (int i = 0; i < 15; i++) {
    depth += lr_adapt_depth(&c->view, prev, t[i], lr_depth_tol(c, t[i] - prev), 0);
    prev = t[i];
    double f = exp(-depth) * lr_density(&c->view, t[i]);
    if (c->sun && f != 0.0) { /* skip the sun ray where it cannot matter */
      double p[3];
      for (int x = 0; x < 3; x++) p[x] = c->view.o[x] + t[i] * c->view.d[x];
      f *= exp(-lr_depth(c->view.m, p, c->sun, 0.0, HUGE_VAL, 0.05 * c->tol, c->view.work));
    }
    k += wk[i] * f;
    g += wgs[i] * f;
    *mag += wk[i] * fabs(f);
  }
  *d_b = depth + lr_adapt_depth(&c->view, prev, b, lr_depth_tol(c, b - prev), 0);
  *err = fabs((k - g) * h);
  *mag *= h;
  return k * h;
}

static double lr_adapt_scatter(lr_scatter *c, double a, double b, double d_a, double tol,
                               int depth, double *d_b) {
  double err, mag;
  double val = lr_gk15_scatter(c, a, b, d_a, &err, &mag, d_b);
  if (isnan(val)) return val;
  if (err <= tol || err <= LR_ROUNDOFF * mag || depth >= LR_MAX_DEPTH || lr_too_short(a, b))
    return val;
  double mid = 0.5 * (a + b), d_mid;
  double left = lr_adapt_scatter(c, a, mid, d_a, 0.5 * tol, depth + 1, &d_mid);
  return left + lr_adapt_scatter(c, mid, b, d_mid, 0.5 * tol, depth + 1, d_b);
}

/* One break-free piece [a, b] of optical depth d_ab, *d_run = D(a): halved until at most
 * LR_PIECE_DEPTH thick, then integrated into *s. Returns 1 once tau(a) < tol/1000 (the
 * rest of the ray adds at most tau(a) to S: stop), 0 otherwise. */
static int lr_scatter_piece(lr_scatter *c, double a, double b, double d_ab, double *d_run,
                            double *s, int depth) {
  double tau_a = exp(-*d_run);
  if (tau_a < 1e-3 * c->tol) return 1;
  if (isnan(d_ab)) {
    c->failed = 1;
    return 1;
  }
  if (d_ab > LR_PIECE_DEPTH && depth < 400 && !lr_too_short(a, b)) {
    double mid = 0.5 * (a + b);
    double d_left = lr_adapt_depth(&c->view, a, mid, lr_depth_tol(c, mid - a), 0);
    double d_right = lr_adapt_depth(&c->view, mid, b, lr_depth_tol(c, b - mid), 0);
    return lr_scatter_piece(c, a, mid, d_left, d_run, s, depth + 1) ||
           lr_scatter_piece(c, mid, b, d_right, d_run, s, depth + 1);
  }
  /* The piece's share of S1 = 1 - tau is tau(a) (1 - e^{-d_ab}): those shares sum to <= 1. */
  double share = tau_a * -expm1(-d_ab), d_b;
  double tol = 0.4 * c->tol * (share + (b - a) / c->length);
  *s += lr_adapt_scatter(c, a, b, *d_run, tol, 0, &d_b);
  *d_run += d_ab;
  return 0;
}

double light_ref_sun_inscatter(const light_ref_medium *m, const double o[3], const double d[3],
                               double t_surf, const double sun_dir[3], int shadowed, double tol,
                               double *tau) {
  if (tau) *tau = NAN;
  if (lr_bad_medium(m, tol) || !(t_surf >= 0.0) || (shadowed && !sun_dir)) return NAN;
  double *pts;
  int n = lr_ray_points(m, o, d, 0.0, t_surf, &pts);
  if (n < 0) return NAN;
  long work = 0;
  lr_scatter c = {.view = {.m = m, .o = o, .d = d, .work = &work},
                  .sun = shadowed ? sun_dir : NULL, .tol = tol,
                  .length = n >= 2 ? pts[n - 1] - pts[0] : 1.0};
  double s = 0.0, d_run = 0.0;
  for (int i = 0; i + 1 < n && !c.failed; i++) {
    double d_ab = lr_adapt_depth(&c.view, pts[i], pts[i + 1],
                                 lr_depth_tol(&c, pts[i + 1] - pts[i]), 0);
    if (lr_scatter_piece(&c, pts[i], pts[i + 1], d_ab, &d_run, &s, 0)) break;
  }
  free(pts);
  if (c.failed || work > LR_WORK_LIMIT) return NAN;
  if (tau) *tau = exp(-light_ref_optical_depth(m, o, d, 0.0, t_surf, 0.05 * tol));
  return s;
}

/* ----------------------------------------------------------------------------------------
 * Media. */

/* Appends (up to capacity, counting all) the t in (t0, t1) where c(t) = c0 + t dc crosses
 * base + step (n + (degree+1)/2), n integer: the ends of the supports of
 * phi_degree((c - base)/step - i), where the piecewise polynomial may break. */
static int lr_knots(double c0, double dc, double base, double step, int degree, double t0,
                    double t1, double *out, int n, int capacity) {
  if (dc == 0.0) return n;
  double shift = 0.5 * (degree + 1);
  double a = (c0 + t0 * dc - base) / step - shift, b = (c0 + t1 * dc - base) / step - shift;
  if (a > b) {
    double s = a;
    a = b;
    b = s;
  }
  for (double k = ceil(a); k <= b; k += 1.0) {
    double t = (base + step * (k + shift) - c0) / dc;
    if (!(t > t0 && t < t1)) continue;
    if (n < capacity) out[n] = t;
    n++;
  }
  return n;
}

static double lr_fogmap_density(const light_ref_medium *m, const double p[3]) {
  return fog_extinction_oracle(m->user, m->user2, p);
}

/* Knot lines of f: u = (X - origin_x)/h - 1/2 and x = (u - origin_u)/spacing, so the knot
 * x = n + (d+1)/2 sits at X = origin_x + h (1/2 + origin_u) + h spacing (n + (d+1)/2). */
static int lr_fogmap_breaks(const light_ref_medium *m, const double o[3], const double d[3],
                            double t0, double t1, double *out, int capacity) {
  const fog_volume *v = m->user;
  const transform_grid *g = m->user2;
  const fog_profile *p = &v->profile;
  double h = v->cell_size;
  int n = lr_knots(o[0], d[0], v->origin_x + h * (0.5 + g->origin_u), h * g->spacing,
                   g->degree, t0, t1, out, 0, capacity);
  n = lr_knots(o[2], d[2], v->origin_z + h * (0.5 + g->origin_v), h * g->spacing, g->degree,
               t0, t1, out, n, capacity);
  if (p->kind == FOG_PROFILE_BSPLINE)
    n = lr_knots(o[1], d[1], p->origin, p->spacing, p->degree, t0, t1, out, n, capacity);
  if (p->kind == FOG_PROFILE_EXPONENTIAL && d[1] != 0.0) {
    double t = (p->y0 - o[1]) / d[1];
    if (t > t0 && t < t1) {
      if (n < capacity) out[n] = t;
      n++;
    }
  }
  return n;
}

light_ref_medium light_ref_fogmap(const fog_volume *v, const transform_grid *g) {
  light_ref_medium m = {.density = lr_fogmap_density, .user = v, .user2 = g,
                        .breaks = lr_fogmap_breaks};
  fog_box_oracle(v, m.box_min, m.box_max);
  return m;
}

static double lr_height_density(const light_ref_medium *m, const double p[3]) {
  const light_ref_height *h = m->user;
  for (int a = 0; a < 3; a++)
    if (p[a] < m->box_min[a] || p[a] > m->box_max[a]) return 0.0;
  return h->extinction * exp(-(p[1] - h->y0) / h->scale_height);
}

/* Every crossing of y = y0 + k H: one e-fold of K per piece, which G7K15 integrates to
 * roundoff in one pass however long the piece. */
static int lr_height_breaks(const light_ref_medium *m, const double o[3], const double d[3],
                            double t0, double t1, double *out, int capacity) {
  const light_ref_height *h = m->user;
  /* degree -1: lr_knots' shift (degree+1)/2 is 0, so the knots are y0 + k H exactly */
  return lr_knots(o[1], d[1], h->y0, h->scale_height, -1, t0, t1, out, 0, capacity);
}

/* Along a rising ray K(t) = K(t0) e^{-d_y (t - t0)/H}: past t0 + 40 H/d_y the remaining
 * integral is e^{-40} = 4e-18 of the whole. Level and falling rays end at the box. */
static double lr_height_cut(const light_ref_medium *m, const double o[3], const double d[3],
                            double t0, double t1) {
  const light_ref_height *h = m->user;
  if (!(d[1] > 0.0)) return t1;
  double t = t0 + 40.0 * h->scale_height / d[1];
  return t < t1 ? t : t1;
}

light_ref_medium light_ref_height_medium(const light_ref_height *h) {
  light_ref_medium m = {.density = lr_height_density, .user = h,
                        .breaks = lr_height_breaks, .cut = lr_height_cut};
  double big = 1e30;
  m.box_min[0] = m.box_min[2] = -big;
  m.box_max[0] = m.box_max[2] = big;
  m.box_min[1] = h->y0 - 600.0 * h->scale_height;
  m.box_max[1] = h->y0 + 700.0 * h->scale_height;
  return m;
}

double light_ref_sun_point_light(const void *user, const double x[3]) {
  const light_ref_sun_point *u = user;
  return light_ref_sun_transmittance(u->medium, x, u->sun, u->tol);
}
