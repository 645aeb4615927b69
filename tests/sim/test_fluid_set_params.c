/* fluid_sim_set_params changes the per-step parameters in place and keeps the state:
 * - set at time 0 from desc A to desc B (wind drift and turbulence, viscosity, coupling,
 *   advection scheme, emitters, relaxation, dissipation all changed), the next steps are
 *   bit-identical to a sim created with B (so every derived table follows the new desc);
 * - the new drift is what advects: a free, inviscid, sourceless fluid with a uniform
 *   drift of 1 cell per step along x carries a periodic pattern 1 cell per step; after a
 *   set to 2 cells per step along -z, the pattern moves that way (the analytic shift,
 *   within 1e-4);
 * - the state stays: the set call leaves the density bit for bit and the velocity's
 *   fluctuations too (an impulse's divergence-free flow), only the mean moves by the drift
 *   change; time and step count stay;
 * - sizes, seed, emitter count, FFT planning and base cannot change (err names the field)
 *   and a refused or invalid desc leaves the sim untouched. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/sim.h"
#include "test_util.h"

enum { N = 64 };
static const double pi = 3.14159265358979323846;

static double pattern(double x, double z) { /* periodic on the N x N grid */
  return 1.0 + 0.5 * sin(2 * pi * x / N) * cos(4 * pi * z / N) + 0.25 * cos(2 * pi * (x + z) / N);
}

static int same_state(const fluid_sim *a, const fluid_sim *b) {
  const size_t bytes = sizeof(float) * N * N;
  return memcmp(fluid_sim_density(a)->density, fluid_sim_density(b)->density, bytes) == 0 &&
         memcmp(fluid_sim_velocity_x(a), fluid_sim_velocity_x(b), bytes) == 0 &&
         memcmp(fluid_sim_velocity_z(a), fluid_sim_velocity_z(b), bytes) == 0;
}

typedef struct snapshot {
  float density[N * N], u[N * N], v[N * N];
} snapshot;

static void take(const fluid_sim *sim, snapshot *s) {
  memcpy(s->density, fluid_sim_density(sim)->density, sizeof s->density);
  memcpy(s->u, fluid_sim_velocity_x(sim), sizeof s->u);
  memcpy(s->v, fluid_sim_velocity_z(sim), sizeof s->v);
}

static int unchanged(const fluid_sim *sim, const snapshot *s) {
  return memcmp(s->density, fluid_sim_density(sim)->density, sizeof s->density) == 0 &&
         memcmp(s->u, fluid_sim_velocity_x(sim), sizeof s->u) == 0 &&
         memcmp(s->v, fluid_sim_velocity_z(sim), sizeof s->v) == 0;
}

