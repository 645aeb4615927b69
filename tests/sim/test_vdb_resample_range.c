/* vdb_columns_resample writes only fogmaps that fogmap_load takes back: a cell whose
 * extinction f = τ / T passes FOGMAP_MAX_DENSITY (1e12) is an error naming the cell (the
 * import wrote 3e38, and the map it wrote did not load); up to it the value is kept. */
#include <math.h>
#include <string.h>

#include "sim/sim.h"
#include "sim/vdb_import.h"
#include "test_util.h"

/* One 2x1 map over two unit columns of optical depth tau0, tau1 (profile thickness 1): f
 * equals tau. */
static int resample(double tau0, double tau1, fogmap *map, fog_error *err) {
  double tau[2] = {tau0, tau1};
  const vdb_columns columns = {.width = 2, .height = 1, .cell_x = 1, .cell_z = 1, .tau = tau,
                               .mass = tau0 + tau1};
  const vdb_fogmap_place place = {.cell_size = 1, .width = 2, .height = 1};
  if (fogmap_create(map, 2, 1, err)) return -1;
  return vdb_columns_resample(&columns, &place, 1.0, map, err);
}

int main(void) {
  fogmap map = {0};
  fog_error err = {0};
  CHECK(resample(3.0, 1e12, &map, &err) == 0, "f of 1e12 (the largest a fogmap holds): %s",
        err.message);
  CHECK(map.density[0] == 3.0f && map.density[1] == 1e12f, "kept as %g and %g",
        (double)map.density[0], (double)map.density[1]);
  fogmap_destroy(&map);
  err = (fog_error){0};
  CHECK(resample(3.0, 3e38, &map, &err) != 0, "a cell of 3e38 was resampled without an error");
  CHECK(strstr(err.message, "fogmap cell (1, 0) would hold 3e+38"), "the error: %s",
        err.message);
  fogmap_destroy(&map);
  return test_finish("test_vdb_resample_range");
}
