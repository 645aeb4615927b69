/* inverse(forward(f)) == f to float rounding (<= 1e-6 relative to max |f|) for every
 * basis x boundary mode x standard/non-standard x odd/even sizes x levels (up to the
 * largest J the size allows), with one and two threads; forward in place == out of
 * place. The quadratic basis with symmetric ends on sizes whose halvings run odd
 * (2^k + 1) keeps 2^J float epsilons (transform/transform.h): its right-end ghost rules
 * extrapolate with weights growing 2x a level (1025^2, J = 10: 1.2e-4). */
#include <float.h>
#include <stdbool.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "transform_test_util.h"

/* How many of the J halvings of n start from an odd length above 1 (257 -> 129 -> 65: all
 * of them): the quadratic's right-end rules chain only over such runs. */
static int odd_halvings(int n, int levels) {
  int odd = 0;
  for (int l = 0; l < levels && n > 1; l++, n = (n + 1) / 2) odd += n % 2;
  return odd;
}

static void check(transform_basis basis, transform_boundary mode, transform_decomposition dec,
                  int w, int h, int levels, int threads) {
  transform_plan *plan;
  fog_error err;
  int rc = !(plan = transform_plan_create(&(transform_desc){.width = w, .height = h,
      .levels = levels, .basis = basis, .boundary = mode, .decomposition = dec,
      .threads = threads}, &err));
  CHECK(rc == 0, "plan %dx%d J=%d: %s", w, h, levels, err.message);
  if (rc) return;
  size_t n = (size_t)w * h;
  float *f = malloc(n * sizeof *f), *c = malloc(n * sizeof *c), *r = malloc(n * sizeof *r);
  test_fill_fogmap(f, w, h);
  transform_forward(plan, f, c);
  transform_inverse(plan, c, r);
  double worst = 0.0;
  for (size_t i = 0; i < n; i++) worst = fmax(worst, fabs((double)r[i] - f[i]));
  worst /= test_max_abs(f, n);
  const bool chained = basis == TRANSFORM_QUADRATIC && mode == TRANSFORM_SYMMETRIC &&
                       odd_halvings(w, levels) + odd_halvings(h, levels) >= 2;
  const double bound = chained ? fmax(1e-6, ldexp(FLT_EPSILON, levels)) : 1e-6;
  CHECK(worst <= bound, "%s %s %s %dx%d J=%d threads=%d: error %.3g",
        test_basis_names[basis == TRANSFORM_HAAR ? 0 : basis == TRANSFORM_LINEAR ? 1 : 2],
        mode ? "periodic" : "symmetric", dec ? "standard" : "nonstandard", w, h, levels,
        threads, worst);
  /* in place gives the same coefficients */
  memcpy(r, f, n * sizeof *r);
  transform_forward(plan, r, r);
  /* (in place, level J cannot stream through the single-pass path: last-bit differences) */
  double diff = 0.0;
  for (size_t i = 0; i < n; i++) diff = fmax(diff, fabs((double)r[i] - c[i]));
  CHECK(diff <= bound * test_max_abs(c, n), "in-place forward differs by %.3g (%dx%d J=%d)", diff,
        w, h, levels);
  /* and the in-place inverse (the CLI's --inverse) gives the map back as well */
  transform_inverse(plan, r, r);
  double back = 0.0;
  for (size_t i = 0; i < n; i++) back = fmax(back, fabs((double)r[i] - f[i]));
  back /= test_max_abs(f, n);
  CHECK(back <= bound, "in-place inverse %dx%d J=%d: error %.3g (bound %.3g)", w, h, levels,
        back, bound);
  free(f), free(c), free(r);
  transform_plan_destroy(plan);
}

static void check_one_thread(int b, transform_boundary mode, transform_decomposition dec, int w,
                             int h, int levels) {
  check(test_bases[b], mode, dec, w, h, levels, 1);
}

int main(void) {
  const int sizes[][2] = {{1, 1}, {2, 3}, {5, 7}, {16, 16}, {17, 9}, {33, 20}, {48, 40},
                          {64, 64}, {67, 35}, {96, 128}};
  test_each_transform(sizes, sizeof sizes / sizeof sizes[0], 0, check_one_thread);
  /* the 2^k + 1 sizes at every level they allow, where the quadratic's bound grows */
  for (int b = 0; b < 3; b++) {
    check(test_bases[b], TRANSFORM_SYMMETRIC, TRANSFORM_NONSTANDARD, 257, 257, 8, 1);
    check(test_bases[b], TRANSFORM_SYMMETRIC, TRANSFORM_NONSTANDARD, 1025, 1025, 10, 1);
  }
  /* two threads on sizes big enough to use them */
  for (int b = 0; b < 3; b++)
    for (int dec = 0; dec < 2; dec++) {
      check(test_bases[b], TRANSFORM_SYMMETRIC, (transform_decomposition)dec, 257, 131, 5, 2);
      check(test_bases[b], TRANSFORM_PERIODIC, (transform_decomposition)dec, 256, 192, 6, 2);
    }
  return test_finish("test_perfect_reconstruction");
}
