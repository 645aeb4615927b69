/* The exported grids are exact as continuous functions on the fog box
 * [-1/2, W-1/2] x [-1/2, H-1/2], evaluated by an independent double-precision B-spline
 * sum at random points, for every basis x boundary mode x decomposition x odd/even
 * size x level:
 *  (i)  grid(A_l) == grid at level J of the inverse transform with the bands finer
 *       than l set to zero (so ghosts and origins of every level are right);
 *  (ii) grid(A_0) + grid(D_1) + ... + grid(D_l) == grid(A_l);
 *  (iii) the level-J grid of the fogmap interpolates... its own samples are the
 *       coefficients (degree 0 and 1 only: B-spline sums interpolate there).
 * Tolerance 1e-5 of the largest density. */
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "transform_test_util.h"

#define POINTS 150

static void check(int b, transform_boundary mode, transform_decomposition dec, int w, int h,
                  int J) {
  transform_plan *plan;
  fog_error err;
  int rc = !(plan = transform_plan_create(&(transform_desc){.width = w, .height = h,
      .levels = J, .basis = test_bases[b], .boundary = mode, .decomposition = dec}, &err));
  CHECK(rc == 0, "plan: %s", err.message);
  if (rc) return;
  char what[160];
  snprintf(what, sizeof what, "%s %s %s %dx%d J=%d", test_basis_names[b],
           mode ? "periodic" : "symmetric", dec ? "standard" : "nonstandard", w, h, J);
  size_t n = (size_t)w * h;
  float *f = malloc(n * sizeof *f), *c = malloc(n * sizeof *c), *z = malloc(n * sizeof *z);
  float *approx[16], *detail[16];
  transform_grid ga[16], gd[16];
  test_fill_fogmap(f, w, h);
  double scale = test_max_abs(f, n), tol = 1e-5 * scale;
  transform_forward(plan, f, c);
  for (int l = 0; l <= J; l++) {
    int lw, lh;
    transform_level_size(plan, l, &lw, &lh);
    approx[l] = malloc((size_t)lw * lh * sizeof(float));
    detail[l] = malloc((size_t)lw * lh * sizeof(float));
  }
  transform_pyramid(plan, c, approx);
  transform_details(plan, c, detail);
  double e_top = 0.0;
  for (size_t i = 0; i < n; i++) e_top = fmax(e_top, fabs((double)approx[J][i] - f[i]));
  CHECK(e_top <= 1e-6 * scale, "%s: A_J differs from the fogmap by %.3g", what, e_top);
  for (int l = 0; l <= J; l++) {
    CHECK(!transform_grid_create_level(plan, l, approx[l], &ga[l], &err), "%s", err.message);
    if (l > 0)
      CHECK(!transform_grid_create_level(plan, l, detail[l], &gd[l], &err), "%s", err.message);
  }
  for (int l = 0; l <= J; l++) {
    /* inverse with bands finer than l zeroed, as a level-J grid */
    int lw, lh;
    transform_level_size(plan, l, &lw, &lh);
    memset(z, 0, n * sizeof *z);
    for (int y = 0; y < lh; y++) memcpy(z + (size_t)y * w, c + (size_t)y * w, lw * sizeof(float));
    transform_inverse(plan, z, z);
    transform_grid fine;
    transform_grid_create_level(plan, J, z, &fine, &err);
    double e1 = 0.0, e2 = 0.0;
    for (int k = 0; k < POINTS; k++) {
      double u = -0.5 + w * test_uniform(), v = -0.5 + h * test_uniform();
      double al = test_grid_eval(&ga[l], u, v);
      e1 = fmax(e1, fabs(al - test_grid_eval(&fine, u, v)));
      double sum = test_grid_eval(&ga[0], u, v);
      for (int m = 1; m <= l; m++) sum += test_grid_eval(&gd[m], u, v);
      e2 = fmax(e2, fabs(al - sum));
    }
    CHECK(e1 <= tol, "%s: A_%d vs inverse with finer bands zeroed: %.3g", what, l, e1);
    CHECK(e2 <= tol, "%s: A_0 + D_1..D_%d vs A_%d: %.3g", what, l, l, e2);
    transform_grid_destroy(&fine);
  }
  /* degree 0/1 grids interpolate their coefficients at the sample positions */
  if (test_bases[b] != TRANSFORM_QUADRATIC) {
    double e3 = 0.0;
    for (int y = 0; y < h; y += 3)
      for (int x = 0; x < w; x += 3)
        e3 = fmax(e3, fabs(test_grid_eval(&ga[J], x, y) - f[(size_t)y * w + x]));
    CHECK(e3 <= tol, "%s: level-J grid does not interpolate the fogmap: %.3g", what, e3);
  }
  for (int l = 0; l <= J; l++) {
    transform_grid_destroy(&ga[l]);
    if (l > 0) transform_grid_destroy(&gd[l]);
    free(approx[l]), free(detail[l]);
  }
  free(f), free(c), free(z);
  transform_plan_destroy(plan);
}

int main(void) {
  const int sizes[][2] = {{2, 2}, {3, 5}, {7, 6}, {16, 16}, {21, 13}, {32, 24}, {37, 40},
                          {64, 48}};
  test_each_transform(sizes, sizeof sizes / sizeof sizes[0], 1, check);
  return test_finish("test_grid_continuous");
}
