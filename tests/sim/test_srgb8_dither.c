/* The dithered sRGB encoder (sim/image.h: srgb8_encode_dithered) against references written
 * apart from it (tests/reference/srgb8_dither_reference.h):
 *   - the level of pixel (x, y) is Bayer's 8 x 8 index matrix, built by its recursion
 *     M_2n = [4M_n, 4M_n + 2; 4M_n + 3, 4M_n + 1] from M_1 = [0];
 *   - the code is floor(255 srgb(x) + (b + 1/2)/64), IEC 61966-2-1 in double, for every
 *     float tried at every level (a sweep, random values, and the floats either side of
 *     each code's rounding threshold);
 *   - what dithering is for: over each 8 x 8 tile a constant value's codes average to within
 *     1/128 of 255 srgb(x), where rounding is off by up to 1/2; black stays 0, white 255, a
 *     value on a code stays on it;
 *   - the sRGB PNG writer stores exactly those codes at each pixel, top row y = 0. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim/image_io.h"
#include "sim/sim.h"
#include "tests/reference/srgb8_dither_reference.h"
#include "tests/test_util.h"

static int bayer[8][8]; /* [y][x] */

static void build_bayer(void) {
  for (int y = 0; y < 8; y++)
    for (int x = 0; x < 8; x++) bayer[y][x] = reference_bayer_level(x, y);
}

static double srgb255(float x) { return reference_srgb255(x); }

static int reference(float x, int px, int py) { return reference_srgb8_dithered(x, px, py); }

static long mismatches, tried;
static float first_bad;

static void try_value(const srgb8_encoder *e, float x) {
  for (int py = 0; py < 8; py++)
    for (int px = 0; px < 8; px++, tried++)
      if (srgb8_encode_dithered(e, x, px + 8 * (int)(tried % 5), py) != reference(x, px, py) &&
          !mismatches++)
        first_bad = x;
}

int main(void) {
  build_bayer();
  srgb8_encoder *e = malloc(sizeof *e);
  CHECK(e != NULL, "out of memory");
  if (!e) return test_finish("test_srgb8_dither");
  srgb8_encoder_init(e);

  for (int y = 0; y < 16; y++)
    for (int x = 0; x < 16; x++)
      CHECK(srgb8_dither_level(x, y) == bayer[y & 7][x & 7], "level at (%d, %d): %d, not %d",
            x, y, srgb8_dither_level(x, y), bayer[y & 7][x & 7]);

  for (int i = 0; i <= 110000; i++) try_value(e, (float)i / 100000.0f);
  srand(5);
  for (int i = 0; i < 20000; i++) {
    float x = (float)rand() / (float)RAND_MAX;
    try_value(e, x * x * x); /* many small values, where the curve is steep */
  }
  for (int k = 1; k < 256; k++) { /* about each code's rounding threshold */
    float t = e->threshold[k];
    try_value(e, nextafterf(t, 0.0f)), try_value(e, t), try_value(e, nextafterf(t, 2.0f));
  }
  CHECK(mismatches == 0, "%ld of %ld dithered codes differ from floor(255 srgb(x) + "
        "(b + 1/2)/64) (first at x = %.9g)", mismatches, tried, first_bad);

  /* What it is for: a tile's mean is the value, to within half a Bayer step. */
  double worst_dithered = 0.0, worst_rounded = 0.0;
  for (int i = 1; i < 4000; i++) {
    float x = (float)pow(i / 4000.0, 2.2);
    double sum = 0.0;
    for (int py = 0; py < 8; py++)
      for (int px = 0; px < 8; px++) sum += srgb8_encode_dithered(e, x, px, py);
    worst_dithered = fmax(worst_dithered, fabs(sum / 64.0 - srgb255(x)));
    worst_rounded = fmax(worst_rounded, fabs(srgb8_encode(e, x) - srgb255(x)));
  }
  CHECK(worst_dithered <= 1.0 / 128.0 + 1e-9,
        "an 8 x 8 tile's mean is %.4f of a level from 255 srgb(x), more than 1/128",
        worst_dithered);
  CHECK(worst_rounded > 0.49, "rounding's error should reach half a level (%.3f)",
        worst_rounded);

  int kept = 1;
  for (int py = 0; py < 8; py++)
    for (int px = 0; px < 8; px++) {
      kept &= srgb8_encode_dithered(e, 0.0f, px, py) == 0;
      kept &= srgb8_encode_dithered(e, NAN, px, py) == 0;
      kept &= srgb8_encode_dithered(e, -1.0f, px, py) == 0;
      kept &= srgb8_encode_dithered(e, 1.0f, px, py) == 255;
      kept &= srgb8_encode_dithered(e, 7.0f, px, py) == 255;
      for (int k = 0; k < 256; k += 17) { /* a value encoding to exactly k */
        float on = (float)(k / 255.0 <= 0.04045 ? k / 255.0 / 12.92
                                                 : pow((k / 255.0 + 0.055) / 1.055, 2.4));
        if (fabs(srgb255(on) - k) < 1e-4) kept &= srgb8_encode_dithered(e, on, px, py) == k;
      }
    }
  CHECK(kept, "black, white, NaN or a value on a code moved under dithering");

  /* The writer: RGB, a 37 x 11 ramp (not a multiple of 8), read back channel by channel. */
  enum { W = 37, H = 11 };
  float rgb[W * H * 3];
  for (int i = 0; i < W * H * 3; i++) rgb[i] = (float)pow((i * 7 % 211) / 210.0, 2.2);
  const char *path = "/tmp/fogpipe-test-srgb8-dither.png";
  fog_error err = {0};
  CHECK(image_write_png_srgb(path, W, H, 3, rgb, SRGB8_DITHER, &err) == 0, "write: %s",
        err.message);
  static const char *const names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; c++) {
    fogmap back = {0};
    if (fogmap_load(path, &(fogmap_load_desc){.channel = names[c]}, &back, &err)) {
      CHECK(0, "read %s: %s", names[c], err.message);
      continue;
    }
    int bad = 0;
    for (int y = 0; y < H; y++)
      for (int x = 0; x < W; x++) {
        int stored = (int)lrintf(back.density[y * W + x] * 255.0f); /* row 0 the top */
        bad += stored != reference(rgb[(y * W + x) * 3 + c], x, y);
      }
    CHECK(bad == 0, "channel %s: %d bytes differ from the dithered reference", names[c], bad);
    fogmap_destroy(&back);
  }
  remove(path);
  free(e);
  return test_finish("test_srgb8_dither");
}
