/* Quadric fog volumes, the test reference (quadric_reference.h): adaptive G7K15 on the
 * pointwise extinction K, the ray first cut where K is not smooth (adaptive quadrature
 * alone cannot be trusted across a jump or kink that falls between its nodes):
 *   - where it enters and leaves each box (slab test);
 *   - per volume, inside its box: where Q turns along the ray, i.e. where the directional
 *     derivative grad Q . d (linear in t) changes sign, found by bisection, so that Q is
 *     monotone on each side; then on each side the one t (if any) where Q crosses 0, and
 *     -edge when soft, by bisection on the sign of Q(t) - level.
 * No root of the quadratic Q(o + t d) is ever computed in closed form: only Q and its
 * gradient are evaluated, pointwise. Between the cuts every K_i is 0, density or
 * density (-Q/edge), a polynomial of degree <= 2 in t that G7K15 integrates exactly, so
 * each piece passes on its first estimate. The adaptive bisection (down to 1e-13 of the
 * span) only backs up cuts a roundoff off: it cannot see a jump that falls between its
 * nodes (measured: without the cuts, random scenes are off by up to 4e-5).
 *
 * Q's sign decides a hard edge and Q's value a soft ramp, so near those levels Q is taken
 * in double-double: the double value comes with an error bound, and only where it cannot
 * tell the level apart (|Q| within the bound of 0, or Q between -edge and 0) is Q
 * recomputed from the exact point o + t d. The bisections use that same Q, so the cuts and
 * the integrand agree on which side of an edge every node lies. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "reference/quadric_reference.h"
#include "reference/ref_slab.h"

enum {
  QR_MAX_DEPTH = 60,
  /* Per volume: 2 box ends, 1 turning point, 2 monotone sides x 2 levels. */
  QR_MAX_POINTS = 7 * QUADRIC_REFERENCE_MAX_VOLUMES
};
/* An interval is accepted when |K15 - G7| <= QR_REL_TOL of its integral (K >= 0) plus its
 * length's share of QR_ABS_TOL: well inside the promised 1e-12 / 1e-13. */
#define QR_REL_TOL 1e-13
#define QR_ABS_TOL 1e-14
/* The adaptive rule stops halving at this fraction of the integrated span: a jump the cuts
 * missed then costs at most its height times 1e-13 of the span. */
#define QR_MIN_WIDTH 1e-13
/* Bisections stop at this fraction of |a| + |b|, below t's own ulp (1.1e-16 of |t|). */
#define QR_BISECT_FLOOR 1e-17

#include "reference/gauss_kronrod.h"

typedef struct qr_ray {
  const quadric_reference_volume *v;
  int n;
  const double *o, *d;
} qr_ray;

/* ----------------------------------------------------------------------------------------
 * Q at a point of the ray. */

/* a + b = *s + *e exactly (Knuth's TwoSum; no branch on magnitudes). */
static void qr_two_sum(double a, double b, double *s, double *e) {
  double x = a + b, z = x - a;
  *s = x;
  *e = (a - (x - z)) + (b - z);
}

/* a b = *p + *e exactly (fma gives the product's rounding error). */
static void qr_two_prod(double a, double b, double *p, double *e) {
  double x = a * b;
  *p = x;
  *e = fma(a, b, -x);
}

/* Indices into p of the quadratic monomials in q[]'s order: x^2, y^2, z^2, xy, yz, xz. */
static const int qr_monomial[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};

/* Q at the exact point o + t d, to ~1e-31 of the magnitude of Q's terms: the point as a
 * double-double ph + pl, each term as its exact leading product plus first-order
 * corrections, the terms summed by TwoSum with the errors carried apart (Ogita, Rump and
 * Oishi's Sum2). Rounded to double at the end: its sign is Q's whenever |Q| > ~1e-31 of
 * the terms. */
