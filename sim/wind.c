/* Spectral wind synthesis (see wind.h). */
#include "sim/wind.h"

#include <fftw3.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "sim/fluid_rng.h"

static const double two_pi = 6.283185307179586476925286766559;

float wind_symbol(int m, int n) { return (float)sin(two_pi * (double)m / (double)n); }

/* Signed integer frequency of FFT index j on an n-point axis. */
static int signed_frequency(int j, int n) { return j <= n / 2 ? j : j - n; }

void wind_field_destroy(wind_field *wind) {
  if (!wind) return;
  if (wind->plan_inverse) fftwf_destroy_plan((fftwf_plan)wind->plan_inverse);
  fftwf_free(wind->amplitude_x);
  fftwf_free(wind->amplitude_z);
  fftwf_free(wind->phasor);
  fftwf_free(wind->initial_phasor);
  fftwf_free(wind->omega);
  fftwf_free(wind->rotation);
  fftwf_free(wind->spectrum);
  fftwf_free(wind->real);
  fftwf_free(wind);
}

/* Whether a mode of the w x h grid lies in the turbulence band (spectrum_tables' rule). */
static bool band_has_mode(int w, int h, double scale) {
  const double k0 = 1.0 / scale, k_max = 0.25;
  for (int j = 0; j < h; j++)
    for (int i = 0; i <= w / 2; i++) {
      const int fz = signed_frequency(j, h);
      const double kx = (double)i / w, kz = (double)fz / h, k = sqrt(kx * kx + kz * kz);
      const double sx = wind_symbol(i, w), sz = wind_symbol(fz, h);
      if (i != w / 2 && j != h / 2 && k >= k0 && k <= k_max && sx * sx + sz * sz > 0)
        return true;
    }
  return false;
}

static int check_desc(const wind_desc *desc, fog_error *err) {
  const int w = desc->width, h = desc->height;
  if (w < 8 || h < 8 || (w & 1) || (h & 1)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "wind grid %dx%d: both sides must be even and at least 8", w, h);
    return 1;
  }
  const double scale = desc->scale, slope = desc->slope;
  /* one message per fault: a list of every rule blamed turbulence on a grid too small */
  if (!isfinite(desc->turbulence) || desc->turbulence < 0)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "wind: turbulence %g: expected >= 0",
                    desc->turbulence);
  /* the scale shapes the eddies only: without turbulence any scale will do (the default, a
   * quarter of the shorter side, is 4 or less on a grid of 16 or less) */
  if (desc->turbulence > 0 && !(scale > 4.0))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "wind: turbulence scale (its largest eddies) %g cells: expected more than "
                    "4 (by default a quarter of the %dx%d grid's shorter side)", scale, w, h);
  if (desc->turbulence > 0 && !band_has_mode(w, h, scale))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "wind: turbulence scale %g cells on the %dx%d grid: no wave of the grid "
                    "lies between that wavelength and 4 cells, so turbulence %g would have "
                    "no eddy to drive (a larger scale, or a larger grid)", scale, w, h,
                    desc->turbulence);
  if (!isfinite(desc->drift_x) || !isfinite(desc->drift_z))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "wind: drift (%g, %g) must be finite",
                    desc->drift_x, desc->drift_z);
  /* |slope| <= 20 (Kolmogorov's -5/3, Kraichnan's -3 well inside): the amplitudes
   * k^((slope - 1)/2), stored as float before their normalisation, overflowed at -64 (every
   * velocity NaN) and a slope of 1000 left no turbulence at all */
  if (!(fabs(slope) <= WIND_MAX_SLOPE))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "wind: slope %g: expected -%g to %g", slope,
                    WIND_MAX_SLOPE, WIND_MAX_SLOPE);
  return 0;
}

/* The mode tables of a checked desc: amplitudes (the spectrum's shape and rms speed),
 * angular frequencies and the drift; with write_phases also the phases at time 0 (the
 * seed's draws). Without it the current phasors stay: wind_field_set. */
