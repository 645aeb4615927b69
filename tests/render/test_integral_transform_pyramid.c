/* The integrator on real pyramids from transform/ (not test-made grids): the placement
 * conventions of the two libraries agree and the LOD identity holds.
 *  - Degree 0 and 1 B-splines interpolate their coefficients at sample centres, so a
 *    vertical ray through fogmap sample (x, y) in a unit slab has optical depth exactly
 *    fogmap[x, y] (grid A_J, with its ghosts and origin as exported).
 *  - For every degree, A_J's optical depth along random rays equals the ray integral of
 *    the fogmap's own grid exported from the identity (the fogmap is A_J).
 *  - Sum of details == approximation switching for the same mu (A_l = A_0 + D_1..D_l as
 *    functions, transform.h), to float rounding. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/fog_field.h"
#include "fog_test_scene.h"
#include "test_util.h"
#include "transform/transform.h"

enum { MAP_W = 37, MAP_H = 26, LEVELS = 2 };

int main(void) {
  const transform_basis bases[3] = {TRANSFORM_HAAR, TRANSFORM_LINEAR, TRANSFORM_QUADRATIC};
  float *fogmap = malloc(sizeof(float) * MAP_W * MAP_H);
  float *coefficients = malloc(sizeof(float) * MAP_W * MAP_H);
  for (int y = 0; y < MAP_H; y++)
    for (int x = 0; x < MAP_W; x++)
      fogmap[y * MAP_W + x] = (float)(0.6 + 0.3 * sin(0.4 * x) * cos(0.3 * y) + 0.1 * fog_test_uniform());
  double worst_sample = 0.0, worst_methods = 0.0;
  for (int b = 0; b < 3; b++) {
    fog_error terr = {0};
    transform_plan *plan = NULL;
    transform_desc desc = {.width = MAP_W, .height = MAP_H, .levels = LEVELS, .basis = bases[b]};
    CHECK((plan = transform_plan_create(&desc, &terr)) != NULL, "plan: %s", terr.message);
    if (!plan) continue;
    int degree = transform_basis_degree(bases[b]);
    float *approx[LEVELS + 1], *detail[LEVELS + 1];
    for (int l = 0; l <= LEVELS; l++) {
      int w, h;
      transform_level_size(plan, l, &w, &h);
      approx[l] = malloc(sizeof(float) * w * h);
      detail[l] = malloc(sizeof(float) * w * h);
    }
    CHECK(transform_forward(plan, fogmap, coefficients) == 0, "forward");
    CHECK(transform_pyramid(plan, coefficients, approx) == 0, "pyramid");
    CHECK(transform_details(plan, coefficients, detail) == 0, "details");
    transform_grid ga[LEVELS + 1], gd[LEVELS], fine;
    for (int l = 0; l <= LEVELS; l++) {
      CHECK(transform_grid_create_level(plan, l, approx[l], &ga[l], &terr) == 0, "A_%d: %s", l,
            terr.message);
      if (l > 0)
        CHECK(transform_grid_create_level(plan, l, detail[l], &gd[l - 1], &terr) == 0, "D_%d: %s",
              l, terr.message);
    }
    CHECK(transform_grid_create_level(plan, LEVELS, fogmap, &fine, &terr) == 0, "fine: %s",
          terr.message);
    fog_volume v = {.map_width = MAP_W, .map_height = MAP_H, .origin_x = -40.0, .origin_z = 10.0,
                    .cell_size = 2.0, .extinction = 1.0, .profile = {.kind = FOG_PROFILE_SLAB, .y_floor = 0.0, .y_top = 1.0}};
    /* Vertical rays through sample centres: X = origin_x + (x + 1/2) h. */
    if (degree <= 1)
      for (int y = 0; y < MAP_H; y++)
        for (int x = 0; x < MAP_W; x++) {
          double cam[3] = {v.origin_x + (x + 0.5) * v.cell_size, 5.0,
                           v.origin_z + (y + 0.5) * v.cell_size};
          double down[3] = {0.0, -1.0, 0.0};
          double od = fog_optical_depth(&v, &fine, cam, down, 0.0, HUGE_VAL);
          double od_a = fog_optical_depth(&v, &ga[LEVELS], cam, down, 0.0, HUGE_VAL);
          double e = fmax(fabs(od - fogmap[y * MAP_W + x]), fabs(od_a - fogmap[y * MAP_W + x]));
          if (e > worst_sample) worst_sample = e;
          CHECK(e <= 2e-6, "degree %d sample (%d, %d): optical depth %.9g / %.9g, fogmap %.9g",
                degree, x, y, od, od_a, fogmap[y * MAP_W + x]);
        }
    fog_lod lod = {.levels = LEVELS, .approx = ga, .detail = gd};
    for (int r = 0; r < 300; r++) {
      double cam[3], dir[3];
      v.profile.y_top = 10.0;
      double lo[3], hi[3];
      fog_volume_box(&v, lo, hi);
      for (int a = 0; a < 3; a++) {
        double ext = hi[a] - lo[a];
        cam[a] = fog_test_range(lo[a] - ext, hi[a] + ext);
        dir[a] = fog_test_range(lo[a], hi[a]) - cam[a];
      }
      fog_test_unit(dir);
      double a_j = fog_optical_depth(&v, &ga[LEVELS], cam, dir, 0.0, HUGE_VAL);
      double f_j = fog_optical_depth(&v, &fine, cam, dir, 0.0, HUGE_VAL);
      CHECK(fabs(a_j - f_j) <= 1e-5 * fmax(1.0, f_j), "degree %d: A_J %.9g vs fogmap grid %.9g",
            degree, a_j, f_j);
      lod.mu = fog_test_uniform();
      double sum = fog_optical_depth_lod(&v, &lod, FOG_LOD_SUM_OF_DETAILS, cam, dir, HUGE_VAL);
      double sw = fog_optical_depth_lod(&v, &lod, FOG_LOD_SWITCH, cam, dir, HUGE_VAL);
      double e = fabs(sum - sw) / fmax(1.0, sw);
      if (e > worst_methods) worst_methods = e;
      CHECK(e <= 1e-5, "degree %d mu %g: sum of details %.9g, switching %.9g", degree, lod.mu, sum, sw);
    }
    for (int l = 0; l <= LEVELS; l++) {
      transform_grid_destroy(&ga[l]);
      if (l > 0) transform_grid_destroy(&gd[l - 1]);
      free(approx[l]);
      free(detail[l]);
    }
    transform_grid_destroy(&fine);
    transform_plan_destroy(plan);
  }
  printf("sample-centre optical depth vs fogmap %.2e; sum of details vs switching %.2e\n",
         worst_sample, worst_methods);
  free(fogmap);
  free(coefficients);
  return test_finish("test_integral_transform_pyramid");
}
