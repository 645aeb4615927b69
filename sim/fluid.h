/* The fluid simulation: Stam's FFT stable-fluid solver on a periodic 2D grid driving a
 * fog density field. (Part of the sim library; include "sim/sim.h".)
 *
 * Velocity (Stam 2001, "A Simple Fluid Solver based on the FFT", J. Graphics Tools 6(2)):
 * each step adds forces, advects the velocity semi-Lagrangianly, then in Fourier space
 * applies viscosity and projects onto divergence-free fields. The wind (sim/wind.h) sets
 * the mean flow (the constant drift) and pulls the fluctuating velocity toward the
 * synthesised turbulence (a drag toward the ambient wind, see wind_coupling).
 * Density (a fogmap): advected by the same velocity with the chosen scheme
 * (sim/advect.h), then sources (emitters, painted strokes), relaxation toward a base
 * fogmap and dissipation. The density is never negative and never NaN.
 *
 * Units: lengths in cells (cell (x, z) at the integer point (x, z), fogmap layout
 * density[z * width + x]), time in seconds, velocity in cells per second. The domain is
 * periodic: what leaves one side enters the other.
 *
 * Determinism: fixed time step, our own seeded RNG (sim/fluid_rng.h), one thread and
 * FFTW plans chosen without measuring (FFTW_ESTIMATE, the default): the same desc gives
 * bit-identical frames run after run on the same build and machine. See fft_planning.
 *
 * Lifecycle: fluid_sim_create (allocates, plans) -> fluid_sim_step per dt (never
 * allocates), fluid_sim_paint / fluid_sim_add_impulse / fluid_sim_set_params between
 * steps -> fluid_sim_reset -> fluid_sim_destroy. */
#ifndef FOGPIPE_SIM_FLUID_H
#define FOGPIPE_SIM_FLUID_H

#include <stdbool.h>
#include <stdint.h>

#include "sim/advect.h"
#include "sim/fogmap.h"
#include "sim/wind.h"

typedef enum fluid_advection {
  /* FLUID_ADVECT_MONOTONE_CUBIC: nearly MacCormack's accuracy (better at small CFL) for
   * about 0.55 of its cost a step (docs/simulation.md). */
  FLUID_ADVECT_DEFAULT = 0,
  FLUID_ADVECT_BILINEAR = ADVECT_BILINEAR,
  FLUID_ADVECT_MONOTONE_CUBIC = ADVECT_MONOTONE_CUBIC,
  FLUID_ADVECT_MACCORMACK = ADVECT_MACCORMACK, /* BFECC in MacCormack form, limited */
  FLUID_ADVECT_MACCORMACK_BILINEAR = ADVECT_MACCORMACK_BILINEAR,
} fluid_advection;

typedef enum fluid_fft_planning {
  /* FFTW_ESTIMATE, no wisdom read or written: the plan depends only on the size, the
   * build and the CPU, so results are reproducible whatever the cache holds. */
  FLUID_FFT_REPRODUCIBLE = 0,
  /* Import wisdom from $XDG_CACHE_HOME/fogpipe/fftw3f.wisdom (or
   * ~/.cache/fogpipe/fftw3f.wisdom), plan with FFTW_MEASURE (instant when the wisdom
   * has the size), export the wisdom back (temp file + rename; read or write failures
   * are ignored). Faster plans, but the first run of a size (no wisdom yet) may pick a
   * different plan than later runs, so frames are reproducible only once the wisdom
   * file holds the size. */
  FLUID_FFT_MEASURED_WISDOM = 1,
} fluid_fft_planning;

/* A Gaussian emitter: adds rate * dt * exp(-r^2 / (2 radius^2)) density per step (cut
 * at 4 radii; tabulated at create and again by fluid_sim_set_params). */
/* Positions and radii of emitters, strokes and impulses: within 1e6 cells of the grid's
 * origin (a source wraps around the periodic grid; past this its cell span overflowed an
 * int: a radius of 3.75e8 covered no cell). Impulses: at most 1e12 cells/s a component. */
#define FLUID_MAX_REACH 1e6
#define FLUID_MAX_IMPULSE 1e12

typedef struct fluid_emitter {
  float x, z;   /* centre, cells */
  float radius; /* Gaussian sigma, cells (> 0) */
  float rate;   /* density per second at the centre (>= 0) */
} fluid_emitter;

/* A painted brush stroke along the segment (x0,z0)-(x1,z1): adds
 * amount * (1 - (d/radius)^2)^2 where d < radius (d: distance to the segment); a
 * negative amount erases, the result clamped at 0. */
typedef struct fluid_stroke {
  float x0, z0, x1, z1;
  float radius; /* cells, > 0 */
  float amount; /* density at the centre line; negative erases */
  /* true: cells past the grid's edges are left alone (a brush at the fog box's edge paints
   * only inside it); false: they wrap around, as the periodic fluid does */
  bool within_grid;
} fluid_stroke;

/* Start from fluid_sim_desc_default(width, height), which sets every field, and change
 * what differs: each physical value is taken as given (0 viscosity is inviscid, 0
 * coupling a free fluid, 0 slope a flat spectrum), never read as "use the default". */
