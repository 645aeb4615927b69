/* Blending two frames of a played volume sequence (app/volume_blend.h). */
#include "app/volume_blend.h"

#include <stdlib.h>

bool volume_blend_placed_alike(const vdb_frame *a, const vdb_frame *b) {
  for (int k = 0; k < 3; k++)
    if (a->world.index_axis[k] != b->world.index_axis[k] ||
        a->world.base[k] != b->world.base[k] || a->world.step[k] != b->world.step[k])
      return false;
  return true;
}

int volume_blend(const vdb_frame *fa, const volume_grid_desc *a, const vdb_frame *fb,
                 const volume_grid_desc *b, double w, volume_grid_desc *out, fog_error *err) {
  const vdb_dense_grid *grids[2] = {&fa->grid, &fb->grid};
  const float *sources[2] = {a->values, b->values};
  const double weights[2] = {1.0 - w, w};
  /* An empty frame's placeholder sits at index 0: in a union with smoke whose indices
   * count from its world position (Houdini, EmberGen: index -3000..-2992 at 2 cm voxels
   * 60 m from the origin) it spanned 3e9 voxels. With neither holding fog, a's zero. */
  bool used[2] = {grids[0]->active_voxels > 0, grids[1]->active_voxels > 0};
  if (!used[0] && !used[1]) used[0] = true;
  int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, dim[3];
  bool first = true;
  for (int s = 0; s < 2; s++) {
    if (!used[s]) continue;
    for (int c = 0; c < 3; c++) {
      const int l = grids[s]->index_min[c], h = l + grids[s]->dim[c];
      lo[c] = first || l < lo[c] ? l : lo[c];
      hi[c] = first || h > hi[c] ? h : hi[c];
    }
    first = false;
  }
  for (int c = 0; c < 3; c++) dim[c] = hi[c] - lo[c];
  const size_t n = (size_t)dim[0] * dim[1] * dim[2];
  float *values = calloc(n, sizeof *values);
  if (!values)
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY,
                    "out of memory blending two volume frames (%d x %d x %d voxels)", dim[0],
                    dim[1], dim[2]);
  for (int s = 0; s < 2; s++) {
    if (!used[s]) continue;
    const vdb_dense_grid *g = grids[s];
    for (int k = 0; k < g->dim[2]; k++)
      for (int j = 0; j < g->dim[1]; j++)
        for (int i = 0; i < g->dim[0]; i++) {
          const size_t to = ((size_t)(k + g->index_min[2] - lo[2]) * dim[1] + j +
                             g->index_min[1] - lo[1]) * dim[0] + i + g->index_min[0] - lo[0];
          values[to] += (float)(weights[s] *
                                sources[s][((size_t)k * g->dim[1] + j) * g->dim[0] + i]);
        }
  }
  *out = *a;
  for (int c = 0; c < 3; c++) {
    out->dim[c] = dim[c];
    /* index u counts from the union's corner */
    out->index_offset[c] += grids[0]->index_min[c] - lo[c];
  }
  out->values = values;
  return 0;
}
