/* The terrain's LOD mesh (render/terrain_lod.h), on the CPU and exactly:
 * - for random level fields over terrains whose tiles divide the grid (129) and whose last
 *   tiles are clipped (101 x 77), and for all-equal levels: every triangle winds as the full
 *   mesh's do, their areas (integer grid coordinates: exact) sum to the footprint, and every
 *   edge inside the footprint is shared by exactly two triangles, every edge on its border
 *   by one: the mesh tiles the footprint with no crack (T-junction) and no overlap;
 * - level 0 everywhere is the full mesh's triangle set;
 * - each level's error is the max height difference to the full mesh at the grid vertices
 *   (checked against terrain_height_at of the level mesh's own plane... through a sampled
 *   independent evaluation: the level mesh's triangles, barycentric at each vertex);
 * - terrain_lod_choose: a level's error seen from the tile's nearest point is within the
 *   pixel budget, and the next coarser level's is not (or it is the coarsest). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "test_util.h"

static uint64_t rng = 0x243F6A8885A308D3ull;
static double uniform(void) {
  rng ^= rng >> 12, rng ^= rng << 25, rng ^= rng >> 27;
  return (double)((rng * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct edge {
  uint32_t a, b;
} edge;
static int edge_cmp(const void *x, const void *y) {
  const edge *p = x, *q = y;
  if (p->a != q->a) return p->a < q->a ? -1 : 1;
  return (p->b > q->b) - (p->b < q->b);
}

/* Emits every tile, checks the tiling; returns the triangle count. */
static long check_mesh(const terrain_lod *lod, const char *what) {
  const terrain *t = lod->terrain;
  const int rx = t->resolution_x, rz = t->resolution_z, tiles = lod->tiles_x * lod->tiles_z;
  /* the whole mesh's bound (the sanitizer pass catches a write past it) */
  const size_t bound = terrain_lod_all_max_indices(lod);
  uint32_t *idx = malloc(bound * sizeof *idx);
  size_t n = 0;
  for (int k = 0; k < tiles; k++) n += terrain_lod_emit(lod, k, idx + n);
  CHECK(n <= bound, "%s: %zu indices emitted, past terrain_lod_all_max_indices' %zu", what, n,
        bound);
  const long triangles = (long)(n / 3);
  edge *edges = malloc(n * sizeof *edges);
  double area = 0.0;
  int wrong_winding = 0;
  for (long f = 0; f < triangles; f++) {
    double x[3], z[3];
    for (int c = 0; c < 3; c++) x[c] = idx[3 * f + c] % rx, z[c] = idx[3 * f + c] / rx;
    /* the full mesh's (a, c, b) = (i,j), (i,j+1), (i+1,j): (x1-x0)(z2-z0)-(z1-z0)(x2-x0) < 0 */
    double cross = (x[1] - x[0]) * (z[2] - z[0]) - (z[1] - z[0]) * (x[2] - x[0]);
    wrong_winding += !(cross < 0);
    area += 0.5 * fabs(cross);
    for (int c = 0; c < 3; c++) {
      uint32_t a = idx[3 * f + c], b = idx[3 * f + (c + 1) % 3];
      edges[3 * f + c] = (edge){a < b ? a : b, a < b ? b : a};
    }
  }
  qsort(edges, n, sizeof *edges, edge_cmp);
  int bad_edges = 0;
  for (size_t e = 0; e < n;) {
    size_t run = 1;
    while (e + run < n && !edge_cmp(&edges[e], &edges[e + run])) run++;
    int xa = edges[e].a % rx, za = edges[e].a / rx, xb = edges[e].b % rx, zb = edges[e].b / rx;
    bool border = (xa == xb && (xa == 0 || xa == rx - 1)) || (za == zb && (za == 0 || za == rz - 1));
    if ((int)run != (border ? 1 : 2)) {
      if (bad_edges < 5)
        fprintf(stderr, "%s: edge (%d,%d)-(%d,%d) used %zu times\n", what, xa, za, xb, zb, run);
      bad_edges++;
    }
    e += run;
  }
  CHECK(wrong_winding == 0, "%s: %d triangles wind the other way (or are degenerate)", what,
        wrong_winding);
  CHECK(area == (double)(rx - 1) * (rz - 1), "%s: triangles cover %.1f, the footprint %d", what,
        area, (rx - 1) * (rz - 1));
  CHECK(bad_edges == 0, "%s: %d edges not shared by exactly two triangles (one on the border)",
        what, bad_edges);
  free(edges);
  free(idx);
  return triangles;
}

