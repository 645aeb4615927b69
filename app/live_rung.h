/* The live demo's model selector (issue 17, docs/demo.md): the simulated fogmap shown through
 * a cheaper rung of the model ladder, fitted to it as it moves, with the rung's measured
 * error against it. What the panel's "model" menu runs in the pipeline (app/pipeline.c):
 *
 *   live_rung_fit(&fogmap_model, LIVE_RUNG_HEIGHT, &rung);       every step (or every few)
 *   ...draw live_rung_model(&rung) instead of the fogmap...
 *   live_rung_measure(&fogmap_model, &cam, w, h, depth, &rung);  every few frames
 *
 * The fit is fit's (app/fit_density.h) on the model's extinction sampled over its box; the
 * error is |tau_rung - tau_fogmap| on a grid of the view's pixels, both exact CPU twins in
 * double along each pixel's ray to its surface. */
#ifndef FOGPIPE_APP_LIVE_RUNG_H
#define FOGPIPE_APP_LIVE_RUNG_H

#include "render/render.h"

typedef enum live_rung_kind {
  LIVE_RUNG_FOGMAP = 0, /* the simulated fogmap itself */
  LIVE_RUNG_HOMOGENEOUS,
  LIVE_RUNG_HEIGHT,
  LIVE_RUNG_GAUSSIANS,  /* LIVE_RUNG_GAUSSIAN_COUNT Gaussians (model rbf), fit's k-means */
  LIVE_RUNG_ELLIPSOIDS, /* LIVE_RUNG_ELLIPSOID_COUNT uniform ellipsoids (model quadric) */
  LIVE_RUNG_COUNT,
} live_rung_kind;

#define LIVE_RUNG_GAUSSIAN_COUNT 16
#define LIVE_RUNG_ELLIPSOID_COUNT 4

/* Whether a rung is bounded fog that needs its own sun-shadow volume (Gaussians and
 * ellipsoids; refitted every LIVE_RUNG_REFIT steps, not every step, for that volume's
 * sake). */
bool live_rung_bounded(live_rung_kind kind);
#define LIVE_RUNG_REFIT 8

/* The panel's names, indexed by live_rung_kind. */
extern const char *const live_rung_names[LIVE_RUNG_COUNT];

/* Pixels measured a side of the view's grid (LIVE_RUNG_COLUMNS x LIVE_RUNG_ROWS rays). */
#define LIVE_RUNG_COLUMNS 16
#define LIVE_RUNG_ROWS 9

typedef struct live_rung {
  live_rung_kind kind;
  /* The fitted model's kind and numbers (homogeneous, height fog, rbf or quadric); its
   * Gaussians and volumes are the arrays below: live_rung_model points the model at them. */
  fog_model model;
  fog_rbf rbfs[LIVE_RUNG_GAUSSIAN_COUNT];
  fog_quadric quadrics[LIVE_RUNG_ELLIPSOID_COUNT];
  bool fitted;        /* false: the fog held nothing to fit (the model is then fog-free) */
  double max_error, mean_error; /* |delta tau| on the last measured view (NAN: none yet) */
  int rays;           /* that view's rays */
} live_rung;

/* r's model, pointing at r's own Gaussians and volumes (so take it from the copy in use). */
fog_model live_rung_model(const live_rung *r);
/* The model a rung is drawn and lit as: a quadric rung's fitted volumes, then the [fog]
 * quadric volumes beside the fogmap (the pass has no volumes beside a quadric model, so
 * they are its own), at most FOG_MAX_QUADRICS, in out; any other rung as it is (its
 * volumes beside are drawn beside it). */
fog_model live_rung_with_beside(const fog_model *rung, const fog_quadric *beside, int count,
                                fog_quadric out[FOG_MAX_QUADRICS]);

/* Fits the rung to the fogmap model's extinction sampled over its box (24 x 24 cells
 * across, 16 layers): homogeneous, the mean; height fog, fit_height's k, y0 and H (layers
 * that do not decay upwards fall back to the homogeneous mean); Gaussians and ellipsoids,
 * fit_rbfs's and fit_ellipsoids's moments of the k-means clusters (docs/fit.md). */
void live_rung_fit(const fog_model *fogmap, live_rung_kind kind, live_rung *out);

/* The error of out->model against the fogmap seen by cam (width x height pixels, depth the
 * surface distance per pixel, row 0 at the top, >= 1e29 for the sky) on the grid's pixel
 * centres. */
void live_rung_measure(const fog_model *fogmap, const camera *cam, int width, int height,
                       const float *depth, live_rung *out);

#endif
