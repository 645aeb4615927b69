/* Geomipmapped terrain tiles with zipper-stitched seams (see terrain_lod.h). */
#include "render/terrain_lod.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Tile tx spans grid columns [tx T, tx T + T], the last one to the grid's edge (T to 2T - 1
 * quads), so every tile is at least T quads wide unless the whole grid is narrower. */
static void tile_range(const terrain_lod *lod, int tile, int *i0, int *j0, int *i1, int *j1) {
  const terrain *t = lod->terrain;
  const int tx = tile % lod->tiles_x, tz = tile / lod->tiles_x;
  *i0 = tx * TERRAIN_LOD_TILE;
  *j0 = tz * TERRAIN_LOD_TILE;
  *i1 = tx + 1 == lod->tiles_x ? t->resolution_x - 1 : *i0 + TERRAIN_LOD_TILE;
  *j1 = tz + 1 == lod->tiles_z ? t->resolution_z - 1 : *j0 + TERRAIN_LOD_TILE;
}

/* The positions a0, a0 + s, ... below a1, then a1. Returns their count. */
static int positions(int a0, int a1, int s, int *out) {
  int n = 0;
  for (int a = a0; a < a1; a += s) out[n++] = a;
  out[n++] = a1;
  return n;
}

typedef struct emitter {
  uint32_t *indices;
  size_t count;
  int rx;
} emitter;

/* One triangle of grid vertices (x, z), wound as the full mesh (the cross product of its
 * edges in (x, z) negative, test_terrain_lod); a degenerate one is dropped. */
static void emit(emitter *e, int xa, int za, int xb, int zb, int xc, int zc) {
  long cross = (long)(xb - xa) * (zc - za) - (long)(zb - za) * (xc - xa);
  if (cross == 0) return;
  if (cross > 0) { /* swap b and c */
    int x = xb, z = zb;
    xb = xc, zb = zc, xc = x, zc = z;
  }
  e->indices[e->count++] = (uint32_t)((size_t)za * e->rx + xa);
  e->indices[e->count++] = (uint32_t)((size_t)zb * e->rx + xb);
  e->indices[e->count++] = (uint32_t)((size_t)zc * e->rx + xc);
}

/* A side of the ring between the tile's edge (outer: the along-positions `outer` at
 * across = edge) and the inner rectangle's side (inner: along-positions `inner` at
 * across = inner_across): triangulated by merging the two sorted lists (a zipper). Between
 * two parallel lines every such triangle has vertices on both, so none is degenerate or
 * flipped. swap: along is z and across is x (the west and east sides). */
static void zipper(emitter *e, const int *outer, int n_outer, int edge, const int *inner,
                   int n_inner, int inner_across, bool swap) {
  int i = 0, j = 0;
  /* Where both rows go on to the same position, the full mesh's diagonal (i+1, j)-(i, j+1)
   * runs from the lower row's vertex back to the upper row's: the edge first on the south
   * and west sides (edge below the inner row), the inner row first on the north and east. */
  const bool outer_first = edge < inner_across;
#define V(along, across) (swap ? (across) : (along)), (swap ? (along) : (across))
  while (i + 1 < n_outer || j + 1 < n_inner) {
    bool advance_outer =
        j + 1 >= n_inner ||
        (i + 1 < n_outer && (outer_first ? outer[i + 1] <= inner[j + 1] : outer[i + 1] < inner[j + 1]));
    if (advance_outer) {
      emit(e, V(outer[i], edge), V(outer[i + 1], edge), V(inner[j], inner_across));
      i++;
    } else {
      emit(e, V(outer[i], edge), V(inner[j + 1], inner_across), V(inner[j], inner_across));
      j++;
    }
  }
#undef V
}

/* The parts of a tile's mesh, emitted apart for the seam error tables: the ring's sides (or
 * the fan's, for a tile too narrow for a ring) and the inner grid. */
enum {
  PART_SOUTH = 1, PART_EAST = 2, PART_NORTH = 4, PART_WEST = 8, PART_INNER = 16,
  PART_ALL = 31
};

