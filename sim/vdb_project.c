/* VDB placement and projection: index -> fogpipe world (Y up), the column integral
 * tau(x,z) = ∫ρ dy of a dense grid, and its area-weighted (conservative) resampling onto
 * a fogmap grid. See sim/vdb_import.h for the conventions. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/vdb_import.h"

int vdb_world_map_make(const vdb_dense_grid *grid, const vdb_placement *desc, vdb_world_map *out,
                       fog_error *err) {
  *out = (vdb_world_map){0};
  const double scale = desc && desc->scale != 0 ? desc->scale : 1.0;
  const mantaflow_config *cfg = desc ? desc->config : NULL;
  /* Source world (the VDB's or Blender's) along source axis c: b_c = B[c] + S[c]·u_c. */
  double B[3], S[3];
  if (!cfg) {
    for (int c = 0; c < 3; c++) {
      B[c] = grid->translation[c];
      S[c] = grid->voxel_size[c];
    }
  } else {
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++)
        if (r != c && fabs(cfg->obmat[r][c]) > 1e-6 * fabs(cfg->obmat[r][r])) {
          fog_fail(err, FOG_ERR_BAD_FILE,
                   "the Mantaflow domain object is rotated (obmat[%d][%d] = %g); only "
                   "scaled and translated domains are supported",
                   r, c, cfg->obmat[r][c]);
          return 1;
        }
    int adaptive = 0;
    for (int c = 0; c < 3; c++)
      if (cfg->res[c] != cfg->base_res[c] || cfg->res_min[c] != 0) adaptive = 1;
    /* A grid at k times the domain's resolution (Mantaflow's noise grid, k its upres
     * factor) has voxels dx/k in world units, the object's scale times the cell (the
     * shared bakes have scale 1): the cells are then dx/k and the domain res·k. Any other
     * voxel size is a grid the config does not describe; placed by it, its mass would be
     * off by the cube of the ratio. An adaptive domain's VDB voxel size is wrong anyway
     * (domain size / current sub-box res) and is not read. */
    int upres = 1;
    for (int c = 0; c < 3 && !adaptive; c++) {
      const double world_dx = fabs(cfg->obmat[c][c] * ((double)cfg->p1[c] - cfg->p0[c]) /
                                   cfg->base_res[c]);
      const double k = world_dx / grid->voxel_size[c];
      const long whole = lround(k);
      if (!(whole >= 1 && fabs(k - (double)whole) <= 1e-3 * k && (c == 0 || whole == upres))) {
        fog_fail(err, FOG_ERR_BAD_FILE,
                 "VDB voxel size %g on axis %d is neither the Mantaflow config's cell %g nor "
                 "a whole fraction of it (a noise grid's): the config does not describe this "
                 "grid; --config none places it from the VDB transform alone",
                 grid->voxel_size[c], c, world_dx);
        return 1;
      }
      upres = (int)whole;
    }
    /* the domain in voxels (res x upres) and its first voxel must fit an int: a damaged or
     * foreign config's upres of 2^29 overflowed them (undefined, then "0x0 columns") */
    for (int c = 0; c < 3; c++) {
      const long long cells = (long long)cfg->res[c] * upres,
                      first = ((long long)cfg->res_min[c] + cfg->shift[c]) * upres;
      if (cells > INT_MAX / 2 || first > INT_MAX / 2 || first < -(long long)(INT_MAX / 2)) {
        fog_fail(err, FOG_ERR_BAD_FILE,
                 "the Mantaflow config's domain of %d cells x %d (the VDB's voxels a 1/%d of "
                 "a cell) on axis %d is too large to place (damaged?); --config none places "
                 "the grid from the VDB transform alone", cfg->res[c], upres, upres, c);
        return 1;
      }
    }
    for (int c = 0; c < 3; c++) {
      /* Mantaflow cell n covers [n, n+1]·dx from the domain's min corner p0 (object
       * space), OpenVDB voxel n covers [n-.5, n+.5]: hence the + 0.5. An adaptive domain
       * stores only the sub-box starting at base cell res_min (+ shift): the true cell is
       * (p1 - p0) / base_res (test data README). */
      const double dx = ((double)cfg->p1[c] - cfg->p0[c]) / cfg->base_res[c] / upres;
      const double s = cfg->obmat[c][c], t = cfg->obmat[c][3];
      const double first = (double)(cfg->res_min[c] + cfg->shift[c]) * upres;
      B[c] = t + s * (cfg->p0[c] + (first + 0.5) * dx);
      S[c] = s * dx;
      out->domain_min[c] = 0;
      out->domain_max[c] = cfg->res[c] * upres - 1;
    }
    if (upres > 1)
      snprintf(out->warning, sizeof out->warning,
               "VDB voxels %g are 1/%d of the Mantaflow config's cells: placed as a noise "
               "grid at %d x the domain's resolution", grid->voxel_size[0], upres, upres);
    if (adaptive)
      snprintf(out->warning, sizeof out->warning,
               "adaptive Mantaflow domain (res %d %d %d of %d %d %d): the VDB voxel size %g "
               "is ignored, placement from the config", cfg->res[0], cfg->res[1],
               cfg->res[2], cfg->base_res[0], cfg->base_res[1], cfg->base_res[2],
               grid->voxel_size[0]);
    out->used_config = 1;
  }
  /* Z-up sources: fogpipe (X, Y, Z) = (x, z, -y), right-handed to right-handed. */
  static const int axis_z_up[3] = {0, 2, 1}, axis_y_up[3] = {0, 1, 2};
  static const double sign_z_up[3] = {1, 1, -1}, sign_y_up[3] = {1, 1, 1};
  const int y_up = desc && desc->up == VDB_UP_Y;
  for (int a = 0; a < 3; a++) {
    const int c = y_up ? axis_y_up[a] : axis_z_up[a];
    const double sign = y_up ? sign_y_up[a] : sign_z_up[a];
    out->index_axis[a] = c;
    out->base[a] = sign * scale * B[c] + (desc ? desc->offset[a] : 0);
    out->step[a] = sign * scale * S[c];
    if (!(fabs(out->step[a]) > 0) || !isfinite(out->step[a]) || !isfinite(out->base[a])) {
      fog_fail(err, FOG_ERR_BAD_FILE,
               "degenerate placement on world axis %d "
               "(cell %g)",
               a, out->step[a]);
      return 1;
    }
  }
  return 0;
}

