/* Stam's FFT stable-fluid solver (Stam 2001, "A Simple Fluid Solver based on the FFT",
 * J. Graphics Tools 6(2):43-52) with wind forcing and density transport. See fluid.h. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sim/fluid_internal.h"
#include "sim/fluid_wisdom.h"

static const double two_pi = 6.283185307179586476925286766559;

fluid_sim_desc fluid_sim_desc_default(int width, int height) {
  return (fluid_sim_desc){.width = width, .height = height, .dt = 1.0f / 30.0f,
                          .turbulence_scale = 0.25f * (float)(width < height ? width : height),
                          .turbulence_slope = -5.0 / 3.0, .wind_coupling = 2.0f, .seed = 1,
                          .advection = FLUID_ADVECT_MONOTONE_CUBIC,
                          .fft_planning = FLUID_FFT_REPRODUCIBLE};
}

static int resolve_desc(const fluid_sim_desc *in, fluid_sim_desc *d, fog_error *err) {
  *d = *in;
  if (d->advection == FLUID_ADVECT_DEFAULT) d->advection = FLUID_ADVECT_MONOTONE_CUBIC;
  if (d->width < 8 || d->height < 8 || (d->width & 1) || (d->height & 1)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fluid sim: grid %dx%d: width and height must be even and at least 8", d->width,
             d->height);
    return 1;
  }
  if (!(d->dt > 0) || !isfinite(d->dt))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fluid sim: dt must be positive and finite");
  if (!(d->viscosity >= 0) || !isfinite(d->viscosity))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fluid sim: viscosity must be >= 0 and finite");
  if (!(d->relaxation >= 0) || !isfinite(d->relaxation) || !(d->dissipation >= 0) ||
      !isfinite(d->dissipation))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "fluid sim: relaxation and dissipation must be >= 0 and finite");
  if (!(d->wind_coupling >= 0) || !isfinite(d->wind_coupling))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "fluid sim: wind_coupling must be >= 0 (0: none) and finite");
  if (d->advection != FLUID_ADVECT_BILINEAR && d->advection != FLUID_ADVECT_MONOTONE_CUBIC &&
      d->advection != FLUID_ADVECT_MACCORMACK && d->advection != FLUID_ADVECT_MACCORMACK_BILINEAR)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "fluid sim: advection must be one of the fluid_advection values");
  if (d->fft_planning != FLUID_FFT_REPRODUCIBLE &&
      d->fft_planning != FLUID_FFT_MEASURED_WISDOM)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "fluid sim: fft_planning must be one of the fluid_fft_planning values");
  if (d->emitter_count < 0 || (d->emitter_count > 0 && !d->emitters))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "fluid sim: emitter_count > 0 needs an emitters array");
  for (int e = 0; e < d->emitter_count; e++) {
    const fluid_emitter *em = &d->emitters[e];
    if (!(fabsf(em->x) <= FLUID_MAX_REACH) || !(fabsf(em->z) <= FLUID_MAX_REACH) ||
        !(em->radius > 0) || !(em->radius <= FLUID_MAX_REACH) || !(em->rate >= 0) ||
        !isfinite(em->rate)) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
               "fluid sim: emitter %d: position within %g cells, radius > 0 and at most that, "
               "rate >= 0 and finite", e, FLUID_MAX_REACH);
      return 1;
    }
  }
  if (d->base && (d->base->width != d->width || d->base->height != d->height)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fluid sim: base fogmap is %dx%d, the grid is %dx%d",
             d->base->width, d->base->height, d->width, d->height);
    return 1;
  }
  return 0;
}

/* The per-step tables of sim->desc (create, set_params). Fourier space: viscosity,
 * Stam 2001 §3 multiplies each mode by exp(-k^2 nu dt) (exact for the diffusion
 * equation), k = 2 pi m / N per cell; it is separable, so two 1D tables replace an exp
 * per mode. The projection uses the central-difference symbol sin(2 pi m / N) (see
 * fluid_fourier_step). Then the exact per-step gains of the wind coupling, relaxation
 * and dissipation. */
