/* fogpipe transform: B-spline wavelet decomposition of fogmaps (Giroud & Biri 2010).
 *
 * The public header of the transform library. (Owner: the transform work; the
 * transform_grid contract below is shared with render/ and must not change shape
 * without updating both.) */
#ifndef FOGPIPE_TRANSFORM_H
#define FOGPIPE_TRANSFORM_H

#include "transform/fog_error.h"
#include <stddef.h>

/* Errors are returned, never printed: a failing call fills message and returns non-zero. */

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
int transform_grid_create(transform_grid *grid, int width, int height, fog_error *err);
void transform_grid_destroy(transform_grid *grid);

/* ---------------------------------------------------------------------------------
 * The wavelet transform (docs/transform.md has the maths, conventions and layouts).
 *
 * Lifecycle (FFTW-style): transform_plan_create() allocates everything once for one
 * size/basis/mode; transform_forward(), transform_inverse(), transform_pyramid(),
 * transform_details(), transform_detail_energy() and transform_grid_export() never
 * allocate; transform_plan_destroy() frees.
 *
 * Conventions: UNNORMALISED lifting, so approximation coefficients are density-like
 * (a constant fogmap c gives A_l = c at every level). PyWavelets' coefficients are
 * ours times sqrt(2) per level per dimension (2 per level in 2D), details included.
 * Levels: l = 0 is the coarsest approximation A_0, l = J the fogmap; detail bands
 * l = 1 (coarsest) .. J (finest); A_l = A_0 + bands 1..l.
 * ------------------------------------------------------------------------------- */

typedef enum transform_basis {
  TRANSFORM_LINEAR = 0,    /* degree 1: CDF 5/3 = PyWavelets 'bior2.2' (the default) */
  TRANSFORM_HAAR = 1,      /* degree 0: Haar */
  TRANSFORM_QUADRATIC = 2  /* degree 2: PyWavelets 'bior3.3' */
} transform_basis;

typedef enum transform_boundary {
  TRANSFORM_SYMMETRIC = 0, /* mirror extension (the default: fog is not periodic) */
  TRANSFORM_PERIODIC = 1   /* periodic; needs width and height divisible by 2^J */
} transform_boundary;

typedef enum transform_decomposition {
  TRANSFORM_NONSTANDARD = 0, /* Mallat: rows and columns once per level (the default) */
  TRANSFORM_STANDARD = 1     /* full 1D transform of every row, then of every column */
} transform_decomposition;

/* Zero is default: linear basis, symmetric, non-standard, one thread. */
typedef struct transform_desc {
  int width, height;  /* fogmap size, any size >= 1 (odd too) */
  int levels;         /* J >= 0 */
  transform_basis basis;
  transform_boundary boundary;
  transform_decomposition decomposition;
  int threads;        /* 0 or 1: one thread; 2: two threads (a worker made at create) */
  /* 0: each level in one streaming pass where the configuration allows (symmetric,
   * non-standard, >= 8 rows); 1: always rows, then strips of columns (the reference
   * the streaming levels are tested against). Same coefficients to float rounding. */
  int two_pass;
} transform_desc;

typedef struct transform_plan transform_plan;

/* Degree of the synthesis B-spline of a basis (0, 1, 2). */
int transform_basis_degree(transform_basis basis);
/* The basis of B-spline degree 0, 1 or 2 (the inverse of transform_basis_degree); any other
 * degree gives the default, linear. */
transform_basis transform_basis_of_degree(int degree);
/* The largest J a width x height fogmap allows in that boundary mode (symmetric: every
 * level split needs >= 2 samples; periodic: also an even length). */
int transform_max_levels(int width, int height, transform_boundary boundary);

/* `count` floats on a 64-byte boundary, for fogmaps, coefficients and pyramid levels:
 * the streaming levels' vector loads and stores then split no cache line (the 1024^2
 * CDF 5/3 level runs ~20 % faster than on malloc's 16-byte offset, docs/transform.md).
 * Any buffer works; free() releases this one. NULL when out of memory. */
float *transform_alloc_floats(size_t count);

/* Fails (naming the largest J that fits) when the size is too small for desc->levels. */
transform_plan *transform_plan_create(const transform_desc *desc, fog_error *err);
void transform_plan_destroy(transform_plan *plan);
const transform_desc *transform_plan_desc(const transform_plan *plan);

/* Size of level l (0..J): stored coefficients of A_l (and of the deconstructed D_l). */
void transform_level_size(const transform_plan *plan, int level, int *width, int *height);

/* Coefficient array layout (width x height floats, row-major, "Mallat layout"): A_0 in
 * the top-left w_0 x h_0 block; detail band l (1..J) fills the L-shaped region of
 * [0,w_l) x [0,h_l) outside [0,w_{l-1}) x [0,h_{l-1}), as three rectangles: */