/* World extent along fogpipe axis a of the index range [lo, hi] (whole voxels), and the
 * world-ordered cell number of index n. */
static void world_range(const vdb_world_map *map, int a, int lo, int hi, double *w0,
                        double *cell) {
  const double e1 = map->base[a] + map->step[a] * (lo - 0.5);
  const double e2 = map->base[a] + map->step[a] * (hi + 0.5);
  *w0 = e1 < e2 ? e1 : e2;
  *cell = fabs(map->step[a]);
}

int vdb_columns_project(const vdb_dense_grid *grid, const vdb_world_map *map, const int *box,
                        vdb_columns *out, fog_error *err) {
  *out = (vdb_columns){0};
  int lo[3], hi[3];
  for (int c = 0; c < 3; c++) {
    lo[c] = grid->index_min[c];
    hi[c] = grid->index_min[c] + grid->dim[c] - 1;
    if (box) {
      if (box[c] > lo[c] || box[3 + c] < hi[c]) {
        fog_fail(err, FOG_ERR_BAD_FILE,
                 "the grid's active voxels [%d..%d] on index axis %d lie outside the domain "
                 "[%d..%d]",
                 lo[c], hi[c], c, box[c], box[3 + c]);
        return 1;
      }
      lo[c] = box[c];
      hi[c] = box[3 + c];
    }
  }
  const int ax = map->index_axis[0], ay = map->index_axis[1], az = map->index_axis[2];
  out->width = hi[ax] - lo[ax] + 1;
  out->height = hi[az] - lo[az] + 1;
  out->layers = hi[ay] - lo[ay] + 1;
  world_range(map, 0, lo[ax], hi[ax], &out->origin_x, &out->cell_x);
  world_range(map, 1, lo[ay], hi[ay], &out->y_min, &out->layer_height);
  world_range(map, 2, lo[az], hi[az], &out->origin_z, &out->cell_z);
  out->tau = calloc((size_t)out->width * (size_t)out->height, sizeof(double));
  out->layer_mass = calloc((size_t)out->layers, sizeof(double));
  if (!out->tau || !out->layer_mass) {
    /* the sizes said before the destroy zeroes them (it said "0x0") */
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for %dx%d columns of %d layers",
             out->width, out->height, out->layers);
    vdb_columns_destroy(out);
    return 1;
  }
  /* World-ordered cell number of source index n along fogpipe axis a: n - lo when the
   * axis keeps its direction, hi - n when it is flipped (Z = -y for Z-up sources). */
  int start[3], stride[3];
  for (int a = 0; a < 3; a++) {
    const int c = map->index_axis[a];
    const int first = grid->index_min[c];
    start[a] = map->step[a] > 0 ? first - lo[c] : hi[c] - first;
    stride[a] = map->step[a] > 0 ? 1 : -1;
  }
  /* For each source axis c: which world axis it feeds. */
  int world_axis[3];
  for (int a = 0; a < 3; a++) world_axis[map->index_axis[a]] = a;
  const double dy = out->layer_height, area = out->cell_x * out->cell_z;
  int cell[3];
  size_t n = 0;
  for (int k = 0; k < grid->dim[2]; k++)
    for (int j = 0; j < grid->dim[1]; j++)
      for (int i = 0; i < grid->dim[0]; i++, n++) {
        const float v = grid->values[n];
        if (v == 0.0f) continue;
        const int idx[3] = {i, j, k};
        for (int c = 0; c < 3; c++) {
          const int a = world_axis[c];
          cell[a] = start[a] + stride[a] * idx[c];
        }
        out->tau[(size_t)cell[2] * (size_t)out->width + (size_t)cell[0]] += (double)v * dy;
        out->layer_mass[cell[1]] += (double)v * area;
      }
  double mass = 0;
  for (int l = 0; l < out->layers; l++) mass += out->layer_mass[l];
  out->mass = mass * dy;
  return 0;
}

