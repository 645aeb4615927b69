/* The rungs `fogpipe fit` tries (docs/fit.md): the ladder's models that can represent the
 * input, each fitted to the density samples (app/fit_density.h) and made into a scene
 * config. Internal to app/fit.c. */
#ifndef FOGPIPE_APP_FIT_RUNGS_H
#define FOGPIPE_APP_FIT_RUNGS_H

#include "app/fit.h"
#include "app/fit_density.h"
#include "app/fit_views.h"

/* Appends the rungs for this input, in ladder order: homogeneous, the classic linear
 * and exp2 factors (fitted on the views: view_sets of them, one per frame), height (where the
 * layers decay), an ellipsoid, Gaussian banks of 1 to 64, the fogmap at three bases x three
 * LOD factors (the input's fogmap or VDB; else the reference's density projected,
 * app/fit_fogmap.h, into a file of r->scratch), the volume (where the reference is one),
 * an analytic input as given. */
int fit_rungs_make(fit_result *r, const scene_config *input, const fog_model *reference,
                   const fit_samples *samples, const fit_views *views, int view_sets,
                   fog_error *err);

#endif
