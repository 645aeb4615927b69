/* Fogmap image round trips: what is written reads back exactly (float EXR, quantised
 * PNG) or within the format's rounding (half EXR), checked against independent
 * references: the raw big-endian PNG samples decoded by libspng itself, PNGs written by
 * libspng directly, the EXR channel list read with the OpenEXR C API, and the half
 * format's own rounding bound. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <openexr.h>
#include <spng.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sim/sim.h"
#include "test_util.h"

static char folder[64];

static const char *in_folder(const char *name) {
  static char path[4][512];
  static int next;
  char *p = path[next++ % 4];
  snprintf(p, 512, "%s/%s", folder, name);
  return p;
}

/* Deterministic pseudo-random numbers (xorshift), independent of the code under test. */
static uint32_t rng = 12345u;
static uint32_t next_u32(void) {
  rng ^= rng << 13;
  rng ^= rng >> 17;
  rng ^= rng << 5;
  return rng;
}
static float uniform(void) { return (float)(next_u32() >> 8) / 16777216.0f; }

static void test_exr_float_bit_exact(void) {
  const int w = 37, h = 23; /* not a multiple of the 16-line ZIP chunk */
  fogmap map;
  fog_error err;
  CHECK(fogmap_create(&map, w, h, &err) == 0, "%s", err.message);
  for (int i = 0; i < w * h; i++) {
    /* every exponent range a fogmap may hold: zeros, denormals, tiny, ordinary, huge */
    float v = uniform();
    switch (i % 5) {
      case 0: v = 0.0f; break;
      case 1: v *= 1e-40f; break;
      case 2: v *= 1e-20f; break;
      case 3: v *= 7.0f; break;
      case 4: v *= 1e11f; break; /* near FOGMAP_MAX_DENSITY */
    }
    map.density[i] = v;
  }
  const char *path = in_folder("float.exr");
  CHECK(fogmap_save_exr(path, &map, &err) == 0, "save: %s", err.message);
  fogmap back;
  CHECK(fogmap_load(path, NULL, &back, &err) == 0, "load: %s", err.message);
  CHECK(back.width == w && back.height == h, "size %dx%d", back.width, back.height);
  if (back.density)
    CHECK(!memcmp(back.density, map.density, sizeof(float) * w * h),
          "float EXR round trip is not bit-exact");

  fogmap scaled;
  CHECK(fogmap_load(path, NULL, &scaled, &err) == 0 && fogmap_scale(&scaled, 2.5, &err) == 0,
        "scaled load: %s", err.message);
  int scale_ok = scaled.density != NULL;
  for (int i = 0; scale_ok && i < w * h; i++)
    if (scaled.density[i] != map.density[i] * 2.5f) scale_ok = 0;
  CHECK(scale_ok, "density_scale 2.5 does not multiply every value");
  fogmap_destroy(&scaled);
  fogmap_destroy(&back);
  fogmap_destroy(&map);
  unlink(path);
}

