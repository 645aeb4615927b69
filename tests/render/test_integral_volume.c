/* The volume model's CPU integrals (fog_models.h, FOG_MODEL_VOLUME: a dense grid,
 * trilinear, zero beyond its outer voxels), exact (3D DDA, two Gauss nodes per lattice
 * cell) and marched, against integrals known independently:
 *   - a linear density a + b.u is reproduced exactly by trilinear interpolation inside the
 *     grid, and both the Gauss nodes and the midpoint rule are exact for it: random rays
 *     that stay inside agree with L (a + b.u(L/2)) to rounding, through a placement that
 *     permutes, scales and flips the axes (a Z-up VDB seen Y-up);
 *   - a random grid along random rays, in and out of it, finite and to infinity: the exact
 *     walk against composite Simpson with 20000 panels (the trilinear field is piecewise
 *     cubic: Simpson's kinks error ~1e-8), and the march converging to it as the step falls;
 *   - one voxel of density 1 alone is a tent of half-width one voxel along an index axis:
 *     the ray through its centre integrates to one voxel's length;
 *   - a ray that misses the grid, or ends before it, integrates to 0;
 *   - the light gathered per lattice cell (fog_grid3d_light_integral: S = int tau K T_s)
 *     with 1, 2 and 3 nodes against the light reference's S (tests/reference/
 *     volume_reference.h: the voxels' trilinear density and its breaks, listed; T_s by
 *     nested quadrature towards the sun, the same T_s handed to the walk): the error falls
 *     with the nodes (2 nodes within 2e-3 of S on voxels thick enough that tau curves within
 *     a cell). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "reference/volume_reference.h"
#include "render/fog_models.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { NX = 12, NY = 9, NZ = 10 };

/* The test's placement, written out: index (x / 0.5 - 20, -z / 0.5 - 10, y / 0.25 - 8). */
static void index_position(const double p[3], double u[3]) {
  u[0] = 2.0 * p[0] - 20.0, u[1] = -2.0 * p[2] - 10.0, u[2] = 4.0 * p[1] - 8.0;
}
static void index_direction(const double d[3], double u[3]) {
  u[0] = 2.0 * d[0], u[1] = -2.0 * d[2], u[2] = 4.0 * d[1];
}

/* The model's K at world point p, from its definition: trilinear between voxel centres,
 * zero beyond the grid. */
static double trilinear(const float *values, const double p[3]) {
  double u[3], k = 0.0;
  index_position(p, u);
  int base[3] = {(int)floor(u[0]), (int)floor(u[1]), (int)floor(u[2])};
  const int dim[3] = {NX, NY, NZ};
  for (int corner = 0; corner < 8; corner++) {
    double w = 1.0;
    int idx[3], inside = 1;
    for (int c = 0; c < 3; c++) {
      int o = (corner >> c) & 1;
      idx[c] = base[c] + o;
      w *= o ? u[c] - base[c] : 1.0 - (u[c] - base[c]);
      inside &= idx[c] >= 0 && idx[c] < dim[c];
    }
    if (inside) k += w * values[(idx[2] * NY + idx[1]) * NX + idx[0]];
  }
  return k;
}

static int compare_doubles(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}


