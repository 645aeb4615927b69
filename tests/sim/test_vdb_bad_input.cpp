// Bad VDB input gives a clear error naming the file, never a crash or an exception:
// missing files, non-VDB bytes, truncated files, no such grid (the message lists the
// grids that exist), a vector grid named as density, a level set, empty grids, a
// background other than 0, NaN/Inf voxels, absurd dimensions, a broken Mantaflow config.
// (C++ only to write the odd grids via OpenVDB.)
#include <openvdb/openvdb.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "sim/sim.h"
#include "test_util.h"

static std::string dir;

static void write_grid(const std::string &path, openvdb::GridBase::Ptr grid) {
  openvdb::GridPtrVec grids;
  grids.push_back(grid);
  openvdb::io::File(path).write(grids);
}

static void write_bytes(const std::string &path, const void *bytes, size_t n) {
  FILE *f = fopen(path.c_str(), "wb");
  fwrite(bytes, 1, n, f);
  fclose(f);
}

// Reading path (grid name) must fail with a message containing path and every word.
static void expect_failure(const std::string &path, const char *grid,
                           std::initializer_list<const char *> words) {
  vdb_dense_grid g;
  fog_error err{};
  vdb_read_desc desc{};
  desc.grid = grid;
  desc.max_voxels = 1LL << 24;
  const int status = vdb_read_dense(path.c_str(), &desc, &g, &err);
  CHECK(status != 0, "%s: read succeeded", path.c_str());
  if (!status) {
    vdb_dense_grid_destroy(&g);
    return;
  }
  CHECK(g.values == nullptr, "%s: values left allocated", path.c_str());
  CHECK(strstr(err.message, path.c_str()) != nullptr, "message does not name the file: %s",
        err.message);
  for (const char *w : words)
    CHECK(strstr(err.message, w) != nullptr, "message lacks '%s': %s", w, err.message);
  printf("ok: %s\n", err.message);
  // The frame loader says the same, and list_grids too for unreadable files.
  vdb_frame f;
  vdb_frame_desc fd{};
  fd.grid = grid;
  fd.max_voxels = 1LL << 24;
  CHECK(vdb_frame_load(path.c_str(), &fd, &f, &err) != 0, "%s: frame load succeeded",
        path.c_str());
  CHECK(strstr(err.message, path.c_str()) != nullptr, "frame message lacks the file: %s",
        err.message);
}

