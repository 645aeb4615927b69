/* The 8-bit sRGB codes fogpipe's dithered output should hold, written for the tests apart
 * from sim/image_srgb.c: Bayer's 8 x 8 index matrix by its recursion
 * M_2n = [4M_n, 4M_n + 2; 4M_n + 3, 4M_n + 1] from M_1 = [0], and the code of a linear
 * value x at pixel (px, py), row 0 at the top: floor(255 srgb(x) + (b + 1/2)/64), the
 * IEC 61966-2-1 formula in double, x clamped to [0, 1] (NaN: 0). */
#ifndef FOGPIPE_TESTS_SRGB8_DITHER_REFERENCE_H
#define FOGPIPE_TESTS_SRGB8_DITHER_REFERENCE_H

#include <math.h>
#include <string.h>

/* The level in [0, 64) of pixel (px, py) >= 0. */
static inline int reference_bayer_level(int px, int py) {
  int m[8][8] = {{0}};
  for (int n = 1; n < 8; n *= 2) { /* M_n in m[0..n)[0..n) -> M_2n */
    int next[8][8];
    for (int y = 0; y < n; y++)
      for (int x = 0; x < n; x++) {
        next[y][x] = 4 * m[y][x];
        next[y][x + n] = 4 * m[y][x] + 2;
        next[y + n][x] = 4 * m[y][x] + 3;
        next[y + n][x + n] = 4 * m[y][x] + 1;
      }
    memcpy(m, next, sizeof m);
  }
  return m[py & 7][px & 7];
}

/* 255 srgb(x), x clamped to [0, 1]. */
static inline double reference_srgb255(double x) {
  if (!(x > 0.0)) return 0.0;
  double v = x >= 1.0 ? 1.0 : x;
  return 255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055);
}

static inline int reference_srgb8_dithered(float x, int px, int py) {
  int k = (int)floor(reference_srgb255(x) + (reference_bayer_level(px, py) + 0.5) / 64.0);
  return k > 255 ? 255 : k;
}

#endif
