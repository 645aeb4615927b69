/* Quadric fog volumes (FOG_MODEL_QUADRIC, render/fog_models.h), in double: the shapes, the
 * exact optical depth and the pointwise extinction. The GLSL twin is in
 * render/shaders/fog_models.glsl (fog_quadric_optical_depth_from), break for break. */
#include <math.h>

#include "render/fog_models.h"

void fog_quadric_matrix(const fog_quadric *v, double m[3][3], double l[3]) {
  const double *q = v->q;
  m[0][0] = q[0], m[1][1] = q[1], m[2][2] = q[2];
  m[0][1] = m[1][0] = 0.5 * q[3]; /* D xy */
  m[1][2] = m[2][1] = 0.5 * q[4]; /* E yz */
  m[0][2] = m[2][0] = 0.5 * q[5]; /* F xz */
  l[0] = 0.5 * q[6], l[1] = 0.5 * q[7], l[2] = 0.5 * q[8];
}

double fog_quadric_value(const fog_quadric *v, const double p[3]) {
  const double *q = v->q;
  const double x = p[0], y = p[1], z = p[2];
  return q[0] * x * x + q[1] * y * y + q[2] * z * z + q[3] * x * y + q[4] * y * z +
         q[5] * x * z + q[6] * x + q[7] * y + q[8] * z + q[9];
}

static fog_quadric shape(const double q[10], const double lo[3], const double hi[3],
                         double density, double edge) {
  fog_quadric v = {.density = density, .edge = edge};
  for (int k = 0; k < 10; k++) v.q[k] = q[k];
  for (int a = 0; a < 3; a++) v.lo[a] = lo[a], v.hi[a] = hi[a];
  return v;
}

fog_quadric fog_quadric_ellipsoid(const double c[3], const double r[3], double density,
                                  double edge) {
  /* sum ((x_a - c_a)/r_a)^2 - 1 */
  double w[3] = {1.0 / (r[0] * r[0]), 1.0 / (r[1] * r[1]), 1.0 / (r[2] * r[2])};
  double q[10] = {w[0], w[1], w[2], 0, 0, 0, -2 * c[0] * w[0], -2 * c[1] * w[1],
                  -2 * c[2] * w[2], c[0] * c[0] * w[0] + c[1] * c[1] * w[1] + c[2] * c[2] * w[2] - 1};
  double lo[3] = {c[0] - r[0], c[1] - r[1], c[2] - r[2]};
  double hi[3] = {c[0] + r[0], c[1] + r[1], c[2] + r[2]};
  return shape(q, lo, hi, density, edge);
}

fog_quadric fog_quadric_sphere(const double centre[3], double r, double density, double edge) {
  return fog_quadric_ellipsoid(centre, (double[3]){r, r, r}, density, edge);
}

/* ((x - X)^2 + (z - Z)^2)/r^2 - s(y), s = 1 (cylinder) or ((Y + h - y)/h)^2 (cone), clipped
 * to y in [Y, Y + h]. */
static fog_quadric upright(const double b[3], double r, double h, double density, double edge,
                           int cone) {
  double w = 1.0 / (r * r), top = b[1] + h, k = cone ? 1.0 / (h * h) : 0.0;
  double q[10] = {w, -k, w, 0, 0, 0, -2 * b[0] * w, 2 * top * k, -2 * b[2] * w,
                  (b[0] * b[0] + b[2] * b[2]) * w - (cone ? top * top * k : 1.0)};
  double lo[3] = {b[0] - r, b[1], b[2] - r}, hi[3] = {b[0] + r, top, b[2] + r};
  return shape(q, lo, hi, density, edge);
}

fog_quadric fog_quadric_cylinder(const double base[3], double r, double h, double density,
                                 double edge) {
  return upright(base, r, h, density, edge, 0);
}

fog_quadric fog_quadric_cone(const double base[3], double r, double h, double density,
                             double edge) {
  return upright(base, r, h, density, edge, 1);
}

/* The roots of a t^2 + 2 b t + c = 0 without cancellation (one of the pair through c/q);
 * a = 0 leaves the linear root, a double root (a tangent ray) is returned twice. */