static double qr_q_exact(const double *c, const double o[3], const double d[3], double t) {
  double ph[3], pl[3];
  for (int k = 0; k < 3; k++) {
    double m, me, s, se;
    qr_two_prod(t, d[k], &m, &me);
    qr_two_sum(o[k], m, &s, &se);
    ph[k] = s;
    pl[k] = se + me;
  }
  double sum = c[9], carry = 0.0;
  for (int k = 0; k < 9; k++) {
    double r, re, s, se;
    if (k < 6) {
      int i = qr_monomial[k][0], j = qr_monomial[k][1];
      double m, me;
      qr_two_prod(ph[i], ph[j], &m, &me);
      me += ph[i] * pl[j] + pl[i] * ph[j];
      qr_two_prod(c[k], m, &r, &re);
      re += c[k] * me;
    } else {
      qr_two_prod(c[k], ph[k - 6], &r, &re);
      re += c[k] * pl[k - 6];
    }
    qr_two_sum(sum, r, &s, &se);
    sum = s;
    carry += se + re;
  }
  return sum + carry;
}

/* The ray's point in double, p = o + t d, and m >= |p| with |p - (o + t d)| <= eps m. */
static void qr_point(const double o[3], const double d[3], double t, double p[3], double m[3]) {
  for (int k = 0; k < 3; k++) {
    double td = t * d[k];
    p[k] = o[k] + td;
    m[k] = fabs(o[k]) + fabs(td);
  }
}

/* Q of volume v at o + t d (p, m from qr_point): in double where that is decisive, else
 * from qr_q_exact. The double value's error is below 16 eps S(m), S the sum of Q's terms'
 * magnitudes at the magnitudes m: ~6 eps S from rounding its ten terms and their sum, ~2
 * eps S from p's own rounding; the factor 2 left over is margin (fma contraction only
 * lowers the error). */
static double qr_q(const quadric_reference_volume *v, const double o[3], const double d[3],
                   double t, const double p[3], const double m[3]) {
  const double *c = v->q;
  double q = c[9], s = fabs(c[9]);
  for (int k = 0; k < 6; k++) {
    int i = qr_monomial[k][0], j = qr_monomial[k][1];
    q += c[k] * p[i] * p[j];
    s += fabs(c[k]) * m[i] * m[j];
  }
  for (int k = 0; k < 3; k++) {
    q += c[6 + k] * p[k];
    s += fabs(c[6 + k]) * m[k];
  }
  double bound = 16.0 * DBL_EPSILON * s;
  /* Outside [-edge - bound, bound] the double decides: K_i is 0 or density either way. */
  if (q > bound || q < -v->edge - bound) return q;
  return qr_q_exact(c, o, d, t);
}

/* K_i at o + t d: 0 outside the closed box, then the hard or soft edge of the definition. */
static double qr_volume_extinction(const quadric_reference_volume *v, const double o[3],
                                   const double d[3], double t) {
  double p[3], m[3];
  qr_point(o, d, t, p, m);
  for (int k = 0; k < 3; k++)
    if (!(p[k] >= v->lo[k] && p[k] <= v->hi[k])) return 0.0;
  if (v->density == 0.0) return 0.0;
  double q = qr_q(v, o, d, t, p, m);
  if (v->edge == 0.0) return q < 0.0 ? v->density : 0.0;
  double f = -q / v->edge;
  return v->density * (f <= 0.0 ? 0.0 : f >= 1.0 ? 1.0 : f);
}

static double qr_extinction_at(const qr_ray *r, double t) {
  double k = 0.0;
  for (int i = 0; i < r->n; i++) k += qr_volume_extinction(&r->v[i], r->o, r->d, t);
  return k;
}

/* ----------------------------------------------------------------------------------------
 * Where K breaks along the ray. */

/* Which side of its break t lies on: 1 or 0. */
typedef int (*qr_side_fn)(const qr_ray *r, const quadric_reference_volume *v, double level,
                          double t);

/* Q(o + t d) < level: the hard edge's inside (level 0), a soft ramp's end (0 or -edge). */
static int qr_below(const qr_ray *r, const quadric_reference_volume *v, double level, double t) {
  double p[3], m[3];
  qr_point(r->o, r->d, t, p, m);
  return qr_q(v, r->o, r->d, t, p, m) < level;
}

/* grad Q(o + t d) . d, Q's slope along the ray; linear in t. Double suffices: the turning
 * point only has to split Q into monotone sides, and an error dt in it moves Q by ~dt^2. */
