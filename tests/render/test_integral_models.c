/* The analytic fog models (fog_models.h) against numerical quadrature of their K along the
 * ray (composite 8-node Gauss-Legendre, 4000 panels: K is smooth): homogeneous and
 * exponential height fog, rays up, down, level and nearly level (where the closed form's
 * (1 - e^{-x})/x switches to its series); and the switch itself against long double. */
#include <math.h>
#include <stdio.h>

#include "render/fog_models.h"
#include "fog_test_scene.h"
#include "test_util.h"

static const double gl8_x[4] = {0.18343464249564980, 0.52553240991632899, 0.79666647741362674,
                                0.96028985649753623};
static const double gl8_w[4] = {0.36268378337836198, 0.31370664587788729, 0.22238103445337447,
                                0.10122853629037626};

static double height_k(double k, double y0, double H, double y) { return k * exp(-(y - y0) / H); }

static double quadrature_height(double k, double y0, double H, const double cam[3],
                                const double dir[3], double L) {
  int panels = 4000;
  double sum = 0.0, h = L / panels;
  for (int p = 0; p < panels; p++) {
    double mid = (p + 0.5) * h;
    for (int i = 0; i < 4; i++)
      for (int s = -1; s <= 1; s += 2) {
        double t = mid + s * 0.5 * h * gl8_x[i];
        sum += gl8_w[i] * height_k(k, y0, H, cam[1] + t * dir[1]);
      }
  }
  return sum * 0.5 * h;
}

int main(void) {
  double worst = 0.0;
  for (int r = 0; r < 400; r++) {
    double cam[3] = {fog_test_range(-100, 100), fog_test_range(-20, 60), fog_test_range(-100, 100)};
    double dir[3] = {fog_test_range(-1, 1), 0.0, fog_test_range(-1, 1)};
    /* A quarter of the rays nearly level: |dir_y| L / H below the series switch. */
    dir[1] = (r % 4 == 0) ? fog_test_range(-1e-3, 1e-3) : fog_test_range(-1, 1);
    fog_test_unit(dir);
    double L = fog_test_range(1.0, 300.0);
    fog_model m = {.kind = FOG_MODEL_HEIGHT, .extinction = 0.02, .y0 = 5.0, .scale_height = 8.0};
    double got = fog_model_optical_depth(&m, cam, dir, L);
    double want = quadrature_height(0.02, 5.0, 8.0, cam, dir, L);
    double e = fabs(got - want) / fmax(want, 1e-300);
    if (e > worst) worst = e;
    CHECK(e <= 1e-12, "height fog: closed form %.15g, quadrature %.15g (dir_y %g, L %g)", got, want,
          dir[1], L);
    fog_model hm = {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = 0.013};
    CHECK(fabs(fog_model_optical_depth(&hm, cam, dir, L) - 0.013 * L) <= 1e-15 * L,
          "homogeneous fog");
  }
  printf("height fog, 400 rays: worst relative error %.2e\n", worst);
  /* To infinity: upward rays converge to k e^{-(y_c - y0)/H} H / dir_y, downward diverge. */
  double cam[3] = {0, 2, 0}, up[3] = {0.6, 0.8, 0}, down[3] = {0.6, -0.8, 0};
  fog_model m = {.kind = FOG_MODEL_HEIGHT, .extinction = 0.02, .y0 = 5.0, .scale_height = 8.0};
  double inf_up = fog_model_optical_depth(&m, cam, up, HUGE_VAL);
  double far_up = quadrature_height(0.02, 5.0, 8.0, cam, up, 2000.0);
  CHECK(fabs(inf_up - far_up) <= 1e-12 * far_up, "height fog to infinity: %.15g vs %.15g", inf_up,
        far_up);
  CHECK(isinf(fog_model_optical_depth(&m, cam, down, HUGE_VAL)), "downward ray to infinity");
  fog_model none = {.kind = FOG_MODEL_HOMOGENEOUS};
  CHECK(fog_model_optical_depth(&none, cam, up, HUGE_VAL) == 0.0, "zero extinction to infinity");
  /* The exprel switch: both forms agree at the switch; the direct form fails far below. */
  for (int side = -1; side <= 1; side += 2) {
    double x = side * FOG_EXPREL_SWITCH;
    long double ref = (1.0L - expl(-(long double)x)) / (long double)x;
    double series = fog_exprel(x * (1 - 1e-12)), direct = fog_exprel(x * (1 + 1e-12));
    CHECK(fabsl(series - ref) <= 1e-13L && fabsl(direct - ref) <= 1e-13L,
          "exprel at the switch x=%g: series %.17g direct %.17g", x, series, direct);
  }
  double x = 1e-9;
  double direct = (1.0 - exp(-x)) / x, switched = fog_exprel(x);
  long double ref = -expm1l(-(long double)x) / (long double)x;
  printf("exprel at 1e-9: direct form error %.2e, switched %.2e\n", (double)fabsl(direct - ref),
         (double)fabsl(switched - ref));
  CHECK(fabsl(direct - ref) > 1e-9L && fabsl(switched - ref) <= 1e-16L, "exprel switch at 1e-9");
  return test_finish("test_integral_models");
}
