/* libFuzzer harness: OpenVDB files, as the import and render commands read them:
 * vdb_precheck_file (sim/vdb_precheck.c, the C walk of the header, metadata, descriptors
 * and grid headers that runs before OpenVDB sees a file), then vdb_list_grids and
 * vdb_read_dense (sim/vdb_read.cpp over Debian's OpenVDB 10, each of which runs the
 * pre-check again first). The input is the .vdb file (a memfd path). The grid read is
 * "density" when the file lists one, else the first grid listed (so non-float grids reach
 * their error path too).
 *
 * max_voxels is 2^22 here, not the default 2^28 (1 GiB of floats, what the commands allow
 * by design): a damaged bounding box reaching the default is refused the same way, just
 * after a 1 GiB calloc, which only slows the fuzzer down. */
#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "sim/sim.h"

enum { max_grids = 32 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *path = fuzz_memfd_path(data, size);
  fog_error err;
  memset(&err, 0x55, sizeof err);
  if (vdb_precheck_file(path, &err) != 0) {
    if (!memchr(err.message, '\0', sizeof err.message)) abort();
    return 0; /* vdb_list_grids and vdb_read_dense would refuse it the same way */
  }
  vdb_grid_info grids[max_grids];
  int count = 0;
  memset(&err, 0x55, sizeof err);
  if (vdb_list_grids(path, grids, max_grids, &count, &err) != 0) {
    if (!memchr(err.message, '\0', sizeof err.message)) abort();
    return 0;
  }
  if (count < 0) abort();
  const char *name = count > 0 ? grids[0].name : "density";
  for (int g = 0; g < count && g < max_grids; g++)
    if (!strcmp(grids[g].name, "density")) name = "density";
  vdb_read_desc desc = {.grid = name, .max_voxels = 1LL << 22};
  vdb_dense_grid grid;
  memset(&err, 0x55, sizeof err);
  if (vdb_read_dense(path, &desc, &grid, &err) == 0) {
    const long long voxels = (long long)grid.dim[0] * grid.dim[1] * grid.dim[2];
    if (grid.dim[0] <= 0 || grid.dim[1] <= 0 || grid.dim[2] <= 0 || voxels > desc.max_voxels)
      abort();
    float sum = 0;
    for (long long i = 0; i < voxels; i++) {
      /* finite (NaN and Inf refused), negatives clamped to 0 */
      if (!(grid.values[i] >= 0 && grid.values[i] <= FLT_MAX)) abort();
      sum += grid.values[i];
    }
    (void)sum;
    vdb_dense_grid_destroy(&grid);
  } else if (!memchr(err.message, '\0', sizeof err.message)) {
    abort();
  }
  return 0;
}