static void step_tables(fluid_sim *sim) {
  const fluid_sim_desc *d = &sim->desc;
  const int w = sim->width, h = sim->height;
  for (int i = 0; i < sim->modes_x; i++) {
    double k = two_pi * i / w;
    sim->viscous_x[i] = (float)exp(-k * k * d->viscosity * d->dt);
    sim->symbol_x[i] = wind_symbol(i, w);
  }
  for (int j = 0; j < h; j++) {
    int m = j <= h / 2 ? j : j - h;
    double k = two_pi * m / h;
    sim->viscous_z[j] = (float)exp(-k * k * d->viscosity * d->dt);
    sim->symbol_z[j] = wind_symbol(m, h);
  }
  sim->coupling_gain = d->wind_coupling > 0 ? (float)(1.0 - exp(-d->wind_coupling * d->dt)) : 0;
  sim->relax_gain = (float)(1.0 - exp(-(double)d->relaxation * d->dt));
  sim->keep = (float)exp(-(double)d->dissipation * d->dt);
}

void fluid_sim_destroy(fluid_sim *sim) {
  if (!sim) return;
  if (sim->forward) fftwf_destroy_plan(sim->forward);
  if (sim->inverse) fftwf_destroy_plan(sim->inverse);
  wind_field_destroy(sim->wind);
  float *buffers[] = {sim->arena, sim->spectrum, sim->base, sim->emission, sim->scratch,
                      sim->viscous_x, sim->viscous_z, sim->symbol_x, sim->symbol_z};
  for (size_t b = 0; b < sizeof buffers / sizeof *buffers; b++) fftwf_free(buffers[b]);
  fftwf_free(sim->emitters);
  fftwf_free(sim);
}

