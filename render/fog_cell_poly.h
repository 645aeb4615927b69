/* The fogmap grid as one polynomial per knot cell, for the GL walk (fog_integral.glsl).
 *
 * Inside knot cell (cx, cz) a degree-d grid f = sum c_ij phi_d(x - i) phi_d(z - j) is a
 * tensor polynomial in the cell-local coordinates (sx, sz) in [0, 1]^2:
 *   f = sum_{k,l <= d} A_kl sx^k sz^l,  A_kl = sum_{a,b} M_ka M_lb c(i0 + a, j0 + b),
 * i0 = cx - d/2, where M_ka is the s^k coefficient of the cell weight of coefficient
 * i0 + a (fog_cell_weights in the GLSL, docs/integral.md). Storing A per cell lets the walk
 * fetch one texel per cell (degree 1) instead of (d+1)^2 coefficients, and evaluate f with
 * d^2 + 2d fused multiply-adds, no weights.
 *
 * Layout (RGBA32F): cells cx = -(d - d/2) .. W - 1 + d/2 (every cell that touches a
 * coefficient), texel column tx = cx + d - d/2 (so i0 = tx - d), row tz likewise.
 *   degree 0: texel (tx, tz) = (A00, 0, 0, 0)
 *   degree 1: texel (tx, tz) = (A00, A10, A01, A11)
 *   degree 2: texel (3 tx + l, tz) = (A0l, A1l, A2l, 0), l = 0, 1, 2
 * The A are computed in double and rounded once to float. */
#ifndef FOGPIPE_RENDER_FOG_CELL_POLY_H
#define FOGPIPE_RENDER_FOG_CELL_POLY_H

#include "transform/transform.h"

/* The texture size in texels of a width x height grid of degree 0..2. */
void fog_cell_poly_size(int width, int height, int degree, int *texels_w, int *texels_h);

/* Fills rgba (4 floats per texel, texels_w * texels_h texels, rows tz fastest x) from the
 * grid's coefficients (zero outside the grid). */
void fog_cell_poly_build(const transform_grid *grid, float *rgba);

#endif
