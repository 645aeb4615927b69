/* `fogpipe fit`'s fogmap rungs for an input without a fogmap of its own (an analytic model:
 * Gaussians, quadrics, Perlin or height fog): its density, sampled (app/fit_density.h),
 * projected to a 2D fogmap f(x, z) and a vertical profile g(y), K = f g, the way `import`
 * projects a VDB grid (sim/vdb_import.h, docs/vdb_import.md):
 *   - each sample column's optical depth, resampled by area onto square fogmap cells
 *     (as many along the longer side as the samples have), so that f ∫g dy is the
 *     column's optical depth to rounding;
 *   - g: the mean vertical distribution, a degree-1 B-spline with a knot per layer,
 *     max g = 1 (f is then the extinction at the profile's densest height).
 * Separable fog (a ground layer of any footprint under one vertical shape) is held to the
 * samples' resolution; a plume whose shape changes with height is not, and its error on
 * the views says by how much. */
#ifndef FOGPIPE_APP_FIT_FOGMAP_H
#define FOGPIPE_APP_FIT_FOGMAP_H

#include "app/config.h"
#include "app/fit.h"
#include "app/fit_density.h"
#include "sim/sim.h"

/* The projected fogmap's file name in fit_result.scratch. */
#define FIT_FOGMAP_FILE "fogmap.exr"
/* Profile layers: one knot each (sim/vdb_import.h's limit). */
#define FIT_FOGMAP_LAYERS VDB_PROFILE_MAX_KNOTS

typedef struct fit_fogmap {
  fogmap map;             /* extinction per world unit at g = 1 (density_scale 1) */
  vdb_fogmap_place place; /* where the map lies: [box] origin and cell_size */
  vdb_profile profile;    /* g, and its support: [box] floor and top */
} fit_fogmap;

/* The projection of the model's density over the domain [lo, hi]: side cells along the
 * longer horizontal side, FIT_FOGMAP_LAYERS layers (a ground layer is thin beside its
 * footprint: the fit's own samples, isotropic, would give it a handful). Returns -1 for a
 * domain without fog (nothing to project), 1 out of memory (err); nothing stays allocated
 * unless it returns 0. */
int fit_fogmap_project(const fog_model *model, const double lo[3], const double hi[3], int side,
                       fit_fogmap *out, fog_error *err);
void fit_fogmap_destroy(fit_fogmap *f);

/* c's fog becomes this fogmap, read from `path` (the caller saves f->map there,
 * fogmap_save_exr): model fogmap, density_scale 1, the box placed and the profile set
 * (both as written keys, so scene_config_write gives them back). The input's other fog
 * lines are cleared. An input lit per piece of its walk ([light] shadow_pieces, Perlin
 * fog's auto) keeps that light: shadow_pieces = on. */
void fit_fogmap_apply(const fit_fogmap *f, const char *path, scene_config *c);

#endif
