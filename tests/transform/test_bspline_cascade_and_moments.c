/* Two properties of the filter banks themselves:
 *  1. Cascade: one A_0 coefficient pushed through J synthesis levels (details zero)
 *     converges to the synthesis scaling function, which must be the centred B-spline
 *     of the basis' degree (box, hat, quadratic), at the level's position and scale.
 *     Degrees 0 and 1 are exact after any number of levels; degree 2's refined
 *     coefficients differ from samples by -h^2 phi''/8, so J = 6 gives ~1e-4.
 *  2. Vanishing moments of the dual wavelet: polynomials of degree <= d (the basis
 *     degree; the dual has d+1 vanishing moments) give zero details away from the
 *     boundary at every level, and degree d+1 does not. */
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "transform_test_util.h"

static void cascade(int b) {
  const int N = 256, J = 6;
  transform_plan *plan;
  fog_error err;
  CHECK((plan = transform_plan_create(&(transform_desc){.width = N, .height = N, .levels = J,
      .basis = test_bases[b], .boundary = TRANSFORM_PERIODIC}, &err)) != NULL, "%s", err.message);
  float *c = calloc((size_t)N * N, sizeof *c);
  int w0, h0;
  transform_level_size(plan, 0, &w0, &h0);
  c[2 * N + 2] = 1.0f; /* A_0 coefficient (2,2) */
  transform_inverse(plan, c, c);
  int degree = transform_basis_degree(test_bases[b]);
  double s = 64.0, centre = (degree == 1 ? 0.0 : 0.5 * (s - 1.0)) + 2 * s;
  double worst = 0.0, integral = 0.0;
  for (int y = 0; y < N; y++)
    for (int x = 0; x < N; x++) {
      double want = test_bspline(degree, (x - centre) / s) * test_bspline(degree, (y - centre) / s);
      worst = fmax(worst, fabs(c[(size_t)y * N + x] - want));
      integral += c[(size_t)y * N + x];
    }
  double tol = degree == 2 ? 2e-4 : 1e-6;
  CHECK(worst <= tol, "%s: cascade differs from the degree-%d B-spline by %.3g",
        test_basis_names[b], degree, worst);
  /* B-splines integrate to 1: at spacing 64 the refined sum is 64^2 */
  CHECK(fabs(integral / (s * s) - 1.0) < 1e-5, "%s: integral %.6g", test_basis_names[b],
        integral / (s * s));
  free(c);
  transform_plan_destroy(plan);
}

/* max |detail| over band interiors (a margin away from every band edge), all levels */
static double interior_details(transform_plan *plan, const float *c, int W, int margin) {
  double m = 0.0;
  for (int l = 1; l <= transform_plan_desc(plan)->levels; l++)
    for (int o = 0; o < 3; o++) {
      int x, y, w, h;
      transform_band_rect(plan, l, (transform_orientation)o, &x, &y, &w, &h);
      for (int j = margin; j < h - margin; j++)
        for (int i = margin; i < w - margin; i++)
          m = fmax(m, fabs(c[(size_t)(y + j) * W + x + i]));
    }
  return m;
}

static void moments(int b, transform_decomposition dec) {
  const int W = 160, H = 144, J = 3;
  transform_plan *plan;
  fog_error err;
  CHECK((plan = transform_plan_create(&(transform_desc){.width = W, .height = H, .levels = J,
      .basis = test_bases[b], .decomposition = dec}, &err)) != NULL, "%s", err.message);
  int degree = transform_basis_degree(test_bases[b]);
  float *f = malloc(sizeof(float) * W * H), *c = malloc(sizeof(float) * W * H);
  for (int p = 0; p <= degree + 1; p++) {
    for (int y = 0; y < H; y++)
      for (int x = 0; x < W; x++) {
        double u = (x - 70.3) / 25.0, v = (y - 60.7) / 25.0;
        /* a full polynomial of total degree p in x and y (mixed terms too) */
        double mixed = p > 0 ? pow(u, p - 1) * v : 0.0;
        f[(size_t)y * W + x] = (float)(pow(u, p) + 0.7 * pow(v, p) - 0.4 * mixed + 2.0);
      }
    transform_forward(plan, f, c);
    double scale = test_max_abs(f, (size_t)W * H);
    double d = interior_details(plan, c, W, 3) / scale;
    if (p <= degree)
      CHECK(d < 2e-6, "%s %s: degree-%d polynomial gives interior details %.3g",
            test_basis_names[b], dec ? "standard" : "nonstandard", p, d);
    else
      CHECK(d > 2e-5, "%s %s: degree-%d polynomial should not be reproduced (%.3g)",
            test_basis_names[b], dec ? "standard" : "nonstandard", p, d);
  }
  free(f), free(c);
  transform_plan_destroy(plan);
}

int main(void) {
  for (int b = 0; b < 3; b++) {
    cascade(b);
    moments(b, TRANSFORM_NONSTANDARD);
    moments(b, TRANSFORM_STANDARD);
  }
  return test_finish("test_bspline_cascade_and_moments");
}
