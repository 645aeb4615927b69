/* Shared helpers of the transform tests: configurations to sweep, deterministic random
 * fogmaps, and an independent double-precision evaluator of B-spline sums (written from
 * the B-spline definitions, not from the library). */
#ifndef FOGPIPE_TEST_TRANSFORM_UTIL_H
#define FOGPIPE_TEST_TRANSFORM_UTIL_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "tests/test_util.h"
#include "transform/transform.h"

static uint64_t test_rng_state = 0x9E3779B97F4A7C15ull;
static inline double test_uniform(void) { /* xorshift64*, in [0,1) */
  test_rng_state ^= test_rng_state >> 12;
  test_rng_state ^= test_rng_state << 25;
  test_rng_state ^= test_rng_state >> 27;
  return (double)((test_rng_state * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}

/* A smooth-ish positive fogmap plus noise, like real fog. */
static inline void test_fill_fogmap(float *f, int w, int h) {
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++)
      f[(size_t)y * w + x] = (float)(1.0 + 0.5 * sin(0.3 * x + 0.2 * y) + 0.5 * test_uniform());
}

/* Centred cardinal B-spline of degree d: box [-1/2,1/2), hat, quadratic. */
static inline double test_bspline(int degree, double t) {
  double a = fabs(t);
  switch (degree) {
    case 0: return (t >= -0.5 && t < 0.5) ? 1.0 : 0.0;
    case 1: return a < 1.0 ? 1.0 - a : 0.0;
    default:
      if (a < 0.5) return 0.75 - a * a;
      if (a < 1.5) return 0.5 * (1.5 - a) * (1.5 - a);
      return 0.0;
  }
}

/* f(u,v) of a transform_grid, by brute force over all coefficients near (u,v). */
static inline double test_grid_eval(const transform_grid *g, double u, double v) {
  double s = 0.0;
  double gu = (u - g->origin_u) / g->spacing, gv = (v - g->origin_v) / g->spacing;
  int i0 = (int)floor(gu) - 2, j0 = (int)floor(gv) - 2;
  for (int j = j0; j <= j0 + 4; j++) {
    if (j < 0 || j >= g->height) continue;
    double bv = test_bspline(g->degree, gv - j);
    if (bv == 0.0) continue;
    for (int i = i0; i <= i0 + 4; i++) {
      if (i < 0 || i >= g->width) continue;
      s += (double)g->coefficients[(size_t)j * g->width + i] * bv * test_bspline(g->degree, gu - i);
    }
  }
  return s;
}

static const transform_basis test_bases[3] = {TRANSFORM_HAAR, TRANSFORM_LINEAR,
                                              TRANSFORM_QUADRATIC};
static const char *const test_basis_names[3] = {"haar", "linear", "quadratic"};

/* Calls check(b, mode, dec, w, h, levels) for every basis (b indexes test_bases), boundary
 * mode and decomposition, every size of sizes[0 .. count) and every level count from
 * first_level to the most the size allows. */
typedef void (*test_transform_case)(int b, transform_boundary mode, transform_decomposition dec,
                                    int w, int h, int levels);
static inline void test_each_transform(const int (*sizes)[2], size_t count, int first_level,
                                       test_transform_case check) {
  for (int b = 0; b < 3; b++)
    for (int mode = 0; mode < 2; mode++)
      for (int dec = 0; dec < 2; dec++)
        for (size_t s = 0; s < count; s++) {
          const int w = sizes[s][0], h = sizes[s][1];
          const int most = transform_max_levels(w, h, (transform_boundary)mode);
          for (int J = first_level; J <= most; J++)
            check(b, (transform_boundary)mode, (transform_decomposition)dec, w, h, J);
        }
}

/* The same transform planned with single-pass levels on one thread, and as the two-pass
 * reference (rows, then strips of columns, on two threads): the pair the fused-level
 * tests compare. Fails the test with the plan's message. */
static inline void test_plan_pair(transform_desc d, transform_plan **fused,
                                  transform_plan **two_pass) {
  fog_error err;
  d.threads = 1;
  CHECK((*fused = transform_plan_create(&d, &err)) != NULL, "%s", err.message);
  d.threads = 2, d.two_pass = 1;
  CHECK((*two_pass = transform_plan_create(&d, &err)) != NULL, "%s", err.message);
}

static inline double test_max_abs(const float *a, size_t n) {
  double m = 0.0;
  for (size_t i = 0; i < n; i++) m = fmax(m, fabs((double)a[i]));
  return m;
}

#endif
