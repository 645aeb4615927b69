/* Linear float -> 8-bit sRGB by table (see sim/fogmap.h). */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sim/image_io.h"
#include "sim/sim.h"

/* IEC 61966-2-1: the encoding and its inverse. */
static double srgb_from_linear(double x) {
  return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}
static double linear_from_srgb(double s) {
  return s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4);
}

static unsigned char search(const srgb8_encoder *e, float linear) {
  int k = 0;
  for (int step = 128; step > 0; step >>= 1) /* the largest k with threshold[k] <= linear */
    if (k + step < 256 && e->threshold[k + step] <= linear) k += step;
  return (unsigned char)k;
}

static uint32_t float_bits(float x) {
  uint32_t bits;
  memcpy(&bits, &x, sizeof bits);
  return bits;
}

void srgb8_encoder_init(srgb8_encoder *e) {
  e->threshold[0] = 0.0f;
  for (int k = 1; k < 256; k++) {
    /* The smallest float x with lround(255 srgb(x)) >= k: start from the exact inverse of
     * (k - 1/2)/255 and step to the float where the rounded encoding changes. */
    float x = (float)linear_from_srgb((k - 0.5) / 255.0);
    while (x > 0 && lround(255.0 * srgb_from_linear(nextafterf(x, 0.0f))) >= k)
      x = nextafterf(x, 0.0f);
    while (lround(255.0 * srgb_from_linear(x)) < k) x = nextafterf(x, 2.0f);
    e->threshold[k] = x;
  }
  e->threshold[256] = INFINITY;
  for (uint32_t i = 0; i < sizeof e->start; i++) {
    uint32_t bits = i << 16;
    float x;
    memcpy(&x, &bits, sizeof x);
    e->start[i] = search(e, x);
  }
  for (int b = 0; b < SRGB8_DITHER_LEVELS; b++) {
    const double offset = (b + 0.5) / SRGB8_DITHER_LEVELS;
    e->dither[b][0] = 0.0f;
    for (int k = 1; k < 256; k++) {
      /* the smallest float x with floor(255 srgb(x) + offset) >= k, as threshold[] above */
      float x = (float)linear_from_srgb((k - offset) / 255.0);
      while (x > 0 && floor(255.0 * srgb_from_linear(nextafterf(x, 0.0f)) + offset) >= k)
        x = nextafterf(x, 0.0f);
      while (floor(255.0 * srgb_from_linear(x) + offset) < k) x = nextafterf(x, 2.0f);
      e->dither[b][k] = x;
    }
    e->dither[b][256] = INFINITY;
  }
}

unsigned char srgb8_encode(const srgb8_encoder *e, float linear) {
  if (!(linear > 0.0f)) return 0; /* and NaN */
  if (linear >= 1.0f) return 255;
  unsigned k = e->start[float_bits(linear) >> 16];
  return (unsigned char)(k + (e->threshold[k + 1] <= linear)); /* at most one level up */
}

/* Bayer's recursive matrix M_2n = [4M_n, 4M_n + 2; 4M_n + 3, 4M_n + 1] at n = 8, [y][x]
 * (the GLSL twin computes it by bit-interleaving x ^ y with y) */
static const unsigned char bayer8[8][8] = {
    {0, 32, 8, 40, 2, 34, 10, 42},   {48, 16, 56, 24, 50, 18, 58, 26},
    {12, 44, 4, 36, 14, 46, 6, 38},  {60, 28, 52, 20, 62, 30, 54, 22},
    {3, 35, 11, 43, 1, 33, 9, 41},   {51, 19, 59, 27, 49, 17, 57, 25},
    {15, 47, 7, 39, 13, 45, 5, 37},  {63, 31, 55, 23, 61, 29, 53, 21}};

static srgb8_encoder shared_encoder;
static pthread_once_t shared_encoder_once = PTHREAD_ONCE_INIT;
static void shared_encoder_init(void) { srgb8_encoder_init(&shared_encoder); }

const srgb8_encoder *srgb8_encoder_shared(void) {
  pthread_once(&shared_encoder_once, shared_encoder_init); /* 2 ms, once a process */
  return &shared_encoder;
}

int srgb8_dither_level(int x, int y) { return bayer8[y & 7][x & 7]; }

unsigned char srgb8_encode_dithered(const srgb8_encoder *e, float linear, int x, int y) {
  if (!(linear > 0.0f)) return 0; /* and NaN */
  if (linear >= 1.0f) return 255;
  const float *level = e->dither[srgb8_dither_level(x, y)];
  const int k = srgb8_encode(e, linear); /* the offset moves it by at most one level */
  /* without branches: a dither pattern makes them unpredictable (3x slower measured) */
  return (unsigned char)(k + (linear >= level[k + 1]) - (linear < level[k]));
}

int image_write_png_srgb(const char *path, int width, int height, int channels, const float *linear,
                         srgb8_quantise quantise, fog_error *err) {
  if (channels != 3 && channels != 4)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "%s: sRGB PNG writing takes 3 (RGB) or 4 (RGBA) channels, not %d", path,
                    channels);
  if (width <= 0 || height <= 0) /* before the values are read */
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: image size %dx%d: both must be positive",
                    path, width, height);
  static const char *const names[] = {"R", "G", "B", "A"};
  for (int c = 0; c < channels; c++)
    if (image_check_finite(path, names[c], linear + c, width, height, channels, FLT_MAX, err))
      return 1;
  return png_write_floats(path, width, height, channels, linear, srgb8_encoder_shared(),
                          quantise, err);
}
