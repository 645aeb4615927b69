/* The Gaussian RBF fog model (fog_models.h, FOG_MODEL_RBF) against numerical quadrature of
 * its K along the ray: composite 8-node Gauss-Legendre on panels of a quarter of the
 * narrowest radius (a Gaussian is smooth: the rule is exact far below 1e-12 there), over
 * random sets of 1-16 Gaussians, rays that pass through them, graze them and miss them,
 * finite and to infinity; relative error <= 1e-12. And the erf difference where plain erf
 * cancels (both arguments large and of the same sign) against long double. */
#include <math.h>
#include <stdio.h>

#include "render/fog_models.h"
#include "fog_test_scene.h"
#include "test_util.h"

static const double gl8_x[4] = {0.18343464249564980, 0.52553240991632899, 0.79666647741362674,
                                0.96028985649753623};
static const double gl8_w[4] = {0.36268378337836198, 0.31370664587788729, 0.22238103445337447,
                                0.10122853629037626};

static double rbf_k(double base, const fog_rbf *g, int n, const double p[3]) {
  double k = base;
  for (int i = 0; i < n; i++) {
    double r2 = 0.0;
    for (int a = 0; a < 3; a++) r2 += (p[a] - g[i].centre[a]) * (p[a] - g[i].centre[a]);
    k += g[i].density * exp(-r2 / (g[i].radius * g[i].radius));
  }
  return k;
}

static double quadrature(double base, const fog_rbf *g, int n, const double cam[3],
                         const double dir[3], double L) {
  double r_min = HUGE_VAL;
  for (int i = 0; i < n; i++) r_min = fmin(r_min, g[i].radius);
  long panels = (long)ceil(L / (0.25 * r_min));
  double sum = 0.0, h = L / (double)panels;
  for (long p = 0; p < panels; p++) {
    double mid = ((double)p + 0.5) * h;
    for (int i = 0; i < 4; i++)
      for (int s = -1; s <= 1; s += 2) {
        double t = mid + s * 0.5 * h * gl8_x[i], q[3];
        for (int a = 0; a < 3; a++) q[a] = cam[a] + t * dir[a];
        sum += gl8_w[i] * rbf_k(base, g, n, q);
      }
  }
  return sum * 0.5 * h;
}

int main(void) {
  fog_rbf g[16];
  double worst = 0.0, worst_inf = 0.0;
  for (int r = 0; r < 300; r++) {
    int n = 1 + r % 16;
    for (int i = 0; i < n; i++)
      g[i] = (fog_rbf){.centre = {fog_test_range(-40, 40), fog_test_range(0, 30),
                                  fog_test_range(-40, 40)},
                       .radius = fog_test_range(0.5, 15.0),
                       .density = fog_test_range(0.01, 0.3)};
    double cam[3] = {fog_test_range(-60, 60), fog_test_range(-5, 40), fog_test_range(-60, 60)};
    double dir[3];
    if (r % 3 == 0) { /* straight at a Gaussian's centre, or past it by up to 2 radii */
      const fog_rbf *t = &g[r % n];
      for (int a = 0; a < 3; a++)
        dir[a] = t->centre[a] + fog_test_range(-2, 2) * t->radius * (r % 2) - cam[a];
    } else {
      for (int a = 0; a < 3; a++) dir[a] = fog_test_range(-1, 1);
    }
    fog_test_unit(dir);
    double base = (r % 4 == 0) ? 0.0 : fog_test_range(0.0, 0.01);
    double L = fog_test_range(0.5, 150.0);
    fog_model m = {.kind = FOG_MODEL_RBF, .extinction = base, .rbfs = g, .rbf_count = n};
    double got = fog_model_optical_depth(&m, cam, dir, L);
    double want = quadrature(base, g, n, cam, dir, L);
    double e = fabs(got - want) / fmax(want, 1e-300);
    worst = fmax(worst, e);
    CHECK(e <= 1e-12, "ray %d (%d RBFs, L %g): closed form %.15g, quadrature %.15g", r, n, L, got,
          want);
    /* To infinity without a base: the quadrature to beyond every Gaussian (12 radii past
     * the farthest centre, where e^{-144} is left). */
    m.extinction = 0.0;
    double far = 0.0;
    for (int i = 0; i < n; i++) {
      double tc = 0.0;
      for (int a = 0; a < 3; a++) tc += (g[i].centre[a] - cam[a]) * dir[a];
      far = fmax(far, tc + 12.0 * g[i].radius);
    }
    if (far > 0.0) {
      double inf = fog_model_optical_depth(&m, cam, dir, HUGE_VAL);
      double want_inf = quadrature(0.0, g, n, cam, dir, far);
      double ei = fabs(inf - want_inf) / fmax(want_inf, 1e-300);
      worst_inf = fmax(worst_inf, ei);
      CHECK(ei <= 1e-12 || fabs(inf - want_inf) <= 1e-300,
            "ray %d to infinity: %.15g, quadrature to %g: %.15g", r, inf, far, want_inf);
    }
  }
  printf("RBF fog, 300 rays: worst relative error %.2e (to infinity %.2e)\n", worst, worst_inf);
  double cam[3] = {0, 0, 0}, dir[3] = {1, 0, 0};
  fog_model based = {.kind = FOG_MODEL_RBF, .extinction = 0.01, .rbfs = g, .rbf_count = 1};
  CHECK(isinf(fog_model_optical_depth(&based, cam, dir, HUGE_VAL)), "a base to infinity");
  fog_model none = {.kind = FOG_MODEL_RBF};
  CHECK(fog_model_optical_depth(&none, cam, dir, HUGE_VAL) == 0.0, "no fog at all");
  /* A ray whose whole stretch lies 6-7 radii past a Gaussian: plain erf(7) - erf(6) is 0 in
   * double; the erfc form keeps every digit. */
  const double u[4][2] = {{6.0, 7.0}, {-7.0, -6.0}, {3.0, 3.5}, {-0.5, 2.0}};
  for (int k = 0; k < 4; k++) {
    /* erf is odd: on a negative stretch, the mirrored positive one */
    long double ref = u[k][1] <= 0 ? erfcl(-(long double)u[k][1]) - erfcl(-(long double)u[k][0])
                                   : erfcl((long double)u[k][0]) - erfcl((long double)u[k][1]);
    double got = fog_erf_difference(u[k][0], u[k][1]);
    double e = (double)(fabsl(got - ref) / fabsl(ref));
    printf("erf(%g) - erf(%g): %.17g, relative error %.1e (plain erf: %.17g)\n", u[k][1], u[k][0],
           got, e, erf(u[k][1]) - erf(u[k][0]));
    CHECK(e <= 1e-14, "erf difference on [%g, %g]: %.17g vs %.17Lg", u[k][0], u[k][1], got, ref);
  }
  CHECK(erf(7.0) - erf(6.0) == 0.0, "plain erf cancels there (what the erfc form avoids)");
  return test_finish("test_integral_rbf");
}
