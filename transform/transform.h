/* fogpipe transform: B-spline wavelet decomposition of fogmaps (Giroud & Biri 2010).
 *
 * The public header of the transform library. (Owner: the transform work; the
 * transform_grid contract below is shared with render/ and must not change shape
 * without updating both.) */
#ifndef FOGPIPE_TRANSFORM_H
#define FOGPIPE_TRANSFORM_H

#include <stddef.h>

/* Errors are returned, never printed: a failing call fills message and returns non-zero. */
typedef struct transform_error {
  char message[512];
} transform_error;

/* A scaling-function grid ready to be rendered: the continuous function
 *   f(u, v) = sum_{i<width, j<height} coefficients[j*width + i]
 *             * phi_d((u - origin_u)/spacing - i) * phi_d((v - origin_v)/spacing - j)
 * where phi_d is the *centred* B-spline of degree d (0: box on [-1/2,1/2], 1: hat on
 * [-1,1], 2: quadratic on [-3/2,3/2]) and (u, v) are fine-fogmap sample units: fogmap
 * sample (x, y) sits at (u, v) = (x, y), and the fog's box is [-1/2, W-1/2] x [-1/2, H-1/2]
 * for a W x H fogmap. Ghost coefficients needed by the boundary extension (symmetric or
 * periodic) are already materialised in the grid, so a renderer can treat coefficients
 * outside it as zero and integrate only inside the box. */
typedef struct transform_grid {
  int width, height;    /* coefficients stored, ghosts included */
  float *coefficients;  /* row-major, width fastest */
  double origin_u;      /* position of coefficient (0,0), fine-sample units */
  double origin_v;
  double spacing;       /* 2^(J-l) at pyramid level l; 1 at the finest level */
  int degree;           /* 0, 1, 2 */
} transform_grid;

/* Allocates a zeroed grid's coefficients; transform_grid_destroy frees them. */
int transform_grid_create(transform_grid *grid, int width, int height, transform_error *err);
void transform_grid_destroy(transform_grid *grid);

#endif
