/* Cell polynomials of a B-spline grid (see fog_cell_poly.h). */
#include "render/fog_cell_poly.h"

#include <stddef.h>

/* M[d][k][a]: the s^k coefficient of the centred B-spline weight of coefficient i0 + a in a
 * knot cell, s in [0, 1] (fog_cell_weights: d = 1: 1 - s, s; d = 2: (1-s)^2/2,
 * 1/2 + s (1 - s), s^2/2). */
static const double cell_monomials[3][3][3] = {
    {{1, 0, 0}, {0, 0, 0}, {0, 0, 0}},
    {{1, 0, 0}, {-1, 1, 0}, {0, 0, 0}},
    {{0.5, 0.5, 0}, {-1, 1, 0}, {0.5, -1, 0.5}},
};

void fog_cell_poly_size(int width, int height, int degree, int *texels_w, int *texels_h) {
  *texels_w = (width + degree) * (degree == 2 ? 3 : 1);
  *texels_h = height + degree;
}

static double coefficient(const transform_grid *g, int i, int j) {
  if (i < 0 || j < 0 || i >= g->width || j >= g->height) return 0.0;
  return g->coefficients[(size_t)j * (size_t)g->width + (size_t)i];
}

/* Degree 1 (the default basis) runs every frame for every LOD grid: a direct loop,
 * A00 = c00, A10 = c10 - c00, A01 = c01 - c00, A11 = c11 - c10 - c01 + c00 (the general
 * formula with M = [[1, 0], [-1, 1]]), in double. */
static void linear_cell(double c00, double c10, double c01, double c11, float *out) {
  out[0] = (float)c00;
  out[1] = (float)(c10 - c00);
  out[2] = (float)(c01 - c00);
  out[3] = (float)((c11 - c10) - (c01 - c00));
}

static void build_linear(const transform_grid *grid, float *rgba, int texels_w) {
  const int w = grid->width, h = grid->height, cells_w = w + 1, cells_h = h + 1;
  for (int tz = 0; tz < cells_h; tz++) {
    const int j0 = tz - 1;
    float *out = rgba + 4 * (size_t)tz * (size_t)texels_w;
    if (j0 < 0 || j0 + 1 >= h) { /* the first and last rows of cells: half outside */
      for (int tx = 0; tx < cells_w; tx++)
        linear_cell(coefficient(grid, tx - 1, j0), coefficient(grid, tx, j0),
                    coefficient(grid, tx - 1, j0 + 1), coefficient(grid, tx, j0 + 1),
                    out + 4 * tx);
      continue;
    }
    /* interior rows: both coefficient rows exist; only the end cells reach outside */
    const float *r0 = grid->coefficients + (size_t)j0 * (size_t)w, *r1 = r0 + w;
    linear_cell(0.0, r0[0], 0.0, r1[0], out);
    for (int tx = 1; tx < w; tx++)
      linear_cell(r0[tx - 1], r0[tx], r1[tx - 1], r1[tx], out + 4 * tx);
    linear_cell(r0[w - 1], 0.0, r1[w - 1], 0.0, out + 4 * w);
  }
}

void fog_cell_poly_build(const transform_grid *grid, float *rgba) {
  int d = grid->degree, cells_w = grid->width + d, cells_h = grid->height + d;
  int texels_w, texels_h;
  fog_cell_poly_size(grid->width, grid->height, d, &texels_w, &texels_h);
  if (d == 1) {
    build_linear(grid, rgba, texels_w);
    return;
  }
  const double(*M)[3] = cell_monomials[d];
  for (int tz = 0; tz < cells_h; tz++)
    for (int tx = 0; tx < cells_w; tx++) {
      int i0 = tx - d, j0 = tz - d;
      double c[3][3] = {{0}}; /* c[a][b] = coefficient(i0 + a, j0 + b) */
      for (int a = 0; a <= d; a++)
        for (int b = 0; b <= d; b++) c[a][b] = coefficient(grid, i0 + a, j0 + b);
      double A[3][3] = {{0}}; /* A[k][l]: sx^k sz^l */
      for (int k = 0; k <= d; k++)
        for (int l = 0; l <= d; l++)
          for (int a = 0; a <= d; a++)
            for (int b = 0; b <= d; b++) A[k][l] += M[k][a] * M[l][b] * c[a][b];
      float *out;
      switch (d) {
        case 0:
          out = rgba + 4 * ((size_t)tz * (size_t)texels_w + (size_t)tx);
          out[0] = (float)A[0][0], out[1] = out[2] = out[3] = 0.0f;
          break;
        case 1:
          out = rgba + 4 * ((size_t)tz * (size_t)texels_w + (size_t)tx);
          out[0] = (float)A[0][0], out[1] = (float)A[1][0];
          out[2] = (float)A[0][1], out[3] = (float)A[1][1];
          break;
        default:
          for (int l = 0; l < 3; l++) {
            out = rgba + 4 * ((size_t)tz * (size_t)texels_w + (size_t)(3 * tx + l));
            out[0] = (float)A[0][l], out[1] = (float)A[1][l], out[2] = (float)A[2][l];
            out[3] = 0.0f;
          }
      }
    }
}
