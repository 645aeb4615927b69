/* Fogmap allocation. Image I/O lives in fogmap_io.c. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/fogmap.h"
#include "sim/image_io.h"

int fogmap_create(fogmap *map, int width, int height, fog_error *err) {
  *map = (fogmap){.width = width, .height = height};
  if (width <= 0 || height <= 0) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fogmap size %dx%d: both must be positive", width,
             height);
    return 1;
  }
  /* 64-byte aligned (aligned_alloc wants a multiple): the transform's streaming levels
   * read it with vector loads that then split no cache line (transform_alloc_floats) */
  size_t count = (size_t)width * (size_t)height;
  size_t bytes = (count * sizeof(float) + 63) / 64 * 64;
  map->density = count <= (SIZE_MAX - 64) / sizeof(float) ? aligned_alloc(64, bytes) : NULL;
  if (map->density) memset(map->density, 0, bytes);
  if (!map->density) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for a %dx%d fogmap", width, height);
    return 1;
  }
  return 0;
}

void fogmap_destroy(fogmap *map) {
  free(map->density);
  *map = (fogmap){0};
}

int fogmap_scale(fogmap *map, double factor, fog_error *err) {
  if (!(factor >= 0.0) || !isfinite(factor))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fogmap scale %g: expected a finite factor >= 0",
                    factor);
  size_t count = (size_t)map->width * (size_t)map->height;
  for (size_t i = 0; i < count; i++) map->density[i] = (float)(map->density[i] * factor);
  return 0;
}
