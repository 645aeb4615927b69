/* The table sRGB encoder (sim/fogmap.h: srgb8_encode) equals lround(255 srgb(x)) with the
 * IEC 61966-2-1 formula evaluated in double, for every float tried: a sweep of [0, 1.1],
 * random values, and the floats on either side of every table threshold; and the sRGB
 * PNG writer stores exactly those bytes (read back through libspng), and refuses a bad size
 * before reading a value. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sim/image_io.h"
#include "sim/sim.h"
#include "tests/test_util.h"

static int reference(float x) {
  if (!(x > 0.0f)) return 0;
  double v = x >= 1.0f ? 1.0 : x;
  double s = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
  return (int)lround(255.0 * s);
}

int main(void) {
  srgb8_encoder e;
  srgb8_encoder_init(&e);
  long mismatches = 0, tried = 0;
  float first_bad = 0;
  for (int i = 0; i <= 1100000; i++) {
    float x = (float)i / 1000000.0f;
    tried++;
    if (srgb8_encode(&e, x) != reference(x) && !mismatches++) first_bad = x;
  }
  srand(3);
  for (int i = 0; i < 200000; i++) {
    float x = (float)rand() / (float)RAND_MAX;
    x = x * x * x; /* many small values, where the curve is steep */
    tried++;
    if (srgb8_encode(&e, x) != reference(x) && !mismatches++) first_bad = x;
  }
  for (int k = 1; k < 256; k++) {
    float t = e.threshold[k];
    float around[3] = {nextafterf(t, 0.0f), t, nextafterf(t, 2.0f)};
    for (int j = 0; j < 3; j++, tried++)
      if (srgb8_encode(&e, around[j]) != reference(around[j]) && !mismatches++) first_bad = around[j];
  }
  CHECK(mismatches == 0, "%ld of %ld values differ from the double formula (first %.9g)",
        mismatches, tried, first_bad);
  CHECK(srgb8_encode(&e, NAN) == 0 && srgb8_encode(&e, -1.0f) == 0 &&
            srgb8_encode(&e, 7.0f) == 255,
        "NaN, negative and above-one inputs");

  /* The writer: a 64 x 4 RGBA ramp, read back channel by channel. */
  enum { W = 64, H = 4 };
  float rgba[W * H * 4];
  for (int i = 0; i < W * H; i++)
    for (int c = 0; c < 4; c++) rgba[4 * i + c] = (float)((i * 7 + c * 13) % 97) / 90.0f;
  const char *path = "/tmp/fogpipe-test-srgb8.png";
  fog_error err = {0};
  CHECK(image_write_png_srgb(path, W, H, 4, rgba, SRGB8_ROUND, &err) == 0, "write: %s",
        err.message);
  static const char *const names[4] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; c++) {
    fogmap back = {0};
    if (fogmap_load(path, &(fogmap_load_desc){.channel = names[c]}, &back, &err)) {
      CHECK(0, "read %s: %s", names[c], err.message);
      continue;
    }
    int bad = 0;
    for (int i = 0; i < W * H; i++) {
      float v = rgba[4 * i + c];
      int expect = c == 3 ? (int)(fminf(fmaxf(v, 0), 1) * 255.0f + 0.5f) : reference(v); /* alpha: half up */
      bad += (int)lrintf(back.density[i] * 255.0f) != expect;
    }
    CHECK(bad == 0, "channel %s: %d bytes differ", names[c], bad);
    fogmap_destroy(&back);
  }
  remove(path);
  /* A bad size is refused before any value is read (with -2 x 3 the values' count once
   * wrapped around and the finite check read past the buffer), and nothing is written. */
  for (int k = 0; k < 2; k++) {
    const int w = k ? -1 : -2, h = k ? -1 : 3;
    fog_error size_err = {0};
    CHECK(image_write_png_srgb(path, w, h, 3, k ? NULL : rgba, SRGB8_DITHER, &size_err) != 0 &&
              size_err.code == FOG_ERR_INVALID_ARGUMENT &&
              strstr(size_err.message, "both must be positive"),
          "size %dx%d: '%s'", w, h, size_err.message);
    CHECK(access(path, F_OK) != 0, "a file was written for size %dx%d", w, h);
  }
  return test_finish("test_srgb8");
}
