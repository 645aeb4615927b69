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

int fog_occupancy_create(fog_occupancy *o, const transform_grid *grid, fog_error *err) {
  int bw, bh;
  fog_occupancy_size(grid->width, grid->height, grid->degree, &bw, &bh);
  float *bound = malloc((size_t)bw * (size_t)bh * sizeof *bound);
  if (!bound)
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for a %dx%d occupancy map", bw,
                    bh);
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

void fog_bricks_size(const int dim[3], int bricks[3]) {
  for (int a = 0; a < 3; a++) bricks[a] = (dim[a] + 1 + FOG_OCCUPANCY_BLOCK - 1) / FOG_OCCUPANCY_BLOCK;
}

int fog_bricks_build(const volume_grid_desc *grid, float *bound) {
  const int b = FOG_OCCUPANCY_BLOCK, m = FOG_OCCUPANCY_MARGIN, *d = grid->dim;
  int n[3];
  fog_bricks_size(d, n);
  const size_t count = (size_t)n[0] * n[1] * n[2];
  for (size_t i = 0; i < count; i++) bound[i] = 0.0f;
  /* Voxel v is read by lattice cells c = v - 1 and v, i.e. c + 1 in [v, v + 1]; widened by
   * the margin, [v - m, v + 1 + m]: one or two bricks per axis. */
  for (int k = 0; k < d[2]; k++) {
    const int z0 = (k - m > 0 ? k - m : 0) / b, z1 = (k + 1 + m) / b;
    for (int j = 0; j < d[1]; j++) {
      const int y0 = (j - m > 0 ? j - m : 0) / b, y1 = (j + 1 + m) / b;
      const float *row = grid->values + ((size_t)k * d[1] + j) * d[0];
      for (int i = 0; i < d[0]; i++) {
        float a = fabsf(row[i]);
        if (!(a > 0.0f)) continue;
        const int x0 = (i - m > 0 ? i - m : 0) / b, x1 = (i + 1 + m) / b;
        for (int bz = z0; bz <= z1 && bz < n[2]; bz++)
          for (int by = y0; by <= y1 && by < n[1]; by++)
            for (int bx = x0; bx <= x1 && bx < n[0]; bx++) {
              float *slot = &bound[((size_t)bz * n[1] + by) * n[0] + bx];
              if (a > *slot) *slot = a;
            }
      }
    }
  }
  int empty = 0;
  for (size_t i = 0; i < count; i++) empty += bound[i] == 0.0f;
  return empty;
}
