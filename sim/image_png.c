/* PNG through libspng: one channel of a PNG to floats, and 8/16-bit PNG writing.
 * Samples are taken as stored (no gamma or sRGB decoding): a fogmap PNG holds data, not
 * colour, and value / (2^depth - 1) must read back exactly what was written. */
#include <math.h>
#include <spng.h>
#include <zlib.h> /* Z_RLE */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sim/image_io.h"

typedef struct png_layout {
  int channels;              /* samples per pixel after decoding */
  const char *names[4];      /* what desc.channel may name */
  const char *kind;          /* for messages */
} png_layout;

static png_layout layout_of(int color_type) {
  switch (color_type) {
    case SPNG_COLOR_TYPE_GRAYSCALE: return (png_layout){1, {"grey"}, "greyscale"};
    case SPNG_COLOR_TYPE_GRAYSCALE_ALPHA:
      return (png_layout){2, {"grey", "A"}, "grey+alpha"};
    case SPNG_COLOR_TYPE_TRUECOLOR: return (png_layout){3, {"R", "G", "B"}, "RGB"};
    case SPNG_COLOR_TYPE_TRUECOLOR_ALPHA:
      return (png_layout){4, {"R", "G", "B", "A"}, "RGBA"};
    /* Indexed colour is expanded through its palette to 8-bit RGBA. */
    case SPNG_COLOR_TYPE_INDEXED: return (png_layout){4, {"R", "G", "B", "A"}, "indexed-colour"};
    default: return (png_layout){0, {0}, "unknown"};
  }
}

static void list_names(const png_layout *layout, char *out, size_t size) {
  out[0] = '\0';
  for (int c = 0; c < layout->channels; c++) {
    size_t used = strlen(out);
    snprintf(out + used, size - used, "%s\"%s\"", c ? ", " : "", layout->names[c]);
  }
}

int png_read_channel(const char *path, const unsigned char *bytes, size_t size, const char *channel,
                     const char *channel_setting, int *width, int *height, float **pixels,
                     fog_error *err) {
  spng_ctx *ctx = spng_ctx_new(0);
  if (!ctx)
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory starting the PNG decoder", path);
  unsigned char *samples = NULL;
  float *out = NULL;
  int status = 1;
  struct spng_ihdr ihdr;
  int e = spng_set_png_buffer(ctx, bytes, size);
  if (!e) e = spng_get_ihdr(ctx, &ihdr);
  if (e) {
    if (e == SPNG_EWIDTH || e == SPNG_EHEIGHT)
      fog_fail(err, FOG_ERR_BAD_FILE, "%s: PNG header has an invalid (zero or too large) size: %s",
               path, spng_strerror(e));
    else
      fog_fail(err, FOG_ERR_BAD_FILE, "%s: not a valid PNG (header): %s", path, spng_strerror(e));
    goto done;
  }
  if (ihdr.width == 0 || ihdr.height == 0) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: PNG has zero size %ux%u", path, ihdr.width, ihdr.height);
    goto done;
  }
  if (ihdr.width > 1u << 20 || ihdr.height > 1u << 20 ||
      (uint64_t)ihdr.width * ihdr.height > (uint64_t)1 << 28) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: PNG size %ux%u is too large for a fogmap", path,
             ihdr.width, ihdr.height);
    goto done;
  }
  png_layout layout = layout_of(ihdr.color_type);
  int indexed = ihdr.color_type == SPNG_COLOR_TYPE_INDEXED;
  int depth = indexed ? 8 : ihdr.bit_depth;
  if (!layout.channels || (depth != 8 && depth != 16)) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: %d-bit %s PNG; expected 8 or 16 bits per sample", path,
             ihdr.bit_depth, layout.kind);
    goto done;
  }

  /* Which sample of each pixel: a one-channel PNG needs no name (but "grey" is fine). */
  char names[64];
  list_names(&layout, names, sizeof names);
  int pick = -1;
  if (!channel) {
    if (layout.channels != 1) {
      char hint[128];
      fog_fail(err, FOG_ERR_BAD_FILE, "%s: %s PNG has channels %s; name the one to load%s", path,
               layout.kind, names, image_channel_setting_hint(channel_setting, hint, sizeof hint));
      goto done;
    }
    pick = 0;
  } else {
    for (int c = 0; c < layout.channels; c++)
      if (!strcmp(channel, layout.names[c])) pick = c;
    if (pick < 0) {
      fog_fail(err, FOG_ERR_NO_SUCH_CHANNEL, "%s: %s PNG has no channel \"%s\"; it has %s", path,
               layout.kind, channel, names);
      goto done;
    }
  }

  int fmt = indexed ? SPNG_FMT_RGBA8 : SPNG_FMT_PNG; /* SPNG_FMT_PNG: host-endian 16-bit */
  size_t decoded_size;
  e = spng_decoded_image_size(ctx, fmt, &decoded_size);
  if (!e) {
    samples = malloc(decoded_size);
    if (!samples) {
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory decoding a %ux%u PNG", path,
               ihdr.width, ihdr.height);
      goto done;
    }
    /* an indexed image's alpha is its tRNS chunk's (without the flag A read 1 everywhere) */
    e = spng_decode_image(ctx, samples, decoded_size, fmt, indexed ? SPNG_DECODE_TRNS : 0);
  }
  if (e) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: PNG image data is damaged: %s", path, spng_strerror(e));
    goto done;
  }
  size_t count = (size_t)ihdr.width * ihdr.height;
  out = malloc(count * sizeof *out);
  if (!out) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory for a %ux%u fogmap", path, ihdr.width,
             ihdr.height);
    goto done;
  }
  if (depth == 8) {
    for (size_t i = 0; i < count; i++)
      out[i] = (float)samples[i * layout.channels + pick] / 255.0f;
  } else {
    const uint16_t *s16 = (const uint16_t *)samples;
    for (size_t i = 0; i < count; i++)
      out[i] = (float)s16[i * layout.channels + pick] / 65535.0f;
  }
  *width = (int)ihdr.width;
  *height = (int)ihdr.height;
  *pixels = out;
  out = NULL;
  status = 0;
