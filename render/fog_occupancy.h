/* Empty-space skipping for the fogmap walk: a conservative bound of |f| per block of knot
 * cells, so the walk (fog_integral_cpu.c and its GLSL twin) can jump over blocks whose
 * fog is zero, or below a threshold, in one step instead of one piece per cell crossed.
 *
 * The bound: inside knot cell c the grid is f = sum w_a(x) w_b(z) c(i0 + a, j0 + b) with
 * B-spline weights w >= 0 that sum to 1 (partition of unity), so |f| <= max |c| over the
 * cell's (d+1)^2 coefficients. A block of FOG_OCCUPANCY_BLOCK x FOG_OCCUPANCY_BLOCK knot
 * cells takes the max over every coefficient any of its cells reads. Blocks are indexed
 * like the cell polynomials' texels (fog_cell_poly.h): knot cell cx is texel column
 * tx = cx + d - d/2, and block bx holds tx in [bx B, bx B + B - 1], which read coefficients
 * i in [bx B - d, bx B + B - 1] (widened by FOG_OCCUPANCY_MARGIN each side).
 *
 * What a skip costs (docs/integral.md, Empty space): a block with bound 0 holds f = 0
 * exactly, so skipping it leaves the walk's sum bit for bit the same (pieces there add
 * +0). Skipping blocks with bound <= epsilon drops at most epsilon * extinction * g_max per
 * unit of ray length skipped: |delta optical depth| <= epsilon * extinction * g_max * L,
 * L the ray's length inside the box, g_max the profile's largest value (1 for slab and
 * exponential, max |b_k| for a B-spline), and |delta tau| <= |delta optical depth|. */
#ifndef FOGPIPE_RENDER_FOG_OCCUPANCY_H
#define FOGPIPE_RENDER_FOG_OCCUPANCY_H

#include "render/volume_march.h"
#include "transform/transform.h"

/* Knot cells per block side. Measured with `fogpipe bench render` (docs/integral.md). */
#define FOG_OCCUPANCY_BLOCK 8
/* Coefficients beyond a block's own that count towards its bound, each side: the hardware
 * filter's (GL_LINEAR) quantised weights can read one past a cell's (d+1)^2 at its edge. */
#define FOG_OCCUPANCY_MARGIN 1

typedef struct fog_occupancy {
  int width, height; /* blocks */
  int degree;        /* of the grid it was built from */
  float *bound;      /* width x height, row-major: max |c| over the block's coefficients */
} fog_occupancy;

/* The block counts of a width x height grid of degree d: ceil((width + d) / B) etc. */
void fog_occupancy_size(int width, int height, int degree, int *blocks_w, int *blocks_h);
/* Fills bound (blocks_w x blocks_h floats) from the grid's coefficients; returns how many
 * blocks are empty (bound 0). */
int fog_occupancy_build(const transform_grid *grid, float *bound);

/* Owned form for the CPU twin: 0 on success, non-zero with err set when out of memory. */
int fog_occupancy_create(fog_occupancy *occupancy, const transform_grid *grid, fog_error *err);
void fog_occupancy_destroy(fog_occupancy *occupancy);

/* The bound of the block holding knot cell (cx, cz); 0 outside the grid's blocks. */
float fog_occupancy_at(const fog_occupancy *occupancy, int cx, int cz);

/* The same for the 3D volume (FOG_MODEL_VOLUME), as NanoVDB's HDDA skips its empty nodes:
 * bricks of FOG_OCCUPANCY_BLOCK^3 lattice cells of index space. Lattice cell c (index
 * positions [c, c + 1] per axis, c = -1 .. dim - 1: the zero ring included) is
 * trilinear between voxels c and c + 1, so its |density| is at most the max |voxel| over
 * those 8; brick b holds cells c + 1 in [b B, b B + B - 1] and its bound is the max over
 * every voxel they read, widened by FOG_OCCUPANCY_MARGIN for the hardware filter. The
 * bricks of a grid: ceil((dim + 1) / B) per axis. */
void fog_bricks_size(const int dim[3], int bricks[3]);
/* Fills bound (bricks[0] x bricks[1] x bricks[2], x fastest) from the voxels; returns how
 * many bricks are empty (bound 0). */
int fog_bricks_build(const volume_grid_desc *grid, float *bound);

#endif
