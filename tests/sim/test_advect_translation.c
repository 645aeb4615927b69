/* Uniform wind through the whole simulation: a blob must move by exactly dt·v·steps,
 * wrapping around the periodic domain. (1) A displacement of a whole number of cells per
 * step: every scheme must reproduce the analytic, shifted and wrapped blob to float
 * rounding. (2) A fractional displacement: bilinear's centroid must land on the analytic
 * position and its mass must stay (its weights sum to one in every cell); the clamped
 * schemes' centroids within a bound; every other scheme must beat bilinear against the
 * analytic blob. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim/sim.h"
#include "test_util.h"

enum { N = 128 };

/* The periodic Gaussian centred at (cx, cz): the sum over the nearest images. */
static double periodic_blob(double x, double z, double cx, double cz, double sigma) {
  double sum = 0;
  for (int iz = -1; iz <= 1; iz++)
    for (int ix = -1; ix <= 1; ix++) {
      double dx = x - cx + ix * N, dz = z - cz + iz * N;
      sum += exp(-(dx * dx + dz * dz) / (2 * sigma * sigma));
    }
  return sum;
}

static double wrap_distance(double a, double b) {
  double d = fmod(a - b, (double)N);
  if (d > N / 2) d -= N;
  if (d < -N / 2) d += N;
  return d;
}

/* The density's first moment about the expected centre (xe, ze), distances wrapped to
 * [-N/2, N/2): the centroid's offset from the analytic position. Exact for a blob much
 * narrower than the domain. */
static double centroid_miss(const float *rho, double xe, double ze) {
  double mx = 0, mz = 0, m = 0;
  for (int z = 0; z < N; z++)
    for (int x = 0; x < N; x++) {
      double r = rho[z * N + x];
      mx += r * wrap_distance(x, xe), mz += r * wrap_distance(z, ze), m += r;
    }
  return hypot(mx / m, mz / m);
}

static double run(fluid_advection scheme, float vx, float vz, float dt, int steps, double x0,
                  double z0, double *max_error, double *l2, double *mass_drift) {
  fog_error err;
  fogmap base;
  fogmap_create(&base, N, N, &err);
  const double sigma = 4;
  *max_error = *l2 = *mass_drift = 1e9;
  double mass0 = 0;
  for (int z = 0; z < N; z++)
    for (int x = 0; x < N; x++) {
      base.density[z * N + x] = (float)periodic_blob(x, z, x0, z0, sigma);
      mass0 += base.density[z * N + x];
    }
  fluid_sim_desc desc = fluid_sim_desc_default(N, N);
  desc.dt = dt, desc.wind_drift_x = vx, desc.wind_drift_z = vz;
  desc.advection = scheme, desc.base = &base;
  fluid_sim *sim = fluid_sim_create(&desc, &err);
  CHECK(sim != NULL, "fluid_sim_create: %s", err.message);
  fogmap_destroy(&base);
  if (!sim) return 1e9;
  for (int s = 0; s < steps; s++) fluid_sim_step(sim, &err);
  const float *rho = fluid_sim_density(sim)->density;
  /* The analytic answer: displaced by dt·v·steps (in double), wrapped. */
  const double xe = x0 + (double)dt * vx * steps, ze = z0 + (double)dt * vz * steps;
  double num = 0, den = 0, mass = 0;
  *max_error = 0;
  for (int z = 0; z < N; z++)
    for (int x = 0; x < N; x++) {
      double exact = periodic_blob(x, z, fmod(xe, N), fmod(ze, N), sigma);
      double e = rho[z * N + x] - exact;
      num += e * e, den += exact * exact, mass += rho[z * N + x];
      if (fabs(e) > *max_error) *max_error = fabs(e);
    }
  *l2 = sqrt(num / den);
  *mass_drift = fabs(mass - mass0) / mass0;
  double miss = centroid_miss(rho, xe, ze);
  fluid_sim_destroy(sim);
  return miss;
}

int main(void) {
  const fluid_advection schemes[4] = {FLUID_ADVECT_BILINEAR, FLUID_ADVECT_MONOTONE_CUBIC,
                                      FLUID_ADVECT_MACCORMACK,
                                      FLUID_ADVECT_MACCORMACK_BILINEAR};
  const char *names[4] = {"bilinear", "cubic", "maccormack", "maccormack-bilinear"};
  double l2_fraction[4];
  for (int s = 0; s < 4; s++) {
    double max_error, l2, drift;
    /* (1) 2 cells per step in x, -1 in z; 75 steps: 150 cells, across the seam. */
    double miss =
        run(schemes[s], 60.0f, -30.0f, 1.0f / 30.0f, 75, 20, 44, &max_error, &l2, &drift);
    printf("%-20s whole cells: centroid miss %.2e  max error %.2e  mass drift %.2e\n",
           names[s], miss, max_error, drift);
    CHECK(max_error <= 2e-4, "%s: whole-cell shift max error %g", names[s], max_error);
    CHECK(miss <= 1e-3, "%s: whole-cell shift centroid missed by %g cells", names[s], miss);
    /* (2) 0.2433 and 0.1367 cells per step; 300 steps = (73.0, 41.0) cells, from
     * (100, 110) across both seams to (45, 23). */
    miss = run(schemes[s], 7.3f, 4.1f, 1.0f / 30.0f, 300, 100, 110, &max_error, &l2, &drift);
    l2_fraction[s] = l2;
    printf("%-20s fractional:  centroid miss %.2e  L2 rel error %.4f  mass drift %.2e\n",
           names[s], miss, l2, drift);
    if (schemes[s] == FLUID_ADVECT_BILINEAR) {
      /* Bilinear under a uniform shift is linear and its weights (1 - a, a) have mean a:
       * the first moment moves exactly, the mass is exactly conserved. */
      CHECK(miss <= 1e-3, "bilinear: fractional shift centroid missed by %g cells", miss);
      /* 1.2e-5 measured after 300 steps: float rounding of the state (~4e-8 per step). */
      CHECK(drift <= 5e-5, "bilinear mass drift under uniform flow %g", drift);
    } else {
      /* The limiters clip undershoots behind the blob (adding mass there) and the peak,
       * so the clamped schemes' centroid lags a little: bounded, not exact (measured:
       * cubic 0.096, maccormack 0.14, maccormack-bilinear 0.47 cells after 84 cells). */
      double bound = schemes[s] == FLUID_ADVECT_MACCORMACK_BILINEAR ? 0.6 : 0.2;
      CHECK(miss <= bound, "%s: fractional shift centroid missed by %g cells", names[s], miss);
    }
  }
  CHECK(l2_fraction[0] > l2_fraction[1] && l2_fraction[0] > l2_fraction[2] &&
        l2_fraction[0] > l2_fraction[3],
        "bilinear (%.4f) should be the least accurate: cubic %.4f maccormack %.4f "
        "maccormack-bilinear %.4f", l2_fraction[0], l2_fraction[1], l2_fraction[2],
        l2_fraction[3]);
  return test_finish("test_advect_translation");
}
