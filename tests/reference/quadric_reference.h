/* The test reference of quadric fog volumes, in double: the pointwise extinction and the
 * optical depth of a ray, by adaptive Gauss-Kronrod quadrature on that pointwise extinction.
 * Written apart from the renderer it checks (it shares no code and no struct with it: it
 * never solves Q(t) = 0 or Q(t) = -edge along the ray in closed form, it finds where the
 * integrand breaks by bisection on the sign of Q); linked by the tests, never shipped.
 *
 * The model (world coordinates, Y up), for volumes i = 0 .. n-1, n <= 64:
 *   Q_i(x, y, z) = A x^2 + B y^2 + C z^2 + D xy + E yz + F xz + G x + H y + I z + J,
 *   K_i(p) = 0                               p outside the closed box [lo, hi],
 *          = density * clamp(-Q_i(p)/edge, 0, 1)        edge > 0,
 *          = density where Q_i(p) < 0, 0 where Q_i(p) >= 0   edge == 0,
 *   K(p)   = sum_i K_i(p)   (extinction per world unit),
 *   D      = int_{t0}^{t1} K(o + t d) dt.
 *
 * Accuracy: D to 1e-12 relative or 1e-13 absolute, whichever is larger (measured against
 * closed-form roots in long double on random scenes: within 3% of that allowance),
 * including grazing rays: Q is re-evaluated in double-double where its double rounding
 * could flip the side of a hard edge or move a soft ramp's value (near 0 and -edge), so a
 * ray tangent to a sphere gives 0 to ~1e-16, not the up to ~1e-8 that Q's double roundoff
 * (~1e-16 of its terms; a chord's ends move by its square root) would allow (measured with
 * double Q only: 6e-10 off on a 4e-6 chord). A code under test that solves the quadratic
 * in double has that error on near-grazing rays: keep such rays out of tight comparisons
 * or loosen the tolerance there. Where a ray crosses a box face, the reference puts the
 * face at the slab test's t (within an ulp of the point test's). Must not be built with
 * -ffast-math (the double-double sums rely on IEEE rounding).
 *
 * Every function returns NAN on bad arguments: n < 0 or n > QUADRIC_REFERENCE_MAX_VOLUMES,
 * a NULL pointer (v may be NULL when n == 0), a non-finite point, origin, direction or
 * coefficient, a zero direction, a box with !(lo < hi) or a non-finite face, density or
 * edge < 0 or not finite, t0 not finite or !(t0 <= t1) (t1 may be HUGE_VAL). */
#ifndef FOGPIPE_TESTS_REFERENCE_QUADRIC_REFERENCE_H
#define FOGPIPE_TESTS_REFERENCE_QUADRIC_REFERENCE_H

#include <stddef.h>

#define QUADRIC_REFERENCE_MAX_VOLUMES 64

typedef struct quadric_reference_volume {
  double q[10];          /* A, B, C, D, E, F, G, H, I, J of Q above */
  double lo[3], hi[3];   /* the clip box, closed, finite, lo < hi */
  double density, edge;  /* extinction per world unit inside, >= 0; soft-edge width, >= 0 */
} quadric_reference_volume;

/* K(p) = sum of the volumes' extinctions at world point p (on a box face: inside). */
double quadric_reference_extinction(const quadric_reference_volume *v, int n, const double p[3]);

/* D = int_0^length K(origin + t dir) dt, dir unit length (not checked: the integral is over
 * t), length >= 0 or HUGE_VAL (the ray then ends where it leaves the last box). */
double quadric_reference_optical_depth(const quadric_reference_volume *v, int n,
                                       const double origin[3], const double dir[3],
                                       double length);

/* D = int_{t0}^{t1} K(origin + t dir) dt (t0 finite, may be < 0; t1 >= t0, may be
 * HUGE_VAL). *error_estimate (may be NULL) receives the summed |K15 - G7| of the accepted
 * intervals (NAN with D). */
double quadric_reference_optical_depth_range(const quadric_reference_volume *v, int n,
                                             const double origin[3], const double dir[3],
                                             double t0, double t1, double *error_estimate);

/* Checks the reference against closed forms (spheres hard and soft, an ellipsoid turned
 * about each axis, a box-clipped cylinder, a double cone, a slab's soft edge, overlapping
 * volumes, tangent and grazing rays, bad arguments). Returns 0 when all pass, with a
 * summary (checks, worst error) in message[0 .. cap-1]; otherwise 1 with the first failure
 * there. message may be NULL. Prints nothing. */
int quadric_reference_self_test(char *message, size_t cap);

#endif
