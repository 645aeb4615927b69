/* After each step the velocity is divergence-free: checked with a double-precision DFT
 * of the float velocity (spectral divergence for the central-difference symbol
 * sin(2 pi m / N) the projection uses) and with central differences in real space (whose
 * symbol is exactly i sin(k), so the two checks must agree). The flow is made non-trivial
 * by turbulence forcing, drift, viscosity and velocity impulses (which are not
 * divergence-free when added). As a control, the un-projected impulse field itself is
 * shown to fail the same measure. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fluid_test_dft.h"
#include "sim/sim.h"
#include "test_util.h"

enum { W = 128, H = 96 };

static void measure(const float *u, const float *v, double *spectral, double *fd) {
  double *ur = malloc(sizeof(double) * W * H), *ui = malloc(sizeof(double) * W * H);
  double *vr = malloc(sizeof(double) * W * H), *vi = malloc(sizeof(double) * W * H);
  dft2_real(u, W, H, ur, ui);
  dft2_real(v, W, H, vr, vi);
  *spectral = spectral_divergence_rel(ur, ui, vr, vi, W, H);
  *fd = fd_divergence_rel(u, v, W, H);
  free(ur), free(ui), free(vr), free(vi);
}

int main(void) {
  fog_error err;
  const fluid_advection schemes[3] = {FLUID_ADVECT_BILINEAR, FLUID_ADVECT_MONOTONE_CUBIC,
                                      FLUID_ADVECT_MACCORMACK};
  for (int s = 0; s < 3; s++) {
    fluid_sim_desc desc = fluid_sim_desc_default(W, H);
    desc.viscosity = 0.5f, desc.wind_drift_x = 4.0f, desc.wind_drift_z = -2.5f;
    desc.turbulence = 20.0f, desc.seed = 7, desc.advection = schemes[s];
    fluid_sim *sim = fluid_sim_create(&desc, &err);
    CHECK(sim != NULL, "create: %s", err.message);
    if (!sim) continue;
    double worst_spectral = 0, worst_fd = 0;
    for (int step = 0; step < 40; step++) {
      if (step % 10 == 0) {
        /* A non-solenoidal push: a Gaussian blob of x velocity. */
        CHECK(!fluid_sim_add_impulse(sim, 30.0f + step, 50.0f, 6.0f, 40.0f, 10.0f, &err),
              "impulse: %s", err.message);
        if (step == 0 && s == 0) {
          double spectral, fd;
          measure(fluid_sim_velocity_x(sim), fluid_sim_velocity_z(sim), &spectral, &fd);
          printf("control, velocity with an un-projected impulse: divergence %.3g / %.3g\n",
                 spectral, fd);
          CHECK(spectral > 1e-2, "the control should be divergent: %g", spectral);
        }
      }
      fluid_sim_step(sim, &err);
      if (step % 5 == 4) {
        double spectral, fd;
        measure(fluid_sim_velocity_x(sim), fluid_sim_velocity_z(sim), &spectral, &fd);
        if (spectral > worst_spectral) worst_spectral = spectral;
        if (fd > worst_fd) worst_fd = fd;
        CHECK(fabs(spectral - fd) <= 1e-6 + 1e-3 * fd,
              "spectral %g and central-difference %g divergence should agree", spectral, fd);
      }
    }
    printf("scheme %d: worst relative divergence after projection: spectral %.3g, "
           "central-difference %.3g\n", (int)schemes[s], worst_spectral, worst_fd);
    CHECK(worst_spectral <= 1e-5, "spectral divergence %g", worst_spectral);
    CHECK(worst_fd <= 1e-5, "central-difference divergence %g", worst_fd);
    fluid_sim_destroy(sim);
  }
  return test_finish("test_fluid_divergence");
}
