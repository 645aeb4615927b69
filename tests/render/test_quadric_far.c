/* A quadric volume seen from far away (fog_quadric_optical_depth, the CPU twin the tests,
 * fit and the sun's volume use): a hard unit sphere of density 1 holds optical depth
 * 2 sqrt(1 - p^2) along a ray passing p from its centre, whatever the distance of the ray's
 * origin. The depth was taken from Q at the origin, whose terms are (distance / size)^2 and
 * cancel: 7.8e-4 off at 1e6, 7.6e-2 at 1e7 (a legal config's scale). Within 1e-8 now. */
#include <math.h>
#include <stdio.h>

#include "render/render.h"
#include "test_util.h"

int main(void) {
  const double centre[3] = {0.0, 0.0, 0.0};
  const fog_quadric sphere = fog_quadric_sphere(centre, 1.0, 1.0, 0.0);
  const double distances[] = {10.0, 1e4, 1e5, 1e6, 1e7};
  const double offsets[] = {0.0, 0.3, 0.6, 0.9};
  double worst = 0.0;
  for (int i = 0; i < 5; i++)
    for (int k = 0; k < 4; k++) {
      const double o[3] = {-distances[i], offsets[k], 0.0}, d[3] = {1.0, 0.0, 0.0};
      const double depth = fog_quadric_optical_depth(&sphere, 1, NULL, o, d, INFINITY);
      const double exact = 2.0 * sqrt(1.0 - offsets[k] * offsets[k]);
      const double error = fabs(depth - exact) / exact;
      worst = fmax(worst, error);
      CHECK(error <= 1e-8, "from %g away, %g off centre: depth %.15g, exact %.15g",
            distances[i], offsets[k], depth, exact);
    }
  printf("a unit sphere from 10 to 1e7 away: worst relative depth error %.2e\n", worst);
  return test_finish("test_quadric_far");
}