/* A triangle as three vertex indices, rotated so the smallest comes first (winding kept). */
typedef struct triangle {
  uint32_t v[3];
} triangle;
static triangle canonical(uint32_t a, uint32_t b, uint32_t c) {
  if (b < a && b < c) return (triangle){{b, c, a}};
  if (c < a && c < b) return (triangle){{c, a, b}};
  return (triangle){{a, b, c}};
}
static int triangle_cmp(const void *x, const void *y) {
  const triangle *p = x, *q = y;
  for (int c = 0; c < 3; c++)
    if (p->v[c] != q->v[c]) return p->v[c] < q->v[c] ? -1 : 1;
  return 0;
}

/* Level 0 everywhere against terrain.h's full mesh, triangle by triangle: cell (i, j) split
 * along (i+1, j)-(i, j+1), wound (i,j), (i,j+1), (i+1,j) and (i+1,j), (i,j+1), (i+1,j+1). */
static void check_full_mesh(terrain_lod *lod) {
  const terrain *t = lod->terrain;
  const int rx = t->resolution_x, rz = t->resolution_z, tiles = lod->tiles_x * lod->tiles_z;
  memset(lod->level, 0, (size_t)tiles);
  const size_t bound = terrain_lod_all_max_indices(lod);
  uint32_t *idx = malloc(bound * sizeof *idx);
  size_t n = 0;
  for (int k = 0; k < tiles; k++) n += terrain_lod_emit(lod, k, idx + n);
  CHECK(n <= bound, "level 0: %zu indices emitted, past terrain_lod_all_max_indices' %zu", n,
        bound);
  const size_t want_count = 2 * (size_t)(rx - 1) * (rz - 1);
  triangle *got = malloc(n / 3 * sizeof *got), *want = malloc(want_count * sizeof *want);
  for (size_t f = 0; f < n / 3; f++) got[f] = canonical(idx[3 * f], idx[3 * f + 1], idx[3 * f + 2]);
  size_t w = 0;
  for (int j = 0; j + 1 < rz; j++)
    for (int i = 0; i + 1 < rx; i++) {
      const uint32_t a = (uint32_t)(j * rx + i), b = a + 1, c = a + (uint32_t)rx, d = c + 1;
      want[w++] = canonical(a, c, b);
      want[w++] = canonical(b, c, d);
    }
  qsort(got, n / 3, sizeof *got, triangle_cmp);
  qsort(want, want_count, sizeof *want, triangle_cmp);
  int differ = 0;
  for (size_t f = 0; f < want_count && f < n / 3; f++) differ += triangle_cmp(&got[f], &want[f]) != 0;
  CHECK(n / 3 == want_count && differ == 0,
        "%dx%d level 0: %zu triangles, %d differ from the full mesh's %zu", rx, rz, n / 3, differ,
        want_count);
  free(got), free(want), free(idx);
}

/* The largest |height| difference (world units) between tile k's emitted triangles (its
 * level, its seams to its neighbours) and the grid, at the grid vertices inside the tile:
 * each vertex located in a triangle that holds it, barycentric in exact grid coordinates. */
static double emitted_error(const terrain_lod *lod, int k, uint32_t *idx) {
  const terrain *t = lod->terrain;
  const int rx = t->resolution_x;
  const size_t n = terrain_lod_emit(lod, k, idx);
  double worst = 0.0;
  for (size_t f = 0; f < n; f += 3) {
    double px[3], pz[3], ph[3];
    for (int c = 0; c < 3; c++)
      px[c] = idx[f + c] % rx, pz[c] = idx[f + c] / rx, ph[c] = t->h[idx[f + c]];
    const double det = (px[1] - px[0]) * (pz[2] - pz[0]) - (pz[1] - pz[0]) * (px[2] - px[0]);
    const int x0 = (int)fmin(px[0], fmin(px[1], px[2])), x1 = (int)fmax(px[0], fmax(px[1], px[2]));
    const int z0 = (int)fmin(pz[0], fmin(pz[1], pz[2])), z1 = (int)fmax(pz[0], fmax(pz[1], pz[2]));
    for (int j = z0; j <= z1; j++)
      for (int i = x0; i <= x1; i++) {
        const double b1 = ((i - px[0]) * (pz[2] - pz[0]) - (j - pz[0]) * (px[2] - px[0])) / det;
        const double b2 = ((px[1] - px[0]) * (j - pz[0]) - (pz[1] - pz[0]) * (i - px[0])) / det;
        if (b1 < -1e-12 || b2 < -1e-12 || b1 + b2 > 1 + 1e-12) continue;
        const double h = ph[0] + b1 * (ph[1] - ph[0]) + b2 * (ph[2] - ph[0]);
        worst = fmax(worst, fabs(h - t->h[(size_t)j * rx + i]) * t->height);
      }
  }
  return worst;
}

