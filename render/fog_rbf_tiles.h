/* Gaussian fog banks at Fogshop's scale (thousands of RBFs, Zhou et al. 2007 use up to
 * 3008): per screen tile, the list of the Gaussians whose rays through that tile can see
 * them, so a pixel's integral sums its tile's list instead of every Gaussian.
 *
 * The bound: a Gaussian c exp(-|x - b|^2 / r^2) adds at most c r sqrt(pi) exp(-h^2 / r^2)
 * to the optical depth of any ray (a line) passing at distance h from b. Each Gaussian gets
 * a cull radius R where that is FOG_RBF_CULL_BOUND / count, and is listed for a tile when
 * its sphere of radius R meets the tile's cone (a circular cone around the four corner
 * pixels' rays, which contains every pixel ray of the tile). So the Gaussians a tile leaves
 * out change any of its rays' optical depth, and tau, by less than FOG_RBF_CULL_BOUND in
 * all (tests/render/test_rbf_tiles.c). */
#ifndef FOGPIPE_RENDER_FOG_RBF_TILES_H
#define FOGPIPE_RENDER_FOG_RBF_TILES_H

#include <stddef.h>
#include <stdint.h>

#include "render/camera.h"
#include "render/fog_models.h"
#include "transform/fog_error.h"

#define FOG_RBF_CULL_BOUND 1e-6 /* optical depth, all culled Gaussians of a ray together */
#define FOG_RBF_TILE_SIZE 16    /* pixels */

/* The radius beyond which Gaussian g (one of count) is left out: r sqrt(ln(c r sqrt(pi) /
 * (FOG_RBF_CULL_BOUND / count))); negative when g cannot reach that bound anywhere. */
double fog_rbf_cull_radius(const fog_rbf *g, int count);

typedef struct fog_rbf_tiles {
  int tiles_x, tiles_y;    /* tiles of FOG_RBF_TILE_SIZE pixels, GL's rows (bottom first) */
  uint32_t *ranges;        /* per tile (x fastest): first index, count */
  uint32_t *indices;       /* the tiles' lists, one after another */
  size_t index_count, index_capacity;
} fog_rbf_tiles;

/* (Re)builds the lists for the camera's width x height image; grows the arrays as needed
 * (fog_rbf_tiles_destroy frees them). Non-zero and a message when out of memory. */
int fog_rbf_tiles_build(fog_rbf_tiles *tiles, const camera *cam, int width, int height,
                        const fog_rbf *rbfs, int count, fog_error *err);
void fog_rbf_tiles_destroy(fog_rbf_tiles *tiles);

#endif