done:
  free(out);
  free(samples);
  spng_ctx_free(ctx);
  return status;
}

int png_write_samples(const char *path, int width, int height, int channels, int bit_depth,
                      bool dithered, const void *samples, fog_error *err) {
  static const uint8_t color_types[5] = {0, SPNG_COLOR_TYPE_GRAYSCALE,
                                         SPNG_COLOR_TYPE_GRAYSCALE_ALPHA,
                                         SPNG_COLOR_TYPE_TRUECOLOR,
                                         SPNG_COLOR_TYPE_TRUECOLOR_ALPHA};
  if (width <= 0 || height <= 0)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: image size %dx%d: both must be positive",
                    path, width, height);
  if (channels < 1 || channels > 4 || (bit_depth != 8 && bit_depth != 16))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: cannot write a %d-channel %d-bit PNG", path,
                    channels, bit_depth);
  spng_ctx *ctx = spng_ctx_new(SPNG_CTX_ENCODER);
  if (!ctx)
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory starting the PNG encoder", path);
  struct spng_ihdr ihdr = {.width = (uint32_t)width,
                           .height = (uint32_t)height,
                           .bit_depth = (uint8_t)bit_depth,
                           .color_type = color_types[channels]};
  size_t size = (size_t)width * height * channels * (bit_depth / 8);
  /* Encode to memory, then write through atomic_file: the file appears only complete. */
  int e = spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
  /* 8-bit images are previews and frames to look at: fast zlib (level 1) after the Sub
   * filter, several times faster than libspng's default (every filter, default effort).
   * Rounded, run-length matches alone (Z_RLE) are best: 6.6 ms / 85 kB for a 640x480
   * night render against 7.0 ms / 103 kB with the default strategy. Dithered, the Bayer
   * pattern leaves no runs: Z_RLE takes 11.4 ms / 223 kB, the default strategy 10.5 ms /
   * 171 kB. 16-bit PNGs are fogmap data: default effort. */
  if (!e && bit_depth == 8) e = spng_set_option(ctx, SPNG_IMG_COMPRESSION_LEVEL, 1);
  if (!e && bit_depth == 8)
    e = spng_set_option(ctx, SPNG_IMG_COMPRESSION_STRATEGY,
                        dithered ? Z_DEFAULT_STRATEGY : Z_RLE);
  if (!e && bit_depth == 8) e = spng_set_option(ctx, SPNG_FILTER_CHOICE, SPNG_FILTER_CHOICE_SUB);
  if (!e) e = spng_set_ihdr(ctx, &ihdr);
  if (!e) e = spng_encode_image(ctx, samples, size, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
  size_t png_size = 0;
  void *png = NULL;
  if (!e) png = spng_get_png_buffer(ctx, &png_size, &e);
  spng_ctx_free(ctx);
  if (e || !png) {
    free(png);
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: PNG encoding failed: %s", path,
                    spng_strerror(e));
  }
  atomic_file file;
  if (atomic_file_open(&file, path, err)) {
    free(png);
    return 1;
  }
  atomic_file_pwrite(&file, png, png_size, 0);
  free(png);
  return atomic_file_commit(&file, err);
}

int image_write_png(const char *path, int width, int height, int channels, const float *interleaved,
                    fog_error *err) {
  if (channels != 1 && channels != 3 && channels != 4)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "%s: PNG writing takes 1 (grey), 3 (RGB) or 4 (RGBA) channels, not %d", path,
                    channels);
  return png_write_floats(path, width, height, channels, interleaved, NULL, SRGB8_ROUND, err);
}

int png_write_floats(const char *path, int width, int height, int channels, const float *values,
                     const srgb8_encoder *srgb, srgb8_quantise quantise, fog_error *err) {
  if (width <= 0 || height <= 0)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: image size %dx%d: both must be positive",
                    path, width, height);
  size_t count = (size_t)width * height * channels;
  uint8_t *samples = malloc(count);
  if (!samples)
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory for a %dx%d PNG", path, width,
                    height);
  size_t i = 0;
  for (int y = 0; y < height; y++)
    for (int x = 0; x < width; x++)
      for (int c = 0; c < channels; c++, i++) {
        float v = values[i];
        if (srgb && !(channels == 4 && c == 3)) { /* colour; alpha stays linear */
          samples[i] = quantise == SRGB8_DITHER ? srgb8_encode_dithered(srgb, v, x, y)
                                                : srgb8_encode(srgb, v);
        } else {
          v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* clamps, and NaN -> 0 */
          samples[i] = (uint8_t)(v * 255.0f + 0.5f);   /* v in [0, 1]: rounds to nearest */
        }
      }
  int status = png_write_samples(path, width, height, channels, 8,
                                 srgb && quantise == SRGB8_DITHER, samples, err);
  free(samples);
  return status;
}