static void test_exr_channels_half_and_sorted(void) {
  const int w = 19, h = 41;
  float *exact = malloc(sizeof(float) * w * h), *any = malloc(sizeof(float) * w * h),
        *depth = malloc(sizeof(float) * w * h);
  for (int i = 0; i < w * h; i++) {
    exact[i] = (float)(i % 2048) / 1024.0f; /* k / 1024 with k < 2048: exact in half */
    any[i] = 6.1e-5f + uniform() * 60000.0f; /* normal half range */
    depth[i] = uniform() * 100.0f;
  }
  /* given unsorted; as_half on two of them */
  image_channel channels[3] = {
      {.name = "depth", .pixels = depth, .as_half = 0},
      {.name = "B", .pixels = any, .as_half = 1},
      {.name = "A", .pixels = exact, .as_half = 1},
  };
  const char *path = in_folder("channels.exr");
  fog_error err;
  CHECK(image_write_exr(path, w, h, channels, 3, &err) == 0, "write: %s", err.message);

  /* Independent check of the file's channel list with the OpenEXR C API. */
  exr_context_t ctxt = NULL;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  CHECK(exr_start_read(&ctxt, path, &init) == EXR_ERR_SUCCESS, "exr_start_read failed");
  const exr_attr_chlist_t *list = NULL;
  if (ctxt) exr_get_channels(ctxt, 0, &list);
  CHECK(list && list->num_channels == 3, "channel count");
  if (list && list->num_channels == 3) {
    CHECK(!strcmp(list->entries[0].name.str, "A") && !strcmp(list->entries[1].name.str, "B") &&
              !strcmp(list->entries[2].name.str, "depth"),
          "channels not sorted by name: %s %s %s", list->entries[0].name.str,
          list->entries[1].name.str, list->entries[2].name.str);
    CHECK(list->entries[0].pixel_type == EXR_PIXEL_HALF &&
              list->entries[1].pixel_type == EXR_PIXEL_HALF &&
              list->entries[2].pixel_type == EXR_PIXEL_FLOAT,
          "pixel types not as asked");
  }
  exr_compression_t compression = EXR_COMPRESSION_LAST_TYPE;
  if (ctxt) exr_get_compression(ctxt, 0, &compression);
  CHECK(compression == EXR_COMPRESSION_ZIP, "compression %d, documented as ZIP",
        (int)compression);
  if (ctxt) exr_finish(&ctxt);

  fogmap a, b, d;
  CHECK(fogmap_load(path, &(fogmap_load_desc){.channel = "A"}, &a, &err) == 0, "A: %s",
        err.message);
  CHECK(fogmap_load(path, &(fogmap_load_desc){.channel = "B"}, &b, &err) == 0, "B: %s",
        err.message);
  CHECK(fogmap_load(path, &(fogmap_load_desc){.channel = "depth"}, &d, &err) == 0,
        "depth: %s", err.message);
  if (a.density && b.density && d.density) {
    int exact_ok = 1, half_ok = 1;
    double worst = 0;
    for (int i = 0; i < w * h; i++) {
      if (a.density[i] != exact[i]) exact_ok = 0;
      /* round to nearest half: relative error <= 2^-11 for normal values */
      double rel = fabs((double)b.density[i] - any[i]) / any[i];
      if (rel > worst) worst = rel;
      if (rel > 1.0 / 2048.0) half_ok = 0;
    }
    CHECK(exact_ok, "half-representable values did not come back exactly");
    CHECK(half_ok, "half round trip relative error %g > 2^-11", worst);
    CHECK(worst > 0, "half channel came back exactly: was it written as float?");
    CHECK(!memcmp(d.density, depth, sizeof(float) * w * h), "float channel not bit-exact");
  }
  fogmap_destroy(&a);
  fogmap_destroy(&b);
  fogmap_destroy(&d);
  free(exact);
  free(any);
  free(depth);
  unlink(path);
}

/* Decodes a PNG with libspng to big-endian raw samples (the independent reference). */
static unsigned char *spng_raw(const char *path, struct spng_ihdr *ihdr, size_t *size) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  spng_ctx *ctx = spng_ctx_new(0);
  spng_set_png_file(ctx, f);
  spng_get_ihdr(ctx, ihdr);
  spng_decoded_image_size(ctx, SPNG_FMT_RAW, size);
  unsigned char *raw = malloc(*size);
  if (spng_decode_image(ctx, raw, *size, SPNG_FMT_RAW, 0)) {
    free(raw);
    raw = NULL;
  }
  spng_ctx_free(ctx);
  fclose(f);
  return raw;
}