fluid_sim *fluid_sim_create(const fluid_sim_desc *in, fog_error *err) {
  fluid_sim_desc d;
  if (resolve_desc(in, &d, err)) return NULL;
  fluid_sim *sim = fftwf_malloc(sizeof *sim);
  if (!sim) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "fluid sim: out of memory");
    return NULL;
  }
  const int w = d.width, h = d.height, mx = w / 2 + 1;
  const size_t n = (size_t)w * h, modes = (size_t)mx * h;
  *sim = (fluid_sim){.width = w, .height = h, .modes_x = mx};
  /* Every array comes from fftwf_malloc: FFTW picks SIMD codelets by alignment, and the
   * same alignment every run is part of getting the same plan every run. */
  /* ADVECT_ARRAY_PAD is 17 cache lines, so every array stays 64-byte aligned. */
  sim->stride = (long)n + ADVECT_ARRAY_PAD;
  sim->mode_stride = (long)modes + ADVECT_ARRAY_PAD / 2;
  sim->arena = fftwf_malloc(6 * (size_t)sim->stride * sizeof(float));
  sim->spectrum = fftwf_malloc(4 * (size_t)sim->mode_stride * sizeof(float));
  sim->scratch = fftwf_malloc((size_t)advect_scratch_floats(w, h, 3) * sizeof(float));
  if (sim->arena) {
    sim->velocity = sim->arena;
    sim->advected = sim->arena + 2 * sim->stride;
    sim->density[0] = sim->arena + 4 * sim->stride;
    sim->density[1] = sim->arena + 5 * sim->stride;
  }
  sim->viscous_x = fftwf_malloc(mx * sizeof(float));
  sim->viscous_z = fftwf_malloc(h * sizeof(float));
  sim->symbol_x = fftwf_malloc(mx * sizeof(float));
  sim->symbol_z = fftwf_malloc(h * sizeof(float));
  if (d.base) sim->base = fftwf_malloc(n * sizeof(float));
  if (d.emitter_count) sim->emitters = fftwf_malloc(d.emitter_count * sizeof(fluid_emitter));
  if (!sim->arena || !sim->spectrum || !sim->scratch || !sim->viscous_x || !sim->viscous_z ||
      !sim->symbol_x || !sim->symbol_z || (d.base && !sim->base) ||
      (d.emitter_count && !sim->emitters)) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "fluid sim: out of memory for %dx%d", w, h);
    fluid_sim_destroy(sim);
    return NULL;
  }
  if (d.emitter_count) memcpy(sim->emitters, d.emitters, d.emitter_count * sizeof *d.emitters);
  if (d.base) {
    /* Sanitise: the density is never negative, NaN or infinite. */
    for (size_t c = 0; c < n; c++) {
      sim->base[c] = fluid_clean_density(d.base->density[c]);
    }
  }
  d.emitters = sim->emitters;
  d.base = NULL;
  sim->desc = d;

  step_tables(sim);

  sim->wind = wind_field_create(
      &(wind_desc){.width = w, .height = h, .drift_x = d.wind_drift_x,
                   .drift_z = d.wind_drift_z, .turbulence = d.turbulence,
                   .scale = d.turbulence_scale, .slope = d.turbulence_slope, .seed = d.seed},
      err);
  if (!sim->wind || fluid_emission_build(sim, err)) {
    fluid_sim_destroy(sim);
    return NULL;
  }

  /* Plans, made once. Two fields per plan (howmany = 2) so one execute transforms u and
   * v. FFTW_ESTIMATE chooses from the problem alone; FFTW_MEASURE times candidates and
   * can choose differently run to run (and wisdom made by MEASURE is used even by
   * ESTIMATE requests), so the reproducible mode forgets any wisdom first. */
  unsigned flags = FFTW_ESTIMATE;
  if (d.fft_planning == FLUID_FFT_MEASURED_WISDOM) {
    fluid_wisdom_load();
    flags = FFTW_MEASURE;
  } else {
    fftwf_forget_wisdom();
  }
  const int dims[2] = {h, w};
  sim->forward = fftwf_plan_many_dft_r2c(2, dims, 2, sim->advected, NULL, 1, (int)sim->stride,
                                         (fftwf_complex *)sim->spectrum, NULL, 1,
                                         (int)sim->mode_stride, flags);
  sim->inverse = fftwf_plan_many_dft_c2r(2, dims, 2, (fftwf_complex *)sim->spectrum, NULL, 1,
                                         (int)sim->mode_stride, sim->velocity, NULL, 1,
                                         (int)sim->stride, flags);
  if (!sim->forward || !sim->inverse) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fluid sim: FFTW could not plan %dx%d", w, h);
    fluid_sim_destroy(sim);
    return NULL;
  }
  if (d.fft_planning == FLUID_FFT_MEASURED_WISDOM) fluid_wisdom_save();
  fluid_sim_reset(sim); /* after planning: FFTW_MEASURE overwrites the arrays */
  return sim;
}

int fluid_sim_set_params(fluid_sim *sim, const fluid_sim_desc *in, fog_error *err) {
  fluid_sim_desc d;
  if (resolve_desc(in, &d, err)) return 1;
  const fluid_sim_desc *now = &sim->desc;
  /* What the buffers, plans or turbulence phases were made for stays. */
  const char *fixed = NULL;
  if (d.width != now->width || d.height != now->height)
    fixed = "width and height";
  else if ((d.seed ? d.seed : 1) != (now->seed ? now->seed : 1))
    fixed = "seed";
  else if (d.emitter_count != now->emitter_count)
    fixed = "emitter_count";
  else if (d.fft_planning != now->fft_planning)
    fixed = "fft_planning";
  else if (d.base)
    fixed = "base (must be NULL: the base fogmap stays)";
  if (fixed) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fluid sim: %s cannot change in place; create a new sim", fixed);
    return 1;
  }
  /* The wind checks its part before changing anything, so a refusal leaves the sim as
   * it was. */
  if (wind_field_set(sim->wind,
                     &(wind_desc){.width = d.width, .height = d.height,
                                  .drift_x = d.wind_drift_x, .drift_z = d.wind_drift_z,
                                  .turbulence = d.turbulence, .scale = d.turbulence_scale,
                                  .slope = d.turbulence_slope, .seed = d.seed},
                     err))
    return 1;
  /* The state stays: density as it is, velocity as it is except its mean, which the
   * solver keeps equal to the drift (fluid_fourier_step), so the new drift advects from
   * the next step on. Unchanged drift: the velocity is untouched, bit for bit. */
  const float shift_x = d.wind_drift_x - now->wind_drift_x;
  const float shift_z = d.wind_drift_z - now->wind_drift_z;
  if (shift_x != 0 || shift_z != 0) {
    const size_t n = (size_t)sim->width * sim->height;
    for (size_t c = 0; c < n; c++) {
      sim->velocity[c] += shift_x;
      sim->velocity[sim->stride + c] += shift_z;
    }
  }
  if (d.emitter_count && d.emitters != sim->emitters)
    memcpy(sim->emitters, d.emitters, d.emitter_count * sizeof *d.emitters);
  d.emitters = sim->emitters;
  d.seed = now->seed;
  sim->desc = d;
  step_tables(sim);
  fluid_emission_fill(sim);
  return 0;
}

