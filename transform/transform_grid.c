/* transform_grid: allocation of renderable scaling-function grids. */
#include <stdio.h>
#include <stdlib.h>

#include "transform/transform.h"

int transform_grid_create(transform_grid *grid, int width, int height, fog_error *err) {
  *grid = (transform_grid){.width = width, .height = height, .spacing = 1.0};
  if (width <= 0 || height <= 0) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "grid size %dx%d: both must be positive", width,
             height);
    return 1;
  }
  grid->coefficients = calloc((size_t)width * (size_t)height, sizeof(float));
  if (!grid->coefficients) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for a %dx%d grid", width, height);
    return 1;
  }
  return 0;
}

void transform_grid_destroy(transform_grid *grid) {
  free(grid->coefficients);
  *grid = (transform_grid){0};
}
