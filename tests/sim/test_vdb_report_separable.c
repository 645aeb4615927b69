/* The 2.5D report measures the model, not its own quadrature: for a separable density
 * rho = a(x,z)·b(y) the 2.5D model f·g is exact (f = a·max b, g = b/max b as linear hats on
 * the layer centres = the trilinear interpolant), so the reported transmittance error is
 * rounding at every elevation; for a tilted (non-separable) blob it is clearly non-zero at
 * oblique views and still zero straight down, where both integrate the same columns. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim/sim.h"
#include "test_util.h"

static double separable(double x, double y, double z) {
  /* Z-up file: z is height */
  const double a = 1.5 * exp(-((x - 0.2) * (x - 0.2) + (y + 0.3) * (y + 0.3)) / 0.5);
  const double b = exp(-z / 0.4) * (1 + 0.5 * sin(6 * z));
  return a * b;
}

static double tilted(double x, double y, double z) {
  /* a blob whose centre moves with height: the columns see a smeared blob */
  const double cx = -0.8 + 1.2 * z;
  return 3.0 * exp(-((x - cx) * (x - cx) + y * y + (z - 0.7) * (z - 0.7)) / 0.08);
}

static int report(double (*fn)(double, double, double), vdb_report_row *rows, int n) {
  const int dim[3] = {40, 40, 28};
  const double h = 0.06;
  vdb_dense_grid g = {.dim = {dim[0], dim[1], dim[2]}, .index_min = {-20, -20, 0},
                      .voxel_size = {h, h, h}, .translation = {0, 0, 0.5 * h}};
  g.values = malloc(sizeof(float) * dim[0] * dim[1] * dim[2]);
  size_t i = 0;
  for (int k = 0; k < dim[2]; k++)
    for (int j = 0; j < dim[1]; j++)
      for (int x = 0; x < dim[0]; x++)
        g.values[i++] = (float)fn(h * (x - 20), h * (j - 20), h * (k + 0.5));
  fog_error err = {0};
  vdb_world_map world;
  vdb_columns cols;
  vdb_profile prof;
  vdb_fogmap_place place;
  fogmap map = {0};
  int status = vdb_world_map_make(&g, &(vdb_placement){0}, &world, &err) ||
               vdb_columns_project(&g, &world, NULL, &cols, &err);
  if (!status)
    status = vdb_profile_fit(cols.layer_mass, cols.layers, cols.y_min, cols.layer_height,
                             &(vdb_profile_desc){0}, &prof, &err) ||
             vdb_fogmap_place_fit(cols.origin_x, cols.origin_x + cols.width * cols.cell_x,
                                  cols.origin_z, cols.origin_z + cols.height * cols.cell_z, 0, 0,
                                  cols.cell_x, &place, &err) ||
             fogmap_create(&map, place.width, place.height, &err) ||
             vdb_columns_resample(&cols, &place, prof.thickness, &map, &err) ||
             vdb_report_run(&g, &world, &map, &place, &prof,
                            &(vdb_report_desc){.rays_per_side = 24, .azimuths = 3}, rows, n,
                            &err);
  CHECK(!status, "%s", err.message);
  fogmap_destroy(&map);
  vdb_columns_destroy(&cols);
  vdb_dense_grid_destroy(&g);
  return status;
}

int main(void) {
  enum { n = 5 };
  const double elevations[n] = {5, 20, 45, 70, 90};
  vdb_report_row rows[n];
  for (int r = 0; r < n; r++) rows[r] = (vdb_report_row){.elevation_deg = elevations[r]};
  if (!report(separable, rows, n))
    for (int r = 0; r < n; r++) {
      printf("separable %2.0f deg: %d rays, mean %.2e, max %.2e, mean T %.3f\n",
             rows[r].elevation_deg, rows[r].rays, rows[r].mean_abs_error,
             rows[r].max_abs_error, rows[r].mean_transmittance);
      CHECK(rows[r].rays > 100, "separable %g deg: only %d rays met fog", elevations[r],
            rows[r].rays);
      CHECK(rows[r].max_abs_error < 2e-5, "separable %g deg: max error %.3g", elevations[r],
            rows[r].max_abs_error);
      CHECK(rows[r].mean_transmittance < 0.95, "separable: fog too thin to test (T %.3f)",
            rows[r].mean_transmittance);
    }
  for (int r = 0; r < n; r++) rows[r] = (vdb_report_row){.elevation_deg = elevations[r]};
  if (!report(tilted, rows, n))
    for (int r = 0; r < n; r++) {
      printf("tilted    %2.0f deg: %d rays, mean %.2e, max %.2e, mean T %.3f\n",
             rows[r].elevation_deg, rows[r].rays, rows[r].mean_abs_error,
             rows[r].max_abs_error, rows[r].mean_transmittance);
      if (elevations[r] < 80)
        CHECK(rows[r].max_abs_error > 0.05, "tilted %g deg: max error only %.3g", elevations[r],
              rows[r].max_abs_error);
      else
        CHECK(rows[r].max_abs_error < 2e-5, "tilted, straight down: max error %.3g",
              rows[r].max_abs_error);
    }
  return test_finish("test_vdb_report_separable");
}
