/* The volume model's CPU march (fog_models.h, FOG_MODEL_VOLUME: a dense grid, trilinear,
 * zero beyond its outer voxels) against integrals known in closed form:
 *   - a linear density a + b.u is reproduced exactly by trilinear interpolation inside the
 *     grid, and the midpoint rule is exact for a linear integrand: random rays that stay
 *     inside agree with L (a + b.u(L/2)) to rounding, through a placement that permutes,
 *     scales and flips the axes (a Z-up VDB seen Y-up);
 *   - one voxel of density 1 alone is a tent of half-width one voxel along an index axis:
 *     the ray through its centre integrates to one voxel's length;
 *   - a ray that misses the grid, or ends before it, integrates to 0. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/fog_models.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { NX = 12, NY = 9, NZ = 10 };

int main(void) {
  static float values[NX * NY * NZ];
  const double a = 0.3, b[3] = {0.02, -0.01, 0.015};
  for (int k = 0; k < NZ; k++)
    for (int j = 0; j < NY; j++)
      for (int i = 0; i < NX; i++)
        values[(k * NY + j) * NX + i] = (float)(a + b[0] * i + b[1] * j + b[2] * k);
  /* Index axis 0 <- world x / 0.5, axis 1 <- world -z / 0.5, axis 2 <- world y / 0.25
   * (a Z-up grid placed Y-up), offsets putting voxel (0,0,0) at world (10, 2, -5). */
  volume_grid_desc g = {.dim = {NX, NY, NZ}, .values = values,
                        .index_from_world = {{2.0, 0.0, 0.0}, {0.0, 0.0, -2.0}, {0.0, 4.0, 0.0}},
                        .index_offset = {-20.0, -10.0, -8.0}};
  fog_model m = {.kind = FOG_MODEL_VOLUME, .grid3d = &g, .grid3d_step = 0.07};
  double worst = 0.0;
  for (int r = 0; r < 500; r++) {
    /* A camera inside the grid's interior, a random direction, a length that stays in. */
    double u[3] = {fog_test_range(0.5, NX - 1.5), fog_test_range(0.5, NY - 1.5),
                   fog_test_range(0.5, NZ - 1.5)};
    double cam[3] = {(u[0] + 20.0) / 2.0, (u[2] + 8.0) / 4.0, -(u[1] + 10.0) / 2.0};
    double dir[3] = {fog_test_range(-1, 1), fog_test_range(-1, 1), fog_test_range(-1, 1)};
    fog_test_unit(dir);
    double du[3] = {2.0 * dir[0], -2.0 * dir[2], 4.0 * dir[1]}, dims[3] = {NX, NY, NZ};
    double L = HUGE_VAL; /* to the interior's edge [0, dim - 1] */
    for (int c = 0; c < 3; c++)
      if (du[c] != 0.0) L = fmin(L, ((du[c] > 0 ? dims[c] - 1.0 : 0.0) - u[c]) / du[c]);
    L *= fog_test_range(0.1, 1.0);
    double mid[3], want;
    for (int c = 0; c < 3; c++) mid[c] = u[c] + 0.5 * L * du[c];
    want = L * (a + b[0] * mid[0] + b[1] * mid[1] + b[2] * mid[2]);
    double got = fog_model_optical_depth(&m, cam, dir, L);
    double e = fabs(got - want) / want;
    worst = fmax(worst, e);
    CHECK(e <= 1e-6, "ray %d: march %.12g, linear field %.12g (L %g)", r, got, want, L);
  }
  /* float values of a + b.u carry 3e-8 of rounding; the march itself adds ~1e-15. */
  printf("linear field, 500 rays inside: worst relative error %.2e\n", worst);

  /* One voxel alone: the tent along index axis 0 through (5, 4, 3), from outside the grid. */
  for (int i = 0; i < NX * NY * NZ; i++) values[i] = 0.0f;
  values[(3 * NY + 4) * NX + 5] = 1.0f;
  double cam[3] = {(-3.0 + 20.0) / 2.0, (3.0 + 8.0) / 4.0, -(4.0 + 10.0) / 2.0};
  double along_x[3] = {1.0, 0.0, 0.0};
  m.grid3d_step = 0.01;
  double tent = fog_model_optical_depth(&m, cam, along_x, HUGE_VAL);
  printf("single voxel, along x through its centre: %.9f (one voxel: 0.5 world units)\n", tent);
  CHECK(fabs(tent - 0.5) <= 1e-4, "single voxel tent: %.9f, expected 0.5", tent);
  /* Beside it by 1.5 voxels along index axis 1 (world -z): past the tent's support. */
  cam[2] -= 0.75;
  CHECK(fog_model_optical_depth(&m, cam, along_x, HUGE_VAL) == 0.0, "a ray beside the voxel");
  /* Ending before the grid. */
  double back[3] = {-1.0, 0.0, 0.0};
  CHECK(fog_model_optical_depth(&m, cam, back, HUGE_VAL) == 0.0, "a ray away from the grid");
  return test_finish("test_integral_volume");
}