/* After terrain_lod_choose from `cam`, every tile as drawn (seams included) is within the
 * budget seen from its box's nearest point. Returns the number of tiles above level 0. */
static int check_budget(terrain_lod *lod, const double cam[3], double ppu, double budget,
                        const char *what) {
  terrain_lod_choose(lod, cam, ppu, budget);
  const int tiles = lod->tiles_x * lod->tiles_z;
  uint32_t *idx = malloc(terrain_lod_max_indices() * sizeof *idx);
  int over = 0, coarse = 0;
  double worst_pixels = 0.0;
  for (int k = 0; k < tiles; k++) {
    double d2 = 0;
    for (int c = 0; c < 3; c++) {
      double g = fmax(0.0, fmax(lod->lo[3 * k + c] - cam[c], cam[c] - lod->hi[3 * k + c]));
      d2 += g * g;
    }
    const double e = emitted_error(lod, k, idx), distance = sqrt(d2);
    const double pixels = e > 0 ? e * ppu / distance : 0.0;
    worst_pixels = fmax(worst_pixels, pixels);
    over += pixels > budget * (1 + 1e-9);
    coarse += lod->level[k] > 0;
  }
  printf("%s, budget %g px: %d of %d tiles coarser than level 0, the worst as drawn %.3f px\n",
         what, budget, coarse, tiles, worst_pixels);
  CHECK(over == 0, "%s: %d tiles as drawn (seams included) over the %g px budget, up to %.3f px",
        what, over, budget, worst_pixels);
  free(idx);
  return coarse;
}