static void test_png8_exact(void) {
  const int w = 256, h = 3;
  float *grey = malloc(sizeof(float) * w * h);
  for (int i = 0; i < w * h; i++) grey[i] = (float)((i * 7) % 256) / 255.0f;
  const char *path = in_folder("grey8.png");
  fog_error err;
  CHECK(image_write_png(path, w, h, 1, grey, &err) == 0, "write: %s", err.message);
  struct spng_ihdr ihdr = {0};
  size_t size = 0;
  unsigned char *raw = spng_raw(path, &ihdr, &size);
  CHECK(raw && ihdr.bit_depth == 8 && ihdr.color_type == SPNG_COLOR_TYPE_GRAYSCALE &&
            size == (size_t)w * h,
        "not an 8-bit grey PNG");
  int raw_ok = raw != NULL;
  for (int i = 0; raw_ok && i < w * h; i++)
    if (raw[i] != (i * 7) % 256) raw_ok = 0;
  CHECK(raw_ok, "8-bit samples are not round(v * 255)");
  free(raw);
  fogmap back;
  CHECK(fogmap_load(path, NULL, &back, &err) == 0, "load: %s", err.message);
  int ok = back.density && back.width == w && back.height == h;
  for (int i = 0; ok && i < w * h; i++)
    if (back.density[i] != grey[i]) ok = 0;
  CHECK(ok, "8-bit grey PNG does not read back value / 255 exactly");
  fogmap_destroy(&back);

  /* clamping: out-of-range and NaN values */
  float odd[4] = {-1.0f, 2.0f, NAN, 0.5f};
  CHECK(image_write_png(path, 4, 1, 1, odd, &err) == 0, "write: %s", err.message);
  CHECK(fogmap_load(path, NULL, &back, &err) == 0, "load: %s", err.message);
  if (back.density)
    CHECK(back.density[0] == 0.0f && back.density[1] == 1.0f && back.density[2] == 0.0f &&
              back.density[3] == 128.0f / 255.0f,
          "clamping: %g %g %g %g", back.density[0], back.density[1], back.density[2],
          back.density[3]);
  fogmap_destroy(&back);

  /* RGB and RGBA: the named channel, interleaved correctly */
  float *rgba = malloc(sizeof(float) * w * h * 4);
  for (int i = 0; i < w * h * 4; i++) rgba[i] = (float)((i * 13 + i / 4) % 256) / 255.0f;
  for (int channels = 3; channels <= 4; channels++) {
    const char *p = in_folder(channels == 3 ? "rgb.png" : "rgba.png");
    CHECK(image_write_png(p, w, h, channels, rgba, &err) == 0, "write: %s", err.message);
    const char *names[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < channels; c++) {
      CHECK(fogmap_load(p, &(fogmap_load_desc){.channel = names[c]}, &back, &err) == 0,
            "load %s: %s", names[c], err.message);
      int good = back.density != NULL;
      for (int i = 0; good && i < w * h; i++)
        if (back.density[i] != rgba[i * channels + c]) good = 0;
      CHECK(good, "%d-channel PNG channel %s wrong", channels, names[c]);
      fogmap_destroy(&back);
    }
    unlink(p);
  }
  free(rgba);
  free(grey);
  unlink(path);
}

/* A PNG written by libspng directly from big-endian samples we lay out ourselves. */
static int spng_write_raw(const char *path, int w, int h, int color_type, int depth,
                          const unsigned char *raw, size_t size) {
  FILE *f = fopen(path, "wb");
  if (!f) return 1;
  spng_ctx *ctx = spng_ctx_new(SPNG_CTX_ENCODER);
  spng_set_png_file(ctx, f);
  struct spng_ihdr ihdr = {.width = (uint32_t)w, .height = (uint32_t)h,
                           .bit_depth = (uint8_t)depth, .color_type = (uint8_t)color_type};
  spng_set_ihdr(ctx, &ihdr);
  int e = spng_encode_image(ctx, raw, size, SPNG_FMT_RAW, SPNG_ENCODE_FINALIZE);
  spng_ctx_free(ctx);
  fclose(f);
  return e;
}

