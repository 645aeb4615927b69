// The thin C++ adapter over OpenVDB 10 behind sim/vdb_import.h: list grids, read a
// scalar grid into a dense box (leaf voxels and active tiles alike), write one (tests).
// Every exception stops here and becomes a fog_error message naming the file.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "sim/vdb_import.h"

namespace {

// A missing file gets the system's reason, not OpenVDB's generic "could not open".
bool check_readable(const char *path, fog_error *err) {
  struct stat st;
  if (stat(path, &st) != 0) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot open: %s", path, strerror(errno));
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: not a regular file", path);
    return false;
  }
  FILE *f = fopen(path, "rb");
  if (!f) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot open: %s", path, strerror(errno));
    return false;
  }
  // OpenVDB files start with the magic number 0x56444220 ("VDB " little-endian) as int64.
  unsigned char magic[8] = {0};
  size_t n = fread(magic, 1, sizeof magic, f);
  fclose(f);
  if (n < 4 || !(magic[0] == 0x20 && magic[1] == 0x42 && magic[2] == 0x44 && magic[3] == 0x56)) {
    fog_fail(err, FOG_ERR_BAD_FILE,
             "%s: not an OpenVDB file (no 'VDB' magic number in the first bytes)", path);
    return false;
  }
  // OpenVDB allocates lengths read from the file before checking them: refuse damaged
  // headers first (every io::File opened for reading here goes through this function).
  return vdb_precheck_file(path, err) == 0;
}

std::string grid_names(openvdb::io::File &file) {
  std::string names;
  for (auto it = file.beginName(); it != file.endName(); ++it) {
    if (!names.empty()) names += ", ";
    names += it.gridName();
  }
  return names.empty() ? std::string("(none)") : names;
}

std::string type_names(const openvdb::GridPtrVecPtr &grids) {
  std::string names;
  for (const auto &g : *grids) {
    if (!names.empty()) names += ", ";
    names += g->getName() + " (" + g->valueType() + ")";
  }
  return names.empty() ? std::string("(none)") : names;
}

// The grid's index->world map, which must be axis-aligned (scale + translation).
bool axis_aligned_map(const openvdb::GridBase &grid, const char *path, double voxel_size[3],
                      double translation[3], fog_error *err) {
  const openvdb::math::MapBase::ConstPtr map = grid.transform().baseMap();
  if (!map->isLinear()) {
    fog_fail(err, FOG_ERR_BAD_FILE,
             "%s: grid '%s' has a non-linear (frustum) transform; only linear maps "
             "are supported",
             path, grid.getName().c_str());
    return false;
  }
  // OpenVDB uses row vectors: world = index * M, translation in row 3.
  const openvdb::math::Mat4d m = map->getAffineMap()->getMat4();
  double largest = 0;
  for (int r = 0; r < 3; r++) largest = std::max(largest, std::fabs(m[r][r]));
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++)
      if (r != c && std::fabs(m[r][c]) > 1e-9 * largest) {
        fog_fail(err, FOG_ERR_BAD_FILE,
                 "%s: grid '%s' has a rotated or sheared transform; only scale + "
                 "translation is supported",
                 path, grid.getName().c_str());
        return false;
      }
  for (int a = 0; a < 3; a++) {
    voxel_size[a] = m[a][a];
    translation[a] = m[3][a];
    if (!(std::fabs(voxel_size[a]) > 0) || !std::isfinite(voxel_size[a])) {
      fog_fail(err, FOG_ERR_BAD_FILE, "%s: grid '%s' has a degenerate voxel size along axis %d",
               path, grid.getName().c_str(), a);
      return false;
    }
  }
  return true;
}