/* Tile `tile` at step s with its four edges at steps (south, east, north, west), the parts
 * in `parts`. All of it with every edge at step s is the step-s grid triangulated as
 * terrain.h triangulates the full one (level 0: the full mesh, triangle for triangle);
 * otherwise the interior grid at step s and a ring of zippers to the edges; or, when the
 * tile is too narrow for a ring at this step, a fan from a grid vertex strictly inside. */
static size_t emit_tile(const terrain_lod *lod, int tile, int s, const int edge_step[4],
                        unsigned parts, uint32_t *indices) {
  int i0, j0, i1, j1;
  tile_range(lod, tile, &i0, &j0, &i1, &j1);
  emitter e = {.indices = indices, .rx = lod->terrain->resolution_x};
  int xs[2 * TERRAIN_LOD_TILE + 2], zs[2 * TERRAIN_LOD_TILE + 2];
  const int nx = positions(i0, i1, s, xs), nz = positions(j0, j1, s, zs);
  if (parts == PART_ALL && edge_step[0] == s && edge_step[1] == s && edge_step[2] == s &&
      edge_step[3] == s) {
    for (int b = 0; b + 1 < nz; b++)
      for (int a = 0; a + 1 < nx; a++) {
        emit(&e, xs[a], zs[b], xs[a], zs[b + 1], xs[a + 1], zs[b]);
        emit(&e, xs[a + 1], zs[b], xs[a], zs[b + 1], xs[a + 1], zs[b + 1]);
      }
    return e.count;
  }
  int south[2 * TERRAIN_LOD_TILE + 2], east[2 * TERRAIN_LOD_TILE + 2],
      north[2 * TERRAIN_LOD_TILE + 2], west[2 * TERRAIN_LOD_TILE + 2];
  const int ns = positions(i0, i1, edge_step[0], south), ne = positions(j0, j1, edge_step[1], east);
  const int nn = positions(i0, i1, edge_step[2], north), nw = positions(j0, j1, edge_step[3], west);
  if (i1 - i0 == 1 && j1 - j0 == 1) { /* a one-quad terrain */
    if (!(parts & PART_INNER)) return 0;
    emit(&e, i0, j0, i0, j1, i1, j0);
    emit(&e, i1, j0, i0, j1, i1, j1);
    return e.count;
  }
  if (nx >= 3 && nz >= 3) {
    /* interior quads between xs[1..nx-2] x zs[1..nz-2], the full mesh's diagonal */
    for (int b = 1; (parts & PART_INNER) && b + 2 < nz; b++)
      for (int a = 1; a + 2 < nx; a++) {
        emit(&e, xs[a], zs[b], xs[a], zs[b + 1], xs[a + 1], zs[b]);
        emit(&e, xs[a + 1], zs[b], xs[a], zs[b + 1], xs[a + 1], zs[b + 1]);
      }
    if (parts & PART_SOUTH) zipper(&e, south, ns, j0, xs + 1, nx - 2, zs[1], false);
    if (parts & PART_NORTH) zipper(&e, north, nn, j1, xs + 1, nx - 2, zs[nz - 2], false);
    if (parts & PART_WEST) zipper(&e, west, nw, i0, zs + 1, nz - 2, xs[1], true);
    if (parts & PART_EAST) zipper(&e, east, ne, i1, zs + 1, nz - 2, xs[nx - 2], true);
    return e.count;
  }
  /* A fan around the boundary (counter-clockwise in (x, z): south, east, north, west) from
   * a vertex strictly inside; a tile one quad across has none: split it along its length
   * (its only neighbours there are the grid's edge or tiles sharing its short edges, whose
   * one quad has no vertex for a step to drop: the whole strip counts as inner). */
  const int cx = (i0 + i1) / 2, cz = (j0 + j1) / 2;
  if (cx > i0 && cz > j0) {
    for (int k = 0; (parts & PART_SOUTH) && k + 1 < ns; k++)
      emit(&e, cx, cz, south[k], j0, south[k + 1], j0);
    for (int k = 0; (parts & PART_EAST) && k + 1 < ne; k++)
      emit(&e, cx, cz, i1, east[k], i1, east[k + 1]);
    for (int k = 0; (parts & PART_NORTH) && k + 1 < nn; k++)
      emit(&e, cx, cz, north[k], j1, north[k + 1], j1);
    for (int k = 0; (parts & PART_WEST) && k + 1 < nw; k++)
      emit(&e, cx, cz, i0, west[k], i0, west[k + 1]);
    return e.count;
  }
  if (!(parts & PART_INNER)) return 0;
  /* one quad wide (i1 - i0 == 1 or j1 - j0 == 1): zipper the two long sides */
  if (i1 - i0 == 1)
    zipper(&e, west, nw, i0, east, ne, i1, true);
  else
    zipper(&e, south, ns, j0, north, nn, j1, false);
  return e.count;
}

