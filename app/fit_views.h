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

#include "render/fog_light.h"
#include "render/fog_models.h"
#include "render/fog_sun_shadow.h"

#define FIT_VIEW_COUNT 9

typedef struct fit_views {
  int count;          /* rays that meet the domain */
  double (*origin)[3];
  double (*dir)[3];   /* unit */
  double *length;     /* from the camera to the domain's far side */
  double *reference;  /* the reference's tau along each */
  double *light;      /* lit inputs: the reference's in-scatter along each (fit_views_light) */
} fit_views;

/* Non-zero with err set: out of memory (nothing allocated). */
int fit_views_create(fit_views *v, const fog_model *reference, const double lo[3],
                     const double hi[3], int rays_per_side, fog_error *err);
void fit_views_destroy(fit_views *v);
/* The rung's max and mean |delta tau| against the reference. */
void fit_views_measure(const fit_views *v, const fog_model *rung, double *max_error,
                       double *mean_error);
/* A lit input's light (its [fog] albedo > 0): per ray the in-scattered luminance
 * I = (Y(L_amb) + a Y(L_sun) p(theta) Tbar_s) (1 - tau), Tbar_s the tau K-weighted mean of
 * the fog's shadow on itself along the ray (the renderer's CPU twin,
 * fog_sun_mean_transmittance, with the model's own optical-depth volume towards the sun
 * where it needs one), Y the mean of the three channels. */
typedef struct fit_light {
  fog_sun sun;
  double ambient[3];
  bool self_shadow;  /* [light] fog_self_shadow */
  int resolution;    /* the sun's volume: samples per axis */
  fog_light_rule rule; /* how the mean along a ray is taken */
} fit_light;

/* The reference's in-scatter on each ray (v->light, allocated here). Non-zero: out of
 * memory or a volume that cannot be made (err). */
int fit_views_light(fit_views *v, const fog_model *reference, const fit_light *light,
                    fog_error *err);
/* The rung's in-scatter error: max |I_rung - I_reference| over the rays, relative to the
 * reference's brightest ray. */
int fit_views_measure_light(const fit_views *v, const fog_model *rung, const fit_light *light,
                            double *relative_error, fog_error *err);

/* The classic fog factors on the rays of `count` views (frames): each view's camera is
 * their eye, as a classic fog's eye is the camera that draws it. Their parameters are
 * searched for the least max |delta tau| against the reference: the exp2 density around
 * the least-squares fit of (a L)^2 to the depth, the linear fog's start over [0, the
 * longest ray) and its length from 1/32 to 8 longest rays (a grid, then a pattern search). */
double fit_views_exp2(const fit_views *v, int count);
void fit_views_linear(const fit_views *v, int count, double *start, double *end);

/* Re-fits the amplitudes of n Gaussians (centres and radii kept) on the optical depth
 * along the rays of `count` views: weighted non-negative least squares of sum_i c_i D_i
 * against the reference's depth (capped at 10), each ray weighted by max(tau, 0.05)^2, so
 * that the fit follows tau where tau can still change. Non-zero: out of memory. */
int fit_views_rbf_amplitudes(const fit_views *v, int count, fog_rbf *g, int n);

/* View `index`'s camera: where it stands and the point it looks at. */
void fit_view_pose(const double lo[3], const double hi[3], int index, double position[3],
                   double target[3]);

#endif
