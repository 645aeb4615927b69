/* Terrain level of detail for the scene pass: geomipmapping (de Boer 2000) over the tiles
 * the pass already culls, with seams stitched by edge collapse so the mesh stays watertight.
 *
 * Tiles are TERRAIN_LOD_TILE x TERRAIN_LOD_TILE quads of the terrain's grid (terrain.h),
 * row-major (tile tx + tz * tiles_x), the last row and column taking the grid's remainder
 * (T to 2T - 1 quads). Level l of a tile keeps the vertices at step s = 2^l from its corner
 * (and its far edge): the inner grid triangulated as terrain.h triangulates the full one
 * (diagonal (i+s, j)-(i, j+s)) and a ring one step wide between it and the tile's edges;
 * a tile too narrow for a ring at that step is a fan from a grid vertex inside it.
 * A tile whose neighbours are at its level or finer is the step-s grid itself, triangulated
 * as the full mesh (level 0 is the full mesh, triangle for triangle).
 * error[l] is the largest height difference between the level's mesh and the full mesh
 * at the full grid's vertices (each located in its level triangle); seam_error the same for
 * each ring side with its edge at a coarser neighbour's step.
 *
 * Level choice: the coarsest level whose error, seen from the camera at the tile box's
 * nearest point, spans at most max_pixels: error * pixels_per_unit / distance <= max_pixels
 * (pixels_per_unit = image height / (2 tan(fov_y / 2))); then, where a side's ring to a
 * coarser neighbour would exceed that, the neighbour is made finer, so every tile as drawn,
 * seams included, keeps within the budget at the grid's vertices.
 *
 * Seams: each tile edge carries the vertices of the coarser step of the two tiles sharing
 * it, so both sides of a seam have the same vertices and no T-junction, whatever the
 * neighbours' levels (no "one level apart" rule). The ring joins the edge's vertices to the
 * inner grid's side by a zipper (merging the two sorted rows), whose triangles all have
 * vertices on both of two parallel lines: none is flipped or degenerate. (A first version
 * collapsed the edge vertices onto the coarser step instead; at a tile's corner two
 * collapses along different edges flipped triangles.) test_terrain_lod checks every
 * interior edge is shared by exactly two triangles, every triangle winds as the full
 * mesh's, and their areas sum to the footprint, for random level fields. */
#ifndef FOGPIPE_RENDER_TERRAIN_LOD_H
#define FOGPIPE_RENDER_TERRAIN_LOD_H

#include <stddef.h>
#include <stdint.h>

#include "transform/fog_error.h"
#include "render/terrain.h"

#define TERRAIN_LOD_TILE 16
#define TERRAIN_LOD_LEVELS 5 /* steps 1, 2, 4, 8, 16 */

typedef struct terrain_lod {
  const terrain *terrain;
  int tiles_x, tiles_z;
  float *error;  /* tiles x TERRAIN_LOD_LEVELS: world height error of each level */
  float *inner_error; /* tiles x levels: the ring layout's inner grid */
  float *seam_error;  /* tiles x 4 sides x levels l x edge levels L >= l: that side's ring */
  double *lo, *hi; /* tiles x 3: world boxes of the tiles' vertices */
  uint8_t *level; /* tiles: the level chosen by terrain_lod_choose (0 at creation) */
  double *allowed; /* tiles: terrain_lod_choose's world error within the budget */
} terrain_lod;

int terrain_lod_create(terrain_lod *lod, const terrain *t, fog_error *err);
void terrain_lod_destroy(terrain_lod *lod);

/* Chooses each tile's level for a camera at `camera` (world). */
void terrain_lod_choose(terrain_lod *lod, const double camera[3], double pixels_per_unit,
                        double max_pixels);

/* The most indices terrain_lod_emit writes for one tile (a remainder tile's level 0). */
size_t terrain_lod_max_indices(void);
/* The most it writes for all of lod's tiles together: the full mesh's, 6 a quad (no tile
 * at any level, seams included, emits more than its quads at level 0). tiles x
 * terrain_lod_max_indices() was 3.75x that: 5.3 GB at the largest terrain. */
size_t terrain_lod_all_max_indices(const terrain_lod *lod);
/* Tile `tile`'s triangles at its level, stitched to its coarser neighbours: vertex indices
 * j * resolution_x + i, three per triangle, counter-clockwise seen from above (the full
 * mesh's winding). Returns the number of indices written. */
size_t terrain_lod_emit(const terrain_lod *lod, int tile, uint32_t *indices);

#endif