int main(void) {
  fog_error err = {0};
  const int sizes[2][2] = {{129, 129}, {101, 77}};
  for (int sz = 0; sz < 2; sz++) {
    terrain t;
    terrain_desc desc = {.size = {800, 600}, .height = 120, .resolution = sizes[sz][0],
                         .octaves = 6, .frequency = 3, .persistence = 0.5, .seed = 9};
    CHECK(terrain_create(&t, &desc, &err) == 0, "terrain: %s", err.message);
    if (sz == 1) { /* a non-square grid: resample the procedural one */
      t.resolution_x = sizes[sz][0];
      t.resolution_z = sizes[sz][1];
    }
    terrain_lod lod;
    CHECK(terrain_lod_create(&lod, &t, &err) == 0, "lod: %s", err.message);
    const int tiles = lod.tiles_x * lod.tiles_z;
    /* level 0: the full mesh */
    check_full_mesh(&lod);
    long full = check_mesh(&lod, "level 0");
    CHECK(full == 2L * (t.resolution_x - 1) * (t.resolution_z - 1), "level 0: %ld triangles", full);
    for (int l = 1; l < TERRAIN_LOD_LEVELS; l++) {
      memset(lod.level, l, (size_t)tiles);
      check_mesh(&lod, "one level");
    }
    for (int trial = 0; trial < 40; trial++) {
      for (int k = 0; k < tiles; k++)
        lod.level[k] = (uint8_t)(trial % 2 ? uniform() * TERRAIN_LOD_LEVELS
                                           : (k * 7 + trial) % TERRAIN_LOD_LEVELS);
      check_mesh(&lod, trial % 2 ? "random levels" : "striped levels");
    }
    /* Errors: 0 at level 0, non-decreasing, and level 1's the max over the vertices the
     * level drops of |h - the mean of the two kept neighbours along the quad's diagonal or
     * edge| for the first tile, recomputed here from the triangles. */
    for (int k = 0; k < tiles; k++) {
      CHECK(lod.error[k * TERRAIN_LOD_LEVELS] == 0.0f, "tile %d: level 0 error %g", k,
            lod.error[k * TERRAIN_LOD_LEVELS]);
      for (int l = 1; l < TERRAIN_LOD_LEVELS; l++)
        CHECK(lod.error[k * TERRAIN_LOD_LEVELS + l] >= lod.error[k * TERRAIN_LOD_LEVELS + l - 1],
              "tile %d: errors decrease at level %d", k, l);
    }
    {
      /* tile 0 at level 1 from its emitted triangles: each full-grid vertex inside a
       * triangle (barycentric, exact rationals here) against its own height */
      memset(lod.level, 1, (size_t)tiles);
      static uint32_t idx[6 * (2 * TERRAIN_LOD_TILE - 1) * (2 * TERRAIN_LOD_TILE - 1)];
      size_t n = terrain_lod_emit(&lod, 0, idx);
      double worst = 0.0;
      for (int j = 0; j <= TERRAIN_LOD_TILE; j++)
        for (int i = 0; i <= TERRAIN_LOD_TILE; i++)
          for (size_t f = 0; f < n; f += 3) {
            double px[3], pz[3], ph[3];
            for (int c = 0; c < 3; c++) {
              px[c] = idx[f + c] % t.resolution_x, pz[c] = idx[f + c] / t.resolution_x;
              ph[c] = t.h[idx[f + c]];
            }
            double det = (px[1] - px[0]) * (pz[2] - pz[0]) - (pz[1] - pz[0]) * (px[2] - px[0]);
            double b1 = ((i - px[0]) * (pz[2] - pz[0]) - (j - pz[0]) * (px[2] - px[0])) / det;
            double b2 = ((px[1] - px[0]) * (j - pz[0]) - (pz[1] - pz[0]) * (i - px[0])) / det;
            if (b1 < -1e-12 || b2 < -1e-12 || b1 + b2 > 1 + 1e-12) continue;
            double h = ph[0] + b1 * (ph[1] - ph[0]) + b2 * (ph[2] - ph[0]);
            worst = fmax(worst, fabs(h - t.h[(size_t)j * t.resolution_x + i]) * t.height);
            break;
          }
      CHECK(fabs(worst - lod.error[1]) <= 1e-4 * (1 + worst),
            "tile 0 level 1: error %.6g, from the triangles %.6g", lod.error[1], worst);
    }
    /* The choice: within budget, and the next level would not be. */
    const double cam[3] = {t.origin[0] + 0.3 * t.size[0], t.max_y + 200.0,
                           t.origin[2] + 0.6 * t.size[1]};
    const double ppu = 360.0 / (2.0 * tan(0.5)), budget = 4.0;
    terrain_lod_choose(&lod, cam, ppu, budget);
    int coarse = 0, finer_for_seams = 0;
    for (int k = 0; k < tiles; k++) {
      double d2 = 0;
      for (int c = 0; c < 3; c++) {
        double g = fmax(0.0, fmax(lod.lo[3 * k + c] - cam[c], cam[c] - lod.hi[3 * k + c]));
        d2 += g * g;
      }
      int l = lod.level[k];
      coarse += l > 0;
      CHECK(lod.error[k * TERRAIN_LOD_LEVELS + l] * ppu <= budget * sqrt(d2) * (1 + 1e-9),
            "tile %d: level %d over budget", k, l);
      /* the coarsest within budget, or finer where a neighbour's seam needs it */
      int coarsest = 0;
      for (int m = 1; m < TERRAIN_LOD_LEVELS; m++)
        if (lod.error[k * TERRAIN_LOD_LEVELS + m] * ppu <= budget * sqrt(d2)) coarsest = m;
      CHECK(l <= coarsest, "tile %d: level %d, coarser than %d, the coarsest within budget", k,
            l, coarsest);
      finer_for_seams += l < coarsest;
    }
    CHECK(coarse > tiles / 4, "only %d of %d tiles coarser than level 0", coarse, tiles);
    CHECK(finer_for_seams < tiles / 4, "%d of %d tiles finer than their own error needs",
          finer_for_seams, tiles);
    /* as drawn, seams included: from above, low over the terrain, and inside a tile */
    const double views[3][3] = {
        {cam[0], cam[1], cam[2]},
        {t.origin[0] + 0.5 * t.size[0], t.max_y + 5.0, t.origin[2] + 0.1 * t.size[1]},
        {t.origin[0] + 0.37 * t.size[0], 0.5 * (t.min_y + t.max_y), t.origin[2] + 0.52 * t.size[1]}};
    for (int v = 0; v < 3; v++)
      for (int b = 0; b < 2; b++) {
        char what[64];
        snprintf(what, sizeof what, "%dx%d view %d", t.resolution_x, t.resolution_z, v);
        check_budget(&lod, views[v], ppu, b ? 4.0 : 1.0, what);
      }
    printf("%dx%d: %d tiles, %d coarser than level 0 from the test camera; tile 0's errors "
           "%.3g %.3g %.3g %.3g\n", t.resolution_x, t.resolution_z, tiles, coarse, lod.error[1],
           lod.error[2], lod.error[3], lod.error[4]);
    terrain_lod_destroy(&lod);
    t.resolution_x = t.resolution_z = sizes[sz][0];
    terrain_destroy(&t);
  }
  return test_finish("test_terrain_lod");
}