typedef struct fluid_sim_desc {
  int width, height;     /* grid; both even and >= 8 */
  float dt;              /* fixed step, seconds; > 0 */
  float viscosity;       /* kinematic, cells^2 per second; 0: inviscid */
  float wind_drift_x;    /* the mean flow, cells per second */
  float wind_drift_z;
  float turbulence;      /* rms speed of the synthesised turbulence, cells/s; 0: none */
  float turbulence_scale;/* largest eddy wavelength, cells; > 4 (with turbulence > 0) */
  double turbulence_slope; /* energy spectrum exponent, -20 to 20; -5/3 is Kolmogorov's */
  float wind_coupling;   /* rate (1/s) at which the fluid's fluctuations relax toward the
                            turbulence; >= 0, 0: no coupling (a free fluid) */
  uint64_t seed;         /* turbulence phases; 0 means 1 */
  fluid_advection advection;
  const fluid_emitter *emitters; /* copied at create */
  int emitter_count;
  float relaxation;      /* rate (1/s) toward the base fogmap; 0: none */
  float dissipation;     /* rate (1/s) of exponential decay; 0: none */
  /* Optional base fogmap (same size as the grid): the initial density and the target of
   * relaxation. Copied (NaN and negative values become 0); NULL: starts empty. */
  const fogmap *base;
  fluid_fft_planning fft_planning;
} fluid_sim_desc;

typedef struct fluid_sim fluid_sim;

/* Every field set: the given grid, dt 1/30 s, no viscosity, wind or sources, turbulence
 * shaped (should it be turned on) with its largest eddies a quarter of the shorter side,
 * Kolmogorov's -5/3 slope and a coupling of 2 per second, seed 1, monotone cubic
 * advection, reproducible FFT plans, no relaxation, dissipation or base. */
fluid_sim_desc fluid_sim_desc_default(int width, int height);

/* Validates the desc, allocates every buffer and makes the FFTW plans. NULL on error
 * (err says which field is wrong). */
fluid_sim *fluid_sim_create(const fluid_sim_desc *desc, fog_error *err);
void fluid_sim_destroy(fluid_sim *sim);
/* Changes the per-step parameters between steps, keeping the state (density, velocity,
 * time, turbulence phases): dt, viscosity, the wind (drift, turbulence, its scale and
 * slope, coupling), advection scheme, the emitters (same count: positions, radii, rates),
 * relaxation and dissipation. Never allocates, never replans FFTW. The velocity keeps
 * its fluctuations; its mean becomes the new drift (the solver holds the mean flow at
 * the drift), so the new drift is what advects from the next step on. The base fogmap
 * stays (desc->base must be NULL). width, height, seed, emitter_count and fft_planning
 * are fixed at create: a desc that changes one is refused with err naming the field, as
 * is an invalid desc (as fluid_sim_create); a refused call leaves the sim untouched.
 * Returns 0 on success. fluid_sim_reset then goes back to the base with the new
 * parameters. */
int fluid_sim_set_params(fluid_sim *sim, const fluid_sim_desc *desc, fog_error *err);
/* Back to the state after create: density = base (or 0), velocity = the drift, time 0,
 * initial turbulence phases. */
void fluid_sim_reset(fluid_sim *sim);

/* Advances one fixed step dt. Never allocates; returns 0 (non-zero only for a NULL sim).
 * Order: advect (u, v, density) by the current velocity in one fused pass; to Fourier
 * space; mean flow := drift, relax toward the turbulence, viscosity, projection; back;
 * then the density's emitters, relaxation, dissipation and clamp. */
int fluid_sim_step(fluid_sim *sim, fog_error *err);

/* Paints a stroke into the density now (clamped at 0). Non-finite values or a
 * non-positive radius are rejected (returns non-zero, density untouched). */
int fluid_sim_paint(fluid_sim *sim, const fluid_stroke *stroke, fog_error *err);
/* Adds a Gaussian velocity impulse (sigma `radius`, peak (du, dv) cells/s) now; the next
 * step projects it to its divergence-free part. Non-finite input is rejected. */
int fluid_sim_add_impulse(fluid_sim *sim, float x, float z, float radius, float du, float dv,
                          fog_error *err);

/* Accessors, valid until the next step/paint/reset. */
const fogmap *fluid_sim_density(const fluid_sim *sim);
const float *fluid_sim_velocity_x(const fluid_sim *sim); /* width*height, cells/s */
const float *fluid_sim_velocity_z(const fluid_sim *sim);
const fluid_sim_desc *fluid_sim_settings(const fluid_sim *sim); /* defaults resolved */
double fluid_sim_time(const fluid_sim *sim);
long fluid_sim_step_count(const fluid_sim *sim);
wind_field *fluid_sim_wind(fluid_sim *sim);

/* Profiling hooks for `fogpipe bench sim`: run exactly the FFTW plans one step executes
 * (forward r2c of u, v and inverse c2r of them), or exactly its fused advection pass, on
 * the sim's own buffers. They scramble the velocity: call fluid_sim_reset afterwards. */
void fluid_sim_profile_transforms(fluid_sim *sim);
void fluid_sim_profile_advection(fluid_sim *sim);

#endif
