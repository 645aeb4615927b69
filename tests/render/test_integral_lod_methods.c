/* LOD by distance (docs/integral.md): the paper's sum of deconstructed details (A_0 over the
 * whole ray, D_l up to d_l = ||OP|| mu^l) and approximation switching (A_l on
 * (d_{l+1}, d_l]) give the same optical depth for the same mu, on a pyramid where
 * A_l = A_{l-1} + D_l holds as functions; mu = 1 gives the finest grid A_J, mu = 0 the
 * coarsest A_0, both checked against the oracle; at random mu, switching against the
 * oracle over its segments, d_l = ||OP|| mu^l computed here. */
#include <math.h>
#include <stdio.h>

#include "render/fog_field.h"
#include "reference/fog_oracle.h"
#include "fog_test_scene.h"
#include "test_util.h"

int main(void) {
  enum { J = 2 };
  const fog_profile_kind kinds[3] = {FOG_PROFILE_SLAB, FOG_PROFILE_EXPONENTIAL,
                                     FOG_PROFILE_BSPLINE};
  double worst_methods = 0.0, worst_limits = 0.0, worst_mu = 0.0;
  for (int degree = 0; degree <= 2; degree++)
    for (int k = 0; k < 3; k++) {
      transform_grid approx[J + 1], detail[J];
      fog_test_pyramid(degree, J, approx, detail);
      fog_volume v = fog_test_volume(kinds[k]);
      fog_lod lod = {.levels = J, .approx = approx, .detail = detail};
      for (int r = 0; r < 400; r++) {
        double cam[3], dir[3];
        fog_test_ray(&v, cam, dir);
        double t_surface = fog_test_uniform() < 0.5 ? fog_test_range(1.0, 80.0) : HUGE_VAL;
        lod.mu = fog_test_uniform();
        double sum = fog_optical_depth_lod(&v, &lod, FOG_LOD_SUM_OF_DETAILS, cam, dir, t_surface);
        double sw = fog_optical_depth_lod(&v, &lod, FOG_LOD_SWITCH, cam, dir, t_surface);
        /* Float coefficients: A_l = refine(A_{l-1}) + D_l holds to float rounding (1e-7). */
        double e = fabs(sum - sw) / fmax(1.0, fabs(sw));
        if (e > worst_methods) worst_methods = e;
        CHECK(e <= 1e-6 && fabs(exp(-sum) - exp(-sw)) <= 1e-6,
              "degree %d profile %d mu %g: sum of details %.12g, switching %.12g", degree, k,
              lod.mu, sum, sw);
        double op = fog_lod_ray_length(&v, cam, dir, t_surface);
        /* What mu means, against the oracle segment by segment: switching is A_J on
         * [0, d_J], A_l on (d_{l+1}, d_l], A_0 on (d_1, ||OP||], d_l = ||OP|| mu^l (the two
         * methods only agreeing with each other, and at mu = 0 and 1, let any d_l
         * through that is 0 at mu 0 and ||OP|| at mu 1: mu^(2l), say) */
        {
          double want = 0.0, upper = op;
          for (int l = 1; l <= J + 1; l++) {
            const double lower = l <= J ? op * pow(lod.mu, l) : 0.0; /* d_l; 0 past d_J */
            want += fog_optical_depth_oracle(&v, &approx[l - 1], cam, dir, lower, upper,
                                             1e-12, NULL);
            upper = lower;
          }
          const double e = fabs(sw - want) / fmax(1.0, fabs(want));
          if (e > worst_mu) worst_mu = e;
          CHECK(e <= 1e-6, "degree %d profile %d mu %g: switching %.12g, the segments' oracle "
                "%.12g", degree, k, lod.mu, sw, want);
        }
        /* The limits against the oracle on one grid. */
        for (int m = 0; m <= 1; m++) {
          lod.mu = m;
          const transform_grid *g = m ? &approx[J] : &approx[0];
          double want = fog_optical_depth_oracle(&v, g, cam, dir, 0.0, op, 1e-12, NULL);
          for (int method = 0; method <= 1; method++) {
            double got = fog_optical_depth_lod(&v, &lod, method, cam, dir, t_surface);
            double el = fabs(got - want) / fmax(1.0, fabs(want));
            if (el > worst_limits) worst_limits = el;
            CHECK(el <= 1e-6, "degree %d mu %d method %d: %.12g vs oracle %.12g", degree, m,
                  method, got, want);
          }
        }
      }
      for (int l = 0; l <= J; l++) transform_grid_destroy(&approx[l]);
      for (int l = 0; l < J; l++) transform_grid_destroy(&detail[l]);
    }
  printf("worst |sum - switching| (relative) %.2e; worst limit (mu = 0, 1) vs oracle %.2e; "
         "switching at random mu vs the oracle over its segments %.2e\n",
         worst_methods, worst_limits, worst_mu);
  return test_finish("test_integral_lod_methods");
}