void fluid_sim_reset(fluid_sim *sim) {
  const size_t n = (size_t)sim->width * sim->height;
  for (size_t c = 0; c < n; c++) {
    sim->velocity[c] = sim->desc.wind_drift_x;
    sim->velocity[sim->stride + c] = sim->desc.wind_drift_z;
  }
  if (sim->base)
    memcpy(sim->density[0], sim->base, n * sizeof(float));
  else
    memset(sim->density[0], 0, n * sizeof(float));
  sim->current = 0;
  sim->density_view = (fogmap){sim->width, sim->height, sim->density[0]};
  wind_field_reset(sim->wind);
  sim->time = 0;
  sim->steps = 0;
}

/* The Fourier-space part of Stam 2001 §3 on the advected velocity (u^, v^), per mode:
 *  - k = 0 (the mean flow) := the wind drift;
 *  - the turbulence forcing, a relaxation of the fluctuations toward the synthesised wind
 *    w^: u^ += g (w^ - u^), g = 1 - exp(-coupling dt) (exact for du/dt = c (w - u));
 *  - viscosity: u^ *= exp(-nu k^2 dt);
 *  - projection onto divergence-free fields, u^ -= k~ (k~ . u^) / |k~|^2 (Stam's
 *    "u0 = (1 - x*x/r) U - x*y/r V" with his exact k replaced by the central-difference
 *    symbol k~ = sin k, so the result is divergence-free for the grid's central
 *    difference as well as spectrally in that symbol);
 *  - Nyquist modes (sin k~ = 0 there, invisible to central differences) are removed;
 *  - FFTW's unnormalised round trip scales by W H: divide here, once. */
