/* Noise inside quadric fog volumes (fog_models.h, fog_quadric.noise): the CPU twin against a
 * reference written here, apart from fog_quadric_cpu.c.
 *
 * The model as docs/config.md states it: inside volume i's box, where Q_i < 0,
 *   K_i(p) = density w(Q_i) (1 - noise + noise T(p, time) / T_mean),
 *   w = 1 (hard edge) or min(1, -Q/edge),
 * T the Perlin octaves' turbulence (perlin_ref_turbulence, tests/reference) and T_mean the
 * mean of sum_i 2^-i N_i over the texels (computed here from the texels).
 *
 * The reference integrates K along the ray by adaptive Gauss-Kronrod (G7K15) on pieces cut
 * where K is not smooth: the boxes' faces, every octave's texel planes (enumerated from the
 * ray's texel coordinates), and where Q crosses 0 and -edge (found by scanning Q and
 * bisecting its sign; it never solves the quadratic). Checks:
 *   - T_mean = fog_perlin.mean_turbulence;
 *   - K pointwise, and the optical depth of random noisy scenes (spheres, ellipsoids,
 *     cylinders, hard and soft, noise 0..1, the octaves drifting) along random rays, to
 *     1e-9 (1 + depth);
 *   - noise 0 gives the homogeneous volume's depth bit for bit, and no octaves (NULL) do too.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "reference/gauss_kronrod.h"
#include "reference/perlin_reference.h"
#include "render/fog_models.h"
#include "fog_test_scene.h"
#include "test_util.h"

#define MAX_CUTS 20000

typedef struct ref_scene {
  const fog_quadric *v;
  int n;
  const fog_perlin *perlin;
  double time, mean;
  const double *o, *d;
} ref_scene;

static double ref_mean(const fog_perlin *p) {
  const size_t per = (size_t)p->desc.size * p->desc.size * p->desc.size;
  double mean = 0.0;
  for (int i = 0; i < p->desc.octaves; i++) {
    double sum = 0.0;
    for (size_t k = 0; k < per; k++) sum += p->texels[per * (size_t)i + k];
    mean += sum / (double)per / pow(2.0, i);
  }
  return mean;
}

static double ref_q(const fog_quadric *v, const double p[3]) {
  const double *q = v->q, x = p[0], y = p[1], z = p[2];
  return q[0] * x * x + q[1] * y * y + q[2] * z * z + q[3] * x * y + q[4] * y * z +
         q[5] * x * z + q[6] * x + q[7] * y + q[8] * z + q[9];
}

static double ref_k(const ref_scene *s, const double p[3]) {
  double k = 0.0;
  for (int i = 0; i < s->n; i++) {
    const fog_quadric *v = &s->v[i];
    if (p[0] < v->lo[0] || p[0] > v->hi[0] || p[1] < v->lo[1] || p[1] > v->hi[1] ||
        p[2] < v->lo[2] || p[2] > v->hi[2])
      continue;
    double q = ref_q(v, p);
    if (!(q < 0.0)) continue;
    double w = v->edge > 0.0 ? fmin(1.0, -q / v->edge) : 1.0;
    double m = 1.0;
    if (v->noise > 0.0 && s->perlin)
      m = 1.0 - v->noise + v->noise * perlin_ref_turbulence(s->perlin, s->time, p) / s->mean;
    k += v->density * w * m;
  }
  return k;
}

static double k_at(const ref_scene *s, double t) {
  double p[3] = {s->o[0] + t * s->d[0], s->o[1] + t * s->d[1], s->o[2] + t * s->d[2]};
  return ref_k(s, p);
}

static double gk15(const ref_scene *s, double a, double b, double *error) {
  double c = 0.5 * (a + b), h = 0.5 * (b - a), fc = k_at(s, c);
  double kronrod = wgk[7] * fc, gauss = wg[3] * fc;
  for (int j = 0; j < 7; j++) {
    double x = h * xgk[j], f = k_at(s, c - x) + k_at(s, c + x);
    kronrod += wgk[j] * f;
    if (j % 2 == 1) gauss += wg[j / 2] * f;
  }
  *error = fabs((kronrod - gauss) * h);
  return kronrod * h;
}

static double adaptive(const ref_scene *s, double a, double b, int depth) {
  double error, value = gk15(s, a, b, &error);
  if (error <= 1e-14 * (b - a) + 1e-13 * fabs(value) || depth > 40) return value;
  double m = 0.5 * (a + b);
  return adaptive(s, a, m, depth + 1) + adaptive(s, m, b, depth + 1);
}

static int add_cut(double *cut, int n, double t, double t0, double t1) {
  if (t > t0 && t < t1 && n < MAX_CUTS) cut[n++] = t;
  return n;
}

static int by_value(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Where Q(t) + level changes sign in (a, b): a scan of 64 steps, then bisection. */
static int q_crossings(const ref_scene *s, const fog_quadric *v, double level, double a,
                       double b, double *cut, int n, double t0, double t1) {
  double prev_t = a, prev = 0.0;
  for (int k = 0; k <= 64; k++) {
    double t = a + (b - a) * k / 64.0;
    double p[3] = {s->o[0] + t * s->d[0], s->o[1] + t * s->d[1], s->o[2] + t * s->d[2]};
    double f = ref_q(v, p) + level;
    if (k > 0 && (f < 0.0) != (prev < 0.0)) {
      double lo = prev_t, hi = t;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * (1.0 + fabs(hi)); it++) {
        double mid = 0.5 * (lo + hi);
        double pm[3] = {s->o[0] + mid * s->d[0], s->o[1] + mid * s->d[1], s->o[2] + mid * s->d[2]};
        if (((ref_q(v, pm) + level) < 0.0) == (prev < 0.0)) lo = mid;
        else hi = mid;
      }
      n = add_cut(cut, n, 0.5 * (lo + hi), t0, t1);
    }
    prev_t = t, prev = f;
  }
  return n;
}