void vdb_columns_destroy(vdb_columns *columns) {
  free(columns->tau);
  free(columns->layer_mass);
  *columns = (vdb_columns){0};
}

int vdb_fogmap_place_fit_columns(const vdb_columns *const *columns, int count, int resolution,
                                 double cell_size, vdb_fogmap_place *out, fog_error *err) {
  double x0 = INFINITY, x1 = -INFINITY, z0 = INFINITY, z1 = -INFINITY, native = 0;
  for (int i = 0; i < count; i++) {
    const vdb_columns *c = columns[i];
    if (!c->width) continue; /* a frame without fog: no footprint */
    if (!(native > 0)) native = fmax(c->cell_x, c->cell_z);
    x0 = fmin(x0, c->origin_x);
    x1 = fmax(x1, c->origin_x + c->width * c->cell_x);
    z0 = fmin(z0, c->origin_z);
    z1 = fmax(z1, c->origin_z + c->height * c->cell_z);
  }
  return vdb_fogmap_place_fit(x0, x1, z0, z1, resolution, cell_size, native, out, err);
}

int vdb_fogmap_place_fit(double x0, double x1, double z0, double z1, int resolution,
                         double cell_size, double native_cell, vdb_fogmap_place *out,
                         fog_error *err) {
  *out = (vdb_fogmap_place){0};
  const double sx = x1 - x0, sz = z1 - z0;
  double cell = native_cell;
  if (resolution > 0)
    cell = (sx > sz ? sx : sz) / resolution;
  else if (cell_size > 0)
    cell = cell_size;
  if (!(sx > 0) || !(sz > 0) || !(cell > 0) || !isfinite(cell)) {
    fog_fail(err, FOG_ERR_BAD_FILE, "cannot fit a fogmap to [%g, %g] x [%g, %g] with cell %g", x0,
             x1, z0, z1, cell);
    return 1;
  }
  /* ceil with a tolerance, so that an exact multiple gives no extra empty cell; at least
   * one cell (a cell wider than the domain is one cell, not "-0": the tolerance took the
   * ratio below 0) */
  const double w = fmax(1.0, ceil(sx / cell - 1e-6)), h = fmax(1.0, ceil(sz / cell - 1e-6));
  if (w * h > (double)(1 << 28)) {
    fog_fail(err, FOG_ERR_BAD_FILE, "a fogmap of %.0f x %.0f cells (cell %g) is out of range", w, h,
             cell);
    return 1;
  }
  *out = (vdb_fogmap_place){.origin_x = x0, .origin_z = z0, .cell_size = cell,
                            .width = (int)w, .height = (int)h};
  return 0;
}

/* 1D conservative redistribution: source cells [s0 + i·sc, s0 + (i+1)·sc], i < sn, onto
 * destination cells [d0 + a·dc, ...], a < dn. in[i*in_stride] is a per-source-cell amount;
 * out[a*out_stride] receives each source amount times (overlap length / sc). Returns the
 * amount that fell outside the destination. */
