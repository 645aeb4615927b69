/* Internal to the sim library (not part of its public API, not included by sim/sim.h):
 * the pieces fogmap_io.c, image_png.c and image_exr.c share. Their output files are
 * written through sim/atomic_file.h. */
#ifndef FOGPIPE_SIM_IMAGE_IO_H
#define FOGPIPE_SIM_IMAGE_IO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdint.h>

#include "sim/atomic_file.h" /* every writer here writes through one */
#include "sim/fogmap.h"

/* Decoded single-channel float images: both readers allocate *pixels (width*height
 * floats, top row first) only on success. channel_setting: how the caller's user names
 * the channel (fogmap_load_desc), named by the error an image of several channels gives
 * when channel is NULL; NULL names none. */
int png_read_channel(const char *path, const unsigned char *bytes, size_t size, const char *channel,
                     const char *channel_setting, int *width, int *height, float **pixels,
                     fog_error *err);
int exr_read_channel(const char *path, const char *channel, const char *channel_setting,
                     int *width, int *height, float **pixels, fog_error *err);
/* ", with SETTING" when the caller names one, "" otherwise: the end of the ambiguous-channel
 * error ("name the one to load, with [fog] channel"). */
static inline const char *image_channel_setting_hint(const char *channel_setting, char *buffer,
                                                     size_t size) {
  if (!channel_setting || !*channel_setting) return "";
  snprintf(buffer, size, ", with %s", channel_setting);
  return buffer;
}

/* Writes an 8- or 16-bit PNG of interleaved samples (uint8_t or host-endian uint16_t);
 * dithered: 8-bit samples with an ordered dither in them (deflated another way). */
int png_write_samples(const char *path, int width, int height, int channels, int bit_depth,
                      bool dithered, const void *samples, fog_error *err);

/* Writes an 8-bit PNG of interleaved float values: each clamped to [0, 1] and rounded
 * (NaN -> 0), or with srgb (not NULL) sRGB-encoded by it (dithered or rounded by
 * quantise), alpha (the 4th of 4 channels) staying linear. The caller checked the
 * channels; the size is checked here. */
struct srgb8_encoder;
int png_write_floats(const char *path, int width, int height, int channels, const float *values,
                     const struct srgb8_encoder *srgb, srgb8_quantise quantise, fog_error *err);

#endif