static void test_png16_exact(void) {
  const int w = 300, h = 7;
  size_t n = (size_t)w * h;
  unsigned char *raw = malloc(n * 2);
  uint16_t *values = malloc(n * sizeof *values);
  for (size_t i = 0; i < n; i++) {
    values[i] = (uint16_t)((i * 2654435761u) >> 16); /* spread over 0..65535 */
    if (i == 0) values[i] = 0;
    if (i == 1) values[i] = 65535;
    raw[2 * i] = (unsigned char)(values[i] >> 8);
    raw[2 * i + 1] = (unsigned char)(values[i] & 0xff);
  }
  const char *path = in_folder("grey16.png");
  CHECK(spng_write_raw(path, w, h, SPNG_COLOR_TYPE_GRAYSCALE, 16, raw, n * 2) == 0,
        "libspng could not write the reference PNG");
  fog_error err;
  fogmap back;
  CHECK(fogmap_load(path, NULL, &back, &err) == 0 && fogmap_scale(&back, 3.0, &err) == 0,
        "load: %s", err.message);
  int ok = back.density != NULL;
  for (size_t i = 0; ok && i < n; i++)
    if (back.density[i] != ((float)values[i] / 65535.0f) * 3.0f) ok = 0;
  CHECK(ok, "16-bit PNG does not read back value / 65535 * density_scale");

  /* Our 16-bit writer: samples round(d / max * 65535), big-endian on disk. */
  if (back.density) {
    const char *out = in_folder("saved16.png");
    CHECK(fogmap_save_png16(out, &back, 3.0f, &err) == 0, "save16: %s", err.message);
    struct spng_ihdr ihdr = {0};
    size_t size = 0;
    unsigned char *again = spng_raw(out, &ihdr, &size);
    CHECK(again && ihdr.bit_depth == 16 && ihdr.color_type == SPNG_COLOR_TYPE_GRAYSCALE &&
              size == n * 2 && !memcmp(again, raw, n * 2),
          "fogmap_save_png16 samples differ from the original 16-bit file");
    free(again);
    fogmap twice;
    CHECK(fogmap_load(out, NULL, &twice, &err) == 0 && fogmap_scale(&twice, 3.0, &err) == 0,
          "load: %s", err.message);
    CHECK(twice.density && !memcmp(twice.density, back.density, n * sizeof(float)),
          "16-bit PNG save/load is not a fixed point");
    fogmap_destroy(&twice);
    unlink(out);
  }
  fogmap_destroy(&back);

  /* grey+alpha (written by libspng): "grey" and "A" select; nothing named fails */
  unsigned char *ga = malloc(n * 2);
  for (size_t i = 0; i < n; i++) {
    ga[2 * i] = (unsigned char)(i % 251);
    ga[2 * i + 1] = (unsigned char)(255 - i % 251);
  }
  const char *ga_path = in_folder("ga.png");
  CHECK(spng_write_raw(ga_path, w, h, SPNG_COLOR_TYPE_GRAYSCALE_ALPHA, 8, ga, n * 2) == 0,
        "libspng could not write grey+alpha");
  fogmap g, a;
  CHECK(fogmap_load(ga_path, &(fogmap_load_desc){.channel = "grey"}, &g, &err) == 0, "grey: %s",
        err.message);
  CHECK(fogmap_load(ga_path, &(fogmap_load_desc){.channel = "A"}, &a, &err) == 0, "A: %s",
        err.message);
  int ga_ok = g.density && a.density;
  for (size_t i = 0; ga_ok && i < n; i++)
    if (g.density[i] != (float)(i % 251) / 255.0f ||
        a.density[i] != (float)(255 - i % 251) / 255.0f)
      ga_ok = 0;
  CHECK(ga_ok, "grey+alpha channels wrong");
  fogmap_destroy(&g);
  fogmap_destroy(&a);
  free(ga);
  unlink(ga_path);
  free(raw);
  free(values);
  unlink(path);
}

