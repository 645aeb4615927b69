/* The test reference of single-scattered sunlight in fog, in double: optical depth, the sun's
 * transmittance and the sun in-scatter factor of a view ray, by adaptive Gauss-Kronrod
 * quadrature on a pointwise density. Written apart from the renderer's integrators it
 * checks (it shares the struct definitions and tests/reference/fog_oracle.c's pointwise
 * fogmap density, nothing else); linked by the tests, never shipped.
 *
 * The physics (K(p) >= 0 the extinction per world unit at world point p, Y up):
 *   D(o, d; t0, t1) = int_{t0}^{t1} K(o + t d) dt,       tau = exp(-D)
 *   T_s(p)          = exp(-int_0^inf K(p + s w_s) ds)     w_s: unit vector towards the sun
 *   S               = int_0^{t_surf} tau(o, u) K(o + u d) T_s(o + u d) du,
 *                     tau(o, u) = exp(-D(o, d; 0, u)),
 * and with T_s = 1 the identity S1 = int tau K du = 1 - tau(o, t_surf).
 *
 * tol is absolute everywhere; below ~1e-13 it is not met (the roundoff floor of each
 * Gauss-Kronrod interval is 1e-14 of its magnitude and wins). Every function returns NAN
 * on bad arguments (NULL medium or density, tol <= 0 or NaN), when out of memory, when a
 * breaks callback fails, or when the work limit (a runaway subdivision) is hit. */
#ifndef FOGPIPE_TESTS_REFERENCE_FOG_LIGHT_REFERENCE_H
#define FOGPIPE_TESTS_REFERENCE_FOG_LIGHT_REFERENCE_H

#include "render/fog_field.h"
#include "transform/transform.h"

typedef struct light_ref_medium light_ref_medium;

/* The extinction per world unit at world point p (>= 0). The callbacks get the medium so
 * that a medium can carry two pointers (user, user2) and still be copied by value. */
typedef double (*light_ref_density_fn)(const light_ref_medium *m, const double p[3]);
/* Writes the ray parameters t in (t0, t1) where K(o + t d) is not smooth (jumps, kinks:
 * adaptive quadrature cannot be trusted across one that falls between its nodes) into
 * out[0 .. capacity-1] and returns how many there are, which may exceed capacity (the
 * caller then calls again with room for all), or < 0 on failure. Order does not matter. */
typedef int (*light_ref_breaks_fn)(const light_ref_medium *m, const double o[3],
                                   const double d[3], double t0, double t1, double *out,
                                   int capacity);
/* Returns a t in (t0, t1] past which the ray's remaining integral of K is negligible (below
 * 1e-17 of the integral from t0): the integrals stop there. For unbounded media. */
typedef double (*light_ref_cut_fn)(const light_ref_medium *m, const double o[3],
                                   const double d[3], double t0, double t1);

struct light_ref_medium {
  light_ref_density_fn density;
  const void *user, *user2;
  /* K = 0 outside this box: every integral clips its ray to it first. Must be finite
   * (a ray to t = HUGE_VAL ends at the box). */
  double box_min[3], box_max[3];
  light_ref_breaks_fn breaks; /* may be NULL: K smooth along every ray inside the box */
  light_ref_cut_fn cut;       /* may be NULL */
};

/* D = int_{t0}^{t1} K(o + t d) dt, d unit length, t1 may be HUGE_VAL. */
double light_ref_optical_depth(const light_ref_medium *m, const double o[3], const double d[3],
                               double t0, double t1, double tol);
/* T_s(p) = exp(-D(p, sun_dir; 0, inf)); tol absolute on that optical depth. */
double light_ref_sun_transmittance(const light_ref_medium *m, const double p[3],
                                   const double sun_dir[3], double tol);
/* S of the view ray from o along unit d up to the surface at t_surf >= 0 (HUGE_VAL: sky),
 * S <= 1. With shadowed = 0, T_s = 1 and sun_dir is not read (may be NULL); shadowed needs
 * sun_dir (unit, towards the sun). *tau (if non-NULL) receives tau(o, t_surf) from a
 * separate optical-depth integral (NAN when S is). Cost: ~225 density evaluations per
 * outer interval, each break-free piece of the view ray at least one, times the sun ray's
 * ~15 per break-free piece when shadowed (~1e6 evaluations, ~0.1 s, on a 64 x 64 fogmap). */
double light_ref_sun_inscatter(const light_ref_medium *m, const double o[3], const double d[3],
                               double t_surf, const double sun_dir[3], int shadowed, double tol,
                               double *tau);

/* T_s at x through `medium` towards unit `sun` to `tol`, as a callback (user: this struct):
 * the exact sun light handed to the renderer's per-piece walks (fog_point_light_fn). */
typedef struct light_ref_sun_point {
  const light_ref_medium *medium;
  double sun[3];
  double tol;
} light_ref_sun_point;
double light_ref_sun_point_light(const void *user, const double x[3]);

/* The fogmap model K = extinction f(x, z) g(y) (render/fog_field.h): the density is
 * fog_extinction_oracle (brute-force B-spline sums), the box fog_box_oracle, the breaks the
 * knot lines of f in x and z, the knots of a B-spline profile and y0 of the exponential
 * one. v and g are referenced, not copied: they must outlive the medium. */
light_ref_medium light_ref_fogmap(const fog_volume *v, const transform_grid *g);

/* Height fog K = extinction exp(-(y - y0) / scale_height) (scale_height > 0), unbounded in
 * principle; here truncated to the box |x|, |z| <= 1e30, y in [y0 - 600 H, y0 + 700 H]
 * (K there is e^{600} and e^{-700} times its value at y0). Breaks at every scale height
 * (y = y0 + k H) so that each quadrature piece spans one e-fold; the cut stops a rising
 * ray 40 e-folds (ln 1e17 = 39.1) after its start: remaining/integral < e^{-40}. The
 * integrals are numerical; the closed form only sizes that cut. h must outlive the medium. */
typedef struct light_ref_height {
  double extinction, y0, scale_height;
} light_ref_height;
light_ref_medium light_ref_height_medium(const light_ref_height *h);

#endif
