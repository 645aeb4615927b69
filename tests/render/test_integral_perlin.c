/* Animated Perlin turbulence fog (render/fog_perlin.h), the CPU twin in double:
 *   - the noise: |n| is 0 at every lattice point (every 4th texel), the octaves repeat with
 *     the texture's period, and the animation is each octave's drift (one octave: T(p, s) =
 *     T(p - w s, 0));
 *   - the exact optical depth against an independent reference: the same density evaluated
 *     here from the texels (trilinear, wrapped), integrated between the ray's breaks (every
 *     crossing of a texel plane of any octave, listed and sorted, not walked) by 8-node
 *     Gauss-Legendre, halved until two levels agree to 1e-13; rays inside and outside the
 *     box, grazing, vertical, at several times: relative error <= 1e-9;
 *   - the paper's variant is T at the ray's last point in the box times the height fog there:
 *     checked against the reference's own height integral and turbulence;
 *   - bad descriptors are refused naming the field. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "test_util.h"

static const double g8_x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                               -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                               0.7966664774136267,  0.9602898564975363};
static const double g8_w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                               0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                               0.2223810344533745, 0.1012285362903763};

typedef struct ref_ray {
  const fog_perlin *p;
  const fog_perlin_medium *m;
  const double *o, *d;
} ref_ray;

/* The density as the header defines it, from the texels. */
static double ref_turbulence(const fog_perlin *p, double time, const double x[3]) {
  const int n = p->desc.size;
  double sum = 0;
  for (int i = 0; i < p->desc.octaves; i++) {
    double s = pow(2.0, i) * FOG_PERLIN_TEXELS_PER_LATTICE / p->desc.feature_size;
    double u[3], f[3];
    long c[3];
    for (int a = 0; a < 3; a++) {
      u[a] = (x[a] - p->desc.wind[i][a] * time) * s;
      c[a] = (long)floor(u[a]);
      f[a] = u[a] - floor(u[a]);
    }
    double v = 0;
    for (int dz = 0; dz < 2; dz++)
      for (int dy = 0; dy < 2; dy++)
        for (int dx = 0; dx < 2; dx++) {
          long X = ((c[0] + dx) % n + n) % n, Y = ((c[1] + dy) % n + n) % n,
               Z = ((c[2] + dz) % n + n) % n;
          double w = (dx ? f[0] : 1 - f[0]) * (dy ? f[1] : 1 - f[1]) * (dz ? f[2] : 1 - f[2]);
          v += w * p->texels[(((size_t)i * n + Z) * n + Y) * n + X];
        }
    sum += v / pow(2.0, i);
  }
  return sum;
}

static double ref_density(const ref_ray *r, double t) {
  double x[3];
  for (int a = 0; a < 3; a++) x[a] = r->o[a] + t * r->d[a];
  return r->m->extinction * exp(-(x[1] - r->m->y0) / r->m->scale_height) *
         ref_turbulence(r->p, r->m->time, x);
}

static double gauss8(const ref_ray *r, double a, double b) {
  double sum = 0, h = 0.5 * (b - a), c = 0.5 * (a + b);
  for (int j = 0; j < 8; j++) sum += g8_w[j] * ref_density(r, c + h * g8_x[j]);
  return h * sum;
}

static double adaptive(const ref_ray *r, double a, double b, double whole, int depth) {
  double m = 0.5 * (a + b), left = gauss8(r, a, m), right = gauss8(r, m, b);
  if (depth > 30 || fabs(left + right - whole) <= 1e-13 * fmax(fabs(whole), 1e-300))
    return left + right;
  return adaptive(r, a, m, left, depth + 1) + adaptive(r, m, b, right, depth + 1);
}

static int compare_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The box's slab, independently. */
static int ref_stretch(const fog_perlin *p, const double o[3], const double d[3], double length,
                       double *t0, double *t1) {
  double lo = 0, hi = length;
  for (int a = 0; a < 3; a++) {
    if (d[a] == 0) {
      if (o[a] < p->desc.lo[a] || o[a] > p->desc.hi[a]) return 0;
      continue;
    }
    double ta = (p->desc.lo[a] - o[a]) / d[a], tb = (p->desc.hi[a] - o[a]) / d[a];
    lo = fmax(lo, fmin(ta, tb));
    hi = fmin(hi, fmax(ta, tb));
  }
  *t0 = lo, *t1 = hi;
  return hi > lo;
}