int main() {
  char tmpl[] = "/tmp/test_vdb_bad_XXXXXX";
  if (!mkdtemp(tmpl)) return 1;
  dir = tmpl;
  openvdb::initialize();
  const std::string real = "../shared/data/vdb/groundfog/data/fluid_data_0048.vdb";

  expect_failure(dir + "/missing.vdb", nullptr, {"No such file"});

  const char text[] = "this is not a VDB file, just some text\n";
  write_bytes(dir + "/text.vdb", text, sizeof text);
  expect_failure(dir + "/text.vdb", nullptr, {"not an OpenVDB file"});
  write_bytes(dir + "/empty_file.vdb", text, 0);
  expect_failure(dir + "/empty_file.vdb", nullptr, {"not an OpenVDB file"});

  // truncated: the first half and the first 300 bytes of a real file
  {
    FILE *f = fopen(real.c_str(), "rb");
    CHECK(f != nullptr, "cannot open %s", real.c_str());
    if (f) {
      std::string bytes(1 << 20, '\0');
      const size_t n = fread(&bytes[0], 1, bytes.size(), f);
      fclose(f);
      write_bytes(dir + "/half.vdb", bytes.data(), n / 2);
      expect_failure(dir + "/half.vdb", nullptr, {"cannot read"});
      write_bytes(dir + "/head.vdb", bytes.data(), 300);
      expect_failure(dir + "/head.vdb", nullptr, {});
      // cut inside the last grid (velocity)
      write_bytes(dir + "/tail_cut.vdb", bytes.data(), n - n / 10);
      expect_failure(dir + "/tail_cut.vdb", nullptr, {"cannot read"});
    }
  }

  // no such grid: the message lists what exists
  expect_failure(real, "smoke", {"no grid named 'smoke'", "density", "shadow", "velocity"});
  // a vector grid named as density
  expect_failure(real, "velocity", {"vec3s", "expected a scalar float grid"});
  {
    openvdb::Vec3SGrid::Ptr v = openvdb::Vec3SGrid::create();
    v->setName("density");
    v->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1, 0, 0));
    write_grid(dir + "/vector_density.vdb", v);
    expect_failure(dir + "/vector_density.vdb", nullptr, {"vec3s"});
  }
  // a level set (signed distances) is no density: it would render a hollow shell
  {
    openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create(0.3f);
    g->setName("density");
    g->setGridClass(openvdb::GRID_LEVEL_SET);
    g->tree().setValue(openvdb::Coord(0, 0, 0), -0.1f);
    g->tree().setValue(openvdb::Coord(1, 0, 0), 0.1f);
    write_grid(dir + "/level_set.vdb", g);
    expect_failure(dir + "/level_set.vdb", nullptr, {"is a level set", "-ls2fog"});
  }
  // empty grids: Mantaflow's 'flame' and one of our own
  expect_failure(real, "flame", {"empty"});
  {
    openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create();
    g->setName("density");
    write_grid(dir + "/empty_grid.vdb", g);
    expect_failure(dir + "/empty_grid.vdb", nullptr, {"empty"});
  }
  // NaN and Inf voxels: the voxel is named
  {
    openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create();
    g->setName("density");
    g->tree().setValue(openvdb::Coord(0, 0, 0), 0.5f);
    g->tree().setValue(openvdb::Coord(4, 5, 6), std::numeric_limits<float>::quiet_NaN());
    write_grid(dir + "/nan.vdb", g);
    expect_failure(dir + "/nan.vdb", nullptr, {"non-finite", "(4, 5, 6)"});
    g->tree().setValue(openvdb::Coord(4, 5, 6), std::numeric_limits<float>::infinity());
    write_grid(dir + "/inf.vdb", g);
    expect_failure(dir + "/inf.vdb", nullptr, {"non-finite", "(4, 5, 6)"});
  }
  // a background other than 0: every inactive voxel, out to infinity, holds it (the reader
  // copied the active voxels alone and dropped it without a word); a negative background
  // reads as 0, as negative active voxels do
  {
    openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create(0.5f);
    g->setName("density");
    g->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
    g->tree().setValue(openvdb::Coord(3, 2, 1), 1.0f);
    write_grid(dir + "/background.vdb", g);
    expect_failure(dir + "/background.vdb", nullptr, {"background value 0.5", "expected 0"});
    openvdb::FloatGrid::Ptr n = openvdb::FloatGrid::create(-0.25f);
    n->setName("density");
    n->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
    n->tree().setValue(openvdb::Coord(3, 2, 1), 1.0f);
    write_grid(dir + "/negative_background.vdb", n);
    vdb_dense_grid dense;
    fog_error err{};
    CHECK(vdb_read_dense((dir + "/negative_background.vdb").c_str(), nullptr, &dense, &err) == 0,
          "a negative background: %s", err.message);
    if (!err.message[0]) {
      double sum = 0;
      const long long n_voxels = (long long)dense.dim[0] * dense.dim[1] * dense.dim[2];
      for (long long i = 0; i < n_voxels; i++) sum += dense.values[i];
      CHECK(n_voxels == 24 && sum == 2.0, "a negative background: %lld voxels, sum %g",
            n_voxels, sum);
      vdb_dense_grid_destroy(&dense);
    }
  }
  // absurd dimensions: two voxels far apart span 2e5^3 voxels
  {
    openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create();
    g->setName("density");
    g->tree().setValue(openvdb::Coord(-100000, -100000, -100000), 1.0f);
    g->tree().setValue(openvdb::Coord(100000, 100000, 100000), 1.0f);
    write_grid(dir + "/huge.vdb", g);
    expect_failure(dir + "/huge.vdb", nullptr, {"more than the limit"});
  }
  // list_grids names the file for bad bytes, and lists a real file's five grids
  {
    vdb_grid_info info[16];
    int count = 0;
    fog_error err{};
    CHECK(vdb_list_grids((dir + "/text.vdb").c_str(), info, 16, &count, &err) != 0,
          "list of a text file succeeded");
    CHECK(strstr(err.message, "text.vdb") != nullptr, "list message: %s", err.message);
    CHECK(vdb_list_grids(real.c_str(), info, 16, &count, &err) == 0, "%s", err.message);
    CHECK(count == 5, "%d grids in %s", count, real.c_str());
    for (int i = 0; i < count && i < 16; i++)
      if (!strcmp(info[i].name, "shadow"))
        CHECK(info[i].active_voxels == 64 * 64 * 16, "shadow: %lld active voxels (tiles)",
              info[i].active_voxels);
    // shadow is all tiles: -1 everywhere, which the reader clamps to 0 and counts
    vdb_dense_grid g;
    vdb_read_desc desc{};
    desc.grid = "shadow";
    CHECK(vdb_read_dense(real.c_str(), &desc, &g, &err) == 0, "%s", err.message);
    CHECK(g.tile_voxels == 64 * 64 * 16 && g.negative_voxels == 64 * 64 * 16,
          "shadow: %lld tile voxels, %lld negative", g.tile_voxels, g.negative_voxels);
    vdb_dense_grid_destroy(&g);
  }
  // a broken config beside the cache: gzip magic missing, or wrong size
  {
    mantaflow_config cfg;
    fog_error err{};
    CHECK(mantaflow_config_read((dir + "/text.vdb").c_str(), &cfg, &err) != 0, "text config");
    CHECK(strstr(err.message, "text.vdb") && strstr(err.message, "gzip"), "%s", err.message);
    CHECK(mantaflow_config_read("../shared/data/vdb/plume/config/config_0001.uni", &cfg, &err) ==
              0, "%s", err.message);
    CHECK(cfg.base_res[2] == 64 && fabs(cfg.obmat[2][3] - 2.0f) < 1e-6,
          "plume config: base_res z %d, obmat z translation %g", cfg.base_res[2], cfg.obmat[2][3]);
  }
  // a cache whose config beside it does not fit its voxels (0.1 against the plume's cell
  // 0.0625): the error names that config, which was read without being asked for
  {
    const std::string mixed = dir + "/mixed";
    std::string setup = "mkdir -p '" + mixed + "/data' '" + mixed + "/config' && cp "
                        "../shared/data/vdb/plume/config/config_0001.uni '" + mixed +
                        "/config/'";
    CHECK(system(setup.c_str()) == 0, "setup failed: %s", setup.c_str());
    openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create();
    g->setName("density");
    g->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    g->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
    g->tree().setValue(openvdb::Coord(3, 2, 1), 1.0f);
    const std::string vdb = mixed + "/data/fluid_data_0001.vdb";
    write_grid(vdb, g);
    vdb_frame f;
    fog_error err{};
    CHECK(vdb_frame_load(vdb.c_str(), nullptr, &f, &err) != 0, "a 0.1 voxel under the plume's "
          "config loaded");
    CHECK(strstr(err.message, vdb.c_str()) && strstr(err.message, "config_0001.uni") &&
              strstr(err.message, "voxel size"),
          "the error does not name the VDB, the config and the voxel size: %s", err.message);
  }
  std::string cmd = "rm -rf '" + dir + "'";
  if (system(cmd.c_str()) != 0) fprintf(stderr, "could not remove %s\n", dir.c_str());
  return test_finish("test_vdb_bad_input");
}
