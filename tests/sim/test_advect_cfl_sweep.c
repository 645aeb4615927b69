/* CFL sweep 0.5 ... 20: every scheme, many steps, on a rough field (random values and a
 * sharp-edged square) in a periodic divergence-free cellular flow; then the whole
 * simulation in strong turbulence at large time steps. Nothing may become NaN, and the
 * monotone schemes (all four here are limited) never go above the initial maximum nor
 * below the initial minimum (0). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim/fluid_rng.h"
#include "sim/sim.h"
#include "test_util.h"

enum { N = 64, STEPS = 150 };

int main(void) {
  const double pi = 3.14159265358979323846;
  float *vx = malloc(sizeof(float) * N * N), *vz = malloc(sizeof(float) * N * N);
  float *init = malloc(sizeof(float) * N * N), *a = malloc(sizeof(float) * N * N);
  float *b = malloc(sizeof(float) * N * N);
  float *scratch = malloc(sizeof(float) * advect_scratch_floats(N, N, 1));
  /* Cellular flow from the stream function psi = sin(2 pi x / L) sin(2 pi z / L) / k,
   * u = d psi / dz, w = -d psi / dx: periodic, divergence-free, max speed 1. */
  const double k = 2 * pi / 32.0;
  fluid_rng rng = {99};
  float max0 = 0;
  for (int z = 0; z < N; z++)
    for (int x = 0; x < N; x++) {
      vx[z * N + x] = (float)(sin(k * x) * cos(k * z));
      vz[z * N + x] = (float)(-cos(k * x) * sin(k * z));
      float v = (float)fluid_rng_uniform(&rng);
      if (x >= 20 && x < 36 && z >= 10 && z < 26) v = 3.0f;
      init[z * N + x] = v;
      if (v > max0) max0 = v;
    }
  const double cfls[] = {0.5, 1, 2, 5, 10, 20};
  const advect_scheme schemes[4] = {ADVECT_BILINEAR, ADVECT_MONOTONE_CUBIC, ADVECT_MACCORMACK,
                                    ADVECT_MACCORMACK_BILINEAR};
  for (int s = 0; s < 4; s++)
    for (size_t c = 0; c < sizeof cfls / sizeof *cfls; c++) {
      /* dt * max|u| = CFL cells per step. */
      advect_pass pass = {.width = N, .height = N, .velocity_x = vx, .velocity_z = vz,
                          .dt = (float)cfls[c], .scheme = schemes[s], .scratch = scratch};
      for (int i = 0; i < N * N; i++) a[i] = init[i];
      float lo = INFINITY, hi = -INFINITY;
      int nans = 0;
      for (int step = 0; step < STEPS; step++) {
        const float *src[1] = {a};
        float *dst[1] = {b};
        advect_fields(&pass, 1, src, dst);
        float *t = a;
        a = b, b = t;
        for (int i = 0; i < N * N; i++) {
          if (isnan(a[i])) nans++;
          if (a[i] < lo) lo = a[i];
          if (a[i] > hi) hi = a[i];
        }
      }
      CHECK(nans == 0, "scheme %d CFL %g: %d NaN", (int)schemes[s], cfls[c], nans);
      CHECK(lo >= 0.0f, "scheme %d CFL %g: below 0: %g", (int)schemes[s], cfls[c], lo);
      CHECK(hi <= max0, "scheme %d CFL %g: above the initial max %g: %.9g", (int)schemes[s],
            cfls[c], max0, hi);
    }

  /* The full simulation at large steps: turbulence rms 40 cells/s, dt 0.05..0.5 s
   * (CFL ~2-20 and more at the gusts), no sources: density stays in [0, max0]. */
  fog_error err;
  fogmap base;
  fogmap_create(&base, N, N, &err);
  for (int i = 0; i < N * N; i++) base.density[i] = init[i];
  const float dts[] = {0.0125f, 0.05f, 0.125f, 0.25f, 0.5f};
  const fluid_advection fschemes[3] = {FLUID_ADVECT_BILINEAR, FLUID_ADVECT_MONOTONE_CUBIC,
                                       FLUID_ADVECT_MACCORMACK};
  for (int s = 0; s < 3; s++)
    for (size_t d = 0; d < sizeof dts / sizeof *dts; d++) {
      fluid_sim_desc desc = fluid_sim_desc_default(N, N);
      desc.dt = dts[d], desc.turbulence = 40.0f, desc.turbulence_scale = 32.0f;
      desc.seed = 5, desc.advection = fschemes[s], desc.base = &base;
      fluid_sim *sim = fluid_sim_create(&desc, &err);
      CHECK(sim != NULL, "create: %s", err.message);
      if (!sim) continue;
      int bad = 0;
      float lo = INFINITY, hi = -INFINITY;
      for (int step = 0; step < 100; step++) {
        fluid_sim_step(sim, &err);
        const float *rho = fluid_sim_density(sim)->density;
        const float *u = fluid_sim_velocity_x(sim), *v = fluid_sim_velocity_z(sim);
        for (int i = 0; i < N * N; i++) {
          if (!isfinite(rho[i]) || !isfinite(u[i]) || !isfinite(v[i])) bad++;
          if (rho[i] < lo) lo = rho[i];
          if (rho[i] > hi) hi = rho[i];
        }
      }
      CHECK(bad == 0, "sim scheme %d dt %g: %d non-finite values", (int)fschemes[s], dts[d],
            bad);
      CHECK(lo >= 0.0f && hi <= max0, "sim scheme %d dt %g: density range [%g, %g]",
            (int)fschemes[s], dts[d], lo, hi);
      fluid_sim_destroy(sim);
    }
  fogmap_destroy(&base);
  free(vx), free(vz), free(init), free(a), free(b), free(scratch);
  return test_finish("test_advect_cfl_sweep");
}
