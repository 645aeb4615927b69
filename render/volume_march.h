/* A GL ray march of a dense 3D density grid (a GL_R32F 3D texture, hardware trilinear):
 * the GPU twin of the CPU reference march in `fogpipe import --report` (sim/vdb_report.c),
 * for the same orthographic views, rays and midpoint samples.
 *
 * The grid: values[(k * dim[1] + j) * dim[0] + i], voxel (i, j, k) centred at index
 * position u = (i, j, k); density between centres is trilinear and zero beyond the outer
 * centres' neighbours (a zero border), as the CPU march's. World points map to index
 * positions by u = index_from_world * p + index_offset (an axis permutation and scale for
 * VDB grids).
 *
 * A view (volume_march_view): parallel rays along the unit direction dir through the
 * points o = (lo.x + (ix + 1/2)(hi.x - lo.x)/side, y_mid, lo.z + (iz + 1/2)(hi.z - lo.z)/side),
 * each clipped to the box [lo, hi], n = ceil((t1 - t0)/step) midpoint samples; the result
 * is the optical depth per ray, iz major, or -1 where the ray misses the box. */
#ifndef FOGPIPE_RENDER_VOLUME_MARCH_H
#define FOGPIPE_RENDER_VOLUME_MARCH_H

#include "transform/fog_error.h"

typedef struct volume_grid_desc {
  int dim[3];
  const float *values;
  double index_from_world[3][3]; /* row c: index coordinate c from the world point */
  double index_offset[3];
} volume_grid_desc;

/* The index position u = index_from_world p + index_offset of world point p. */
void volume_grid_index_of(const volume_grid_desc *grid, const double p[3], double u[3]);
/* index_from_world as GLSL's mat3 wants it: float, column-major. */
void volume_grid_gl_matrix(const volume_grid_desc *grid, float m[9]);

typedef struct volume_view_desc {
  double lo[3], hi[3]; /* the box rays are clipped to, world */
  double dir[3];       /* unit direction */
  double y_mid;        /* the ray origins' height */
  int side;            /* side x side rays */
  double step;         /* march step, world units */
} volume_view_desc;

typedef struct volume_march volume_march;

/* Needs a current GL context. Uploads the grid and compiles the program. */
volume_march *volume_march_create(const volume_grid_desc *grid, fog_error *err);
void volume_march_destroy(volume_march *march);

/* optical_depth: side * side floats (iz major, ix minor). */
int volume_march_view(volume_march *march, const volume_view_desc *view, float *optical_depth,
                      fog_error *err);

#endif