/* A tiled EXR (written here with the OpenEXR C API): fogmap_load reads level (0, 0). */
static void test_exr_tiled(void) {
  const int w = 45, h = 30, tile = 16;
  float *values = malloc(sizeof(float) * w * h);
  for (int i = 0; i < w * h; i++) values[i] = uniform() * 4.0f;
  const char *path = in_folder("tiled.exr");
  exr_context_t ctxt = NULL;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  int part = 0;
  exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
  if (!rv) rv = exr_add_part(ctxt, "tiles", EXR_STORAGE_TILED, &part);
  if (!rv) rv = exr_initialize_required_attr_simple(ctxt, part, w, h, EXR_COMPRESSION_ZIP);
  if (!rv) rv = exr_set_tile_descriptor(ctxt, part, tile, tile, EXR_TILE_ONE_LEVEL,
                                        EXR_TILE_ROUND_DOWN);
  if (!rv) rv = exr_add_channel(ctxt, part, "Y", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
  if (!rv) rv = exr_write_header(ctxt);
  exr_encode_pipeline_t encode = EXR_ENCODE_PIPELINE_INITIALIZER;
  int started = 0;
  for (int ty = 0; !rv && ty * tile < h; ty++)
    for (int tx = 0; !rv && tx * tile < w; tx++) {
      exr_chunk_info_t chunk;
      rv = exr_write_tile_chunk_info(ctxt, part, tx, ty, 0, 0, &chunk);
      if (!rv) rv = started ? exr_encoding_update(ctxt, part, &chunk, &encode)
                            : exr_encoding_initialize(ctxt, part, &chunk, &encode);
      if (rv) break;
      exr_coding_channel_info_t *info = &encode.channels[0];
      info->encode_from_ptr = (const uint8_t *)(values + ty * tile * w + tx * tile);
      info->user_pixel_stride = 4;
      info->user_line_stride = 4 * w;
      info->user_bytes_per_element = 4;
      info->user_data_type = EXR_PIXEL_FLOAT;
      if (!started) rv = exr_encoding_choose_default_routines(ctxt, part, &encode);
      started = 1;
      if (!rv) rv = exr_encoding_run(ctxt, part, &encode);
    }
  if (started) exr_encoding_destroy(ctxt, &encode);
  if (ctxt) exr_finish(&ctxt);
  CHECK(rv == EXR_ERR_SUCCESS, "writing the tiled reference failed: %d", (int)rv);
  fog_error err;
  fogmap back;
  CHECK(fogmap_load(path, NULL, &back, &err) == 0, "tiled load: %s", err.message);
  CHECK(back.density && back.width == w && back.height == h &&
            !memcmp(back.density, values, sizeof(float) * w * h),
        "tiled EXR not read back exactly");
  fogmap_destroy(&back);
  free(values);
  unlink(path);
}

/* A file name the file system takes (245 bytes) is written: its temporary's name cut the
 * name short (".NAME.tmp.PID.N" passed 255: "File name too long" for a legal name). */
static void test_long_name(void) {
  char name[250];
  memset(name, 'a', 241);
  memcpy(name + 241, ".exr", 5); /* 245 bytes */
  fogmap map;
  fog_error err = {0};
  CHECK(fogmap_create(&map, 2, 2, &err) == 0, "%s", err.message);
  const char *path = in_folder(name);
  CHECK(fogmap_save_exr(path, &map, &err) == 0, "a 245-byte file name: %s", err.message);
  fogmap_destroy(&map);
  unlink(path);
}

int main(void) {
  snprintf(folder, sizeof folder, "/tmp/fogmap_roundtrip.XXXXXX");
  if (!test_scratch_folder(folder)) return 1;
  test_exr_float_bit_exact();
  test_exr_channels_half_and_sorted();
  test_png8_exact();
  test_png16_exact();
  test_exr_tiled();
  test_long_name();
  CHECK(rmdir(folder) == 0, "temporary folder %s not empty afterwards", folder);
  return test_finish("test_fogmap_roundtrip");
}
