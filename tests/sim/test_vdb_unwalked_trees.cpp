// A grid whose tree the pre-check does not walk (bool, mask, vectors) is never read: its
// type is checked from the metadata first, and `--list` takes its box and count from the
// file's statistics. A bool grid whose level-2 child mask was overwritten with 0xFF (4 KB
// of damage) made OpenVDB allocate a node for every bit: 1.1 GB and 2-4 s, and --list
// reported the damaged tree (76803 voxels) instead of the one the file records (1).
#include <openvdb/openvdb.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

extern "C" {
#include "sim/sim.h" /* fogmap.h has no C++ guard of its own */
#include "sim/vdb_import.h"
}
#include "test_util.h"

int main() {
  char dir[] = "/tmp/fogpipe-unwalked-XXXXXX";
  if (!test_scratch_folder(dir)) return 1;
  const std::string path = std::string(dir) + "/damaged.vdb";
  openvdb::initialize();
  {
    auto mask = openvdb::BoolGrid::create(false);
    mask->setName("mask");
    mask->tree().setValue(openvdb::Coord(10, 20, 30), true);
    auto density = openvdb::FloatGrid::create(0.0f);
    density->setName("density");
    density->tree().setValue(openvdb::Coord(1, 2, 3), 1.0f);
    openvdb::io::File file(path);
    file.setCompression(openvdb::io::COMPRESS_NONE);
    file.write(openvdb::GridPtrVec{mask, density});
    file.close();
  }
  // The mask grid's level-2 child mask: 4096 bytes holding the one set bit, at byte 0x208
  // of this layout (OpenVDB 10, uncompressed); checked before it is damaged.
  std::vector<unsigned char> bytes;
  if (FILE *f = fopen(path.c_str(), "rb")) {
    int c;
    while ((c = fgetc(f)) != EOF) bytes.push_back((unsigned char)c);
    fclose(f);
  }
  const size_t at = 0x208, n = 4096;
  int bits = 0;
  for (size_t i = at; i < at + n && i < bytes.size(); i++) bits += __builtin_popcount(bytes[i]);
  CHECK(bytes.size() > at + n && bits == 1,
        "the layout moved: %d bits set in the 4096 bytes at 0x208 of %zu (expected 1)", bits,
        bytes.size());
  if (bits == 1) {
    memset(bytes.data() + at, 0xFF, n);
    FILE *f = fopen(path.c_str(), "wb");
    CHECK(f && fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size(), "cannot rewrite %s",
          path.c_str());
    if (f) fclose(f);
    vdb_grid_info info[4];
    int count = 0;
    fog_error err{};
    CHECK(vdb_list_grids(path.c_str(), info, 4, &count, &err) == 0, "list: %s", err.message);
    for (int g = 0; g < count; g++)
      if (!strcmp(info[g].name, "mask"))
        CHECK(info[g].active_voxels == 1 && info[g].bbox_min[0] == 10 && info[g].bbox_max[2] == 30,
              "the damaged bool grid listed with %lld voxels in [%d..%d] (its tree read), "
              "expected the file's statistics: 1 voxel at (10, 20, 30)",
              info[g].active_voxels, info[g].bbox_min[0], info[g].bbox_max[0]);
    vdb_dense_grid grid{};
    vdb_read_desc desc{};
    desc.grid = "mask";
    err = fog_error{};
    const int status = vdb_read_dense(path.c_str(), &desc, &grid, &err);
    CHECK(status != 0 && strstr(err.message, "holds bool values"), "--grid mask: %s",
          status ? err.message : "read");
    if (!status) vdb_dense_grid_destroy(&grid);
    // the float grid beside it still reads
    desc.grid = "density";
    err = fog_error{};
    CHECK(vdb_read_dense(path.c_str(), &desc, &grid, &err) == 0 && grid.active_voxels == 1,
          "the density beside the damaged mask: %s", err.message);
    vdb_dense_grid_destroy(&grid);
  }
  test_remove_tree(dir);
  return test_finish("test_vdb_unwalked_trees");
}
