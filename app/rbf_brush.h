/* The Gaussian brush (Zhou et al. 2007, Fogshop §6): an artist paints RBF fog onto the
 * scene, erases it and copies groups of Gaussians about, in `fogpipe view` (or `demo`) on a
 * `[fog] model = rbf` scene (app/window_session.c wires the mouse and keys to it).
 *
 *   rbf_bank bank = {.rbfs = cfg.fog.rbfs, .count = cfg.fog.rbf_count,
 *                    .capacity = SCENE_CONFIG_MAX_RBFS};
 *   double carried = rbf_brush_stroke_start(&brush);
 *   rbf_brush_stroke(&bank, &brush, last_hit, hit, &carried);   (each frame of a drag)
 *
 * Positions are surface points (where the cursor's ray meets the terrain or a box); a
 * painted Gaussian sits `lift` above its surface point. Everything is plain arithmetic on
 * the bank: the caller rebuilds the fog from it. */
#ifndef FOGPIPE_APP_RBF_BRUSH_H
#define FOGPIPE_APP_RBF_BRUSH_H

#include "render/fog_models.h"

typedef struct rbf_brush {
  double radius;  /* of each Gaussian painted, > 0 (world units) */
  double density; /* its peak c, > 0 ([fog] rbf's density, before density_scale) */
  double spacing; /* along a stroke between consecutive Gaussians, > 0 */
  double lift;    /* a Gaussian's centre above its surface point */
} rbf_brush;

/* The brush for a bank: its Gaussians' mean radius and density where it has any, else a
 * radius of `size` / 40 (size: the scene's extent) and density `fallback_density`; the
 * spacing half a radius (the strokes look continuous), the lift half a radius. */
rbf_brush rbf_brush_for(const fog_rbf *rbfs, int count, double size, double fallback_density);

typedef struct rbf_bank {
  fog_rbf *rbfs;
  int count, capacity;
} rbf_bank;

/* The stroke length a new stroke starts with: one spacing, so its first point paints. */
double rbf_brush_stroke_start(const rbf_brush *brush);
/* Paints along the stroke's segment from `from` to `to`: a Gaussian wherever the stroke's
 * length since the last one reaches the spacing (*carried: that length, updated), at the
 * point there lifted by `lift`. Returns how many were added (it stops at the capacity). */
int rbf_brush_stroke(rbf_bank *bank, const rbf_brush *brush, const double from[3],
                     const double to[3], double *carried);
/* Removes the Gaussians whose centre lies within `reach` of p horizontally (x, z), the
 * others keeping their order. Returns how many went. */
int rbf_brush_erase(rbf_bank *bank, const double p[3], double reach);
/* Appends copies of the Gaussians whose centre lies within `reach` of `from` horizontally,
 * moved by to - from (a group picked up and put down elsewhere). Returns how many were
 * added (it stops at the capacity). */
int rbf_brush_copy(rbf_bank *bank, const double from[3], double reach, const double to[3]);

#endif