/* D = int_0^length K(o + t d) dt, length finite. */
static double ref_depth(const ref_scene *s, double length) {
  static double cut[MAX_CUTS];
  int n = 0;
  cut[n++] = 0.0, cut[n++] = length;
  for (int i = 0; i < s->n; i++) {
    const fog_quadric *v = &s->v[i];
    double a = 0.0, b = length;
    for (int ax = 0; ax < 3; ax++) {
      n = add_cut(cut, n, (v->lo[ax] - s->o[ax]) / s->d[ax], 0.0, length);
      n = add_cut(cut, n, (v->hi[ax] - s->o[ax]) / s->d[ax], 0.0, length);
    }
    n = q_crossings(s, v, 0.0, a, b, cut, n, 0.0, length);
    if (v->edge > 0.0) n = q_crossings(s, v, v->edge, a, b, cut, n, 0.0, length);
  }
  for (int i = 0; s->perlin && i < s->perlin->desc.octaves; i++) {
    double scale = pow(2.0, i) * FOG_PERLIN_TEXELS_PER_LATTICE / s->perlin->desc.feature_size;
    for (int ax = 0; ax < 3; ax++) {
      if (s->d[ax] == 0.0) continue;
      double w = s->perlin->desc.wind[i][ax] * s->time;
      double u0 = (s->o[ax] - w) * scale, u1 = (s->o[ax] + length * s->d[ax] - w) * scale;
      for (double k = ceil(fmin(u0, u1)); k <= floor(fmax(u0, u1)); k++)
        n = add_cut(cut, n, (k / scale + w - s->o[ax]) / s->d[ax], 0.0, length);
    }
  }
  CHECK(n < MAX_CUTS, "reference: too many cuts");
  qsort(cut, (size_t)n, sizeof cut[0], by_value);
  double sum = 0.0;
  for (int k = 0; k + 1 < n; k++)
    if (cut[k + 1] > cut[k]) sum += adaptive(s, cut[k], cut[k + 1], 0);
  return sum;
}

static void unit(double d[3]) {
  double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int a = 0; a < 3; a++) d[a] /= l;
}

static fog_quadric random_volume(void) {
  double c[3] = {fog_test_range(-100, 100), fog_test_range(0, 80), fog_test_range(-100, 100)};
  double density = fog_test_range(0.001, 0.05);
  double edge = fog_test_uniform() < 0.3 ? 0.0 : fog_test_range(0.05, 1.0);
  fog_quadric v;
  switch ((int)(fog_test_uniform() * 3)) {
    case 0: v = fog_quadric_sphere(c, fog_test_range(10, 60), density, edge); break;
    case 1:
      v = fog_quadric_ellipsoid(c, (double[3]){fog_test_range(10, 80), fog_test_range(5, 40),
                                               fog_test_range(10, 80)}, density, edge);
      break;
    default: v = fog_quadric_cylinder(c, fog_test_range(5, 40), fog_test_range(10, 90), density, edge);
  }
  v.noise = fog_test_uniform() < 0.15 ? 0.0 : fog_test_range(0.0, 1.0);
  return v;
}