typedef enum transform_orientation {
  TRANSFORM_DETAIL_X = 0,  /* x in [w_{l-1}, w_l), y in [0, h_{l-1})  (high-pass in x) */
  TRANSFORM_DETAIL_Y = 1,  /* x in [0, w_{l-1}), y in [h_{l-1}, h_l)  (high-pass in y) */
  TRANSFORM_DETAIL_XY = 2  /* x in [w_{l-1}, w_l), y in [h_{l-1}, h_l) (both)          */
} transform_orientation;
void transform_band_rect(const transform_plan *plan, int level, transform_orientation o,
                         int *x, int *y, int *width, int *height);

/* fogmap (width*height) -> coefficients (width*height). in == out is allowed. */
int transform_forward(transform_plan *plan, const float *fogmap, float *coefficients);
/* coefficients -> fogmap; perfect reconstruction to float rounding: within 1e-6 of the
 * largest |value| (test_perfect_reconstruction), but for the quadratic basis with
 * symmetric ends on sizes whose halvings run odd (2^k + 1), whose right-end ghost rules
 * extrapolate with weights growing 2x a level: 2^J float epsilons (1025^2, J = 10:
 * 1.2e-4; 257^2, J = 8: 1.7e-6; the renderer's J <= 7). in == out allowed. */
int transform_inverse(transform_plan *plan, const float *coefficients, float *fogmap);

/* The approximation pyramid: approx[l] (w_l*h_l floats, l = 0..J) = A_l, the inverse
 * transform with all bands finer than l set to zero (approx[J] = the fogmap). */
int transform_pyramid(transform_plan *plan, const float *coefficients, float *const *approx);
/* Deconstructed details (Giroud & Biri §4.4): detail[l] (w_l*h_l floats, l = 1..J;
 * detail[0] is ignored and may be NULL) = band l pushed once through the synthesis
 * filters, i.e. the three orientations merged into one scaling grid at level l, so
 * that A_l = refine(A_{l-1}) + D_l and, as functions, A_l = A_0 + D_1 + ... + D_l. */
int transform_details(transform_plan *plan, const float *coefficients, float *const *detail);
/* The pyramid the renderer draws as fog (non-standard decomposition only; else, or out of
 * memory, non-zero with err set):
 *  - approx[l] = A_l as transform_pyramid makes it, and approx[J] the fogmap itself (its
 *    synthesis is skipped: the reconstruction rounds 0 to -1e-9, and cost 3/4 of the work);
 *  - approx[l] (l < J) clamped at 0: the linear and quadratic bases' filters have negative
 *    taps, so a coarse A_l dips below 0 next to a sharp edge (-0.18 on a ground fog of
 *    peak 1), and a ray through it would leave the fog with transmittance > 1;
 *  - with detail != NULL, transform_details' D_l, rewritten next to a clamped level as
 *    D_l = A_l - refine(A_{l-1}), so that the sum of details still telescopes: A_0 + D_1 +
 *    ... + D_l = A_l, the same fog as switching.
 * The first clamp that rewrites a D_l allocates the plan's zero band (kept with it). */
int transform_density_pyramid(transform_plan *plan, const float *fogmap, const float *coefficients,
                              float *const *approx, float *const *detail, fog_error *err);
/* energy[3*l + o] = sum of squared coefficients of band l, orientation o (l = 1..J;
 * entries 0..2 are set to zero). For LOD decisions; coefficients are unnormalised. */
void transform_detail_energy(const transform_plan *plan, const float *coefficients,
                             double *energy);

/* Renderable grid of level l (0..J) from its stored coefficients (w_l*h_l, e.g.
 * approx[l], detail[l], or the fogmap for l = J): size (w_l+2g) x (h_l+2g) with
 * g = 1 ghost ring for degree 1 and 2 (0 for Haar), ghosts materialised from the
 * boundary extension so that inside the fog box the grid's function is exactly the
 * transform's; origin = position of grid coefficient (0,0); spacing 2^(J-l). */
void transform_grid_size(const transform_plan *plan, int level, int *width, int *height);
int transform_grid_export(const transform_plan *plan, int level, const float *stored,
                          transform_grid *grid, fog_error *err);
/* transform_grid_create (right size) + transform_grid_export: allocates. */
int transform_grid_create_level(const transform_plan *plan, int level, const float *stored,
                                transform_grid *grid, fog_error *err);

/* GPU upload: the grids of one pyramid (approximations A_0..A_J, or deconstructed
 * details D_1..D_J) packed in one single-channel float texture ("atlas"), unused texels
 * zero. Level J's grid sits at (0,0); levels l < J are stacked in a column to its right,
 * coarsest at the bottom: x = width of level J's grid, y = sum of the grid heights of
 * levels l+1 .. J-1. Grid coefficient (i,j) of level l is texel (x_l + i, y_l + j). */
void transform_atlas_size(const transform_plan *plan, int *width, int *height);
void transform_atlas_offset(const transform_plan *plan, int level, int *x, int *y);
/* grids[l] for l = 0..J (from transform_grid_export); a grid with no coefficients
 * (e.g. grids[0] of the details) leaves its place zero. atlas: width*height floats. */
void transform_atlas_pack(const transform_plan *plan, const transform_grid *grids, float *atlas);

#endif