template <typename GridT>
int copy_to_dense(const GridT &grid, const char *path, long long max_voxels, bool empty_ok,
                  vdb_dense_grid *out, fog_error *err) {
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  // Inactive voxels hold the background value, inside the active box and to infinity
  // around it: a density that is not 0 there has no bounded fog to read (negative ones are
  // clamped to 0 as the active voxels are).
  const double background = (double)grid.background();
  if (!(background <= 0)) {
    fog_fail(err, FOG_ERR_BAD_FILE,
             "%s: grid '%s' has the background value %g (what every inactive voxel holds, "
             "out to infinity): expected 0, a fog volume's density outside the smoke",
             path, grid.getName().c_str(), background);
    return 1;
  }
  if ((box.empty() || grid.activeVoxelCount() == 0) && empty_ok) {
    float *zero = (float *)calloc(1, sizeof(float));
    if (!zero) {
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
      return 1;
    }
    *out = vdb_dense_grid{};
    out->dim[0] = out->dim[1] = out->dim[2] = 1;
    out->values = zero;
    return 0;
  }
  if (box.empty() || grid.activeVoxelCount() == 0) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: grid '%s' is empty (no active voxels)", path,
             grid.getName().c_str());
    return 1;
  }
  // In 64 bits: CoordBBox::dim() is int and a damaged file's box spans up to 2^32 a side,
  // whose product overflowed long long too.
  const openvdb::Coord lo = box.min(), hi = box.max();
  long long dim[3];
  for (int a = 0; a < 3; a++) dim[a] = (long long)hi[a] - lo[a] + 1;
  const bool fits = dim[0] > 0 && dim[1] > 0 && dim[2] > 0 && dim[0] <= INT_MAX &&
                    dim[1] <= INT_MAX && dim[2] <= INT_MAX && dim[0] <= max_voxels &&
                    dim[1] <= max_voxels / dim[0] && dim[2] <= max_voxels / (dim[0] * dim[1]);
  if (!fits) {
    fog_fail(err, FOG_ERR_BAD_FILE,
             "%s: grid '%s' spans %lld x %lld x %lld voxels (%.6g), more than the limit "
             "of %lld",
             path, grid.getName().c_str(), dim[0], dim[1], dim[2],
             (double)dim[0] * (double)dim[1] * (double)dim[2], max_voxels);
    return 1;
  }
  const long long count = dim[0] * dim[1] * dim[2];
  float *values = (float *)calloc((size_t)count, sizeof(float));
  if (!values) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory for %lld voxels", path, count);
    return 1;
  }
  const long long sy = dim[0], sz = dim[0] * dim[1];
  long long tiles = 0, negative = 0;
  for (auto it = grid.cbeginValueOn(); it; ++it) {
    const double v = (double)*it;
    openvdb::CoordBBox b;
    if (it.isVoxelValue())
      b = openvdb::CoordBBox(it.getCoord(), it.getCoord());
    else {
      b = it.getBoundingBox();
      b.intersect(box);
      if (b.empty()) continue;
      tiles += (long long)b.volume();
    }
    // A double grid's finite values past FLT_MAX would turn infinite in the float copy.
    if (!std::isfinite(v) || std::fabs(v) > (double)FLT_MAX) {
      const openvdb::Coord c = b.min();
      fog_fail(err, FOG_ERR_BAD_FILE, "%s: grid '%s' has a %s value (%g) at voxel (%d, %d, %d)",
               path, grid.getName().c_str(),
               std::isfinite(v) ? "too large (past float's range)" : "non-finite", v, c.x(), c.y(),
               c.z());
      free(values);
      return 1;
    }
    float f = (float)v;
    if (f < 0) {
      negative += (long long)b.volume();
      f = 0;
    }
    for (long long k = b.min().z(); k <= b.max().z(); k++)
      for (long long j = b.min().y(); j <= b.max().y(); j++) {
        float *row = values + (k - lo.z()) * sz + (j - lo.y()) * sy;
        for (long long i = b.min().x(); i <= b.max().x(); i++) row[i - lo.x()] = f;
      }
  }
  out->dim[0] = (int)dim[0];
  out->dim[1] = (int)dim[1];
  out->dim[2] = (int)dim[2];
  out->index_min[0] = lo.x();
  out->index_min[1] = lo.y();
  out->index_min[2] = lo.z();
  out->values = values;
  out->active_voxels = (long long)grid.activeVoxelCount();
  out->tile_voxels = tiles;
  out->negative_voxels = negative;
  return 0;
}

}  // namespace