/* Light per lattice cell against the reference (see the header). */
static void check_light(void) {
  enum { LX = 12, LY = 8, LZ = 10 };
  static float values[LX * LY * LZ];
  for (int i = 0; i < LX * LY * LZ; i++) values[i] = (float)fog_test_range(0.0, 0.25);
  volume_grid_desc g = {.dim = {LX, LY, LZ}, .values = values,
                        .index_from_world = {{0.5, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 0.5}},
                        .index_offset = {2.0, 1.0, 3.0}};
  light_ref_medium medium = light_ref_volume_medium(&g);
  light_ref_sun_point user = {.medium = &medium, .tol = 1e-10, .sun = {0.5, 0.6, -0.62}};
  fog_test_unit(user.sun);
  double worst[3] = {0, 0, 0}, worst_tau = 0;
  for (int r = 0; r < 4; r++) {
    double o[3] = {-10.0 + 3 * r, 1.0 + r, -12.0}, d[3] = {0.3 + 0.1 * r, 0.05, 1.0};
    fog_test_unit(d);
    double ref_tau, s_ref = light_ref_sun_inscatter(&medium, o, d, HUGE_VAL, user.sun, 1, 1e-10,
                                                    &ref_tau);
    CHECK(s_ref == s_ref && s_ref > 1e-3, "light ray %d: reference S %g", r, s_ref);
    for (int nodes = 1; nodes <= 3; nodes++) {
      double D, S = fog_grid3d_light_integral(&g, o, d, HUGE_VAL, nodes, HUGE_VAL,
                                              light_ref_sun_point_light, &user, &D);
      worst[nodes - 1] = fmax(worst[nodes - 1], fabs(S - s_ref) / s_ref);
      if (nodes == 2) worst_tau = fmax(worst_tau, fabs(exp(-D) - ref_tau));
    }
  }
  printf("light per cell vs the reference's S: 1 node %.2e, 2 nodes %.2e, 3 nodes %.2e "
         "(relative); the 2-node walk's tau %.2e off\n", worst[0], worst[1], worst[2],
         worst_tau);
  CHECK(worst[1] < worst[0] && worst[2] <= worst[1] * 1.01, "no convergence with the nodes: "
        "%.3e %.3e %.3e", worst[0], worst[1], worst[2]);
  /* (measured 1.3e-2, 6.8e-4, 2.1e-4: voxels of up to 0.25 per unit, 2 units long, so a
   * piece's own optical depth reaches 0.5 and tau curves within it) */
  CHECK(worst[1] <= 2e-3 && worst[2] <= 5e-4 && worst_tau <= 1e-9,
        "per-cell light off: 2 nodes %.3e, 3 nodes %.3e, tau %.3e", worst[1], worst[2],
        worst_tau);
}

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
  fog_model m = {.kind = FOG_MODEL_VOLUME, .grid3d = &g};
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
    double marched = fog_grid3d_optical_depth_march(&g, 0.07, cam, dir, L);
    double e = fmax(fabs(got - want), fabs(marched - want)) / want;
    worst = fmax(worst, e);
    CHECK(e <= 1e-6, "ray %d: exact %.12g, march %.12g, linear field %.12g (L %g)", r, got,
          marched, want, L);
  }
  /* float values of a + b.u carry 3e-8 of rounding; the integrators add ~1e-15. */
  printf("linear field, 500 rays inside: worst relative error %.2e\n", worst);

  /* A random grid: the DDA against Simpson's rule on every piece between the ray's
   * crossings of the lattice planes, found independently (all of them listed and sorted,
   * not stepped): the field is a cubic on each piece, where Simpson is exact. */
  for (int i = 0; i < NX * NY * NZ; i++) values[i] = (float)fog_test_range(0.0, 1.0);
  double worst_exact = 0.0, march_error[3] = {0, 0, 0};
  for (int r = 0; r < 200; r++) {
    double cam[3] = {fog_test_range(8, 18), fog_test_range(1, 5), fog_test_range(-12, -3)};
    double dir[3] = {fog_test_range(-1, 1), fog_test_range(-1, 1), fog_test_range(-1, 1)};
    fog_test_unit(dir);
    double L = (r % 3 == 0) ? HUGE_VAL : fog_test_range(0.5, 12.0);
    double got = fog_model_optical_depth(&m, cam, dir, L);
    double reach = fmin(L, 40.0); /* every ray leaves the grid within ~20 units */
    double breaks[512];
    int count = 0;
    breaks[count++] = 0.0;
    breaks[count++] = reach;
    double u0[3], du[3];
    index_position(cam, u0);
    index_direction(dir, du);
    for (int c = 0; c < 3; c++)
      for (int plane = -2; plane <= 14 && du[c] != 0.0; plane++) {
        double t = (plane - u0[c]) / du[c];
        if (t > 0.0 && t < reach && count < 512) breaks[count++] = t;
      }
    qsort(breaks, (size_t)count, sizeof breaks[0], compare_doubles);
    double simpson = 0.0;
    for (int k = 0; k + 1 < count; k++) {
      double a0 = breaks[k], a1 = breaks[k + 1], q[3][3];
      for (int n = 0; n < 3; n++)
        for (int c = 0; c < 3; c++) q[n][c] = cam[c] + (a0 + 0.5 * n * (a1 - a0)) * dir[c];
      simpson += (a1 - a0) / 6.0 *
                 (trilinear(values, q[0]) + 4.0 * trilinear(values, q[1]) + trilinear(values, q[2]));
    }
    double e = fabs(got - simpson) / fmax(simpson, 1e-3);
    worst_exact = fmax(worst_exact, e);
    CHECK(e <= 1e-12, "random grid ray %d: exact %.15g, Simpson per piece %.15g", r, got,
          simpson);
    for (int k = 0; k < 3; k++) {
      double step = 0.4 / (1 << (2 * k)); /* 0.4, 0.1, 0.025 */
      march_error[k] = fmax(march_error[k],
                            fabs(fog_grid3d_optical_depth_march(&g, step, cam, dir, L) - got));
    }
  }
  printf("random grid, 200 rays: exact vs Simpson per piece %.2e relative; march error at "
         "steps 0.4, 0.1, 0.025: %.2e %.2e %.2e\n",
         worst_exact, march_error[0], march_error[1], march_error[2]);
  CHECK(march_error[2] < march_error[1] && march_error[1] < march_error[0] &&
            march_error[2] < 1e-3,
        "the march does not converge to the exact integral");

  /* One voxel alone: the tent along index axis 0 through (5, 4, 3), from outside the grid. */
  for (int i = 0; i < NX * NY * NZ; i++) values[i] = 0.0f;
  values[(3 * NY + 4) * NX + 5] = 1.0f;
  double cam[3] = {(-3.0 + 20.0) / 2.0, (3.0 + 8.0) / 4.0, -(4.0 + 10.0) / 2.0};
  double along_x[3] = {1.0, 0.0, 0.0};
  double tent = fog_model_optical_depth(&m, cam, along_x, HUGE_VAL);
  printf("single voxel, along x through its centre: %.9f (one voxel: 0.5 world units)\n", tent);
  CHECK(fabs(tent - 0.5) <= 1e-12, "single voxel tent: %.9f, expected 0.5", tent);
  /* Beside it by 1.5 voxels along index axis 1 (world -z): past the tent's support. */
  cam[2] -= 0.75;
  CHECK(fog_model_optical_depth(&m, cam, along_x, HUGE_VAL) == 0.0, "a ray beside the voxel");
  /* Ending before the grid. */
  double back[3] = {-1.0, 0.0, 0.0};
  CHECK(fog_model_optical_depth(&m, cam, back, HUGE_VAL) == 0.0, "a ray away from the grid");
  check_light();
  return test_finish("test_integral_volume");
}
