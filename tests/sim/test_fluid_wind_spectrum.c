/* The synthesised turbulence (sim/wind.h) against a double-precision DFT: it is
 * divergence-free (spectrally, for the central-difference symbol the solver uses, and by
 * real-space central differences), its rms speed is the one requested, it has no energy
 * outside the band, and its shell-summed energy spectrum follows the requested slope
 * (least-squares fit in log-log) — for Kolmogorov's -5/3, for -3 and for 0 (flat). Also
 * after the phases have advanced (the animation keeps all of this). Small grids take no
 * turbulence without refusing the simulation, and a scale whose band holds no wave of the
 * grid is refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fluid_test_dft.h"
#include "sim/sim.h"
#include "test_util.h"

enum { N = 256 };

static void check_wind(float slope, float scale, int advance_steps) {
  fog_error err;
  const float turbulence = 12.0f;
  wind_field *wind = wind_field_create(
      &(wind_desc){.width = N, .height = N, .drift_x = 3.0f, .drift_z = -1.0f,
                   .turbulence = turbulence, .scale = scale, .slope = slope, .seed = 42},
      &err);
  CHECK(wind != NULL, "wind_field_create: %s", err.message);
  if (!wind) return;
  for (int s = 0; s < advance_steps; s++) wind_field_advance(wind, 1.0f / 30.0f);
  float *u = malloc(sizeof(float) * N * N), *v = malloc(sizeof(float) * N * N);
  wind_field_velocity(wind, u, v);
  double mean_u = 0, mean_v = 0, speed2 = 0;
  for (int c = 0; c < N * N; c++) mean_u += u[c], mean_v += v[c];
  mean_u /= N * N, mean_v /= N * N;
  for (int c = 0; c < N * N; c++)
    speed2 += (u[c] - mean_u) * (u[c] - mean_u) + (v[c] - mean_v) * (v[c] - mean_v);
  double rms = sqrt(speed2 / (N * N));
  CHECK(fabs(mean_u - 3.0) < 1e-4 && fabs(mean_v + 1.0) < 1e-4, "drift %g %g", mean_u, mean_v);
  CHECK(fabs(rms - turbulence) < 1e-3 * turbulence, "rms speed %g, asked %g", rms, turbulence);

  double *ur = malloc(sizeof(double) * N * N), *ui = malloc(sizeof(double) * N * N);
  double *vr = malloc(sizeof(double) * N * N), *vi = malloc(sizeof(double) * N * N);
  dft2_real(u, N, N, ur, ui);
  dft2_real(v, N, N, vr, vi);
  double div_spectral = spectral_divergence_rel(ur, ui, vr, vi, N, N);
  double div_fd = fd_divergence_rel(u, v, N, N);
  printf("slope %.3f: rms %.5f  divergence spectral %.2e  central-difference %.2e\n", slope,
         rms, div_spectral, div_fd);
  CHECK(div_spectral <= 1e-5, "spectral divergence %g", div_spectral);
  CHECK(div_fd <= 1e-5, "central-difference divergence %g", div_fd);

  /* Shell sums of |U|^2 + |V|^2 over integer shells of |m| (cycles per domain). */
  double shell[N] = {0}, outside = 0, total = 0;
  const int k_lo = (int)ceil(N / scale), k_hi = N / 4;
  for (int kz = 0; kz < N; kz++)
    for (int kx = 0; kx < N; kx++) {
      if (!kx && !kz) continue;
      double k = hypot(dft_signed(kx, N), dft_signed(kz, N));
      int m = kz * N + kx;
      double e = ur[m] * ur[m] + ui[m] * ui[m] + vr[m] * vr[m] + vi[m] * vi[m];
      total += e;
      if (k < N / scale - 1e-9 || k > k_hi + 1e-9) outside += e;
      int b = (int)floor(k + 0.5);
      if (b < N) shell[b] += e;
    }
  CHECK(outside <= 1e-10 * total, "energy outside the band: %g of %g", outside, total);
  /* Least squares of log E against log k over the shells fully inside the band. */
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int count = 0;
  for (int b = k_lo + 1; b <= k_hi - 1; b++) {
    double x = log((double)b), y = log(shell[b]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, count++;
  }
  double fit = (count * sxy - sx * sy) / (count * sxx - sx * sx);
  printf("  fitted spectrum slope %.4f over shells %d..%d (asked %.4f)\n", fit, k_lo + 1,
         k_hi - 1, slope);
  CHECK(fabs(fit - slope) <= 0.05, "fitted slope %.4f, asked %.4f", fit, slope);
  free(u), free(v), free(ur), free(ui), free(vr), free(vi);
  wind_field_destroy(wind);
}

/* Small grids: the default scale (a quarter of the shorter side, 2 to 4 cells on 8 to 16)
 * is no reason to refuse a simulation without turbulence, and its wind is the drift alone;
 * with turbulence such a scale is refused, and so is a scale with no wave of the grid in
 * its band (10 x 10, scale 4.2: 12 cells/s of turbulence came out as none at all). */
static void check_small_grids(void) {
  for (int n = 8; n <= 16; n += 2) {
    fog_error err = {0};
    fluid_sim_desc d = fluid_sim_desc_default(n, n + 4);
    d.turbulence = 0.0f;
    fluid_sim *sim = fluid_sim_create(&d, &err);
    CHECK(sim != NULL, "%dx%d without turbulence (scale %g): %s", n, n + 4,
          (double)d.turbulence_scale, err.message);
    if (sim) fluid_sim_destroy(sim);
    wind_field *wind = wind_field_create(
        &(wind_desc){.width = n, .height = n, .drift_x = 2.0f, .scale = 0.25f * n}, &err);
    CHECK(wind != NULL, "wind %dx%d without turbulence: %s", n, n, err.message);
    if (wind) {
      float u[16 * 16], v[16 * 16];
      wind_field_advance(wind, 0.5f);
      wind_field_velocity(wind, u, v);
      int off = 0;
      for (int c = 0; c < n * n; c++)
        off += !(fabsf(u[c] - 2.0f) < 1e-6f && fabsf(v[c]) < 1e-6f);
      CHECK(off == 0, "wind %dx%d without turbulence: %d cells are not the drift", n, n, off);
      wind_field_destroy(wind);
    }
    wind = wind_field_create(
        &(wind_desc){.width = n, .height = n, .turbulence = 5.0f, .scale = 0.25f * n}, &err);
    CHECK(!wind && strstr(err.message, "expected more than 4"), "%dx%d, turbulence, scale %g: "
          "%s", n, n, 0.25 * n, wind ? "accepted" : err.message);
    if (wind) wind_field_destroy(wind);
  }
  fog_error err = {0};
  wind_field *wind = wind_field_create(
      &(wind_desc){.width = 10, .height = 10, .turbulence = 12.0f, .scale = 4.2f}, &err);
  CHECK(!wind && strstr(err.message, "no wave of the grid"), "10x10, scale 4.2: %s",
        wind ? "accepted (no eddy to drive)" : err.message);
  if (wind) wind_field_destroy(wind);
}

int main(void) {
  check_small_grids();
  check_wind(-5.0f / 3.0f, 64.0f, 0);
  check_wind(-5.0f / 3.0f, 64.0f, 100); /* animated: phases advanced 100 steps */
  check_wind(-3.0f, 32.0f, 10);
  check_wind(0.0f, 32.0f, 0); /* slope 0 is a flat spectrum, not "the default slope" */
  return test_finish("test_fluid_wind_spectrum");
}