static double qr_slope(const quadric_reference_volume *v, const qr_ray *r, double t) {
  const double *c = v->q, *d = r->d;
  double p[3], m[3];
  qr_point(r->o, d, t, p, m);
  double gx = 2.0 * c[0] * p[0] + c[3] * p[1] + c[5] * p[2] + c[6];
  double gy = 2.0 * c[1] * p[1] + c[3] * p[0] + c[4] * p[2] + c[7];
  double gz = 2.0 * c[2] * p[2] + c[4] * p[1] + c[5] * p[0] + c[8];
  return gx * d[0] + gy * d[1] + gz * d[2];
}

static int qr_rising(const qr_ray *r, const quadric_reference_volume *v, double level,
                     double t) {
  (void)level;
  return qr_slope(v, r, t) > 0.0;
}

/* The t in (a, b) where side() changes, given that it differs at a and b and changes once. */
static double qr_bisect(const qr_ray *r, const quadric_reference_volume *v, double level,
                        qr_side_fn side, double a, double b) {
  int side_a = side(r, v, level, a);
  double resolution = QR_BISECT_FLOOR * (fabs(a) + fabs(b));
  for (;;) {
    double mid = a + 0.5 * (b - a);
    if (!(mid > a && mid < b) || b - a <= resolution) break;
    if (side(r, v, level, mid) == side_a)
      a = mid;
    else
      b = mid;
  }
  return a + 0.5 * (b - a);
}

/* Appends to out the breaks of K_v in (a, b), v's box stretch of the ray; returns how many
 * (<= 5). Q along a line is a polynomial of degree <= 2, hence monotone on each side of
 * its one turning point: on each side a level is crossed at most once, and exactly when
 * the side's two ends lie on different sides of it. */
static int qr_volume_breaks(const qr_ray *r, const quadric_reference_volume *v, double a,
                            double b, double *out) {
  double ends[3] = {a, b, b};
  int n = 0, sides = 1;
  double slope_a = qr_slope(v, r, a), slope_b = qr_slope(v, r, b);
  if ((slope_a < 0.0 && slope_b > 0.0) || (slope_a > 0.0 && slope_b < 0.0)) {
    ends[1] = out[n++] = qr_bisect(r, v, 0.0, qr_rising, a, b);
    sides = 2;
  }
  double levels[2] = {0.0, -v->edge};
  int n_levels = v->edge > 0.0 ? 2 : 1;
  for (int s = 0; s < sides; s++)
    for (int l = 0; l < n_levels; l++)
      if (qr_below(r, v, levels[l], ends[s]) != qr_below(r, v, levels[l], ends[s + 1]))
        out[n++] = qr_bisect(r, v, levels[l], qr_below, ends[s], ends[s + 1]);
  return n;
}

/* Narrows [*lo, *hi] to the ray's stretch in v's closed box (slab test; zero direction
 * components allowed); 0 when less than a point is left. */
static int qr_clip(const quadric_reference_volume *v, const double o[3], const double d[3],
                   double *lo, double *hi) {
  return ref_slab_clip(v->lo, v->hi, o, d, lo, hi);
}

/* ----------------------------------------------------------------------------------------
 * Quadrature. */

typedef struct qr_quad {
  const qr_ray *ray;
  double abs_per_length; /* QR_ABS_TOL over the span */
  double min_width;
  double err; /* summed |K15 - G7| of the accepted intervals */
} qr_quad;

static double qr_gk15(const qr_ray *r, double a, double b, double *err) {
  double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double fc = qr_extinction_at(r, c), k = wgk[7] * fc, g = wg[3] * fc;
  for (int i = 0; i < 7; i++) {
    double f = qr_extinction_at(r, c - h * xgk[i]) + qr_extinction_at(r, c + h * xgk[i]);
    k += wgk[i] * f;
    if (i % 2 == 1) g += wg[i / 2] * f;
  }
  *err = fabs((k - g) * h);
  return k * h;
}

static double qr_adapt(qr_quad *c, double a, double b, int depth) {
  double err, val = qr_gk15(c->ray, a, b, &err), mid = a + 0.5 * (b - a);
  if (err <= QR_REL_TOL * val + c->abs_per_length * (b - a) || depth >= QR_MAX_DEPTH ||
      b - a <= c->min_width || !(mid > a && mid < b)) {
    c->err += err;
    return val;
  }
  return qr_adapt(c, a, mid, depth + 1) + qr_adapt(c, mid, b, depth + 1);
}