extern "C" int vdb_list_grids(const char *path, vdb_grid_info *grids, int capacity, int *count,
                              fog_error *err) {
  *count = 0;
  if (!check_readable(path, err)) return 1;
  try {
    openvdb::initialize();
    openvdb::io::File file(path);
    file.open(false);  // no delayed loading: a truncated file fails here, not later
    // The metadata and transforms, and the trees of float and double grids only: the
    // pre-check walks no other tree (a damaged bool grid's tree took 1.1 GB to read). A
    // grid's box and count come from its file statistics where it has them.
    openvdb::GridPtrVecPtr all = file.readAllGridMetadata();
    for (auto &g : *all) {
      const bool walked = g->valueType() == "float" || g->valueType() == "double";
      if (walked && !g->getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_VOXEL_COUNT))
        g = file.readGrid(g->getName());
    }
    file.close();
    int n = 0;
    for (const auto &g : *all) {
      if (n < capacity) {
        vdb_grid_info *info = &grids[n];
        *info = vdb_grid_info{};
        snprintf(info->name, sizeof info->name, "%s", g->getName().c_str());
        snprintf(info->value_type, sizeof info->value_type, "%s", g->valueType().c_str());
        snprintf(info->grid_class, sizeof info->grid_class, "%s",
                 openvdb::GridBase::gridClassToString(g->getGridClass()).c_str());
        const openvdb::Vec3d vs = g->voxelSize();
        for (int a = 0; a < 3; a++) info->voxel_size[a] = vs[a];
        const auto count = g->getMetadata<openvdb::Int64Metadata>(
            openvdb::GridBase::META_FILE_VOXEL_COUNT);
        const auto lo = g->getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MIN);
        const auto hi = g->getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MAX);
        if (count && lo && hi) {
          for (int a = 0; a < 3; a++) {
            info->bbox_min[a] = lo->value()[a];
            info->bbox_max[a] = hi->value()[a];
          }
          info->active_voxels = (long long)count->value();
        } else if (g->valueType() == "float" || g->valueType() == "double") {
          const openvdb::CoordBBox box = g->evalActiveVoxelBoundingBox();
          for (int a = 0; a < 3; a++) {
            info->bbox_min[a] = box.min()[a];
            info->bbox_max[a] = box.max()[a];
          }
          info->active_voxels = (long long)g->activeVoxelCount();
        } else {  // no statistics and a tree not read: unknown
          info->bbox_min[0] = 1, info->bbox_max[0] = 0;
          info->active_voxels = -1;
        }
      }
      n++;
    }
    *count = n;
    return 0;
  } catch (const std::exception &e) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: cannot read as OpenVDB (truncated or corrupt?): %s", path,
             e.what());
  } catch (...) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: cannot read as OpenVDB (unknown error)", path);
  }
  return 1;
}

extern "C" int vdb_read_dense(const char *path, const vdb_read_desc *desc, vdb_dense_grid *out,
                              fog_error *err) {
  *out = vdb_dense_grid{};
  const char *name = desc && desc->grid ? desc->grid : "density";
  const long long max_voxels = desc && desc->max_voxels > 0 ? desc->max_voxels : (1LL << 28);
  const bool empty_ok = desc && desc->empty_ok;
  if (!check_readable(path, err)) return 1;
  try {
    openvdb::initialize();
    openvdb::io::File file(path);
    file.open(false);
    if (!file.hasGrid(name)) {
      fog_fail(err, FOG_ERR_BAD_FILE, "%s: no grid named '%s'; the file has: %s", path, name,
               grid_names(file).c_str());
      file.close();
      return 1;
    }
    // The metadata of all grids, to name the types when the requested one is wrong. Read
    // before the grid: a damaged tree can leave the stream failed without an exception,
    // and a later read then takes its lengths from whatever the variables held (a 1.1 GB
    // string in Transform::read; tests/fuzz/regressions/vdb/).
    openvdb::GridPtrVecPtr meta = file.readAllGridMetadata();
    // The type from the metadata, before the tree is read: the pre-check walks float and
    // double trees only, and a damaged bool or mask tree allocated a node for every bit
    // of its masks (4 KB of damage: 1.1 GB and 2 s before "holds bool values")
    for (const auto &g : *meta)
      if (g->getName() == name && g->valueType() != "float" && g->valueType() != "double") {
        fog_fail(err, FOG_ERR_BAD_FILE,
                 "%s: grid '%s' holds %s values, expected a scalar float grid (density); "
                 "the file has: %s",
                 path, name, g->valueType().c_str(), type_names(meta).c_str());
        file.close();
        return 1;
      }
    openvdb::GridBase::Ptr base = file.readGrid(name);
    file.close();
    // A level set holds distances to a surface (negative inside, the background a band's
    // width outside), which read as density would render a hollow shell.
    if (base->getGridClass() == openvdb::GRID_LEVEL_SET) {
      fog_fail(err, FOG_ERR_BAD_FILE,
               "%s: grid '%s' is a level set (signed distances to a surface), not fog "
               "density: convert it to a fog volume first (OpenVDB's vdb_tool -ls2fog, "
               "Houdini's VDB Convert)", path, name);
      return 1;
    }
    double voxel_size[3], translation[3];
    int status;
    if (base->isType<openvdb::FloatGrid>()) {
      if (!axis_aligned_map(*base, path, voxel_size, translation, err)) return 1;
      status = copy_to_dense(*openvdb::gridPtrCast<openvdb::FloatGrid>(base), path, max_voxels,
                             empty_ok, out, err);
    } else if (base->isType<openvdb::DoubleGrid>()) {
      if (!axis_aligned_map(*base, path, voxel_size, translation, err)) return 1;
      status = copy_to_dense(*openvdb::gridPtrCast<openvdb::DoubleGrid>(base), path,
                             max_voxels, empty_ok, out, err);
    } else {
      fog_fail(err, FOG_ERR_BAD_FILE,
               "%s: grid '%s' holds %s values, expected a scalar float grid (density); "
               "the file has: %s",
               path, name, base->valueType().c_str(), type_names(meta).c_str());
      return 1;
    }
    if (status) return status;
    for (int a = 0; a < 3; a++) {
      out->voxel_size[a] = voxel_size[a];
      out->translation[a] = translation[a];
    }
    return 0;
  } catch (const std::exception &e) {
    vdb_dense_grid_destroy(out);
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: cannot read grid '%s' (truncated or corrupt file?): %s",
             path, name, e.what());
  } catch (...) {
    vdb_dense_grid_destroy(out);
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: cannot read grid '%s' (unknown error)", path, name);
  }
  return 1;
}