static void fluid_fourier_step(fluid_sim *sim) {
  const int w = sim->width, h = sim->height, mx = sim->modes_x;
  const size_t modes = (size_t)mx * h;
  const float inv_n = 1.0f / ((float)w * (float)h);
  const float g = sim->coupling_gain;
  const wind_field *wind = sim->wind;
  float *restrict su = sim->spectrum, *restrict sv = sim->spectrum + 2 * sim->mode_stride;
  const float *restrict ax = wind->amplitude_x, *restrict az = wind->amplitude_z;
  const float *restrict ph = wind->phasor;
  for (int j = 0; j < h; j++) {
    const float kz = sim->symbol_z[j], vz = sim->viscous_z[j];
    const size_t row = (size_t)j * mx;
    if (j == h / 2) {
      memset(su + 2 * row, 0, 2 * mx * sizeof(float));
      memset(sv + 2 * row, 0, 2 * mx * sizeof(float));
      continue;
    }
    for (int i = 0; i < mx - 1; i++) { /* i = mx - 1 is the x Nyquist column */
      const size_t m = row + i;
      const float kx = sim->symbol_x[i];
      float ur = su[2 * m], ui = su[2 * m + 1], vr = sv[2 * m], vi = sv[2 * m + 1];
      /* Wind forcing (a divergence-free force: w^ is perpendicular to k~). */
      const float wr = ph[2 * m], wi = ph[2 * m + 1];
      ur += g * (ax[m] * wr - ur);
      ui += g * (ax[m] * wi - ui);
      vr += g * (az[m] * wr - vr);
      vi += g * (az[m] * wi - vi);
      const float k2 = kx * kx + kz * kz;
      const float f = sim->viscous_x[i] * vz * inv_n;
      if (k2 > 0) {
        const float inv_k2 = 1.0f / k2;
        const float dr = (kx * ur + kz * vr) * inv_k2, di = (kx * ui + kz * vi) * inv_k2;
        ur -= kx * dr;
        ui -= kx * di;
        vr -= kz * dr;
        vi -= kz * di;
      }
      su[2 * m] = f * ur;
      su[2 * m + 1] = f * ui;
      sv[2 * m] = f * vr;
      sv[2 * m + 1] = f * vi;
    }
    su[2 * (row + mx - 1)] = su[2 * (row + mx - 1) + 1] = 0;
    sv[2 * (row + mx - 1)] = sv[2 * (row + mx - 1) + 1] = 0;
  }
  /* The mean flow is the drift, exactly (forces with a non-zero mean are discarded:
   * on a periodic domain they would accelerate the whole fluid forever). */
  su[0] = sim->desc.wind_drift_x;
  su[1] = 0;
  sv[0] = sim->desc.wind_drift_z;
  sv[1] = 0;
  /* A decaying flow must not end in subnormal floats (x86 arithmetic on them is ~100x
   * slower): flush tiny coefficients. A separate loop that gcc vectorises (inside the
   * loop above the test cost a mispredicted branch per value), every 64 steps: from
   * 1e-20 a mode needs hundreds of steps of damping to reach the subnormal range. */
  if (sim->steps % 64 == 0) {
    for (size_t c = 0; c < 2 * modes; c++) su[c] = fluid_flush_tiny(su[c]);
    for (size_t c = 0; c < 2 * modes; c++) sv[c] = fluid_flush_tiny(sv[c]);
  }
}

static void advect_state(fluid_sim *sim) {
  const long n = sim->stride;
  const advect_pass pass = {.width = sim->width, .height = sim->height,
                            .velocity_x = sim->velocity, .velocity_z = sim->velocity + n,
                            .dt = sim->desc.dt, .scheme = (advect_scheme)sim->desc.advection,
                            .scratch = sim->scratch};
  const float *src[3] = {sim->velocity, sim->velocity + n, sim->density[sim->current]};
  float *dst[3] = {sim->advected, sim->advected + n, sim->density[1 - sim->current]};
  advect_fields(&pass, 3, src, dst);
}

int fluid_sim_step(fluid_sim *sim, fog_error *err) {
  if (!sim)
    return err ? fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fluid sim: step of a NULL sim") : 1;
  /* Self-advection of the velocity and transport of the density by the same
   * divergence-free velocity u^n, traced once (Stam 2001 §3 "advect"). */
  advect_state(sim);
  sim->current = 1 - sim->current;
  fftwf_execute(sim->forward);
  fluid_fourier_step(sim); /* uses the wind at time t^n */
  fftwf_execute(sim->inverse);
  wind_field_advance(sim->wind, sim->desc.dt);
  fluid_density_sources(sim, sim->density[sim->current]);
  sim->density_view.density = sim->density[sim->current];
  sim->time += sim->desc.dt;
  sim->steps++;
  return 0;
}

const fogmap *fluid_sim_density(const fluid_sim *sim) { return &sim->density_view; }
const float *fluid_sim_velocity_x(const fluid_sim *sim) { return sim->velocity; }
const float *fluid_sim_velocity_z(const fluid_sim *sim) {
  return sim->velocity + sim->stride;
}
const fluid_sim_desc *fluid_sim_settings(const fluid_sim *sim) { return &sim->desc; }
double fluid_sim_time(const fluid_sim *sim) { return sim->time; }
long fluid_sim_step_count(const fluid_sim *sim) { return sim->steps; }
wind_field *fluid_sim_wind(fluid_sim *sim) { return sim->wind; }

void fluid_sim_profile_transforms(fluid_sim *sim) {
  fftwf_execute(sim->forward);
  fftwf_execute(sim->inverse);
}

void fluid_sim_profile_advection(fluid_sim *sim) { advect_state(sim); }