static int qr_compare(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* ----------------------------------------------------------------------------------------
 * The API. */

static int qr_finite3(const double p[3]) {
  return p && isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static int qr_bad_scene(const quadric_reference_volume *v, int n) {
  if (n < 0 || n > QUADRIC_REFERENCE_MAX_VOLUMES || (n > 0 && !v)) return 1;
  for (int i = 0; i < n; i++) {
    for (int k = 0; k < 10; k++)
      if (!isfinite(v[i].q[k])) return 1;
    for (int k = 0; k < 3; k++)
      if (!isfinite(v[i].lo[k]) || !isfinite(v[i].hi[k]) || !(v[i].lo[k] < v[i].hi[k]))
        return 1;
    if (!isfinite(v[i].density) || !(v[i].density >= 0.0) || !isfinite(v[i].edge) ||
        !(v[i].edge >= 0.0))
      return 1;
  }
  return 0;
}

double quadric_reference_extinction(const quadric_reference_volume *v, int n, const double p[3]) {
  static const double still[3] = {0.0, 0.0, 0.0};
  if (qr_bad_scene(v, n) || !qr_finite3(p)) return NAN;
  qr_ray r = {.v = v, .n = n, .o = p, .d = still};
  return qr_extinction_at(&r, 0.0);
}

double quadric_reference_optical_depth_range(const quadric_reference_volume *v, int n,
                                             const double origin[3], const double dir[3],
                                             double t0, double t1, double *error_estimate) {
  if (error_estimate) *error_estimate = NAN;
  if (qr_bad_scene(v, n) || !qr_finite3(origin) || !qr_finite3(dir) ||
      (dir[0] == 0.0 && dir[1] == 0.0 && dir[2] == 0.0) || !isfinite(t0) || !(t0 <= t1))
    return NAN;
  qr_ray r = {.v = v, .n = n, .o = origin, .d = dir};
  double points[QR_MAX_POINTS], lo = HUGE_VAL, hi = -HUGE_VAL;
  int count = 0;
  for (int i = 0; i < n; i++) {
    double a = t0, b = t1;
    if (v[i].density == 0.0 || !qr_clip(&v[i], origin, dir, &a, &b)) continue;
    if (!isfinite(b)) return NAN; /* a direction so small that 1/d overflows */
    points[count++] = a;
    points[count++] = b;
    if (a < lo) lo = a;
    if (b > hi) hi = b;
    count += qr_volume_breaks(&r, &v[i], a, b, points + count);
  }
  double sum = 0.0;
  qr_quad quad = {.ray = &r};
  if (count > 0) {
    qsort(points, (size_t)count, sizeof *points, qr_compare);
    quad.abs_per_length = QR_ABS_TOL / (hi - lo);
    quad.min_width = QR_MIN_WIDTH * (hi - lo);
    /* Every piece between consecutive distinct points, gaps between boxes included (K
     * is 0 there, as the integrand finds out for itself). */
    for (int i = 0; i + 1 < count; i++)
      if (points[i + 1] > points[i]) sum += qr_adapt(&quad, points[i], points[i + 1], 0);
  }
  if (error_estimate) *error_estimate = quad.err;
  return sum;
}

double quadric_reference_optical_depth(const quadric_reference_volume *v, int n,
                                       const double origin[3], const double dir[3],
                                       double length) {
  if (!(length >= 0.0)) return NAN;
  return quadric_reference_optical_depth_range(v, n, origin, dir, 0.0, length, NULL);
}

/* ----------------------------------------------------------------------------------------
 * Self-test: every expected value is a closed form worked out by hand, not this code. */

typedef struct qr_test {
  char *message;
  size_t cap;
  int checks;
  double worst; /* largest |got - want| / (1e-12 |want| + 1e-13): <= 1 passes */
  int failed;
} qr_test;

static void qr_expect(qr_test *t, const char *name, double got, double want) {
  double allowed = 1e-12 * fabs(want) + 1e-13, ratio = fabs(got - want) / allowed;
  t->checks++;
  if (t->failed) return;
  if (!(ratio <= 1.0)) { /* NaN fails too */
    t->failed = 1;
    if (t->cap) snprintf(t->message, t->cap, "%s: got %.17g, want %.17g (error %.3g)", name,
                         got, want, got - want);
    return;
  }
  if (ratio > t->worst) t->worst = ratio;
}

static void qr_expect_nan(qr_test *t, const char *name, double got) {
  t->checks++;
  if (t->failed || isnan(got)) return;
  t->failed = 1;
  if (t->cap) snprintf(t->message, t->cap, "%s: got %.17g, want NAN", name, got);
}

/* Hard (edge 0) or soft sphere |p - centre| < radius, boxed by its bounding box:
 * Q = x^2 + y^2 + z^2 - 2 c.p + |c|^2 - R^2. */
static quadric_reference_volume qr_sphere(double cx, double cy, double cz, double radius,
                                          double density, double edge) {
  quadric_reference_volume v = {
      .q = {1, 1, 1, 0, 0, 0, -2 * cx, -2 * cy, -2 * cz,
            cx * cx + cy * cy + cz * cz - radius * radius},
      .lo = {cx - radius, cy - radius, cz - radius},
      .hi = {cx + radius, cy + radius, cz + radius},
      .density = density,
      .edge = edge};
  return v;
}

static double qr_depth(const quadric_reference_volume *v, int n, double ox, double oy, double oz,
                       double dx, double dy, double dz, double length) {
  double o[3] = {ox, oy, oz}, d[3] = {dx, dy, dz};
  return quadric_reference_optical_depth(v, n, o, d, length);
}

/* Sphere centre (1, 2, 3), radius 2, density 0.3, hard: a chord at distance h from the
 * centre is 2 sqrt(4 - h^2) long. */
static void qr_test_hard_sphere(qr_test *t) {
  quadric_reference_volume s = qr_sphere(1, 2, 3, 2, 0.3, 0);
  double u = 1.0 / sqrt(3.0), big = HUGE_VAL;
  qr_expect(t, "sphere: ray through the centre", qr_depth(&s, 1, 1, 2, -20, 0, 0, 1, big), 1.2);
  qr_expect(t, "sphere: diagonal ray through the centre",
            qr_depth(&s, 1, 1 - 50 * u, 2 - 50 * u, 3 - 50 * u, u, u, u, big), 1.2);
  qr_expect(t, "sphere: reversed ray through the centre",
            qr_depth(&s, 1, 1, 40, 3, 0, -1, 0, big), 1.2);
  qr_expect(t, "sphere: chord at h = 1", qr_depth(&s, 1, 2, 2, -20, 0, 0, 1, big),
            0.6 * sqrt(3.0));
  qr_expect(t, "sphere: chord at h = 1.5", qr_depth(&s, 1, -30, 3.5, 3, 1, 0, 0, big),
            0.6 * sqrt(1.75));
  /* dir (0, 0.6, 0.8) is perpendicular to the offset (1.25, 0, 0). */
  qr_expect(t, "sphere: oblique chord at h = 1.25",
            qr_depth(&s, 1, 2.25, 2 - 20 * 0.6, 3 - 20 * 0.8, 0, 0.6, 0.8, big),
            0.6 * sqrt(4 - 1.5625));
  qr_expect(t, "sphere: from the centre", qr_depth(&s, 1, 1, 2, 3, 0, 0, 1, big), 0.6);
  qr_expect(t, "sphere: from the centre, down", qr_depth(&s, 1, 1, 2, 3, 0, -1, 0, big), 0.6);
  qr_expect(t, "sphere: from the centre, length 1", qr_depth(&s, 1, 1, 2, 3, 0, 0, 1, 1), 0.3);
  qr_expect(t, "sphere: length 0", qr_depth(&s, 1, 1, 2, 3, 0, 0, 1, 0), 0.0);
  qr_expect(t, "sphere: pointing away", qr_depth(&s, 1, 1, 2, 10, 0, 0, 1, big), 0.0);
  qr_expect(t, "sphere: from 1000 away", qr_depth(&s, 1, 1, 2, -1000, 0, 0, 1, big), 1.2);
  double o[3] = {1, 2, 3}, d[3] = {0, 0, 1}, err;
  qr_expect(t, "sphere: range [-1, 0.5] about the centre",
            quadric_reference_optical_depth_range(&s, 1, o, d, -1, 0.5, &err), 0.45);
  qr_expect(t, "sphere: its error estimate", err, 0.0);
  /* Tangent (h = R, on the box face x = 3): Q = (z - 3)^2 >= 0 along it, 0 only at one
   * point. Q's double roundoff there (~1e-15) alone would open a ~1e-7 chord. */
  qr_expect(t, "sphere: tangent ray", qr_depth(&s, 1, 3, 2, -20, 0, 0, 1, big), 0.0);
  /* Grazing at h = 2 - 2^-40 (exact in double): chord 2 sqrt((2 - h)(2 + h)). */
  double g = ldexp(1.0, -40);
  qr_expect(t, "sphere: grazing ray", qr_depth(&s, 1, 3 - g, 2, -20, 0, 0, 1, big),
            0.6 * sqrt(g * (4 - g)));
}

/* Sphere radius 1 at the origin, soft: K = c clamp((1 - r^2)/e, 0, 1). A chord at distance
 * h, half-length w = sqrt(1 - h^2): with e = 1, c int_{-w}^{w} (w^2 - s^2) ds = c 4/3 w^3;
 * with e = 1/2 along a diameter, K = c for |s| <= 1/sqrt2, so
 * c (sqrt2 + 4 int_{1/sqrt2}^{1} (1 - s^2) ds) = c (8/3 - 2 sqrt2 / 3). */
static void qr_test_soft_sphere(qr_test *t) {
  quadric_reference_volume s = qr_sphere(0, 0, 0, 1, 0.7, 1), s2 = qr_sphere(0, 0, 0, 1, 0.7, 0.5);
  double big = HUGE_VAL;
  qr_expect(t, "soft sphere: diameter", qr_depth(&s, 1, -5, 0, 0, 1, 0, 0, big), 0.7 * 4 / 3);
  qr_expect(t, "soft sphere: oblique diameter", qr_depth(&s, 1, -3, 0, -4, 0.6, 0, 0.8, big),
            0.7 * 4 / 3);
  qr_expect(t, "soft sphere: chord at h = 0.5", qr_depth(&s, 1, -5, 0.5, 0, 1, 0, 0, big),
            0.7 * 4 / 3 * pow(0.75, 1.5));
  qr_expect(t, "soft sphere: saturated core, edge 0.5",
            qr_depth(&s2, 1, 0, -5, 0, 0, 1, 0, big), 0.7 * (8.0 / 3 - 2 * sqrt(2.0) / 3));
  double p0[3] = {0.5, 0, 0}, p1[3] = {0, 0, 0}, p2[3] = {1, 0, 0}, p3[3] = {0, 0, 0.5};
  qr_expect(t, "soft sphere: K at r = 0.5", quadric_reference_extinction(&s, 1, p0), 0.7 * 0.75);
  qr_expect(t, "soft sphere: K at the centre, edge 0.5", quadric_reference_extinction(&s2, 1, p1),
            0.7);
  qr_expect(t, "soft sphere: K on the surface", quadric_reference_extinction(&s, 1, p2), 0.0);
  /* (1 - 0.25)/0.5 = 1.5: saturated. */
  qr_expect(t, "soft sphere: K at r = 0.5, edge 0.5", quadric_reference_extinction(&s2, 1, p3),
            0.7);
}

/* Ellipsoid u^2/4 + v^2 + w^2 < 1 with u, v = (p_i +- p_j)/sqrt2 for each plane (i, j) and
 * w the third axis: coefficients 5/8 on p_i^2 and p_j^2, -3/4 on p_i p_j, 1 on w^2. Chords
 * through its centre: 4 along u, 2 along v and w. One copy is also moved to (1, -2, 1/2)
 * (expanded by hand below), which exercises G, H, I beside the cross term. */
static void qr_test_ellipsoids(qr_test *t) {
  static const int planes[3][3] = {{0, 1, 2}, {1, 2, 0}, {0, 2, 1}}; /* i, j, w */
  static const int cross[3] = {3, 4, 5};                             /* D: xy, E: yz, F: xz */
  double r = sqrt(0.5), c = 0.25, big = HUGE_VAL;
  for (int p = 0; p < 3; p++) {
    int i = planes[p][0], j = planes[p][1], w = planes[p][2];
    quadric_reference_volume e = {.lo = {-2, -2, -2}, .hi = {2, 2, 2}, .density = c};
    e.q[i] = e.q[j] = 0.625;
    e.q[w] = 1;
    e.q[cross[p]] = -0.75;
    e.q[9] = -1;
    double du[3] = {0}, dv[3] = {0}, dw[3] = {0};
    du[i] = du[j] = r;
    dv[i] = r;
    dv[j] = -r;
    dw[w] = 1;
    const double *dirs[3] = {du, dv, dw};
    const double want[3] = {4 * c, 2 * c, 2 * c};
    static const char *names[3][3] = {
        {"ellipsoid xy: long axis", "ellipsoid xy: short axis", "ellipsoid xy: z axis"},
        {"ellipsoid yz: long axis", "ellipsoid yz: short axis", "ellipsoid yz: x axis"},
        {"ellipsoid xz: long axis", "ellipsoid xz: short axis", "ellipsoid xz: y axis"}};
    for (int k = 0; k < 3; k++) {
      const double *d = dirs[k];
      qr_expect(t, names[p][k],
                qr_depth(&e, 1, -10 * d[0], -10 * d[1], -10 * d[2], d[0], d[1], d[2], big),
                want[k]);
    }
  }
  /* 5/8 (x-1)^2 + (y+2)^2 + 5/8 (z-1/2)^2 - 3/4 (x-1)(z-1/2) - 1. */
  quadric_reference_volume m = {
      .q = {0.625, 1, 0.625, 0, 0, -0.75, -0.875, 4, 0.125, 3.40625},
      .lo = {-1, -4, -1.5}, .hi = {3, 0, 2.5}, .density = c};
  qr_expect(t, "moved ellipsoid: long axis",
            qr_depth(&m, 1, 1 - 10 * r, -2, 0.5 - 10 * r, r, 0, r, big), 4 * c);
  qr_expect(t, "moved ellipsoid: short axis",
            qr_depth(&m, 1, 1 + 10 * r, -2, 0.5 - 10 * r, -r, 0, r, big), 2 * c);
}

/* Cylinder x^2 + z^2 < 1 along y, cut by the box to y in [0, 2]; a double cone and a
 * hyperboloid of two sheets (Q along a line through them has an inside turning point);
 * a soft half-space y < 0. */
static void qr_test_clipped(qr_test *t) {
  double big = HUGE_VAL;
  quadric_reference_volume cyl = {.q = {1, 0, 1, 0, 0, 0, 0, 0, 0, -1},
                                  .lo = {-1, 0, -1}, .hi = {1, 2, 1}, .density = 0.45};
  qr_expect(t, "cylinder: axis, cut by the box", qr_depth(&cyl, 1, 0, -5, 0, 0, 1, 0, big), 0.9);
  qr_expect(t, "cylinder: chord at z = 0.6", qr_depth(&cyl, 1, -5, 1, 0.6, 1, 0, 0, big), 0.72);
  qr_expect(t, "cylinder: on the box's top face", qr_depth(&cyl, 1, -5, 2, 0, 1, 0, 0, big), 0.9);
  qr_expect(t, "cylinder: above the box", qr_depth(&cyl, 1, -5, 2.5, 0, 1, 0, 0, big), 0.0);

  /* x^2 - y^2 + z^2 < 0: along x = 0.5, z = 0, inside where |y| > 0.5. On the axis
   * Q = -y^2 < 0 but at y = 0. */
  quadric_reference_volume cone = {.q = {1, -1, 1, 0, 0, 0, 0, 0, 0, 0},
                                   .lo = {-2, -2, -2}, .hi = {2, 2, 2}, .density = 0.35};
  qr_expect(t, "cone: vertical at x = 0.5", qr_depth(&cone, 1, 0.5, -2, 0, 0, 1, 0, 4),
            3 * 0.35);
  qr_expect(t, "cone: vertical at x = 0.5, to infinity",
            qr_depth(&cone, 1, 0.5, -7, 0, 0, 1, 0, big), 3 * 0.35);
  qr_expect(t, "cone: its axis", qr_depth(&cone, 1, 0, 5, 0, 0, -1, 0, big), 4 * 0.35);
  /* -x^2 + y^2 - z^2 - 1 < 0 along the y axis: |y| < 1. */
  quadric_reference_volume hyp = {.q = {-1, 1, -1, 0, 0, 0, 0, 0, 0, -1},
                                  .lo = {-2, -2, -2}, .hi = {2, 2, 2}, .density = 0.35};
  qr_expect(t, "two-sheet hyperboloid: axis", qr_depth(&hyp, 1, 0, -5, 0, 0, 1, 0, big),
            2 * 0.35);

  /* Q = y, edge 1/2: K = c clamp(-2y, 0, 1), int over y in [-1, 1] = c (1/2 + 1/4); along
   * (0.6, 0.8, 0) through the origin the box cuts at y = +-1 and dt = dy / 0.8. */
  quadric_reference_volume half = {.q = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0},
                                   .lo = {-1, -1, -1}, .hi = {1, 1, 1}, .density = 0.8,
                                   .edge = 0.5};
  qr_expect(t, "soft half-space: up", qr_depth(&half, 1, 0.3, -5, 0.2, 0, 1, 0, big), 0.6);
  qr_expect(t, "soft half-space: down", qr_depth(&half, 1, 0.3, 5, 0.2, 0, -1, 0, big), 0.6);
  qr_expect(t, "soft half-space: oblique", qr_depth(&half, 1, -1.8, -2.4, 0, 0.6, 0.8, 0, big),
            0.75);
}

/* Overlapping volumes add: the hard unit spheres at 0 and (1/2, 0, 0) each give density x 2
 * along the x axis; a soft unit sphere (edge 1) gives density x 4/3. */
static void qr_test_overlap(qr_test *t) {
  quadric_reference_volume v[3] = {qr_sphere(0, 0, 0, 1, 0.2, 0), qr_sphere(0.5, 0, 0, 1, 0.5, 0),
                                   qr_sphere(0, 0, 0, 1, 0.3, 1)};
  double p[3] = {0.25, 0, 0};
  qr_expect(t, "two spheres: depth", qr_depth(v, 2, -10, 0, 0, 1, 0, 0, HUGE_VAL), 1.4);
  qr_expect(t, "two spheres: K in the overlap", quadric_reference_extinction(v, 2, p), 0.7);
  qr_expect(t, "hard + soft spheres: depth", qr_depth(v + 1, 2, 10, 0, 0, -1, 0, 0, HUGE_VAL),
            1.0 + 0.3 * 4 / 3);
  qr_expect(t, "no volumes", qr_depth(v, 0, -10, 0, 0, 1, 0, 0, HUGE_VAL), 0.0);
}

static void qr_test_bad_arguments(qr_test *t) {
  quadric_reference_volume s = qr_sphere(0, 0, 0, 1, 0.2, 0), flat = s, negative = s;
  double o[3] = {-5, 0, 0}, d[3] = {1, 0, 0}, zero[3] = {0, 0, 0};
  flat.hi[1] = flat.lo[1];
  negative.edge = -1;
  qr_expect_nan(t, "bad: n > 64", quadric_reference_optical_depth(&s, 65, o, d, 1));
  qr_expect_nan(t, "bad: NULL volumes", quadric_reference_optical_depth(NULL, 1, o, d, 1));
  qr_expect_nan(t, "bad: zero direction", quadric_reference_optical_depth(&s, 1, o, zero, 1));
  qr_expect_nan(t, "bad: negative length", quadric_reference_optical_depth(&s, 1, o, d, -1));
  qr_expect_nan(t, "bad: NaN length", quadric_reference_optical_depth(&s, 1, o, d, NAN));
  qr_expect_nan(t, "bad: flat box", quadric_reference_optical_depth(&flat, 1, o, d, 1));
  qr_expect_nan(t, "bad: negative edge", quadric_reference_extinction(&negative, 1, o));
  qr_expect_nan(t, "bad: t1 < t0",
                quadric_reference_optical_depth_range(&s, 1, o, d, 2, 1, NULL));
}

int quadric_reference_self_test(char *message, size_t cap) {
  qr_test t = {.message = message, .cap = message ? cap : 0};
  qr_test_hard_sphere(&t);
  qr_test_soft_sphere(&t);
  qr_test_ellipsoids(&t);
  qr_test_clipped(&t);
  qr_test_overlap(&t);
  qr_test_bad_arguments(&t);
  if (!t.failed && t.cap)
    snprintf(message, cap, "%d checks pass; worst error %.3g of its allowance", t.checks,
             t.worst);
  return t.failed;
}