/* The largest |height difference| (world units) between n/3 emitted triangles and the full
 * mesh at the grid vertices they cover, each found in its triangle. */
static double triangles_error(const terrain *t, const uint32_t *tri, size_t n) {
  const int rx = t->resolution_x;
  double worst = 0.0;
  for (size_t f = 0; f < n; f += 3) {
    int x[3], z[3];
    double h[3];
    for (int c = 0; c < 3; c++) {
      x[c] = (int)(tri[f + c] % (uint32_t)rx), z[c] = (int)(tri[f + c] / (uint32_t)rx);
      h[c] = t->h[tri[f + c]];
    }
    int xl = x[0], xh = x[0], zl = z[0], zh = z[0];
    for (int c = 1; c < 3; c++) {
      xl = x[c] < xl ? x[c] : xl, xh = x[c] > xh ? x[c] : xh;
      zl = z[c] < zl ? z[c] : zl, zh = z[c] > zh ? z[c] : zh;
    }
    const double det = (double)(x[1] - x[0]) * (z[2] - z[0]) - (double)(z[1] - z[0]) * (x[2] - x[0]);
    for (int j = zl; j <= zh; j++)
      for (int i = xl; i <= xh; i++) {
        double b1 = ((double)(i - x[0]) * (z[2] - z[0]) - (double)(j - z[0]) * (x[2] - x[0])) / det;
        double b2 = ((double)(x[1] - x[0]) * (j - z[0]) - (double)(z[1] - z[0]) * (i - x[0])) / det;
        if (b1 < -1e-12 || b2 < -1e-12 || b1 + b2 > 1.0 + 1e-12) continue;
        double hl = h[0] + b1 * (h[1] - h[0]) + b2 * (h[2] - h[0]);
        worst = fmax(worst, fabs(hl - t->h[(size_t)j * rx + i]));
      }
  }
  return worst * t->height;
}

static float *seam_entry(const terrain_lod *lod, int tile, int side, int level, int edge_level) {
  return &lod->seam_error[(((size_t)tile * 4 + side) * TERRAIN_LOD_LEVELS + level) *
                              TERRAIN_LOD_LEVELS + edge_level];
}

/* Tile k's tables: error[l] (the step-2^l grid, never below a finer level's), inner_error[l]
 * (the ring layout's inner grid) and seam_error (each side's ring or fan with its edge at
 * the step of level L >= l, never below a finer edge's). */
