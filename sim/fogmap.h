/* Fogmaps: a 2D density grid f(x, z), one float per cell, loaded from and saved to images
 * (the image writers themselves: sim/image.h). (Part of the sim library; include
 * "sim/sim.h".) */
#ifndef FOGPIPE_SIM_FOGMAP_H
#define FOGPIPE_SIM_FOGMAP_H

#include <stddef.h>

#include "sim/image.h"

/* Row-major, x fastest: density[z * width + x]. Image row r is fogmap row z = r (the top
 * image row is z = 0). Densities are extinction coefficients per world unit times the
 * scene's density scale; never negative, never NaN. */
typedef struct fogmap {
  int width, height;
  float *density;  /* owned; fogmap_destroy frees it */
} fogmap;

/* Allocates a zeroed width x height fogmap. */
int fogmap_create(fogmap *map, int width, int height, fog_error *err);
void fogmap_destroy(fogmap *map);

/* Loading reads the stored values as they are; a scale is the caller's (fogmap_scale), so
 * that no descriptor field is a physical quantity whose zero means something else. */
typedef struct fogmap_load_desc {
  /* Which channel of a multi-channel image to use: an EXR channel name ("R", "Y", ...),
   * or for PNG one of "R", "G", "B", "A". NULL: the image must have one channel (a grey
   * PNG, grey+alpha uses grey only if named "grey"), or loading fails naming the
   * channels that exist. */
  const char *channel;
  /* Where the caller's user names the channel ("[fog] channel", "--channel"): that error
   * says so. NULL: the caller offers no choice, and the error names no setting. */
  const char *channel_setting;
  /* What the values are, for the error naming a bad one ("heights"); NULL: "densities". */
  const char *values_are;
} fogmap_load_desc;

/* Densities above this are refused when loading (the first such pixel is named): the
 * transforms and the renderer multiply and sum them in float, and a value near FLT_MAX
 * (3.4e38) overflows to infinity there and then to NaN pixels. */
#define FOGMAP_MAX_DENSITY 1e12f

/* Multiplies every density by factor (>= 0 and finite). */
int fogmap_scale(fogmap *map, double factor, fog_error *err);

/* Loads a greyscale PNG (8 or 16 bit: value / 255 or / 65535) or an EXR channel (half or
 * float) into a new fogmap. Fails (nothing allocated) on unreadable or non-image files,
 * ambiguous channels, NaN, negative or values above FOGMAP_MAX_DENSITY (the first such
 * pixel is named); PNG samples are taken as stored (no gamma: a fogmap is
 * data), indexed PNGs are expanded to "R", "G", "B", "A", grey bit depths below 8 are
 * refused; EXR reads part 0, scanline or tiled (the full-resolution level). */
int fogmap_load(const char *path, const fogmap_load_desc *desc, fogmap *out, fog_error *err);

/* Saves a fogmap as a single float channel "Y" EXR (what fogmap_load reads back exactly). */
int fogmap_save_exr(const char *path, const fogmap *map, fog_error *err);

/* The largest density of the map (0 for an all-zero map). */
float fogmap_max_density(const fogmap *map);

/* Saves a fogmap as a 16-bit greyscale PNG: pixel = round(density / max_density * 65535),
 * clamped to [0, 65535]; max_density 0 means fogmap_max_density(map) (1 if that is 0).
 * fogmap_load then fogmap_scale by max_density reads it back within max_density / 131070.
 * Temporary file + rename like image_write_exr. */
int fogmap_save_png16(const char *path, const fogmap *map, float max_density, fog_error *err);

#endif