int main(void) {
  fog_perlin_desc desc = fog_perlin_desc_default();
  desc.octaves = 3, desc.size = 16, desc.feature_size = 40.0, desc.seed = 11;
  for (int i = 0; i < 3; i++) desc.wind[i][0] = 3.0 * (i + 1), desc.wind[i][2] = -2.0 * i;
  fog_perlin perlin;
  fog_error err = {0};
  CHECK(fog_perlin_create(&perlin, &desc, &err) == 0, "perlin: %s", err.message);
  const double mean = ref_mean(&perlin);
  CHECK(fabs(perlin.mean_turbulence - mean) <= 1e-12 * mean, "T_mean %.17g, reference %.17g",
        perlin.mean_turbulence, mean);
  printf("T_mean %.6f (reference %.6f)\n", perlin.mean_turbulence, mean);

  double worst_depth = 0.0, worst_k = 0.0, max_depth = 0.0;
  int rays = 0;
  for (int scene = 0; scene < 12; scene++) {
    fog_quadric v[4];
    int n = 1 + scene % 4;
    for (int i = 0; i < n; i++) v[i] = random_volume();
    const double time = fog_test_range(0.0, 30.0);
    const fog_quadric_noise noise = {.perlin = &perlin, .time = time};
    for (int r = 0; r < 6; r++, rays++) {
      const fog_quadric *aim = &v[r % n];
      double o[3], d[3], target[3];
      for (int a = 0; a < 3; a++) {
        target[a] = fog_test_range(aim->lo[a], aim->hi[a]);
        o[a] = r % 3 == 1 ? fog_test_range(aim->lo[a], aim->hi[a]) : fog_test_range(-250, 250);
        d[a] = target[a] - o[a];
      }
      unit(d);
      double length = fog_test_range(50, 500);
      ref_scene s = {.v = v, .n = n, .perlin = &perlin, .time = time, .mean = mean, .o = o, .d = d};
      double want = ref_depth(&s, length);
      double got = fog_quadric_optical_depth(v, n, &noise, o, d, length);
      double error = fabs(got - want) / (1.0 + want);
      worst_depth = fmax(worst_depth, error), max_depth = fmax(max_depth, want);
      CHECK(error <= 1e-9, "scene %d ray %d: twin %.17g, reference %.17g", scene, r, got, want);
      for (int k = 0; k < 20; k++) {
        double t = fog_test_range(0, length), p[3];
        for (int a = 0; a < 3; a++) p[a] = o[a] + t * d[a];
        double kw = ref_k(&s, p), kg = fog_quadric_extinction_at(v, n, &noise, p);
        worst_k = fmax(worst_k, fabs(kg - kw) / (1e-3 + kw));
      }
    }
    /* noise 0 (or no octaves): the homogeneous volume's depth, bit for bit */
    fog_quadric plain[4];
    for (int i = 0; i < n; i++) plain[i] = v[i], plain[i].noise = 0.0;
    double o[3] = {-200, 60, 180}, d[3] = {1, -0.1, -0.9};
    unit(d);
    double homogeneous = fog_quadric_optical_depth(plain, n, NULL, o, d, 600);
    CHECK(fog_quadric_optical_depth(plain, n, &noise, o, d, 600) == homogeneous,
          "noise 0 changed the depth");
    CHECK(fog_quadric_optical_depth(v, n, NULL, o, d, 600) == homogeneous,
          "without octaves the volumes are not homogeneous");
  }
  CHECK(worst_k <= 1e-12, "pointwise K: %.3e", worst_k);
  CHECK(max_depth > 0.5, "the random rays barely meet fog (max depth %.3f)", max_depth);
  printf("noisy quadrics: %d rays (depth up to %.2f), max |twin - reference| / (1 + depth) "
         "%.2e; K pointwise %.2e\n", rays, max_depth, worst_depth, worst_k);
  fog_perlin_destroy(&perlin);
  return test_finish("test_quadric_noise");
}