int main(void) {
  fog_error err = {0};
  fogmap base;
  fogmap_create(&base, N, N, &err);
  for (int z = 0; z < N; z++)
    for (int x = 0; x < N; x++) base.density[z * N + x] = (float)pattern(x, z);

  /* 1. Set at time 0 == created with the new desc, bit for bit. Drifts are dyadic, so
   * the mean shift 1.5 + (-3.75) lands exactly on -2.25. */
  {
    fluid_emitter ea[2] = {{.x = 10, .z = 12, .radius = 3, .rate = 1},
                           {.x = 40, .z = 50, .radius = 5, .rate = 0.5f}};
    fluid_emitter eb[2] = {{.x = 20, .z = 30, .radius = 2, .rate = 4},
                           {.x = 5, .z = 60, .radius = 6, .rate = 2}};
    fluid_sim_desc a = fluid_sim_desc_default(N, N);
    a.wind_drift_x = 1.5f, a.wind_drift_z = -0.5f, a.seed = 5;
    a.emitters = ea, a.emitter_count = 2, a.dissipation = 0.1f, a.base = &base;
    fluid_sim_desc b = {.width = N, .height = N, .dt = 1.0f / 30, .wind_drift_x = -2.25f,
                        .wind_drift_z = 0.75f, .viscosity = 0.5f, .turbulence = 4.0f,
                        .turbulence_scale = 20.0f, .turbulence_slope = -3.0f,
                        .wind_coupling = 1.0f, .seed = 5, .advection = FLUID_ADVECT_MACCORMACK,
                        .emitters = eb, .emitter_count = 2, .relaxation = 0.1f,
                        .dissipation = 0.02f, .base = &base};
    fluid_sim *set = fluid_sim_create(&a, &err);
    CHECK(set != NULL, "create A: %s", err.message);
    fluid_sim *fresh = fluid_sim_create(&b, &err);
    CHECK(fresh != NULL, "create B: %s", err.message);
    if (set && fresh) {
      fluid_sim_desc b_set = b;
      b_set.base = NULL;
      CHECK(fluid_sim_set_params(set, &b_set, &err) == 0, "set A -> B: %s", err.message);
      CHECK(same_state(set, fresh), "state after the set differs from a sim created with B");
      CHECK(fluid_sim_settings(set)->viscosity == 0.5f &&
                fluid_sim_settings(set)->advection == FLUID_ADVECT_MACCORMACK &&
                fluid_sim_settings(set)->emitters[0].rate == 4,
            "settings do not report the new desc");
      int first_diff = -1;
      for (int s = 0; s < 40 && first_diff < 0; s++) {
        fluid_sim_step(set, &err);
        fluid_sim_step(fresh, &err);
        if (!same_state(set, fresh)) first_diff = s;
      }
      CHECK(first_diff < 0, "set sim and created sim differ from step %d", first_diff);
      /* ...and B really differs from A (else the comparison proves nothing). */
      fluid_sim *plain = fluid_sim_create(&a, &err);
      for (int s = 0; s < 40 && plain; s++) fluid_sim_step(plain, &err);
      CHECK(plain && !same_state(plain, fresh), "desc A and B give the same state");
      fluid_sim_destroy(plain);
    }
    fluid_sim_destroy(set);
    fluid_sim_destroy(fresh);
  }

  /* 2. The new drift advects: dt = 1/32 s, drift 32 cells/s = 1 cell per step along x,
   * then -64 cells/s = 2 cells per step along -z. Integer displacements: the scheme
   * reproduces the shifted samples up to float rounding. */
  {
    fluid_sim_desc d = fluid_sim_desc_default(N, N);
    d.dt = 1.0f / 32, d.wind_drift_x = 32.0f, d.wind_coupling = 0, d.base = &base;
    fluid_sim *sim = fluid_sim_create(&d, &err);
    CHECK(sim != NULL, "create: %s", err.message);
    if (sim) {
      enum { STEPS_A = 5, STEPS_B = 4 };
      for (int s = 0; s < STEPS_A; s++) fluid_sim_step(sim, &err);
      double worst_a = 0, worst_b = 0, worst_u = 0;
      const float *rho = fluid_sim_density(sim)->density;
      for (int z = 0; z < N; z++)
        for (int x = 0; x < N; x++)
          worst_a = fmax(worst_a, fabs(rho[z * N + x] - pattern(x - STEPS_A, z)));
      snapshot before;
      take(sim, &before);
      d.wind_drift_x = 0.0f;
      d.wind_drift_z = -64.0f;
      d.base = NULL;
      CHECK(fluid_sim_set_params(sim, &d, &err) == 0, "set drift: %s", err.message);
      CHECK(memcmp(before.density, fluid_sim_density(sim)->density, sizeof before.density) == 0,
            "the set call changed the density");
      for (int c = 0; c < N * N; c++) {
        worst_u = fmax(worst_u, fabs(fluid_sim_velocity_x(sim)[c] - 0.0));
        worst_u = fmax(worst_u, fabs(fluid_sim_velocity_z(sim)[c] + 64.0));
      }
      CHECK(fluid_sim_step_count(sim) == STEPS_A &&
                fabs(fluid_sim_time(sim) - STEPS_A / 32.0) < 1e-12,
            "the set call changed time or step count");
      for (int s = 0; s < STEPS_B; s++) fluid_sim_step(sim, &err);
      rho = fluid_sim_density(sim)->density;
      for (int z = 0; z < N; z++)
        for (int x = 0; x < N; x++)
          worst_b = fmax(worst_b, fabs(rho[z * N + x] - pattern(x - STEPS_A, z + 2 * STEPS_B)));
      printf("drift x 1 cell/step, %d steps: max error %.2e; after set: velocity - new drift "
             "%.2e; -z 2 cells/step, %d steps: max error %.2e\n",
             STEPS_A, worst_a, worst_u, STEPS_B, worst_b);
      CHECK(worst_a <= 1e-4, "first drift: max error %.3e", worst_a);
      CHECK(worst_u <= 1e-4, "velocity after the set is not the new drift: %.3e", worst_u);
      CHECK(worst_b <= 1e-4, "second drift: max error %.3e from the shifted pattern", worst_b);
    }
    fluid_sim_destroy(sim);
  }

  /* 3. The velocity's fluctuations stay; refusals leave everything as it was. */
  {
    fluid_sim_desc d = fluid_sim_desc_default(N, N);
    d.wind_drift_x = 1.0f, d.wind_coupling = 0, d.seed = 9, d.base = &base;
    fluid_sim *sim = fluid_sim_create(&d, &err);
    CHECK(sim != NULL, "create: %s", err.message);
    if (sim) {
      fluid_sim_add_impulse(sim, 30, 20, 4, 6.0f, -3.0f, &err);
      for (int s = 0; s < 3; s++) fluid_sim_step(sim, &err);
      snapshot before;
      take(sim, &before);
      double spread = 0; /* the impulse made a non-uniform flow */
      for (int c = 0; c < N * N; c++) spread = fmax(spread, fabs(before.u[c] - before.u[0]));
      CHECK(spread > 0.1, "no flow structure to keep (spread %.3e)", spread);

      d.base = NULL;
      d.viscosity = 0.25f;
      d.dissipation = 0.5f;
      CHECK(fluid_sim_set_params(sim, &d, &err) == 0, "set: %s", err.message);
      CHECK(unchanged(sim, &before), "a set with the same drift changed the state");

      d.wind_drift_x = 3.0f;
      d.wind_drift_z = -1.0f;
      CHECK(fluid_sim_set_params(sim, &d, &err) == 0, "set drift: %s", err.message);
      int kept = memcmp(before.density, fluid_sim_density(sim)->density,
                        sizeof before.density) == 0;
      for (int c = 0; c < N * N; c++)
        kept &= fluid_sim_velocity_x(sim)[c] == before.u[c] + 2.0f &&
                fluid_sim_velocity_z(sim)[c] == before.v[c] + -1.0f;
      CHECK(kept, "a drift change did not keep the fluctuations (velocity - mean shift)");

      take(sim, &before);
      /* Each differs from the sim's settings (d) in one field. */
      struct {
        fluid_sim_desc desc;
        const char *field;
      } refused[] = {{d, "width"}, {d, "seed"}, {d, "emitter_count"}, {d, "fft_planning"},
                     {d, "base"},  {d, "viscosity"}, {d, "scale"}, {d, "dt"},
                     {d, "wind_coupling"}};
      refused[0].desc.width = 2 * N;
      refused[1].desc.seed = 10;
      refused[2].desc.emitter_count = 1;
      refused[2].desc.emitters = &(fluid_emitter){.x = 1, .z = 1, .radius = 1, .rate = 1};
      refused[3].desc.fft_planning = FLUID_FFT_MEASURED_WISDOM;
      refused[4].desc.base = &base;
      refused[5].desc.viscosity = -1;
      refused[6].desc.turbulence = 1, refused[6].desc.turbulence_scale = 3;
      refused[7].desc.dt = 0; /* not "the default step": there is none */
      refused[8].desc.wind_coupling = -1;
      for (size_t r = 0; r < sizeof refused / sizeof *refused; r++) {
        err.message[0] = 0;
        int status = fluid_sim_set_params(sim, &refused[r].desc, &err);
        CHECK(status != 0 && strstr(err.message, refused[r].field),
              "changing %s: status %d, message '%s'", refused[r].field, status, err.message);
      }
      CHECK(unchanged(sim, &before), "a refused set changed the state");
      CHECK(fluid_sim_settings(sim)->viscosity == 0.25f &&
                fluid_sim_settings(sim)->wind_drift_x == 3.0f &&
                fluid_sim_settings(sim)->dissipation == 0.5f,
            "a refused set changed the settings");
    }
    fluid_sim_destroy(sim);
  }
  fogmap_destroy(&base);
  return test_finish("test_fluid_set_params");
}
