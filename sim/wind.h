/* Wind: a constant drift plus divergence-free turbulence synthesised in Fourier space
 * and animated in time. (Part of the sim library; include "sim/sim.h".)
 *
 * The turbulent velocity is built from a stream function psi, u = (d psi/dz, -d psi/dx),
 * so it is divergence-free by construction. Its modes carry the energy spectrum
 * E(k) ∝ k^slope (Kolmogorov's inertial range: slope -5/3) between the largest eddy
 * (wavelength `scale` cells) and a wavelength of 4 cells, with random phases from a
 * seeded splitmix64. Each mode's phase advances at omega(k) = omega0 (k/k0)^(2/3), the
 * inverse eddy turnover time of Kolmogorov scaling (tau(k) ∝ k^(-2/3)), omega0 being one
 * turnover of the largest eddy per scale/turbulence seconds.
 *
 * Derivatives use the central-difference symbol k~ = sin(2 pi m / N) (per cell), the same
 * one the fluid solver projects with, so the wind's central-difference divergence on the
 * grid is zero to rounding, not only its spectral one. */
#ifndef FOGPIPE_SIM_WIND_H
#define FOGPIPE_SIM_WIND_H

#include <stdint.h>

#include "sim/fogmap.h" /* fog_error */

#define WIND_MAX_SLOPE 20.0

typedef struct wind_desc {
  int width, height;      /* periodic grid, both even and >= 8 */
  float drift_x, drift_z; /* constant wind, cells per second */
  float turbulence;       /* rms speed of the turbulent part, cells per second; 0: none */
  float scale;            /* largest eddy wavelength, cells; > 4 */
  double slope;           /* spectrum exponent of E(k), |slope| <= WIND_MAX_SLOPE: -5/3
                             Kolmogorov's, 0 flat */
  uint64_t seed;          /* 0 means the default seed 1 */
} wind_desc;

/* Read-only to users; the solver reads the mode arrays directly. The r2c half spectrum:
 * mode (i, j), i in [0, width/2], j in [0, height), index j * (width/2 + 1) + i. */
typedef struct wind_field {
  int width, height, modes_x;
  float drift_x, drift_z;
  float turbulence;
  /* Per mode: the turbulent velocity's (unnormalised, FFTW-convention) Fourier
   * coefficients are amplitude_x * phasor and amplitude_z * phasor. */
  float *amplitude_x, *amplitude_z;
  float *phasor;   /* interleaved complex, unit modulus */
  float *initial_phasor; /* the phases at time 0 (wind_field_reset) */
  float *omega;    /* per mode, radians per second (negated on the mirrored half of the
                      i = 0 column so that column stays Hermitian) */
  float *rotation; /* interleaved complex exp(i omega rotation_dt) */
  float rotation_dt;
  long steps;      /* phasor updates since the last renormalisation count */
  double time;
  /* Real-space sampling (wind_field_velocity). */
  void *plan_inverse; /* fftwf_plan */
  float *spectrum;    /* fftwf_complex[2][height][modes_x] */
  float *real;        /* float[2][height][width] */
} wind_field;

/* Allocates the mode tables and the sampling plan (FFTW_ESTIMATE). */
wind_field *wind_field_create(const wind_desc *desc, fog_error *err);
void wind_field_destroy(wind_field *wind);
/* Changes drift, turbulence, scale and slope in place: the amplitudes and frequencies
 * are recomputed, the current phases (and time) kept, nothing allocated. The seed and
 * the grid cannot change (desc->seed is ignored; another size is an error). Returns
 * non-zero with err filled, the field untouched, for a bad desc. */
int wind_field_set(wind_field *wind, const wind_desc *desc, fog_error *err);
/* Back to time 0 with the initial phases. */
void wind_field_reset(wind_field *wind);
/* Advances every phase by omega(k) dt (one complex multiply per mode; the rotations are
 * recomputed only when dt changes, so a fixed step never calls sin/cos). */
void wind_field_advance(wind_field *wind, float dt);
/* The wind velocity (drift + turbulence) at the current time on the grid, cells/s.
 * Runs one inverse FFT pair; never allocates. */
void wind_field_velocity(wind_field *wind, float *velocity_x, float *velocity_z);
/* The central-difference wavenumber of index m on an n-periodic grid, sin(2 pi m/n). */
float wind_symbol(int m, int n);

#endif