static void tile_errors(terrain_lod *lod, int k, uint32_t *scratch) {
  const terrain *t = lod->terrain;
  float *e = &lod->error[(size_t)k * TERRAIN_LOD_LEVELS];
  for (int l = 0; l < TERRAIN_LOD_LEVELS; l++) {
    const int s = 1 << l, steps[4] = {s, s, s, s};
    const double grid = triangles_error(t, scratch, emit_tile(lod, k, s, steps, PART_ALL, scratch));
    e[l] = (float)(l > 0 && e[l - 1] > grid ? e[l - 1] : grid);
    lod->inner_error[(size_t)k * TERRAIN_LOD_LEVELS + l] =
        (float)triangles_error(t, scratch, emit_tile(lod, k, s, steps, PART_INNER, scratch));
    for (int side = 0; side < 4; side++)
      for (int L = l; L < TERRAIN_LOD_LEVELS; L++) {
        int edge[4] = {s, s, s, s};
        edge[side] = 1 << L;
        const double ring = triangles_error(
            t, scratch, emit_tile(lod, k, s, edge, (unsigned)PART_SOUTH << side, scratch));
        const float finer = L > l ? *seam_entry(lod, k, side, l, L - 1) : 0.0f;
        *seam_entry(lod, k, side, l, L) = (float)ring > finer ? (float)ring : finer;
      }
  }
}

int terrain_lod_create(terrain_lod *lod, const terrain *t, fog_error *err) {
  *lod = (terrain_lod){.terrain = t};
  lod->tiles_x = (t->resolution_x - 1) / TERRAIN_LOD_TILE;
  lod->tiles_z = (t->resolution_z - 1) / TERRAIN_LOD_TILE;
  if (lod->tiles_x < 1) lod->tiles_x = 1;
  if (lod->tiles_z < 1) lod->tiles_z = 1;
  const size_t tiles = (size_t)lod->tiles_x * lod->tiles_z, levels = TERRAIN_LOD_LEVELS;
  lod->error = malloc(tiles * levels * sizeof *lod->error);
  lod->inner_error = malloc(tiles * levels * sizeof *lod->inner_error);
  lod->seam_error = malloc(tiles * 4 * levels * levels * sizeof *lod->seam_error);
  lod->lo = malloc(tiles * 3 * sizeof *lod->lo);
  lod->hi = malloc(tiles * 3 * sizeof *lod->hi);
  lod->level = calloc(tiles, 1);
  lod->allowed = malloc(tiles * sizeof *lod->allowed);
  uint32_t *scratch = malloc(terrain_lod_max_indices() * sizeof *scratch);
  if (!lod->error || !lod->inner_error || !lod->seam_error || !lod->lo || !lod->hi ||
      !lod->level || !lod->allowed || !scratch) {
    free(scratch);
    terrain_lod_destroy(lod);
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the terrain's LOD tiles");
    return 1;
  }
  for (size_t k = 0; k < tiles; k++) {
    int i0, j0, i1, j1;
    tile_range(lod, (int)k, &i0, &j0, &i1, &j1);
    for (int c = 0; c < 3; c++) lod->lo[3 * k + c] = INFINITY, lod->hi[3 * k + c] = -INFINITY;
    for (int j = j0; j <= j1; j++)
      for (int i = i0; i <= i1; i++) {
        double p[3];
        terrain_vertex(t, i, j, p);
        for (int c = 0; c < 3; c++) {
          lod->lo[3 * k + c] = fmin(lod->lo[3 * k + c], p[c]);
          lod->hi[3 * k + c] = fmax(lod->hi[3 * k + c], p[c]);
        }
      }
    tile_errors(lod, (int)k, scratch);
  }
  free(scratch);
  return 0;
}

void terrain_lod_destroy(terrain_lod *lod) {
  free(lod->error);
  free(lod->inner_error);
  free(lod->seam_error);
  free(lod->lo);
  free(lod->hi);
  free(lod->level);
  free(lod->allowed);
  *lod = (terrain_lod){0};
}

/* The four neighbours of a tile (south, east, north, west; -1 beyond the grid). */
static void neighbours(const terrain_lod *lod, int tile, int out[4]) {
  const int tx = tile % lod->tiles_x, tz = tile / lod->tiles_x;
  out[0] = tz > 0 ? tile - lod->tiles_x : -1;
  out[1] = tx + 1 < lod->tiles_x ? tile + 1 : -1;
  out[2] = tz + 1 < lod->tiles_z ? tile + lod->tiles_x : -1;
  out[3] = tx > 0 ? tile - 1 : -1;
}

