/* Image files of any kind: EXR (OpenEXR Core) and PNG (libspng) writers, the sRGB encoder,
 * EXR header strings; and fog_error, the library's error. Fogmaps (sim/fogmap.h) load and
 * save through these. (Part of the sim library; include "sim/sim.h".) */
#ifndef FOGPIPE_SIM_IMAGE_H
#define FOGPIPE_SIM_IMAGE_H

#include "transform/fog_error.h"
#include <stddef.h>

/* Errors are returned, never printed: a failing call fills message (naming the file and,
 * for bad pixels, the first offending pixel) and returns non-zero. */

/* One channel of an EXR image to write. */
typedef struct image_channel {
  const char *name;     /* "R", "G", "B", "A", "Y", "transmittance", "depth", ... */
  const float *pixels;  /* width*height values, row-major, top row first */
  int as_half;          /* 0: 32-bit float, 1: 16-bit half */
} image_channel;

/* Writes a scanline EXR with the given channels (any order; written sorted by name as EXR
 * requires), ZIP-compressed (lossless, 16 scanlines per chunk). The file is written to a
 * temporary name beside path and renamed, so a failure never leaves a partial file at path.
 * Refuses (before creating anything) an image holding a NaN or infinite value, or a value a
 * half channel would turn infinite (|v| > 65504), naming the channel and the pixel. */
int image_write_exr(const char *path, int width, int height, const image_channel *channels,
                    int channel_count, fog_error *err);

/* A string attribute of an EXR header: what an image was made from, for the tools that
 * read it back (record --resume). The name must not be one of EXR's standard attributes. */
typedef struct image_exr_string {
  const char *name, *value;
} image_exr_string;

/* A 4x4 float attribute (EXR's M44f), row-major as EXR stores it, for row vectors:
 * p' = p M. The standard worldToCamera and worldToNDC are such matrices. */
typedef struct image_exr_matrix {
  const char *name;
  float m[16];
} image_exr_matrix;

/* Extra attributes of an EXR header. */
typedef struct image_exr_header {
  const image_exr_string *strings;
  int string_count;
  const image_exr_matrix *matrices;
  int matrix_count;
} image_exr_header;

/* image_write_exr with attributes in the header (header may be NULL). */
int image_write_exr_with(const char *path, int width, int height, const image_channel *channels,
                         int channel_count, const image_exr_header *header, fog_error *err);

/* Reads the string attribute name of part 0 into value (at most size - 1 bytes). Fails
 * naming the file when it is not a readable EXR or has no such string attribute. */
int image_read_exr_string(const char *path, const char *name, char *value, size_t size,
                          fog_error *err);
/* Reads channel `channel` of an EXR as floats (*pixels malloc'd, width*height, top row
 * first), its values as they are: an image's light, unlike a fogmap (sim/fogmap.h), may be
 * past 1e12. Fails naming the file when it is unreadable or has no such channel. */
int image_read_exr_channel(const char *path, const char *channel, int *width, int *height,
                           float **pixels, fog_error *err);
/* Reads the M44f attribute name of part 0 (image_exr_matrix's layout). */
int image_read_exr_matrix(const char *path, const char *name, float m[16], fog_error *err);

/* Writes an 8-bit PNG (1 channel grey, 3 RGB or 4 RGBA) from interleaved float values in
 * [0,1] (clamped), top row first; temporary file + rename like image_write_exr. */
int image_write_png(const char *path, int width, int height, int channels, const float *interleaved,
                    fog_error *err);

enum { SRGB8_DITHER_LEVELS = 64 }; /* the 8 x 8 Bayer matrix's levels */

/* The sRGB transfer function (IEC 61966-2-1) to 8 bits, by table, for every float exactly
 * lround(255 srgb(x)) of the formula in double: threshold[k] is the smallest float whose
 * encoding is k; start[] holds the encoding at the bottom of each float interval with the
 * same top 16 bits (exponent and 7 mantissa bits, 0.8 % wide, where the encoding rises by
 * at most one level), so encoding is a lookup and one comparison instead of a pow.
 *
 * Dithered, the pixel (x, y) adds the 8 x 8 Bayer matrix's (b + 1/2)/64 - 1/2 to
 * 255 srgb(x) before rounding: floor(255 srgb(x) + (b + 1/2)/64), exactly, by a threshold
 * table per level b. A smooth gradient then averages to its true value over each 8 x 8
 * tile (within 1/128 of a level) instead of stepping in bands a level apart, which dark
 * fog glows show at 8 bits; black, white and values on a level stay as they are. */
typedef struct srgb8_encoder {
  float threshold[257];          /* threshold[0] unused; threshold[256] = +infinity */
  unsigned char start[0x3F81];   /* indexed by the float's bits >> 16, for 0 <= x <= 1 */
  /* dither[b][k]: the smallest float whose dithered encoding at level b is >= k */
  float dither[SRGB8_DITHER_LEVELS][257];
} srgb8_encoder;
void srgb8_encoder_init(srgb8_encoder *encoder);
/* One encoder for the process, made on first use (thread-safe; never freed). */
const srgb8_encoder *srgb8_encoder_shared(void);
unsigned char srgb8_encode(const srgb8_encoder *encoder, float linear);
/* The Bayer level b in [0, 64) of pixel (x, y), x and y >= 0, the top row y = 0. */
int srgb8_dither_level(int x, int y);
unsigned char srgb8_encode_dithered(const srgb8_encoder *encoder, float linear, int x, int y);

/* How 8-bit sRGB output quantises: rounding each value, or ordered dithering. */
typedef enum srgb8_quantise { SRGB8_ROUND = 0, SRGB8_DITHER } srgb8_quantise;

/* Fails naming the first pixel (x, y) of an interleaved image (stride values per pixel, the
 * channel's value first) that is NaN or whose magnitude exceeds limit (FLT_MAX: infinite;
 * 65504: what a half channel cannot hold). channel names it in the message, path the file
 * that was to hold it. For a caller that maps values before writing them (a display
 * transform turns NaN into black): check first. */
int image_check_finite(const char *path, const char *channel, const float *values, int width,
                       int height, int stride, float limit, fog_error *err);

/* Writes an 8-bit sRGB PNG (3 RGB or 4 RGBA: alpha stays linear) from linear interleaved
 * floats (clamped to [0, 1]), top row first, each colour value rounded or dithered as
 * quantise says; temporary file + rename. NaN or infinite
 * values are refused as image_write_exr refuses them (clamping would hide them). */
int image_write_png_srgb(const char *path, int width, int height, int channels, const float *linear,
                         srgb8_quantise quantise, fog_error *err);

#endif
