/* `fogpipe fit`'s least-squares fits on the density (docs/fit.md): the reference fog's
 * extinction sampled on a grid of cell centres over the fit domain, and from those samples
 * the parameters of the cheap rungs of the model ladder (render/fog_models.def):
 *
 *   homogeneous  K = the mean of the samples (the least-squares constant)
 *   height       k e^{-(y - y0)/H}: log-linear least squares on the layers' means,
 *                each layer weighted by its mean squared (so empty layers count for nothing)
 *   rbf K        K Gaussians: weighted k-means of the samples (weights: the density),
 *                each cluster's mass, centroid and variance as one Gaussian's
 *   ellipsoid    one quadric volume: the axis-aligned ellipsoid of the samples' mass,
 *                centroid and variances (a uniform ellipsoid's variance is a^2/5)
 *   ellipsoids K K quadric volumes: the same per cluster of rbf K's k-means
 *   cylinders K  K upright cylinders: a cluster's horizontal and vertical variances
 *   oriented K   K ellipsoids in any orientation (general quadrics): a cluster's full
 *                covariance
 *
 * All on the CPU, in double, no GL. */
#ifndef FOGPIPE_APP_FIT_DENSITY_H
#define FOGPIPE_APP_FIT_DENSITY_H

#include <stdbool.h>

#include "render/fog_models.h"

typedef struct fit_samples {
  int n[3];               /* cells along x, y, z */
  double lo[3], hi[3];    /* the domain */
  double cell[3];         /* a cell's size */
  double *k;              /* extinction at the cell centres, x fastest, then y, then z */
} fit_samples;

/* Samples the model's pointwise extinction (fog_light_extinction_at) at the centres of a
 * grid over [lo, hi] with `max_side` cells along its longest side (the others in
 * proportion, at least 2); opaque fog (an infinite K) as 40 / the shortest cell side.
 * Non-zero with err set: out of memory (nothing allocated). */
int fit_samples_create(fit_samples *s, const fog_model *model, const double lo[3],
                       const double hi[3], int max_side, fog_error *err);
/* The same on a grid of n[a] cells along axis a (at least 2). */
int fit_samples_create_grid(fit_samples *s, const fog_model *model, const double lo[3],
                            const double hi[3], const int n[3], fog_error *err);
void fit_samples_destroy(fit_samples *s);
/* The centre of cell (i, j, l). */
void fit_sample_position(const fit_samples *s, int i, int j, int l, double p[3]);

/* The mean extinction. */
double fit_homogeneous(const fit_samples *s);
/* k at y0 = the domain's floor and H; false where the layers do not decay upwards (no
 * height fog holds them). */
bool fit_height(const fit_samples *s, double *k, double *y0, double *scale_height);
/* At most `count` Gaussians (fewer where fewer cells hold fog); returns how many. Non-zero
 * `count` with no fog at all gives 0. -1: out of memory. */
int fit_rbfs(const fit_samples *s, int count, fog_rbf *out);
/* At most `count` axis-aligned uniform ellipsoids (hard-edged quadric volumes), one per
 * cluster of the same k-means as fit_rbfs, each with its cluster's mass, centroid and
 * per-axis variances; returns how many (0: no fog, -1 out of memory). */
int fit_ellipsoids(const fit_samples *s, int count, fog_quadric *out);
/* The same with upright uniform cylinders (a cluster's horizontal and vertical variances
 * as a disc's and a height's). */
int fit_cylinders(const fit_samples *s, int count, fog_quadric *out);
/* The same with uniform ellipsoids in any orientation, general quadrics (A..J): each
 * cluster's full covariance, not only its per-axis variances (a tilted bank, a leaning
 * plume). */
int fit_oriented_ellipsoids(const fit_samples *s, int count, fog_quadric *out);
/* The ellipsoid: centre, semi-axes and density (edge 0: a hard edge); false without fog. */
bool fit_ellipsoid(const fit_samples *s, double centre[3], double radii[3], double *density);

#endif