static void spectrum_tables(wind_field *wind, const wind_desc *desc, int write_phases) {
  const int w = wind->width, h = wind->height, mx = wind->modes_x;
  const size_t modes = (size_t)mx * h;
  const double scale = desc->scale, slope = desc->slope;
  wind->drift_x = desc->drift_x;
  wind->drift_z = desc->drift_z;
  wind->turbulence = desc->turbulence;

  /* Wavenumbers in cycles per cell; the band runs from the largest eddy to a 4-cell
   * wavelength, well inside Nyquist (2 cells) where sin(k) still tracks k. */
  const double k0 = 1.0 / scale, k_max = 0.25;
  /* one turnover per scale/speed; none without turbulence (then the scale is unchecked) */
  const double omega0 = desc->turbulence > 0 ? two_pi * desc->turbulence * k0 : 0.0;
  fluid_rng rng = {desc->seed ? desc->seed : 1};
  double energy = 0; /* mean |u|^2 in real space before normalisation */
  for (int j = 0; j < h; j++) {
    for (int i = 0; i < mx; i++) {
      const size_t m = (size_t)j * mx + i;
      const int fz = signed_frequency(j, h);
      const double kx = (double)i / w, kz = (double)fz / h;
      const double k = sqrt(kx * kx + kz * kz);
      /* One draw per mode in a fixed order, used or not, so the phases of a mode do not
       * depend on which other modes are in the band. */
      const double phase = two_pi * fluid_rng_uniform(&rng);
      const int nyquist = (i == w / 2) || (j == h / 2);
      const int mirrored = (i == 0 && j > h / 2); /* set from its partner below */
      double ax = 0, az = 0;
      const double sx = wind_symbol(i, w), sz = wind_symbol(fz, h);
      const double s = sqrt(sx * sx + sz * sz);
      if (!nyquist && k >= k0 && k <= k_max && s > 0) {
        /* 2D: modes per shell ∝ k dk, so |u_k|^2 ∝ E(k)/k. The velocity is i k~_perp psi:
         * direction (k~z, -k~x)/|k~| (divergence-free for the k~ symbol), the factor i
         * folded into the random phase. */
        const double magnitude = pow(k, 0.5 * (slope - 1.0));
        ax = magnitude * sz / s;
        az = -magnitude * sx / s;
      }
      wind->amplitude_x[m] = (float)ax;
      wind->amplitude_z[m] = (float)az;
      const double om = omega0 > 0 && k > 0 ? omega0 * pow(k / k0, 2.0 / 3.0) : 0.0;
      wind->omega[m] = (float)(mirrored ? -om : om);
      if (write_phases) {
        wind->initial_phasor[2 * m] = (float)cos(phase);
        wind->initial_phasor[2 * m + 1] = (float)sin(phase);
      }
      if (!mirrored) energy += (i == 0 || i == w / 2 ? 1.0 : 2.0) * (ax * ax + az * az);
    }
  }
  /* The i = 0 column holds both k and -k: Hermitian symmetry needs
   * amplitude(-k) phasor(-k) = conj(amplitude(k) phasor(k)); amplitude is odd in k~,
   * so phasor(-k) = -conj(phasor(k)). Its energy was counted once above: count the
   * partner too. */
  for (int j = h / 2 + 1; j < h; j++) {
    const size_t m = (size_t)j * mx, partner = (size_t)(h - j) * mx;
    wind->amplitude_x[m] = -wind->amplitude_x[partner];
    wind->amplitude_z[m] = -wind->amplitude_z[partner];
    if (write_phases) {
      wind->initial_phasor[2 * m] = -wind->initial_phasor[2 * partner];
      wind->initial_phasor[2 * m + 1] = wind->initial_phasor[2 * partner + 1];
    }
    energy += (double)wind->amplitude_x[m] * wind->amplitude_x[m] +
              (double)wind->amplitude_z[m] * wind->amplitude_z[m];
  }
  /* Parseval with FFTW's unnormalised transform: mean |u|^2 = sum |U_k|^2 / (W H)^2.
   * Scale so the rms speed is desc->turbulence. */
  const double n_cells = (double)w * h;
  const double gain = energy > 0 ? desc->turbulence * n_cells / sqrt(energy) : 0.0;
  for (size_t m = 0; m < modes; m++) {
    wind->amplitude_x[m] = (float)(gain * wind->amplitude_x[m]);
    wind->amplitude_z[m] = (float)(gain * wind->amplitude_z[m]);
  }
  wind->rotation_dt = -1.0f; /* omega may have changed: wind_field_advance recomputes */
}

