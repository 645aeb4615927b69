/* transform_density_pyramid, the pyramid the renderer draws as fog, on a fogmap with sharp
 * edges (a hard disc and a hard bar, 0 outside), where the linear and quadratic bases'
 * coarse levels dip below zero (checked first: else the test proves nothing):
 *  (i)   every level's coefficients are >= 0 and A_J is the fogmap, bit for bit;
 *  (ii)  as continuous functions (an independent double-precision B-spline sum at random
 *        points, ghosts included), every A_l >= 0;
 *  (iii) grid(A_0) + grid(D_1) + ... + grid(D_l) == grid(A_l), 1e-5 of the peak: the sum
 *        of details draws the same clamped fog as switching;
 *  (iv)  where no level dips (Haar), the levels below J and the details are
 *        transform_pyramid's and transform_details' own, bit for bit;
 *  (v)   the standard decomposition is refused. */
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "transform_test_util.h"

#define POINTS 400
enum { MAX_J = 4 };

static void fill_sharp(float *f, int w, int h) {
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++) {
      const double dx = x - 0.3 * w, dy = y - 0.5 * h;
      const int disc = dx * dx + dy * dy < 0.04 * w * w;
      const int bar = x > 0.6 * w && x < 0.7 * w && y > 0.2 * h && y < 0.8 * h;
      f[(size_t)y * w + x] = disc ? 1.0f : bar ? 0.5f : 0.0f;
    }
}

static void check(int b, transform_boundary mode, int w, int h, int J) {
  transform_plan *plan;
  fog_error err;
  const transform_desc desc = {.width = w, .height = h, .levels = J, .basis = test_bases[b],
                               .boundary = mode};
  if (!(plan = transform_plan_create(&desc, &err))) {
    CHECK(0, "plan: %s", err.message);
    return;
  }
  char what[128];
  snprintf(what, sizeof what, "%s %s %dx%d J=%d", test_basis_names[b],
           mode ? "periodic" : "symmetric", w, h, J);
  const size_t n = (size_t)w * h;
  float *f = malloc(n * sizeof *f), *c = malloc(n * sizeof *c);
  float *approx[MAX_J + 1], *detail[MAX_J + 1], *plain[MAX_J + 1], *plain_detail[MAX_J + 1];
  transform_grid ga[MAX_J + 1], gd[MAX_J + 1];
  fill_sharp(f, w, h);
  transform_forward(plan, f, c);
  for (int l = 0; l <= J; l++) {
    int lw, lh;
    transform_level_size(plan, l, &lw, &lh);
    const size_t bytes = (size_t)lw * lh * sizeof(float);
    approx[l] = malloc(bytes), detail[l] = malloc(bytes);
    plain[l] = malloc(bytes), plain_detail[l] = malloc(bytes);
  }
  transform_pyramid(plan, c, plain);
  transform_details(plan, c, plain_detail);
  double dip = 0.0; /* the plain pyramid's lowest coefficient below J */
  for (int l = 0; l < J; l++) {
    int lw, lh;
    transform_level_size(plan, l, &lw, &lh);
    for (size_t i = 0; i < (size_t)lw * lh; i++) dip = fmin(dip, plain[l][i]);
  }
  CHECK(!transform_density_pyramid(plan, f, c, approx, detail, &err), "%s: %s", what, err.message);
  CHECK(!memcmp(approx[J], f, n * sizeof *f), "%s: A_J is not the fogmap", what);
  if (b == 0) {
    CHECK(dip >= 0.0, "%s: Haar's averages dipped to %g", what, dip);
    for (int l = 0; l <= J; l++) {
      int lw, lh;
      transform_level_size(plan, l, &lw, &lh);
      const size_t bytes = (size_t)lw * lh * sizeof(float);
      CHECK(l == J || !memcmp(approx[l], plain[l], bytes), "%s: A_%d changed", what, l);
      CHECK(l == 0 || !memcmp(detail[l], plain_detail[l], bytes), "%s: D_%d changed", what, l);
    }
  } else {
    CHECK(dip < -0.01, "%s: the plain pyramid does not dip (lowest %g): nothing tested", what,
          dip);
  }
  for (int l = 0; l <= J; l++) {
    int lw, lh;
    transform_level_size(plan, l, &lw, &lh);
    double lowest = 0.0;
    for (size_t i = 0; i < (size_t)lw * lh; i++) lowest = fmin(lowest, approx[l][i]);
    CHECK(lowest >= 0.0, "%s: A_%d has a coefficient %g < 0", what, l, lowest);
    CHECK(!transform_grid_create_level(plan, l, approx[l], &ga[l], &err), "%s", err.message);
    if (l > 0)
      CHECK(!transform_grid_create_level(plan, l, detail[l], &gd[l], &err), "%s", err.message);
  }
  for (int l = 0; l <= J; l++) {
    double lowest = 0.0, gap = 0.0;
    for (int k = 0; k < POINTS; k++) {
      const double u = -0.5 + w * test_uniform(), v = -0.5 + h * test_uniform();
      const double al = test_grid_eval(&ga[l], u, v);
      double sum = test_grid_eval(&ga[0], u, v);
      for (int m = 1; m <= l; m++) sum += test_grid_eval(&gd[m], u, v);
      lowest = fmin(lowest, al), gap = fmax(gap, fabs(sum - al));
    }
    CHECK(lowest >= -1e-7, "%s: the function A_%d reaches %g", what, l, lowest);
    CHECK(gap <= 1e-5, "%s: A_0 + D_1..D_%d differs from A_%d by %g", what, l, l, gap);
  }
  for (int l = 0; l <= J; l++) {
    transform_grid_destroy(&ga[l]);
    if (l > 0) transform_grid_destroy(&gd[l]);
    free(approx[l]), free(detail[l]), free(plain[l]), free(plain_detail[l]);
  }
  free(f), free(c);
  transform_plan_destroy(plan);
}

int main(void) {
  for (int b = 0; b < 3; b++) {
    check(b, TRANSFORM_SYMMETRIC, 64, 48, 3);
    check(b, TRANSFORM_SYMMETRIC, 37, 29, 2);
    check(b, TRANSFORM_PERIODIC, 64, 32, 4);
  }
  fog_error err;
  transform_plan *standard = transform_plan_create(
      &(transform_desc){.width = 32, .height = 32, .levels = 2, .basis = TRANSFORM_LINEAR,
                        .decomposition = TRANSFORM_STANDARD},
      &err);
  CHECK(standard != NULL, "plan: %s", err.message);
  if (standard) {
    float *f = calloc(32 * 32, sizeof *f), *c = calloc(32 * 32, sizeof *c);
    float *levels[3] = {calloc(64, 4), calloc(256, 4), calloc(1024, 4)};
    CHECK(transform_density_pyramid(standard, f, c, levels, NULL, &err) != 0 &&
              strstr(err.message, "non-standard"),
          "the standard decomposition was taken: '%s'", err.message);
    for (int l = 0; l < 3; l++) free(levels[l]);
    free(f), free(c);
    transform_plan_destroy(standard);
  }
  return test_finish("density_pyramid");
}