static int quadratic_roots(double a, double b, double c, double root[2]) {
  if (a == 0.0) {
    if (b == 0.0) return 0;
    root[0] = -c / (2.0 * b);
    return 1;
  }
  double disc = b * b - a * c;
  if (disc < 0.0) return 0;
  double q = -(b + copysign(sqrt(disc), b));
  if (q == 0.0) { /* b = 0 and a c = 0: the double root t = 0 */
    root[0] = 0.0;
    return 1;
  }
  root[0] = q / a, root[1] = c / q;
  return 2;
}

/* The roots of a t^2 + 2 b t + c = 0 strictly inside (t0, t1); the others, and missing
 * ones, at t1 (a piece of length 0). */
static void breaks(double a, double b, double c, double t0, double t1, double out[2]) {
  double root[2];
  int k = quadratic_roots(a, b, c, root);
  for (int i = 0; i < 2; i++) out[i] = i < k && root[i] > t0 && root[i] < t1 ? root[i] : t1;
}

static void order(double *x, double *y) {
  double lo = fmin(*x, *y), hi = fmax(*x, *y);
  *x = lo, *y = hi;
}

/* int over [ta, tb] of w(t) T(o + t d), w = w[0] + w[1] t + w[2] t^2: T is trilinear in each
 * texel cell of each octave, so w T is a quintic between consecutive crossings of any
 * octave's cells (a DDA per octave and axis, as fog_perlin.c's octave_depth), where 3
 * Gauss-Legendre nodes are exact. */
static double weighted_turbulence(const fog_quadric_noise *noise, const double o[3],
                                  const double d[3], double ta, double tb, const double w[3]) {
  static const double x3 = 0.77459666924148338, w_end = 5.0 / 9.0, w_mid = 8.0 / 9.0;
  const fog_perlin *perlin = noise->perlin;
  const int octaves = perlin->desc.octaves;
  double next[FOG_PERLIN_MAX_OCTAVES][3], delta[FOG_PERLIN_MAX_OCTAVES][3];
  for (int i = 0; i < octaves; i++) {
    double s = fog_perlin_octave_scale(perlin, i);
    for (int a = 0; a < 3; a++) {
      double u = (o[a] + ta * d[a] - perlin->desc.wind[i][a] * noise->time) * s, du = d[a] * s;
      double cell = floor(u);
      delta[i][a] = du != 0.0 ? fabs(1.0 / du) : HUGE_VAL;
      next[i][a] = du > 0.0 ? (cell + 1.0 - u) / du : du < 0.0 ? (cell - u) / du : HUGE_VAL;
    }
  }
  double len = tb - ta, t = 0.0, sum = 0.0;
  while (t < len) {
    double tn = len;
    for (int i = 0; i < octaves; i++)
      for (int a = 0; a < 3; a++) tn = fmin(tn, next[i][a]);
    if (tn > t) {
      double half = 0.5 * (tn - t), mid = ta + t + half, piece = 0.0;
      for (int k = -1; k <= 1; k++) {
        double tk = mid + k * x3 * half;
        double p[3] = {o[0] + tk * d[0], o[1] + tk * d[1], o[2] + tk * d[2]};
        double weight = (w[2] * tk + w[1]) * tk + w[0];
        piece += (k ? w_end : w_mid) * weight * fog_perlin_turbulence(perlin, noise->time, p);
      }
      sum += half * piece;
    }
    for (int i = 0; i < octaves; i++)
      for (int a = 0; a < 3; a++)
        if (next[i][a] <= tn) next[i][a] += delta[i][a];
    t = fmax(t, tn);
  }
  return sum;
}

/* Q along the ray o + t d re-centred on t0: start = o + t0 d and Q(t0 + u) = a u^2 + 2 b u +
 * c (from a far origin Q(o)'s terms are (distance / size)^2 and cancel; taken at the
 * stretch's start they do not). */