/* Each tile's level, then the seams: a tile whose side meets a coarser neighbour draws that
 * side's ring to the neighbour's step, which can err more than either tile's own level
 * (test_terrain_lod: up to 1.25x the budget). Where a side does, the neighbour steps one
 * level finer; where the ring at the tile's own step does (its diagonals are not the
 * grid's), the tile does. Levels only go down, so this ends, at worst at level 0 (no error
 * at the grid's vertices). */
void terrain_lod_choose(terrain_lod *lod, const double camera[3], double pixels_per_unit,
                        double max_pixels) {
  const int tiles = lod->tiles_x * lod->tiles_z;
  double *allowed = lod->allowed;
  for (int k = 0; k < tiles; k++) {
    double d2 = 0.0;
    for (int c = 0; c < 3; c++) {
      double below = lod->lo[3 * k + c] - camera[c], above = camera[c] - lod->hi[3 * k + c];
      double g = fmax(0.0, fmax(below, above));
      d2 += g * g;
    }
    const double within = max_pixels * sqrt(d2) / pixels_per_unit;
    allowed[k] = within;
    int level = 0;
    for (int l = 1; l < TERRAIN_LOD_LEVELS; l++)
      if (lod->error[k * TERRAIN_LOD_LEVELS + l] * pixels_per_unit <= max_pixels * sqrt(d2))
        level = l;
    lod->level[k] = (uint8_t)level;
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (int k = 0; k < tiles; k++) {
      const int l = lod->level[k];
      int nb[4];
      neighbours(lod, k, nb);
      bool coarser_side = false;
      for (int side = 0; side < 4; side++)
        coarser_side |= nb[side] >= 0 && lod->level[nb[side]] > l;
      if (!coarser_side) continue; /* the step-2^l grid: error[l], within budget */
      bool own = lod->inner_error[k * TERRAIN_LOD_LEVELS + l] > allowed[k];
      for (int side = 0; side < 4; side++) {
        const int L = nb[side] >= 0 && lod->level[nb[side]] > l ? lod->level[nb[side]] : l;
        if (*seam_entry(lod, k, side, l, L) <= allowed[k]) continue;
        if (L > l) {
          lod->level[nb[side]] = (uint8_t)(L - 1);
          changed = true;
        } else {
          own = true;
        }
      }
      if (own && l > 0) { /* at level 0 a ring at its own step errs nowhere */
        lod->level[k] = (uint8_t)(l - 1);
        changed = true;
      }
    }
  }
}

/* Level 0 of the largest tile (2T - 1 quads a side): two triangles a quad. */
size_t terrain_lod_max_indices(void) {
  return 6 * (size_t)(2 * TERRAIN_LOD_TILE - 1) * (2 * TERRAIN_LOD_TILE - 1);
}

size_t terrain_lod_all_max_indices(const terrain_lod *lod) {
  const terrain *t = lod->terrain;
  return 6 * (size_t)(t->resolution_x - 1) * (size_t)(t->resolution_z - 1);
}

size_t terrain_lod_emit(const terrain_lod *lod, int tile, uint32_t *indices) {
  const int tx = tile % lod->tiles_x, tz = tile / lod->tiles_x, level = lod->level[tile];
  /* each edge at the coarser step of the two tiles that share it: both emit the same
   * vertices along it */
  int neighbour[4] = {
      tz > 0 ? lod->level[tile - lod->tiles_x] : 0,
      tx + 1 < lod->tiles_x ? lod->level[tile + 1] : 0,
      tz + 1 < lod->tiles_z ? lod->level[tile + lod->tiles_x] : 0,
      tx > 0 ? lod->level[tile - 1] : 0,
  };
  int steps[4];
  for (int k = 0; k < 4; k++) steps[k] = 1 << (neighbour[k] > level ? neighbour[k] : level);
  return emit_tile(lod, tile, 1 << level, steps, PART_ALL, indices);
}
