/* A double-precision 2D DFT for the fluid tests: the independent oracle the float FFTW
 * results are checked against (separable, O(N^3), exact twiddles by index mod N). */
#ifndef FOGPIPE_TESTS_FLUID_TEST_DFT_H
#define FOGPIPE_TESTS_FLUID_TEST_DFT_H

#include <math.h>
#include <stdlib.h>

/* out_re/out_im[kz * w + kx] = sum_{z,x} f[z*w+x] exp(-2 pi i (kx x / w + kz z / h)). */
static inline void dft2_real(const float *f, int w, int h, double *out_re, double *out_im) {
  const double two_pi = 6.283185307179586476925286766559;
  double *cw = malloc(sizeof(double) * w), *sw = malloc(sizeof(double) * w);
  double *ch = malloc(sizeof(double) * h), *sh = malloc(sizeof(double) * h);
  double *row_re = malloc(sizeof(double) * w * h), *row_im = malloc(sizeof(double) * w * h);
  for (int i = 0; i < w; i++) cw[i] = cos(two_pi * i / w), sw[i] = sin(two_pi * i / w);
  for (int i = 0; i < h; i++) ch[i] = cos(two_pi * i / h), sh[i] = sin(two_pi * i / h);
  for (int z = 0; z < h; z++)
    for (int kx = 0; kx < w; kx++) {
      double re = 0, im = 0;
      for (int x = 0; x < w; x++) {
        int p = (int)(((long)kx * x) % w);
        re += f[z * w + x] * cw[p];
        im -= f[z * w + x] * sw[p];
      }
      row_re[z * w + kx] = re;
      row_im[z * w + kx] = im;
    }
  for (int kz = 0; kz < h; kz++)
    for (int kx = 0; kx < w; kx++) {
      double re = 0, im = 0;
      for (int z = 0; z < h; z++) {
        int p = (int)(((long)kz * z) % h);
        double a = row_re[z * w + kx], b = row_im[z * w + kx];
        re += a * ch[p] + b * sh[p];
        im += b * ch[p] - a * sh[p];
      }
      out_re[kz * w + kx] = re;
      out_im[kz * w + kx] = im;
    }
  free(cw), free(sw), free(ch), free(sh), free(row_re), free(row_im);
}

/* Signed frequency of index k on an n-point axis. */
static inline int dft_signed(int k, int n) { return k <= n / 2 ? k : k - n; }

/* Relative divergence of (u, v) for the central-difference symbol sin(2 pi m / n), from
 * the spectra: |sum i k~ . U|_2 / |(|k~| |U|)|_2. */
static inline double spectral_divergence_rel(const double *ur, const double *ui, const double *vr,
                                      const double *vi, int w, int h) {
  const double two_pi = 6.283185307179586476925286766559;
  double num = 0, den = 0;
  for (int kz = 0; kz < h; kz++)
    for (int kx = 0; kx < w; kx++) {
      double sx = sin(two_pi * kx / w), sz = sin(two_pi * kz / h);
      int m = kz * w + kx;
      double dr = sx * ur[m] + sz * vr[m], di = sx * ui[m] + sz * vi[m];
      num += dr * dr + di * di;
      den += (sx * sx + sz * sz) * (ur[m] * ur[m] + ui[m] * ui[m] + vr[m] * vr[m] + vi[m] * vi[m]);
    }
  return den > 0 ? sqrt(num / den) : 0;
}

/* The same with central differences in real space (periodic): |div|_2 / |grad|_2, where
 * div = (u[x+1]-u[x-1])/2 + (v[z+1]-v[z-1])/2 — whose symbol is exactly i sin(k). */
static inline double fd_divergence_rel(const float *u, const float *v, int w, int h) {
  double num = 0, den = 0;
  for (int z = 0; z < h; z++)
    for (int x = 0; x < w; x++) {
      int xp = (x + 1) % w, xm = (x + w - 1) % w, zp = (z + 1) % h, zm = (z + h - 1) % h;
      double dudx = 0.5 * ((double)u[z * w + xp] - u[z * w + xm]);
      double dudz = 0.5 * ((double)u[zp * w + x] - u[zm * w + x]);
      double dvdx = 0.5 * ((double)v[z * w + xp] - v[z * w + xm]);
      double dvdz = 0.5 * ((double)v[zp * w + x] - v[zm * w + x]);
      double div = dudx + dvdz;
      num += div * div;
      den += dudx * dudx + dudz * dudz + dvdx * dvdx + dvdz * dvdz;
    }
  return den > 0 ? sqrt(num / den) : 0;
}

#endif