static void ray_quadratic(const fog_quadric *v, const double o[3], const double d[3], double t0,
                          double start[3], double *a, double *b, double *c) {
  double m[3][3], l[3];
  fog_quadric_matrix(v, m, l);
  for (int r = 0; r < 3; r++) start[r] = o[r] + t0 * d[r];
  *a = *b = 0.0;
  for (int r = 0; r < 3; r++) {
    *a += d[r] * (m[r][0] * d[0] + m[r][1] * d[1] + m[r][2] * d[2]);
    *b += d[r] * (m[r][0] * start[0] + m[r][1] * start[1] + m[r][2] * start[2] + l[r]);
  }
  *c = fog_quadric_value(v, start);
}

/* int_{t0}^{t1} of one volume's K along Q(t) = a t^2 + 2 b t + c (from o, unit d): the
 * breaks at Q = 0 and Q = -edge sorted by the GLSL twin's network (a sort without dynamic
 * indexing there); per piece K's weight, 0, density or density (-Q/edge), and with noise
 * that weight times the turbulence's share. */
static double span_integral(const fog_quadric *v, const fog_quadric_noise *noise, double a,
                            double b, double c, const double o[3], const double d[3],
                            double t0, double t1) {
  const double density = v->density, edge = v->edge;
  const bool noisy = v->noise > 0.0 && noise && noise->perlin;
  const double plain = noisy ? 1.0 - v->noise : 1.0;
  const double turbulent = noisy ? v->noise / noise->perlin->mean_turbulence : 0.0;
  double cut[6] = {t0, t1, t1, t1, t1, t1};
  breaks(a, b, c, t0, t1, cut + 1);
  if (edge > 0.0) breaks(a, b, c + edge, t0, t1, cut + 3);
  order(&cut[1], &cut[2]), order(&cut[3], &cut[4]);
  order(&cut[1], &cut[3]), order(&cut[2], &cut[4]);
  order(&cut[2], &cut[3]);
  double sum = 0.0;
  for (int i = 0; i < 5; i++) {
    double ta = cut[i], tb = cut[i + 1], tm = 0.5 * (ta + tb);
    double qm = (a * tm + 2.0 * b) * tm + c;
    if (!(tb > ta) || qm >= 0.0) continue; /* outside */
    bool core = edge == 0.0 || qm <= -edge;
    if (core) {
      sum += plain * density * (tb - ta);
    } else { /* the soft edge: density (-Q/edge), Simpson exact for the quadratic */
      double qa = (a * ta + 2.0 * b) * ta + c, qb = (a * tb + 2.0 * b) * tb + c;
      sum -= plain * density / edge * (tb - ta) * (qa + 4.0 * qm + qb) / 6.0;
    }
    if (noisy) {
      const double w[3] = {core ? density : -density * c / edge,
                           core ? 0.0 : -2.0 * density * b / edge,
                           core ? 0.0 : -density * a / edge};
      sum += turbulent * weighted_turbulence(noise, o, d, ta, tb, w);
    }
  }
  return sum;
}

double fog_quadric_optical_depth(const fog_quadric *v, int count, const fog_quadric_noise *noise,
                                 const double o[3], const double d[3], double length) {
  double sum = 0.0;
  for (int i = 0; i < count; i++) {
    double lo[3], hi[3], t0, t1;
    for (int k = 0; k < 3; k++) lo[k] = v[i].lo[k] - o[k], hi[k] = v[i].hi[k] - o[k];
    if (!(v[i].density > 0.0) || !fog_slab_entry_exit(lo, hi, d, &t0, &t1)) continue;
    t0 = fmax(t0, 0.0), t1 = fmin(t1, length);
    if (!(t1 > t0)) continue;
    /* Q along the ray from where it enters the box, its coefficients taken there: from a
     * far origin, Q(o)'s terms are (distance / size)^2 and cancel (a unit sphere 1e6 away
     * lost 7.8e-4 of its depth, 1e7 away 7.6e-2; the GLSL twin re-centres as well) */
    double start[3], a, b, c;
    ray_quadratic(&v[i], o, d, t0, start, &a, &b, &c);
    sum += span_integral(&v[i], noise, a, b, c, start, d, 0.0, t1 - t0);
  }
  return sum;
}