extern "C" void vdb_dense_grid_destroy(vdb_dense_grid *grid) {
  free(grid->values);
  *grid = vdb_dense_grid{};
}

extern "C" int vdb_write_dense(const char *path, const vdb_dense_grid *grid,
                               const vdb_write_desc *desc, fog_error *err) {
  const char *name = desc && desc->grid ? desc->grid : "density";
  std::string tmp = std::string(path) + ".tmp" + std::to_string((long)getpid());
  try {
    openvdb::initialize();
    openvdb::FloatGrid::Ptr out = openvdb::FloatGrid::create(0.0f);
    out->setName(name);
    out->setGridClass(openvdb::GRID_FOG_VOLUME);
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    for (int a = 0; a < 3; a++) {
      m[a][a] = grid->voxel_size[a];
      m[3][a] = grid->translation[a];
    }
    out->setTransform(openvdb::math::Transform::createLinearTransform(m));
    out->setSaveFloatAsHalf(desc && desc->as_half);
    openvdb::FloatGrid::Accessor acc = out->getAccessor();
    const int *d = grid->dim, *lo = grid->index_min;
    auto at = [&](int i, int j, int k) {
      return grid->values[((long long)k * d[1] + j) * d[0] + i];
    };
    for (int k = 0; k < d[2]; k++)
      for (int j = 0; j < d[1]; j++)
        for (int i = 0; i < d[0]; i++) {
          const float v = at(i, j, k);
          if (v != 0.0f) acc.setValueOn(openvdb::Coord(i + lo[0], j + lo[1], k + lo[2]), v);
        }
    if (desc && desc->constant_blocks_as_tiles) {
      // Each 8^3 leaf-aligned block that is fully inside and constant (non-zero) becomes
      // one active tile at level 1, as Mantaflow stores its 'shadow' grid.
      auto floor8 = [](int v) { return v >= 0 ? v / 8 * 8 : -((-v + 7) / 8 * 8); };
      for (int bz = floor8(lo[2]); bz < lo[2] + d[2]; bz += 8)
        for (int by = floor8(lo[1]); by < lo[1] + d[1]; by += 8)
          for (int bx = floor8(lo[0]); bx < lo[0] + d[0]; bx += 8) {
            if (bx < lo[0] || by < lo[1] || bz < lo[2] || bx + 8 > lo[0] + d[0] ||
                by + 8 > lo[1] + d[1] || bz + 8 > lo[2] + d[2])
              continue;
            const float v0 = at(bx - lo[0], by - lo[1], bz - lo[2]);
            bool constant = v0 != 0.0f;
            for (int k = 0; k < 8 && constant; k++)
              for (int j = 0; j < 8 && constant; j++)
                for (int i = 0; i < 8 && constant; i++)
                  constant = at(bx - lo[0] + i, by - lo[1] + j, bz - lo[2] + k) == v0;
            if (constant) out->tree().addTile(1, openvdb::Coord(bx, by, bz), v0, true);
          }
    }
    openvdb::io::File file(tmp);
    const vdb_compression c = desc ? desc->compression : VDB_COMPRESSION_DEFAULT;
    if (c == VDB_COMPRESSION_NONE) file.setCompression(openvdb::io::COMPRESS_NONE);
    if (c == VDB_COMPRESSION_ZIP)
      file.setCompression(openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK);
    if (c == VDB_COMPRESSION_BLOSC)
      file.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
    openvdb::GridPtrVec grids;
    grids.push_back(out);
    file.write(grids);
    file.close();
  } catch (const std::exception &e) {
    unlink(tmp.c_str());
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot write OpenVDB file: %s", path, e.what());
    return 1;
  } catch (...) {
    unlink(tmp.c_str());
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot write OpenVDB file (unknown error)", path);
    return 1;
  }
  if (rename(tmp.c_str(), path) != 0) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot rename %s into place: %s", path, tmp.c_str(),
             strerror(errno));
    unlink(tmp.c_str());
    return 1;
  }
  return 0;
}
