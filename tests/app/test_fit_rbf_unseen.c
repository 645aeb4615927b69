/* fit_views_rbf_amplitudes (app/fit_views.h) re-fits Gaussian banks' amplitudes on the
 * views' optical depths. A Gaussian the views see is fitted: on rays through a reference
 * Gaussian of amplitude 0.1, the same Gaussian started at 0.05 comes out at 0.1. A Gaussian
 * the views hardly see (its depth ~1e-80 along every ray) keeps the amplitude it came with:
 * the views cannot say what it should be, and a solve step gave it ~1e80 (`fit` listed
 * rungs of c = 9.9e80 with --rays 4 --samples 8). */
#include <math.h>
#include <stdio.h>

#include "app/fit_views.h"
#include "render/fog_models.h"
#include "test_util.h"

enum { RAYS = 4 };

int main(void) {
  const fog_rbf reference = {.centre = {0, 0, 0}, .radius = 10.0, .density = 0.1};
  double origin[RAYS][3], dir[RAYS][3], length[RAYS], tau[RAYS];
  for (int k = 0; k < RAYS; k++) {
    /* along +x, at heights and depths within a radius of the centre */
    origin[k][0] = -100.0, origin[k][1] = -6.0 + 4.0 * k, origin[k][2] = 2.0 * k - 3.0;
    dir[k][0] = 1.0, dir[k][1] = 0.0, dir[k][2] = 0.0;
    length[k] = 200.0;
    tau[k] = exp(-fog_rbf_optical_depth(0.0, &reference, 1, origin[k], dir[k], length[k]));
  }
  const fit_views views = {.count = RAYS, .origin = origin, .dir = dir, .length = length,
                           .reference = tau};
  fog_rbf bank[2] = {
      {.centre = {0, 0, 0}, .radius = 10.0, .density = 0.05},
      /* 96 units from the rays, radius 5: exp(-96^2 / 50) ~ 1e-80 of its peak on them */
      {.centre = {0, 0, 96}, .radius = 5.0, .density = 0.3},
  };
  double unseen_depth = 0.0;
  for (int k = 0; k < RAYS; k++) {
    fog_rbf one = bank[1];
    unseen_depth = fmax(unseen_depth, fog_rbf_optical_depth(0.0, &one, 1, origin[k], dir[k],
                                                            length[k]));
  }
  CHECK(unseen_depth > 0.0 && unseen_depth < 1e-60,
        "the far Gaussian's depth on the rays is %g, not a tiny positive number", unseen_depth);
  CHECK(fit_views_rbf_amplitudes(&views, 1, bank, 2) == 0, "the solve failed");
  CHECK(fabs(bank[0].density - 0.1) < 1e-6, "the seen Gaussian: amplitude %.9g, expected 0.1",
        bank[0].density);
  CHECK(bank[1].density == 0.3, "the unseen Gaussian: amplitude %g, expected its 0.3 kept",
        bank[1].density);
  return test_finish("test_fit_rbf_unseen");
}