int fog_quadric_cuts(const fog_quadric *v, int count, const double o[3], const double d[3],
                     double t0, double t1, double cuts[FOG_QUADRIC_MAX_CUTS]) {
  int n = 0;
  for (int i = 0; i < count && i < FOG_MAX_QUADRICS; i++) {
    double lo[3], hi[3], s0, s1;
    for (int k = 0; k < 3; k++) lo[k] = v[i].lo[k] - o[k], hi[k] = v[i].hi[k] - o[k];
    if (!(v[i].density > 0.0) || !fog_slab_entry_exit(lo, hi, d, &s0, &s1)) continue;
    const double a0 = fmax(s0, t0), a1 = fmin(s1, t1);
    if (!(a1 > a0)) continue;
    /* Q(a0 + u) = a u^2 + 2 b u + c, re-centred as fog_quadric_optical_depth */
    double start[3], a, b, c;
    ray_quadratic(&v[i], o, d, a0, start, &a, &b, &c);
    const double len = a1 - a0;
    /* the box's faces clip fog only where Q < 0 there (a cylinder's caps) */
    if (s0 > t0 && c < 0.0) cuts[n++] = a0;
    if (s1 < t1 && (a * len + 2.0 * b) * len + c < 0.0) cuts[n++] = a1;
    double root[2];
    for (int level = 0; level < (v[i].edge > 0.0 ? 2 : 1); level++) {
      const int k = quadratic_roots(a, b, level ? c + v[i].edge : c, root);
      for (int j = 0; j < k; j++)
        if (root[j] > 0.0 && root[j] < len) cuts[n++] = a0 + root[j];
    }
  }
  return n;
}

double fog_quadric_extinction_at(const fog_quadric *v, int count, const fog_quadric_noise *noise,
                                 const double p[3]) {
  /* K = sum c_i w_i (1 - n_i + n_i T/T_mean) = sum c_i w_i + (T/T_mean - 1) sum c_i w_i n_i,
   * T once (as the GLSL twin) */
  double k = 0.0, noisy = 0.0;
  for (int i = 0; i < count; i++) {
    bool inside = true;
    for (int a = 0; a < 3; a++) inside = inside && p[a] >= v[i].lo[a] && p[a] <= v[i].hi[a];
    double q = inside ? fog_quadric_value(&v[i], p) : 0.0;
    if (!(q < 0.0)) continue;
    double ki = v[i].edge > 0.0 ? v[i].density * fmin(1.0, -q / v[i].edge) : v[i].density;
    k += ki;
    noisy += ki * v[i].noise;
  }
  if (noisy > 0.0 && noise && noise->perlin)
    k += noisy * (fog_perlin_turbulence(noise->perlin, noise->time, p) /
                      noise->perlin->mean_turbulence - 1.0);
  return k;
}

bool fog_quadric_noisy(const fog_quadric *v, int count) {
  for (int i = 0; i < count; i++)
    if (v[i].noise > 0.0) return true;
  return false;
}

fog_quadric_noise fog_model_quadric_noise(const fog_model *m) {
  return (fog_quadric_noise){.perlin = m->perlin, .time = m->time};
}

bool fog_quadric_bounds(const fog_quadric *v, int count, double lo[3], double hi[3]) {
  for (int a = 0; a < 3; a++) lo[a] = HUGE_VAL, hi[a] = -HUGE_VAL;
  for (int i = 0; i < count; i++)
    for (int a = 0; a < 3; a++) lo[a] = fmin(lo[a], v[i].lo[a]), hi[a] = fmax(hi[a], v[i].hi[a]);
  return count > 0 && lo[0] < hi[0] && lo[1] < hi[1] && lo[2] < hi[2];
}

double fog_model_depth_quadric(const fog_model *m, const double camera[3], const double dir[3],
                               double t_surface) {
  const fog_quadric_noise noise = fog_model_quadric_noise(m);
  return fog_quadric_optical_depth(m->quadrics, m->quadric_count, &noise, camera, dir, t_surface);
}