static double ref_optical_depth(const fog_perlin *p, const fog_perlin_medium *m,
                                const double o[3], const double d[3], double length) {
  double t0, t1;
  if (!ref_stretch(p, o, d, length, &t0, &t1)) return 0;
  /* every crossing of an integer texel plane of any octave inside (t0, t1) */
  size_t cap = 1 << 16, count = 0;
  double *breaks = malloc(cap * sizeof(double));
  breaks[count++] = t0;
  for (int i = 0; i < p->desc.octaves; i++) {
    double s = pow(2.0, i) * FOG_PERLIN_TEXELS_PER_LATTICE / p->desc.feature_size;
    for (int a = 0; a < 3; a++) {
      if (d[a] == 0) continue;
      double ua = (o[a] + t0 * d[a] - p->desc.wind[i][a] * m->time) * s,
             ub = (o[a] + t1 * d[a] - p->desc.wind[i][a] * m->time) * s;
      for (double k = ceil(fmin(ua, ub)); k <= floor(fmax(ua, ub)); k++) {
        double t = (k / s + p->desc.wind[i][a] * m->time - o[a]) / d[a];
        if (t > t0 && t < t1) {
          if (count == cap) breaks = realloc(breaks, (cap *= 2) * sizeof(double));
          breaks[count++] = t;
        }
      }
    }
  }
  if (count == cap) breaks = realloc(breaks, (cap + 1) * sizeof(double));
  breaks[count++] = t1;
  qsort(breaks, count, sizeof(double), compare_double);
  ref_ray r = {p, m, o, d};
  double sum = 0;
  for (size_t k = 0; k + 1 < count; k++)
    if (breaks[k + 1] > breaks[k])
      sum += adaptive(&r, breaks[k], breaks[k + 1], gauss8(&r, breaks[k], breaks[k + 1]), 0);
  free(breaks);
  return sum;
}

