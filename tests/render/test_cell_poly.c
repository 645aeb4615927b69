/* The cell polynomials the GL walk reads (render/fog_cell_poly.h) reproduce the B-spline
 * grid f = sum c_ij phi_d(x - i) phi_d(z - j) everywhere, including the cells beyond the
 * grid's edge that only partly overlap it, for degrees 0, 1, 2 and odd sizes.
 * Reference: the centred B-splines summed directly (independent of the cell weights). */
#include <math.h>
#include <stdlib.h>

#include "render/fog_cell_poly.h"
#include "tests/test_util.h"

/* Centred B-spline of degree d (0: box on [-1/2, 1/2), 1: hat, 2: quadratic). */
static double bspline(int d, double x) {
  double a = fabs(x);
  if (d == 0) return (x >= -0.5 && x < 0.5) ? 1.0 : 0.0;
  if (d == 1) return a < 1.0 ? 1.0 - a : 0.0;
  if (a <= 0.5) return 0.75 - a * a;
  return a < 1.5 ? 0.5 * (1.5 - a) * (1.5 - a) : 0.0;
}

static double grid_direct(const transform_grid *g, double x, double z) {
  double sum = 0.0;
  for (int j = 0; j < g->height; j++)
    for (int i = 0; i < g->width; i++)
      sum += g->coefficients[j * g->width + i] * bspline(g->degree, x - i) *
             bspline(g->degree, z - j);
  return sum;
}

/* What fog_cell_load + fog_cell_eval compute in the GLSL, in double from the float texels. */
static double grid_from_cells(const transform_grid *g, const float *rgba, int texels_w,
                              int texels_h, double x, double z) {
  int d = g->degree;
  double off = (d % 2 == 0) ? -0.5 : 0.0;
  int cx = (int)floor(x - off), cz = (int)floor(z - off);
  double sx = x - (cx + off), sz = z - (cz + off);
  int tx = cx + d - d / 2, tz = cz + d - d / 2;
  if (tx < 0 || tz < 0 || tz >= texels_h || tx >= g->width + d) return 0.0;
  double A[3][3] = {{0}}; /* A[k][l] */
  for (int l = 0; l <= d; l++)
    for (int k = 0; k <= d; k++) {
      int texel = (d == 2) ? 3 * tx + l : tx, channel = (d == 2) ? k : (d == 1 ? 2 * l + k : 0);
      A[k][l] = rgba[4 * ((size_t)tz * texels_w + texel) + channel];
    }
  double sum = 0.0;
  for (int k = 0; k <= d; k++)
    for (int l = 0; l <= d; l++) sum += A[k][l] * pow(sx, k) * pow(sz, l);
  return sum;
}

int main(void) {
  srand(7);
  const int sizes[2][2] = {{7, 5}, {12, 9}};
  for (int d = 0; d <= 2; d++)
    for (int s = 0; s < 2; s++) {
      transform_grid g = {.width = sizes[s][0], .height = sizes[s][1], .degree = d, .spacing = 1};
      float coefficients[12 * 9];
      g.coefficients = coefficients;
      for (int k = 0; k < g.width * g.height; k++) coefficients[k] = (float)rand() / RAND_MAX;
      int tw, th;
      fog_cell_poly_size(g.width, g.height, d, &tw, &th);
      CHECK(tw == (g.width + d) * (d == 2 ? 3 : 1) && th == g.height + d,
            "degree %d size %dx%d: %dx%d texels", d, g.width, g.height, tw, th);
      float *rgba = malloc((size_t)tw * th * 4 * sizeof(float));
      fog_cell_poly_build(&g, rgba);
      double worst = 0.0;
      /* Points over the grid and a margin of two cells beyond it, where the edge cells are
       * partly outside. */
      for (int n = 0; n < 4000; n++) {
        double x = -2.0 + (g.width + 3.0) * rand() / RAND_MAX;
        double z = -2.0 + (g.height + 3.0) * rand() / RAND_MAX;
        double e = fabs(grid_from_cells(&g, rgba, tw, th, x, z) - grid_direct(&g, x, z));
        if (e > worst) worst = e;
      }
      CHECK(worst <= 1e-6, "degree %d, %dx%d: max |cells - B-spline sum| = %.3g", d, g.width,
            g.height, worst);
      free(rgba);
    }
  return test_finish("test_cell_poly");
}
