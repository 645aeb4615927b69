// One VDB frame to fogmap + profile + placement: read (vdb_read.cpp), place with the
// Mantaflow config when there is one, project, fit the profile, resample. Glue only; it
// lives in fogpipe_vdb (not fogpipe_sim) because it calls the OpenVDB reader.
#include <cstdio>
#include <cstring>

#include "sim/vdb_import.h"

extern "C" int vdb_frame_load(const char *path, const vdb_frame_desc *desc, vdb_frame *out,
                              fog_error *err) {
  *out = vdb_frame{};
  const vdb_frame_desc d = desc ? *desc : vdb_frame_desc{};
  fog_error inner{};
  vdb_dense_grid grid{};
  vdb_read_desc read{};
  read.grid = d.grid;
  read.max_voxels = d.max_voxels;
  read.empty_ok = d.empty_ok;
  if (vdb_read_dense(path, &read, &grid, err)) return 1;
  bool empty = grid.active_voxels == 0; /* only with empty_ok */

  mantaflow_config config{};
  const mantaflow_config *cfg = nullptr;
  if (d.config && strcmp(d.config, "none") != 0) {
    snprintf(out->config_path, sizeof out->config_path, "%s", d.config);
  } else if (!d.config) {
    if (vdb_config_path_beside(path, out->config_path, sizeof out->config_path))
      out->config_path[0] = 0;
  }
  if (out->config_path[0]) {
    if (mantaflow_config_read(out->config_path, &config, err)) {
      vdb_dense_grid_destroy(&grid);
      *out = vdb_frame{};
      return 1;
    }
    cfg = &config;
  }
  vdb_placement place{};
  place.up = d.up;
  place.scale = d.scale;
  for (int a = 0; a < 3; a++) place.offset[a] = d.offset[a];
  place.config = cfg;
  int status = vdb_world_map_make(&grid, &place, &out->world, &inner);
  bool projected = false; /* the columns exist (a failure after them may be their mass) */
  /* placing and boxing by the Mantaflow config: its errors name it (it was found beside
   * the VDB, the user may not know it is read) */
  bool placed_by_config = status && cfg;
  if (!status && d.grid_only) {
    out->grid = grid;
    out->active_voxels = grid.active_voxels;
    out->negative_voxels = grid.negative_voxels;
    return 0;
  }
  if (!status && !empty) {
    int box[6];
    for (int c = 0; c < 3; c++) {
      box[c] = out->world.domain_min[c];
      box[3 + c] = out->world.domain_max[c];
    }
    status = vdb_columns_project(&grid, &out->world, cfg ? box : nullptr, &out->columns, &inner);
    projected = !status;
    placed_by_config = status && cfg;
    /* voxels all 0 (or negative, clamped): no fog either, in a sequence */
    if (!status && d.empty_ok && !(out->columns.mass > 0)) {
      vdb_columns_destroy(&out->columns);
      empty = true;
    }
  }
  if (!status && empty) {
    /* no fog: no columns (a footprint or layers here would widen the sequence's), the
     * fixed profile or none, a zero fogmap on the sequence's grid where one is given */
    out->empty = 1;
    out->active_voxels = grid.active_voxels;
    out->negative_voxels = grid.negative_voxels;
    vdb_dense_grid_destroy(&grid);
    if (d.fixed_profile) out->profile = *d.fixed_profile;
    if (d.place) {
      out->fogmap_place = *d.place;
      status = fogmap_create(&out->map, d.place->width, d.place->height, &inner);
    }
    if (status) {
      fog_error_wrap(err, &inner, "%.200s: ", path);
      vdb_frame_destroy(out);
      return 1;
    }
    return 0;
  }
  if (!status) {
    if (d.fixed_profile)
      out->profile = *d.fixed_profile;
    else
      status = vdb_profile_fit(out->columns.layer_mass, out->columns.layers, out->columns.y_min,
                               out->columns.layer_height, &d.profile, &out->profile, &inner);
  }
  if (!status) {
    if (d.place) {
      out->fogmap_place = *d.place;
    } else {
      const vdb_columns &c = out->columns;
      status = vdb_fogmap_place_fit(c.origin_x, c.origin_x + c.width * c.cell_x, c.origin_z,
                                    c.origin_z + c.height * c.cell_z, d.resolution, d.cell_size,
                                    c.cell_x > c.cell_z ? c.cell_x : c.cell_z,
                                    &out->fogmap_place, &inner);
      // the footprint came from the config's domain: its errors name it (a damaged res
      // made a fogmap of 16777280 x 64 cells, the config unnamed)
      placed_by_config = placed_by_config || (status && cfg);
    }
  }
  if (!status)
    status = fogmap_create(&out->map, out->fogmap_place.width, out->fogmap_place.height, &inner);
  if (!status)
    status = vdb_columns_resample(&out->columns, &out->fogmap_place, out->profile.thickness,
                                  &out->map, &inner);
  if (status && projected && grid.negative_voxels > 0 && out->columns.mass <= 0) {
    /* what the clamp took is the cause: say so (a signed grid, as a level set) */
    fog_error clamped = inner;
    fog_fail(&inner, clamped.code, "%.300s (%lld of its %lld active voxels were negative, "
             "clamped to 0: a signed grid, not a density?)", clamped.message,
             grid.negative_voxels, grid.active_voxels);
  } else if (status && projected && !(out->columns.mass > 0)) {
    /* voxels all 0: the grid holds no fog (a sequence's frame before the smoke plays as
     * none; one file alone has nothing to import) */
    fog_error zero = inner;
    fog_fail(&inner, zero.code, "%.300s (its %lld active voxels are all 0: the grid holds no "
             "fog)", zero.message, grid.active_voxels);
  }
  if (status) {
    if (placed_by_config)
      fog_error_wrap(err, &inner, "%.200s (placed by its Mantaflow config %.200s): ", path,
                     out->config_path);
    else
      fog_error_wrap(err, &inner, "%.200s: ", path);
    vdb_dense_grid_destroy(&grid);
    vdb_frame_destroy(out);
    return 1;
  }
  out->active_voxels = grid.active_voxels;
  out->negative_voxels = grid.negative_voxels;
  if (d.keep_grid)
    out->grid = grid;
  else
    vdb_dense_grid_destroy(&grid);
  return 0;
}

extern "C" void vdb_frame_destroy(vdb_frame *frame) {
  vdb_dense_grid_destroy(&frame->grid);
  vdb_columns_destroy(&frame->columns);
  fogmap_destroy(&frame->map);
  *frame = vdb_frame{};
}
