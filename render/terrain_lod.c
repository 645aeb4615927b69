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
#define V(along, across) (swap ? (across) : (along)), (swap ? (along) : (across))
  while (i + 1 < n_outer || j + 1 < n_inner) {
    bool advance_outer = j + 1 >= n_inner || (i + 1 < n_outer && outer[i + 1] <= inner[j + 1]);
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

/* Tile `tile` at step s with its four edges at steps (south, east, north, west): the
 * interior grid at step s, a ring of zippers to the edges; or, when the tile is too narrow
 * for a ring at this step, a fan from a grid vertex strictly inside. */
static size_t emit_tile(const terrain_lod *lod, int tile, int s, const int edge_step[4],
                        uint32_t *indices) {
  int i0, j0, i1, j1;
  tile_range(lod, tile, &i0, &j0, &i1, &j1);
  emitter e = {.indices = indices, .rx = lod->terrain->resolution_x};
  int xs[2 * TERRAIN_LOD_TILE + 2], zs[2 * TERRAIN_LOD_TILE + 2];
  const int nx = positions(i0, i1, s, xs), nz = positions(j0, j1, s, zs);
  int south[2 * TERRAIN_LOD_TILE + 2], east[2 * TERRAIN_LOD_TILE + 2],
      north[2 * TERRAIN_LOD_TILE + 2], west[2 * TERRAIN_LOD_TILE + 2];
  const int ns = positions(i0, i1, edge_step[0], south), ne = positions(j0, j1, edge_step[1], east);
  const int nn = positions(i0, i1, edge_step[2], north), nw = positions(j0, j1, edge_step[3], west);
  if (i1 - i0 == 1 && j1 - j0 == 1) { /* a one-quad terrain */
    emit(&e, i0, j0, i0, j1, i1, j0);
    emit(&e, i1, j0, i0, j1, i1, j1);
    return e.count;
  }
  if (nx >= 3 && nz >= 3) {
    /* interior quads between xs[1..nx-2] x zs[1..nz-2], the full mesh's diagonal */
    for (int b = 1; b + 2 < nz; b++)
      for (int a = 1; a + 2 < nx; a++) {
        emit(&e, xs[a], zs[b], xs[a], zs[b + 1], xs[a + 1], zs[b]);
        emit(&e, xs[a + 1], zs[b], xs[a], zs[b + 1], xs[a + 1], zs[b + 1]);
      }
    zipper(&e, south, ns, j0, xs + 1, nx - 2, zs[1], false);
    zipper(&e, north, nn, j1, xs + 1, nx - 2, zs[nz - 2], false);
    zipper(&e, west, nw, i0, zs + 1, nz - 2, xs[1], true);
    zipper(&e, east, ne, i1, zs + 1, nz - 2, xs[nx - 2], true);
    return e.count;
  }
  /* A fan around the boundary (counter-clockwise in (x, z): south, east, north, west) from
   * a vertex strictly inside; a tile one quad across has none: split it along its length
   * (its only neighbours there are the grid's edge or tiles sharing its short edges). */
  const int cx = (i0 + i1) / 2, cz = (j0 + j1) / 2;
  if (cx > i0 && cz > j0) {
    for (int k = 0; k + 1 < ns; k++) emit(&e, cx, cz, south[k], j0, south[k + 1], j0);
    for (int k = 0; k + 1 < ne; k++) emit(&e, cx, cz, i1, east[k], i1, east[k + 1]);
    for (int k = 0; k + 1 < nn; k++) emit(&e, cx, cz, north[k], j1, north[k + 1], j1);
    for (int k = 0; k + 1 < nw; k++) emit(&e, cx, cz, i0, west[k], i0, west[k + 1]);
    return e.count;
  }
  /* one quad wide (i1 - i0 == 1 or j1 - j0 == 1): zipper the two long sides */
  if (i1 - i0 == 1)
    zipper(&e, west, nw, i0, east, ne, i1, true);
  else
    zipper(&e, south, ns, j0, north, nn, j1, false);
  return e.count;
}

/* The tile's level-l mesh (no neighbour coarser) against the full mesh: the largest
 * |height difference| at the grid vertices inside the tile, each found in its triangle. */
static double level_error(const terrain_lod *lod, int tile, int level, uint32_t *scratch) {
  const terrain *t = lod->terrain;
  const int s = 1 << level, steps[4] = {s, s, s, s}, rx = t->resolution_x;
  const size_t n = emit_tile(lod, tile, s, steps, scratch);
  double worst = 0.0;
  for (size_t f = 0; f < n; f += 3) {
    int x[3], z[3];
    double h[3];
    for (int c = 0; c < 3; c++) {
      x[c] = (int)(scratch[f + c] % (uint32_t)rx), z[c] = (int)(scratch[f + c] / (uint32_t)rx);
      h[c] = t->h[scratch[f + c]];
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

int terrain_lod_create(terrain_lod *lod, const terrain *t, fog_error *err) {
  *lod = (terrain_lod){.terrain = t};
  lod->tiles_x = (t->resolution_x - 1) / TERRAIN_LOD_TILE;
  lod->tiles_z = (t->resolution_z - 1) / TERRAIN_LOD_TILE;
  if (lod->tiles_x < 1) lod->tiles_x = 1;
  if (lod->tiles_z < 1) lod->tiles_z = 1;
  const size_t tiles = (size_t)lod->tiles_x * lod->tiles_z;
  lod->error = malloc(tiles * TERRAIN_LOD_LEVELS * sizeof *lod->error);
  lod->lo = malloc(tiles * 3 * sizeof *lod->lo);
  lod->hi = malloc(tiles * 3 * sizeof *lod->hi);
  lod->level = calloc(tiles, 1);
  uint32_t *scratch = malloc(terrain_lod_max_indices() * sizeof *scratch);
  if (!lod->error || !lod->lo || !lod->hi || !lod->level || !scratch) {
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
    float *e = &lod->error[k * TERRAIN_LOD_LEVELS];
    e[0] = 0.0f;
    for (int l = 1; l < TERRAIN_LOD_LEVELS; l++) {
      double worst = level_error(lod, (int)k, l, scratch);
      e[l] = (float)(worst > e[l - 1] ? worst : e[l - 1]); /* never below a finer level's */
    }
  }
  free(scratch);
  return 0;
}

void terrain_lod_destroy(terrain_lod *lod) {
  free(lod->error);
  free(lod->lo);
  free(lod->hi);
  free(lod->level);
  *lod = (terrain_lod){0};
}

void terrain_lod_choose(terrain_lod *lod, const double camera[3], double pixels_per_unit,
                        double max_pixels) {
  const int tiles = lod->tiles_x * lod->tiles_z;
  for (int k = 0; k < tiles; k++) {
    double d2 = 0.0;
    for (int c = 0; c < 3; c++) {
      double below = lod->lo[3 * k + c] - camera[c], above = camera[c] - lod->hi[3 * k + c];
      double g = fmax(0.0, fmax(below, above));
      d2 += g * g;
    }
    const double distance = sqrt(d2);
    int level = 0;
    for (int l = 1; l < TERRAIN_LOD_LEVELS; l++)
      if (lod->error[k * TERRAIN_LOD_LEVELS + l] * pixels_per_unit <= max_pixels * distance)
        level = l;
    lod->level[k] = (uint8_t)level;
  }
}

/* Level 0 of the largest tile (2T - 1 quads a side): two triangles a quad. */
size_t terrain_lod_max_indices(void) {
  return 6 * (size_t)(2 * TERRAIN_LOD_TILE - 1) * (2 * TERRAIN_LOD_TILE - 1);
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
  return emit_tile(lod, tile, 1 << level, steps, indices);
}