int main(void) {
  render_error err = {{0}};
  fog_perlin_desc desc = fog_perlin_desc_default();
  desc.octaves = 4;
  desc.size = 16;
  desc.feature_size = 20.0;
  desc.lo[0] = -60, desc.lo[1] = 0, desc.lo[2] = -50;
  desc.hi[0] = 70, desc.hi[1] = 18, desc.hi[2] = 40;
  fog_perlin p;
  CHECK(fog_perlin_create(&p, &desc, &err) == 0, "create: %s", err.message);
  if (!p.texels) return test_finish("test_integral_perlin");

  /* The noise: zero at lattice points, texels in [0, 1.1), something in between. */
  const int n = desc.size;
  double worst_lattice = 0, largest = 0;
  for (int i = 0; i < desc.octaves; i++)
    for (int z = 0; z < n; z++)
      for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
          float v = p.texels[(((size_t)i * n + z) * n + y) * n + x];
          if (x % 4 == 0 && y % 4 == 0 && z % 4 == 0) worst_lattice = fmax(worst_lattice, v);
          largest = fmax(largest, v);
          CHECK(v >= 0 && v < 1.1, "octave %d texel (%d %d %d) = %g", i, x, y, z, v);
        }
  CHECK(worst_lattice == 0 && largest > 0.3, "lattice values %g, largest %g", worst_lattice,
        largest);
  /* Periodic: octave 0's world period size * feature / 4 holds for every octave. */
  double period = n * desc.feature_size / FOG_PERLIN_TEXELS_PER_LATTICE, worst_period = 0;
  for (int k = 0; k < 50; k++) {
    double x[3] = {-40 + 1.7 * k, 0.3 * k, 13 - 0.9 * k}, y[3] = {x[0] + period, x[1] - period,
                                                                  x[2] + 2 * period};
    worst_period = fmax(worst_period, fabs(fog_perlin_turbulence(&p, 1.5, x) -
                                           fog_perlin_turbulence(&p, 1.5, y)));
    CHECK(fabs(fog_perlin_turbulence(&p, 0.7, x) - ref_turbulence(&p, 0.7, x)) < 1e-12,
          "turbulence at sample %d differs from the definition", k);
  }
  CHECK(worst_period < 1e-9, "turbulence not periodic: %g", worst_period);

  /* The animation: one octave drifts with its wind. */
  {
    fog_perlin_desc one = desc;
    one.octaves = 1;
    fog_perlin q;
    CHECK(fog_perlin_create(&q, &one, &err) == 0, "create one octave: %s", err.message);
    double worst = 0;
    for (int k = 0; k < 30; k++) {
      double s = 0.37 * k, x[3] = {5 + k, 3 + 0.2 * k, -7 + 0.5 * k}, y[3];
      for (int a = 0; a < 3; a++) y[a] = x[a] - one.wind[0][a] * s;
      worst = fmax(worst, fabs(fog_perlin_turbulence(&q, s, x) - fog_perlin_turbulence(&q, 0, y)));
    }
    CHECK(worst < 1e-12, "one octave does not drift with its wind: %g", worst);
    fog_perlin_destroy(&q);
  }

  /* The exact optical depth against the reference. */
  const double cams[4][3] = {{5, 6, -3}, {-120, 30, -90}, {10, 40, 10}, {100, 2, 60}};
  const double targets[4][3] = {{60, 2, 30}, {50, 0, 30}, {12, -5, 11}, {-50, 17.9, -40}};
  double worst = 0, worst_paper = 0, mean_gap = 0;
  int rays = 0;
  for (int c = 0; c < 4; c++)
    for (int k = 0; k < 6; k++) {
      double d[3], norm = 0;
      for (int a = 0; a < 3; a++) {
        d[a] = targets[c][a] + (a == 1 ? 0.0 : 9.0 * (k - 2.5)) - cams[c][a];
        norm += d[a] * d[a];
      }
      for (int a = 0; a < 3; a++) d[a] /= sqrt(norm);
      if (c == 2 && k == 0) d[0] = d[2] = 0, d[1] = -1; /* vertical */
      double length = (k % 3 == 0) ? HUGE_VAL : 35.0 + 20 * k;
      fog_perlin_medium m = {.extinction = 0.05, .y0 = 2.0, .scale_height = 6.0,
                             .time = 0.8 * k, .integral = FOG_PERLIN_EXACT};
      double got = fog_perlin_optical_depth(&p, &m, cams[c], d, length);
      double want = ref_optical_depth(&p, &m, cams[c], d, length);
      double e = fabs(got - want) / fmax(want, 1e-12);
      worst = fmax(worst, e);
      CHECK(e <= 1e-9, "camera %d ray %d: %.15g vs reference %.15g", c, k, got, want);
      /* the paper's variant: T once at the stretch's end times the height fog over it */
      m.integral = FOG_PERLIN_PAPER;
      double paper = fog_perlin_optical_depth(&p, &m, cams[c], d, length), t0, t1;
      double want_paper = 0;
      if (ref_stretch(&p, cams[c], d, length, &t0, &t1)) {
        double end[3], height = 0;
        for (int a = 0; a < 3; a++) end[a] = cams[c][a] + t1 * d[a];
        fog_perlin_medium flat = m;
        /* the height integral by the same quadrature, with T = 1: a one-octave box of ones */
        for (int q = 0; q < 64; q++) {
          double a = t0 + (t1 - t0) * q / 64, b = t0 + (t1 - t0) * (q + 1) / 64, hh = 0;
          for (int j = 0; j < 8; j++) {
            double t = 0.5 * (a + b) + 0.5 * (b - a) * g8_x[j];
            hh += g8_w[j] * flat.extinction *
                  exp(-(cams[c][1] + t * d[1] - flat.y0) / flat.scale_height);
          }
          height += 0.5 * (b - a) * hh;
        }
        want_paper = ref_turbulence(&p, m.time, end) * height;
      }
      worst_paper = fmax(worst_paper, fabs(paper - want_paper) / fmax(want_paper, 1e-12));
      if (want > 0) mean_gap += fabs(paper - want) / want, rays++;
    }
  printf("exact vs reference: worst relative error %.2e; paper vs its definition %.2e; the "
         "paper's mean relative distance from the true integral %.1f %%\n",
         worst, worst_paper, 100 * mean_gap / rays);
  CHECK(worst_paper <= 1e-9, "paper variant off its definition by %.3e", worst_paper);
  CHECK(mean_gap / rays > 0.01, "the paper's single sample matches the integral too well (%g): "
        "is it the integral?", mean_gap / rays);

  /* Bad descriptors. */
  const char *said[4] = {"octaves", "texture size", "feature size", "box"};
  for (int k = 0; k < 4; k++) {
    fog_perlin_desc bad = fog_perlin_desc_default();
    if (k == 0) bad.octaves = 7;
    if (k == 1) bad.size = 24;
    if (k == 2) bad.feature_size = 0;
    if (k == 3) bad.hi[1] = bad.lo[1];
    fog_perlin q;
    render_error e = {{0}};
    CHECK(fog_perlin_create(&q, &bad, &e) != 0 && strstr(e.message, said[k]) && !q.texels,
          "bad descriptor %d: '%s'", k, e.message);
  }
  fog_perlin_destroy(&p);
  return test_finish("test_integral_perlin");
}
