/* The fluid_sim struct, shared by fluid_solver.c and fluid_sources.c (internal). */
#ifndef FOGPIPE_SIM_FLUID_INTERNAL_H
#define FOGPIPE_SIM_FLUID_INTERNAL_H

#include <fftw3.h>
#include <float.h>
#include <math.h>

#include "sim/fluid.h"
#include "sim/fogmap.h"

struct fluid_sim {
  fluid_sim_desc desc; /* defaults resolved; emitters points at our copy, base is NULL */
  fluid_emitter *emitters;
  int width, height, modes_x;
  /* The per-cell arrays share one block (`arena`), each ADVECT_ARRAY_PAD floats after
   * the previous one ends (see advect.h: power-of-two strides thrash the cache). The
   * FFT plans run on two fields `stride` floats apart (howmany = 2, idist/odist). */
  float *arena;
  long stride;           /* width*height + ADVECT_ARRAY_PAD */
  long mode_stride;      /* complex values between the u and v spectra */
  float *velocity;       /* u at velocity, v at velocity + stride: the c2r output */
  float *advected;       /* the advected velocity, same layout: the r2c input */
  float *spectrum;       /* fftwf_complex: u^ then v^ at spectrum + 2 * mode_stride */
  float *density[2];     /* double-buffered; density[current] is the state */
  int current;
  float *base;         /* sanitised copy of desc.base, or NULL */
  float *emission;     /* density added per step by the emitters, or NULL */
  float *scratch;      /* MacCormack scratch, advect_scratch_floats(w, h, 3) */
  float *viscous_x;    /* exp(-nu dt kx^2), per x mode */
  float *viscous_z;    /* exp(-nu dt kz^2), per z mode */
  float *symbol_x;     /* sin(2 pi i / width): central-difference derivative symbol */
  float *symbol_z;
  float coupling_gain; /* 1 - exp(-coupling dt) */
  float relax_gain;    /* 1 - exp(-relaxation dt) */
  float keep;          /* exp(-dissipation dt) */
  fftwf_plan forward, inverse;
  wind_field *wind;
  fogmap density_view; /* width, height, density[current]; not owning */
  double time;
  long steps;
};

/* Densities below this are set to 0. Diffusing Gaussian tails and exponential decay
 * otherwise fill the grid with subnormal floats, and x86 arithmetic on subnormals is
 * ~100x slower: the advection pass slowed 20-50x in `fogpipe bench sim` before this.
 * 1e-20 per cell is far below anything visible. */
#define FLUID_DENSITY_FLOOR 1e-20f

static inline float fluid_clean_density(float v) {
  /* Comparisons, not fminf/fmaxf (libm calls without -ffast-math). NaN fails v > 0. At
   * most what a loaded fogmap may hold: a baked frame loads back, and the transforms' and
   * the renderer's float sums stay finite. */
  v = v > 0.0f ? v : 0.0f;
  v = v < FOGMAP_MAX_DENSITY ? v : FOGMAP_MAX_DENSITY;
  return v < FLUID_DENSITY_FLOOR ? 0.0f : v;
}

/* Velocity components (or their Fourier coefficients) below this magnitude are set to
 * 0, for the same reason: a decaying flow would otherwise end in subnormals. */
static inline float fluid_flush_tiny(float v) { return fabsf(v) < 1e-20f ? 0.0f : v; }

/* fluid_sources.c: the per-step density update after advection (emission, relaxation,
 * dissipation, clamp) and the emission table made at create (refilled by set_params). */
void fluid_density_sources(fluid_sim *sim, float *density);
int fluid_emission_build(fluid_sim *sim, fog_error *err);
/* Recomputes the emission table (allocated by fluid_emission_build) from sim->emitters
 * and sim->desc.dt; no-op without emitters. */
void fluid_emission_fill(fluid_sim *sim);

#endif
