/* Fogmap files: recognise the format by its magic bytes, decode one channel (image_png.c,
 * image_exr.c), scale, and validate every density before handing out a fogmap. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "sim/image_io.h"

static const unsigned char png_magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
static const unsigned char exr_magic[4] = {0x76, 0x2f, 0x31, 0x01};

/* What a file that is neither PNG nor EXR looks like, for the error message. */
static const char *other_kind(const unsigned char *b, size_t n) {
  if (n >= 3 && b[0] == 0xff && b[1] == 0xd8 && b[2] == 0xff) return "a JPEG image";
  if (n >= 4 && !memcmp(b, "GIF8", 4)) return "a GIF image";
  if (n >= 4 && (!memcmp(b, "II*\0", 4) || !memcmp(b, "MM\0*", 4))) return "a TIFF image";
  if (n >= 12 && !memcmp(b, "RIFF", 4) && !memcmp(b + 8, "WEBP", 4)) return "a WebP image";
  if (n >= 2 && b[0] == 'B' && b[1] == 'M') return "a BMP image";
  if (n >= 2 && b[0] == 'P' && b[1] >= '1' && b[1] <= '7') return "a PNM/PAM image";
  if (n >= 10 && !memcmp(b, "#?RADIANCE", 10)) return "a Radiance HDR image";
  if (n >= 4 && b[0] == 0x20 && b[1] == 0x42 && b[2] == 0x44 && b[3] == 0x56)
    return "an OpenVDB volume (use fogpipe import)";
  if (n >= 2 && b[0] == 0x1f && b[1] == 0x8b) return "gzip-compressed data";
  if (n >= 4 && !memcmp(b, "%PDF", 4)) return "a PDF document";
  int text = 1;
  for (size_t i = 0; i < n && i < 512; i++)
    if (b[i] < 0x09 || (b[i] > 0x0d && b[i] < 0x20)) text = 0;
  return text ? "a text file" : "an unknown binary format";
}

/* Reads the file: only its first bytes (enough to recognise it) unless whole is set, then
 * all of it (PNGs are decoded from memory; the EXR reader reads chunks itself). */
static int read_file(const char *path, int whole, unsigned char **bytes, size_t *size,
                     fog_error *err) {
  FILE *f = fopen(path, "rb");
  if (!f) return fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot open: %s", path, strerror(errno));
  struct stat st;
  if (fstat(fileno(f), &st) != 0 || S_ISDIR(st.st_mode)) {
    fclose(f);
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: is a folder, expected a PNG or EXR file", path);
  }
  size_t capacity = whole ? (st.st_size > 0 ? (size_t)st.st_size : 4096) : 512, used = 0;
  unsigned char *data = malloc(capacity + 1);
  for (;;) {
    if (!data) {
      fclose(f);
      return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory reading the file", path);
    }
    used += fread(data + used, 1, capacity - used, f);
    if (used < capacity || !whole) break;
    unsigned char *grown = realloc(data, capacity * 2 + 1); /* the file grew meanwhile */
    if (!grown) free(data);
    data = grown;
    capacity *= 2;
  }
  int failed = ferror(f);
  fclose(f);
  if (failed) {
    free(data);
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: read failed", path);
  }
  *bytes = data;
  *size = used;
  return 0;
}

int fogmap_load(const char *path, const fogmap_load_desc *desc, fogmap *out, fog_error *err) {
  fogmap_load_desc d = desc ? *desc : (fogmap_load_desc){0};
  *out = (fogmap){0};
  if (!path || !*path) return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "no fogmap file name given");

  unsigned char *bytes = NULL;
  size_t size = 0;
  if (read_file(path, 0, &bytes, &size, err)) return 1;
  if (size >= 8 && !memcmp(bytes, png_magic, 8)) {
    free(bytes);
    bytes = NULL;
    if (read_file(path, 1, &bytes, &size, err)) return 1;
  }
  int width = 0, height = 0;
  float *pixels = NULL;
  int status;
  if (size == 0) {
    status = fog_fail(err, FOG_ERR_BAD_FILE, "%s: empty file; expected a PNG or EXR image", path);
  } else if (size >= 8 && !memcmp(bytes, png_magic, 8)) {
    status = png_read_channel(path, bytes, size, d.channel, d.channel_setting, &width, &height,
                              &pixels, err);
  } else if (size >= 4 && !memcmp(bytes, exr_magic, 4)) {
    status = exr_read_channel(path, d.channel, d.channel_setting, &width, &height, &pixels, err);
  } else {
    status = fog_fail(err, FOG_ERR_BAD_FILE, "%s: not a PNG or EXR image (looks like %s)", path,
                      other_kind(bytes, size));
  }
  free(bytes);
  if (status) return 1;

  /* Densities are extinction coefficients: finite and >= 0, or the renderer's exp(-∫K)
   * and the wavelet transforms produce garbage. Name the first offender. */
  size_t count = (size_t)width * (size_t)height;
  for (size_t i = 0; i < count; i++) {
    float v = pixels[i];
    if (!(v >= 0.0f) || !(v <= FOGMAP_MAX_DENSITY)) {
      int x = (int)(i % (size_t)width), z = (int)(i / (size_t)width);
      const char *what = isnan(v) ? "is NaN"
                         : isinf(v) ? "is infinite"
                         : v < 0.0f ? "is negative"
                                    : "is too large";
      fog_fail(err, FOG_ERR_BAD_FILE,
               "%s: pixel (%d, %d) %s (%.9g); %s must be finite, >= 0 and at most %g", path, x,
               z, what, (double)v, d.values_are ? d.values_are : "densities",
               (double)FOGMAP_MAX_DENSITY);
      free(pixels);
      return 1;
    }
  }
  *out = (fogmap){.width = width, .height = height, .density = pixels};
  return 0;
}

int fogmap_save_exr(const char *path, const fogmap *map, fog_error *err) {
  image_channel y = {.name = "Y", .pixels = map->density, .as_half = 0};
  return image_write_exr(path, map->width, map->height, &y, 1, err);
}

float fogmap_max_density(const fogmap *map) {
  float max = 0.0f;
  size_t count = (size_t)map->width * (size_t)map->height;
  for (size_t i = 0; i < count; i++)
    if (map->density[i] > max) max = map->density[i];
  return max;
}

int fogmap_save_png16(const char *path, const fogmap *map, float max_density, fog_error *err) {
  if (max_density == 0.0f) max_density = fogmap_max_density(map);
  if (max_density == 0.0f) max_density = 1.0f;
  if (!(max_density > 0.0f) || isinf(max_density))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "%s: PNG full-scale density %g must be positive and finite", path,
                    (double)max_density);
  if (map->width <= 0 || map->height <= 0 || !map->density)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: fogmap is empty (%dx%d)", path, map->width,
                    map->height);
  /* a NaN or infinite cell is refused, as the EXR writer refuses it (it was stored as 0
   * or full scale, a file that no longer said what the map held) */
  if (image_check_finite(path, "density", map->density, map->width, map->height, 1, FLT_MAX,
                         err))
    return 1;
  size_t count = (size_t)map->width * (size_t)map->height;
  uint16_t *samples = malloc(count * sizeof *samples);
  if (!samples)
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory for a 16-bit PNG", path);
  for (size_t i = 0; i < count; i++) {
    double v = (double)map->density[i] / max_density;
    v = v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; /* clamps */
    samples[i] = (uint16_t)lrint(v * 65535.0);
  }
  int status = png_write_samples(path, map->width, map->height, 1, 16, false, samples, err);
  free(samples);
  return status;
}
