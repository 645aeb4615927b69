/* The GPU atlas holds every level's grid at its documented offset, without overlap:
 * unpacking each grid from the atlas gives it back exactly, and the texels outside
 * all grids are zero (so a grid spilling into another would show). */
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "transform_test_util.h"

static void check(int b, int w, int h, int J) {
  transform_plan *plan;
  fog_error err;
  CHECK((plan = transform_plan_create(&(transform_desc){.width = w, .height = h, .levels = J,
      .basis = test_bases[b]}, &err)) != NULL, "%s", err.message);
  size_t n = (size_t)w * h;
  float *f = malloc(n * sizeof *f), *c = malloc(n * sizeof *c), *approx[12];
  transform_grid grids[12];
  test_fill_fogmap(f, w, h);
  transform_forward(plan, f, c);
  for (int l = 0; l <= J; l++) {
    int lw, lh;
    transform_level_size(plan, l, &lw, &lh);
    approx[l] = malloc((size_t)lw * lh * sizeof(float));
  }
  transform_pyramid(plan, c, approx);
  size_t covered = 0;
  for (int l = 0; l <= J; l++) {
    CHECK(!transform_grid_create_level(plan, l, approx[l], &grids[l], &err), "%s", err.message);
    covered += (size_t)grids[l].width * grids[l].height;
  }
  int aw, ah;
  transform_atlas_size(plan, &aw, &ah);
  float *atlas = malloc(sizeof(float) * (size_t)aw * ah);
  transform_atlas_pack(plan, grids, atlas);
  size_t nonzero = 0;
  for (size_t i = 0; i < (size_t)aw * ah; i++) nonzero += atlas[i] != 0.0f;
  int same = 1;
  for (int l = 0; l <= J; l++) {
    int x, y;
    transform_atlas_offset(plan, l, &x, &y);
    CHECK(x + grids[l].width <= aw && y + grids[l].height <= ah, "level %d outside the atlas", l);
    for (int j = 0; j < grids[l].height && same; j++)
      same = !memcmp(atlas + (size_t)(y + j) * aw + x,
                     grids[l].coefficients + (size_t)j * grids[l].width,
                     sizeof(float) * grids[l].width);
    CHECK(same, "%s %dx%d J=%d: level %d not intact in the atlas", test_basis_names[b], w, h, J, l);
  }
  /* the fogmap values are all positive, so every grid texel is non-zero (approximately) */
  CHECK(nonzero <= covered, "%s %dx%d J=%d: %zu non-zero texels, grids cover %zu",
        test_basis_names[b], w, h, J, nonzero, covered);
  for (int l = 0; l <= J; l++) transform_grid_destroy(&grids[l]), free(approx[l]);
  free(atlas), free(f), free(c);
  transform_plan_destroy(plan);
}

int main(void) {
  for (int b = 0; b < 3; b++) {
    check(b, 64, 48, 4);
    check(b, 37, 70, 6);
    check(b, 16, 16, 0);
    check(b, 300, 200, 3);
  }
  return test_finish("test_atlas_layout");
}