wind_field *wind_field_create(const wind_desc *desc, fog_error *err) {
  if (check_desc(desc, err)) return NULL;
  const int w = desc->width, h = desc->height;
  wind_field *wind = fftwf_malloc(sizeof *wind);
  if (!wind) goto oom;
  const int mx = w / 2 + 1;
  const size_t modes = (size_t)mx * h;
  *wind = (wind_field){.width = w, .height = h, .modes_x = mx};
  wind->amplitude_x = fftwf_malloc(modes * sizeof(float));
  wind->amplitude_z = fftwf_malloc(modes * sizeof(float));
  wind->phasor = fftwf_malloc(modes * 2 * sizeof(float));
  wind->initial_phasor = fftwf_malloc(modes * 2 * sizeof(float));
  wind->omega = fftwf_malloc(modes * sizeof(float));
  wind->rotation = fftwf_malloc(modes * 2 * sizeof(float));
  wind->spectrum = fftwf_malloc(modes * 2 * 2 * sizeof(float));
  wind->real = fftwf_malloc((size_t)w * h * 2 * sizeof(float));
  if (!wind->amplitude_x || !wind->amplitude_z || !wind->phasor || !wind->initial_phasor ||
      !wind->omega || !wind->rotation || !wind->spectrum || !wind->real)
    goto oom;
  spectrum_tables(wind, desc, 1);

  /* Sampling plan: two c2r transforms in one plan (out of place; c2r destroys its input,
   * so wind_field_velocity fills `spectrum` afresh each call). */
  const int dims[2] = {h, w};
  wind->plan_inverse = fftwf_plan_many_dft_c2r(
      2, dims, 2, (fftwf_complex *)wind->spectrum, NULL, 1, (int)modes, wind->real, NULL, 1,
      w * h, FFTW_ESTIMATE);
  if (!wind->plan_inverse) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "wind: FFTW could not plan %dx%d", w, h);
    wind_field_destroy(wind);
    return NULL;
  }
  wind_field_reset(wind);
  return wind;
oom:
  fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "wind: out of memory for a %dx%d grid", w, h);
  wind_field_destroy(wind);
  return NULL;
}

int wind_field_set(wind_field *wind, const wind_desc *desc, fog_error *err) {
  if (check_desc(desc, err)) return 1;
  if (desc->width != wind->width || desc->height != wind->height) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "wind: grid %dx%d cannot change in place (the field is %dx%d)", desc->width,
             desc->height, wind->width, wind->height);
    return 1;
  }
  spectrum_tables(wind, desc, 0);
  return 0;
}

void wind_field_reset(wind_field *wind) {
  const size_t modes = (size_t)wind->modes_x * wind->height;
  memcpy(wind->phasor, wind->initial_phasor, modes * 2 * sizeof(float));
  wind->time = 0;
  wind->steps = 0;
}

void wind_field_advance(wind_field *wind, float dt) {
  const size_t modes = (size_t)wind->modes_x * wind->height;
  if (dt != wind->rotation_dt) {
    for (size_t m = 0; m < modes; m++) {
      const double a = (double)wind->omega[m] * dt;
      wind->rotation[2 * m] = (float)cos(a);
      wind->rotation[2 * m + 1] = (float)sin(a);
    }
    wind->rotation_dt = dt;
  }
  float *restrict p = wind->phasor;
  const float *restrict r = wind->rotation;
  for (size_t m = 0; m < modes; m++) {
    const float re = p[2 * m] * r[2 * m] - p[2 * m + 1] * r[2 * m + 1];
    const float im = p[2 * m] * r[2 * m + 1] + p[2 * m + 1] * r[2 * m];
    p[2 * m] = re;
    p[2 * m + 1] = im;
  }
  /* Float rounding lets |phasor| random-walk away from 1 (~1e-7 per step); renormalise
   * every 256 steps (deterministically, so runs stay bit-identical). Conjugate partners
   * are renormalised identically, so the i = 0 column stays exactly Hermitian. */
  if (++wind->steps % 256 == 0) {
    for (size_t m = 0; m < modes; m++) {
      const float inv = 1.0f / sqrtf(p[2 * m] * p[2 * m] + p[2 * m + 1] * p[2 * m + 1]);
      p[2 * m] *= inv;
      p[2 * m + 1] *= inv;
    }
  }
  wind->time += dt;
}

void wind_field_velocity(wind_field *wind, float *velocity_x, float *velocity_z) {
  const int w = wind->width, h = wind->height;
  const size_t modes = (size_t)wind->modes_x * h;
  float *sx = wind->spectrum, *sz = wind->spectrum + 2 * modes;
  const float inv_n = 1.0f / ((float)w * (float)h);
  for (size_t m = 0; m < modes; m++) {
    sx[2 * m] = wind->amplitude_x[m] * wind->phasor[2 * m] * inv_n;
    sx[2 * m + 1] = wind->amplitude_x[m] * wind->phasor[2 * m + 1] * inv_n;
    sz[2 * m] = wind->amplitude_z[m] * wind->phasor[2 * m] * inv_n;
    sz[2 * m + 1] = wind->amplitude_z[m] * wind->phasor[2 * m + 1] * inv_n;
  }
  fftwf_execute((fftwf_plan)wind->plan_inverse);
  const size_t n = (size_t)w * h;
  for (size_t c = 0; c < n; c++) {
    velocity_x[c] = wind->real[c] + wind->drift_x;
    velocity_z[c] = wind->real[n + c] + wind->drift_z;
  }
}
