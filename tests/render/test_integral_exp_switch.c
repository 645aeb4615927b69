/* The exponential profile's moments J_k = int_{-1}^{1} s^k e^{c0 + b s} ds (docs/integral.md):
 * the closed form cancels as b -> 0, so fog_exp_moments switches to the moments' power
 * series below |b| = FOG_EXP_SWITCH (8-node Gauss-Legendre is the checked alternative).
 * Checks, against a long-double power series summed independently (400 terms):
 *  - at the switch all three agree (and each is accurate) to ~1e-14;
 *  - far below the switch the closed form alone is inaccurate, the quadrature is not;
 *  - far above it the closed form is accurate (the quadrature alone would not be);
 *  - fog_exp_moments is accurate everywhere;
 *  - an integral across the switch (rays whose per-piece |b| straddles it) stays continuous. */
#include <math.h>
#include <stdio.h>

#include "render/fog_field.h"
#include "reference/fog_oracle.h"
#include "fog_test_scene.h"
#include "test_util.h"

/* J_k = e^{c0} sum_j b^j/j! int s^{k+j} ds, int_{-1}^{1} s^m ds = 2/(m+1) for even m. */
static void series_moments(double c0, double b, int n, long double m[]) {
  for (int k = 0; k <= n; k++) {
    long double sum = 0.0L, term = 1.0L; /* b^j / j! */
    for (int j = 0; j < 400; j++) {
      if ((k + j) % 2 == 0) sum += term * 2.0L / (long double)(k + j + 1);
      term *= (long double)b / (long double)(j + 1);
    }
    m[k] = expl((long double)c0) * sum;
  }
}

static double max_rel_error(const double got[], const long double want[], int n) {
  double worst = 0.0;
  for (int k = 0; k <= n; k++) {
    /* odd moments vanish as b -> 0: scale by the k = 0 moment instead of J_k itself */
    double e = (double)fabsl(((long double)got[k] - want[k]) / fabsl(want[0]));
    if (e > worst) worst = e;
  }
  return worst;
}

int main(void) {
  const int n = 4; /* degree 2d for the quadratic basis */
  double closed[8], quad[8], picked[8];
  long double ref[8];
  const double c0s[3] = {0.0, -3.5, -20.0};
  for (int c = 0; c < 3; c++) {
    double c0 = c0s[c];
    /* At the switch, from both sides. */
    for (int side = -1; side <= 1; side += 2) {
      double b = side * FOG_EXP_SWITCH;
      for (int eps = -1; eps <= 1; eps++) {
        double bb = b * (1.0 + eps * 1e-9);
        double series[8];
        fog_exp_moments_closed(c0, bb, n, closed);
        fog_exp_moments_series(c0, bb, n, series);
        fog_exp_moments_quadrature(c0, bb, n, quad);
        series_moments(c0, bb, n, ref);
        double ec = max_rel_error(closed, ref, n), es = max_rel_error(series, ref, n);
        double eq = max_rel_error(quad, ref, n);
        CHECK(ec <= 1e-13 && es <= 1e-14 && eq <= 1e-13,
              "at the switch b=%g c0=%g: closed %.2e series %.2e quadrature %.2e", bb, c0, ec, es, eq);
        printf("b=%+.9f c0=%6.2f: closed %.2e, series %.2e, quadrature %.2e\n", bb, c0, ec, es, eq);
      }
    }
    /* Away from the switch, each method alone against the switched moments: far below the
     * closed form fails (cancellation), far above 8-node quadrature does (from b = 20); the
     * switch never does. */
    const double away[6] = {1e-2, 1e-4, 1e-6, 6.0, 20.0, 60.0};
    for (int i = 0; i < 6; i++) {
      const double b = away[i];
      const bool below = b < FOG_EXP_SWITCH;
      double alone[8];
      if (below) fog_exp_moments_closed(c0, b, n, alone);
      else fog_exp_moments_quadrature(c0, b, n, alone);
      fog_exp_moments(c0, b, n, picked);
      series_moments(c0, b, n, ref);
      double ea = max_rel_error(alone, ref, n), ep = max_rel_error(picked, ref, n);
      printf("b=%g c0=%6.2f: %s alone %.2e, switched %.2e\n", b, c0,
             below ? "closed form" : "quadrature", ea, ep);
      CHECK(ep <= (below ? 1e-14 : 1e-12), "switched moments at b=%g: %.2e", b, ep);
      if (below || b >= 20.0)
        CHECK(ea > 1e-6, "%s unexpectedly accurate at b=%g: %.2e",
              below ? "closed form" : "quadrature", b, ea);
    }
  }
  /* Whole rays through exponential fog with per-piece |b| on both sides of the switch:
   * a thin scale height makes |b| = |dir_y| half_length / H cross 1 within one ray. */
  fog_volume v = fog_test_volume(FOG_PROFILE_EXPONENTIAL);
  v.profile.scale_height = 0.6;
  v.profile.y_top = 12.0;
  transform_grid g = fog_test_grid(2, 2.0, 0.1);
  double worst = 0.0;
  for (int r = 0; r < 3000; r++) {
    double cam[3], dir[3];
    fog_test_ray(&v, cam, dir);
    double exact = fog_optical_depth(&v, &g, cam, dir, 0.0, HUGE_VAL);
    double oracle = fog_optical_depth_oracle(&v, &g, cam, dir, 0.0, HUGE_VAL, 1e-13, NULL);
    double e = fabs(exact - oracle) / fmax(oracle, 1e-3);
    if (e > worst) worst = e;
  }
  printf("thin exponential fog, 3000 rays: worst relative optical depth error %.2e\n", worst);
  CHECK(worst <= 1e-11, "thin exponential fog: %.2e", worst);
  transform_grid_destroy(&g);
  return test_finish("test_integral_exp_switch");
}
