/* Block bounds of a B-spline grid for empty-space skipping (see fog_occupancy.h). */
#include "render/fog_occupancy.h"

#include <math.h>
#include <stdlib.h>

void fog_occupancy_size(int width, int height, int degree, int *blocks_w, int *blocks_h) {
  const int b = FOG_OCCUPANCY_BLOCK;
  *blocks_w = (width + degree + b - 1) / b;
  *blocks_h = (height + degree + b - 1) / b;
}

int fog_occupancy_build(const transform_grid *grid, float *bound) {
  const int b = FOG_OCCUPANCY_BLOCK, d = grid->degree, w = grid->width, h = grid->height;
  int bw, bh;
  fog_occupancy_size(w, h, d, &bw, &bh);
  for (int i = 0; i < bw * bh; i++) bound[i] = 0.0f;
  /* Each coefficient i is read by texel columns tx in [i, i + d]: it raises the bound of
   * every block those columns fall in (one or two per axis). One more column each side
   * (FOG_OCCUPANCY_MARGIN) for the hardware-filtered variant, whose fixed-point filter
   * weights can reach a coefficient beyond the cell's own near its edge. */
  const int m = FOG_OCCUPANCY_MARGIN;
  for (int j = 0; j < h; j++) {
    const float *row = grid->coefficients + (size_t)j * (size_t)w;
    const int by0 = (j - m > 0 ? j - m : 0) / b, by1 = (j + d + m) / b;
    for (int i = 0; i < w; i++) {
      float a = fabsf(row[i]);
      if (!(a > 0.0f)) continue;
      const int bx0 = (i - m > 0 ? i - m : 0) / b, bx1 = (i + d + m) / b;
      for (int by = by0; by <= by1 && by < bh; by++)
        for (int bx = bx0; bx <= bx1 && bx < bw; bx++) {
          float *m = &bound[(size_t)by * (size_t)bw + (size_t)bx];
          if (a > *m) *m = a;
        }
    }
  }
  int empty = 0;
  for (int i = 0; i < bw * bh; i++) empty += bound[i] == 0.0f;
  return empty;
}

int fog_occupancy_create(fog_occupancy *o, const transform_grid *grid) {
  int bw, bh;
  fog_occupancy_size(grid->width, grid->height, grid->degree, &bw, &bh);
  float *bound = malloc((size_t)bw * (size_t)bh * sizeof *bound);
  if (!bound) return 1;
  fog_occupancy_build(grid, bound);
  *o = (fog_occupancy){.width = bw, .height = bh, .degree = grid->degree, .bound = bound};
  return 0;
}

void fog_occupancy_destroy(fog_occupancy *o) {
  free(o->bound);
  *o = (fog_occupancy){0};
}

float fog_occupancy_at(const fog_occupancy *o, int cx, int cz) {
  const int shift = o->degree - o->degree / 2, b = FOG_OCCUPANCY_BLOCK;
  const int tx = cx + shift, tz = cz + shift;
  if (tx < 0 || tz < 0) return 0.0f;
  const int bx = tx / b, bz = tz / b;
  if (bx >= o->width || bz >= o->height) return 0.0f;
  return o->bound[(size_t)bz * (size_t)o->width + (size_t)bx];
}