static double redistribute(const double *in, int sn, size_t in_stride, double s0, double sc,
                           double *out, int dn, size_t out_stride, double d0, double dc) {
  double lost = 0;
  for (int i = 0; i < sn; i++) {
    const double v = in[(size_t)i * in_stride];
    if (v == 0) continue;
    const double a0 = s0 + i * sc, a1 = a0 + sc;
    int first = (int)floor((a0 - d0) / dc), last = (int)floor((a1 - d0) / dc);
    double placed = 0;
    for (int a = first; a <= last; a++) {
      if (a < 0 || a >= dn) continue;
      const double c0 = d0 + a * dc, c1 = c0 + dc;
      const double overlap = fmin(a1, c1) - fmax(a0, c0);
      if (overlap <= 0) continue;
      const double part = v * (overlap / sc);
      out[(size_t)a * out_stride] += part;
      placed += part;
    }
    lost += v - placed;
  }
  return lost;
}

int vdb_columns_resample(const vdb_columns *columns, const vdb_fogmap_place *place,
                         double thickness, fogmap *map, fog_error *err) {
  if (map->width != place->width || map->height != place->height || !(thickness > 0)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "resample: fogmap %dx%d does not match the placement %dx%d (or thickness %g)",
             map->width, map->height, place->width, place->height, thickness);
    return 1;
  }
  const int sw = columns->width, sh = columns->height, dw = place->width, dh = place->height;
  if (sw == 0 || sh == 0) { /* an empty frame's: no fog */
    memset(map->density, 0, (size_t)dw * dh * sizeof *map->density);
    return 0;
  }
  /* Mass per column (tau × column area), redistributed along X then Z: the weights are
   * products of 1D overlap fractions, so the total is preserved exactly (Σ weights = 1
   * for every fully covered column). */
  double *rows = calloc((size_t)sh * (size_t)dw, sizeof(double));
  double *mass = calloc((size_t)dh * (size_t)dw, sizeof(double));
  double *src = malloc((size_t)sw * sizeof(double));
  if (!rows || !mass || !src) {
    free(rows);
    free(mass);
    free(src);
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory resampling to %dx%d", dw, dh);
    return 1;
  }
  const double column_area = columns->cell_x * columns->cell_z;
  double lost = 0;
  for (int z = 0; z < sh; z++) {
    for (int x = 0; x < sw; x++) src[x] = columns->tau[(size_t)z * sw + x] * column_area;
    lost += redistribute(src, sw, 1, columns->origin_x, columns->cell_x, rows + (size_t)z * dw,
                         dw, 1, place->origin_x, place->cell_size);
  }
  for (int x = 0; x < dw; x++)
    lost += redistribute(rows + x, sh, (size_t)dw, columns->origin_z, columns->cell_z,
                         mass + x, dh, (size_t)dw, place->origin_z, place->cell_size);
  const double total = columns->mass;
  if (fabs(lost) > 1e-6 * fabs(total) && fabs(lost) > 0) {
    fog_fail(err, FOG_ERR_BAD_FILE,
             "the fogmap grid (origin %g, %g, %dx%d cells of %g) misses %.3g%% of the fog's "
             "mass",
             place->origin_x, place->origin_z, dw, dh, place->cell_size, 100.0 * lost / total);
    free(rows);
    free(mass);
    free(src);
    return 1;
  }
  /* f = τ / T: the mean optical depth per cell area divided by the profile thickness. */
  const double inv = 1.0 / (place->cell_size * place->cell_size * thickness);
  int status = 0;
  for (size_t n = 0; n < (size_t)dw * dh; n++) {
    const double f = mass[n] * inv;
    /* what fogmap_load takes back (a cell past it was written, and the map did not load) */
    if (!(f <= FLT_MAX && (float)f <= FOGMAP_MAX_DENSITY) && !status)
      status = fog_fail(err, FOG_ERR_BAD_FILE,
                        "fogmap cell (%d, %d) would hold %.6g, more than a fogmap holds (%g): "
                        "the grid's densities are too large (scale them down)",
                        (int)(n % (size_t)dw), (int)(n / (size_t)dw), f,
                        (double)FOGMAP_MAX_DENSITY);
    map->density[n] = f > 0 && !status ? (float)f : 0.0f;
  }
  free(rows);
  free(mass);
  free(src);
  return status;
}
