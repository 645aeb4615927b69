/* A Mantaflow config whose domain in the VDB's voxels does not fit an int is refused,
 * naming it (vdb_world_map_make): res 4 with VDB voxels 2^29 times finer than a cell made
 * res x upres - 1 overflow (undefined behaviour, then "out of memory for 0x0 columns").
 * A config of the same shape at an ordinary size is taken. */
#include <math.h>
#include <string.h>

#include "sim/vdb_import.h"
#include "test_util.h"

static mantaflow_config domain(float cells_of_voxels) {
  mantaflow_config c;
  memset(&c, 0, sizeof c);
  for (int a = 0; a < 3; a++) {
    c.res[a] = c.base_res[a] = c.res_max[a] = 4;
    c.p0[a] = 0.0f;
    c.p1[a] = 4.0f * 0.09375f * cells_of_voxels; /* cells of 0.09375 x upres voxels */
    c.obmat[a][a] = 1.0f;
  }
  c.obmat[3][3] = 1.0f;
  return c;
}

int main(void) {
  float one = 0.0f;
  vdb_dense_grid grid = {.dim = {1, 1, 1}, .voxel_size = {0.09375, 0.09375, 0.09375},
                         .values = &one};
  vdb_world_map map;
  fog_error err = {0};
  mantaflow_config ordinary = domain(2.0f); /* a noise grid at 2x the domain's resolution */
  CHECK(vdb_world_map_make(&grid, &(vdb_placement){.config = &ordinary}, &map, &err) == 0,
        "an ordinary config (upres 2): %s", err.message);
  mantaflow_config huge = domain(536870912.0f); /* upres 2^29 */
  err = (fog_error){0};
  CHECK(vdb_world_map_make(&grid, &(vdb_placement){.config = &huge}, &map, &err) != 0 &&
            strstr(err.message, "too large to place"),
        "a config of 4 cells x 2^29 voxels: %s", err.code ? err.message : "taken");
  return test_finish("test_vdb_config_bounds");
}
