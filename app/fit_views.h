/* The views `fogpipe fit` measures a rung on (docs/fit.md): nine cameras around and inside
 * the fit domain (four around it at mid height, two above it looking down, three inside:
 * two looking across, one from the floor looking up), each a square 60-degree pinhole of
 * rays_per_side^2 rays. Every ray that meets the domain runs from its camera to where it
 * leaves the domain; the reference's transmittance along it is kept, and a rung's error is
 * max and mean |tau_rung - tau_reference| over those rays, each tau = e^{-depth} from the
 * models' exact CPU twins (fog_model_optical_depth, double). The classic factors (linear,
 * exp2) are measured from each view's camera as their eye. */
#ifndef FOGPIPE_APP_FIT_VIEWS_H
#define FOGPIPE_APP_FIT_VIEWS_H

#include "render/fog_models.h"

#define FIT_VIEW_COUNT 9

typedef struct fit_views {
  int count;          /* rays that meet the domain */
  double (*origin)[3];
  double (*dir)[3];   /* unit */
  double *length;     /* from the camera to the domain's far side */
  double *reference;  /* the reference's tau along each */
} fit_views;

/* Non-zero: out of memory (nothing allocated). */
int fit_views_create(fit_views *v, const fog_model *reference, const double lo[3],
                     const double hi[3], int rays_per_side);
void fit_views_destroy(fit_views *v);
/* The rung's max and mean |delta tau| against the reference. */
void fit_views_measure(const fit_views *v, const fog_model *rung, double *max_error,
                       double *mean_error);
/* The classic fog factors on the rays of `count` views (frames): each view's camera is
 * their eye, as a classic fog's eye is the camera that draws it. Their parameters are
 * searched for the least max |delta tau| against the reference: the exp2 density around
 * the least-squares fit of (a L)^2 to the depth, the linear fog's start and end over a grid
 * in (0, twice the longest ray]. */
double fit_views_exp2(const fit_views *v, int count);
void fit_views_linear(const fit_views *v, int count, double *start, double *end);

/* View `index`'s camera: where it stands and the point it looks at. */
void fit_view_pose(const double lo[3], const double hi[3], int index, double position[3],
                   double target[3]);

#endif
