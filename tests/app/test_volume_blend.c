/* Blending two frames of a played volume sequence (app/volume_blend.h). Reference: each
 * blended voxel found by its world point in each frame's own grid, (1 - w)·a + w·b.
 * An empty frame (one voxel of 0 at index 0) beside smoke whose indices count from its
 * world position (index -3000 at 2 cm voxels 60 m away) made a union of 3e9 voxels. */
#include <math.h>
#include <stdlib.h>

#include "app/volume_blend.h"
#include "test_util.h"

typedef struct frame_and_grid {
  vdb_frame frame;
  volume_grid_desc grid;
  float values[64];
} frame_and_grid;

/* A frame of dims at index corner lo, index = world (identity placement), voxel v = seed + v. */
static void make(frame_and_grid *f, const int lo[3], const int dim[3], int active, float seed) {
  *f = (frame_and_grid){0};
  vdb_dense_grid *g = &f->frame.grid;
  for (int c = 0; c < 3; c++) {
    g->index_min[c] = lo[c], g->dim[c] = dim[c];
    f->frame.world.index_axis[c] = c, f->frame.world.step[c] = 1;
    f->grid.dim[c] = dim[c];
    f->grid.index_from_world[c][c] = 1;
    f->grid.index_offset[c] = -lo[c];
  }
  const int n = dim[0] * dim[1] * dim[2];
  for (int v = 0; v < n; v++) f->values[v] = active ? seed + (float)v : 0.0f;
  g->values = f->values;
  g->active_voxels = active ? n : 0;
  f->grid.values = f->values;
}

/* The value of grid g at world point p (the voxel holding it), 0 outside. */
static double value_at(const volume_grid_desc *g, const double p[3]) {
  double u[3];
  volume_grid_index_of(g, p, u);
  int i[3];
  for (int c = 0; c < 3; c++) {
    i[c] = (int)floor(u[c]);
    if (i[c] < 0 || i[c] >= g->dim[c]) return 0;
  }
  return g->values[((size_t)i[2] * g->dim[1] + i[1]) * g->dim[0] + i[0]];
}

static void check_blend(const char *name, frame_and_grid *a, frame_and_grid *b, double w,
                        long long max_voxels) {
  volume_grid_desc out;
  fog_error err = {0};
  CHECK(!volume_blend(&a->frame, &a->grid, &b->frame, &b->grid, w, &out, &err), "%s: %s", name,
        err.message);
  const long long voxels = (long long)out.dim[0] * out.dim[1] * out.dim[2];
  CHECK(voxels <= max_voxels, "%s: %lld x %lld x %lld voxels blended, expected at most %lld", name,
        (long long)out.dim[0], (long long)out.dim[1], (long long)out.dim[2], max_voxels);
  if (voxels > max_voxels) return; /* not walked: it may be billions */
  /* every voxel centre of both frames and of the blend */
  const frame_and_grid *frames[2] = {a, b};
  for (int s = 0; s < 3; s++) {
    const volume_grid_desc *g = s < 2 ? &frames[s]->grid : &out;
    for (int k = 0; k < g->dim[2]; k++)
      for (int j = 0; j < g->dim[1]; j++)
        for (int i = 0; i < g->dim[0]; i++) {
          const double p[3] = {i + 0.5 - g->index_offset[0], j + 0.5 - g->index_offset[1],
                               k + 0.5 - g->index_offset[2]};
          const double want =
              (1 - w) * value_at(&a->grid, p) * (a->frame.grid.active_voxels > 0) +
              w * value_at(&b->grid, p) * (b->frame.grid.active_voxels > 0);
          const double got = value_at(&out, p);
          CHECK(fabs(got - want) <= 1e-6 * fabs(want), "%s: at (%g, %g, %g): %.9g, expected %.9g",
                name, p[0], p[1], p[2], got, want);
        }
  }
  free((float *)out.values);
}

int main(void) {
  frame_and_grid empty, smoke, other;
  const int one[3] = {1, 1, 1}, zero[3] = {0, 0, 0}, far[3] = {-3000, 500, 2000},
            cube[3] = {2, 2, 2}, near[3] = {-2999, 501, 1999}, slab[3] = {3, 1, 2};
  make(&empty, zero, one, 0, 0);
  make(&smoke, far, cube, 1, 1);
  make(&other, near, slab, 1, 100);
  check_blend("empty, then far smoke", &empty, &smoke, 0.25, 8);
  check_blend("far smoke, then empty", &smoke, &empty, 0.75, 8);
  check_blend("two smokes overlapping", &smoke, &other, 0.4, 4 * 2 * 3);
  check_blend("both empty", &empty, &empty, 0.5, 1);
  return test_finish("test_volume_blend");
}
