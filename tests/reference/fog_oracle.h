/* The test reference of the fogmap model's optical depth (render/fog_field.h): written
 * apart from the integrators it checks, linked by the tests and never shipped in
 * fogpipe_render. */
#ifndef FOGPIPE_TESTS_REFERENCE_FOG_ORACLE_H
#define FOGPIPE_TESTS_REFERENCE_FOG_ORACLE_H

#include "render/fog_field.h"

/* Independent reference: adaptive Gauss-Kronrod G7K15 on f and g evaluated pointwise by
 * brute-force B-spline sums (truncated powers, no knot cells, no DDA), split at the box, at
 * y0, and at the ends of the B-spline supports enumerated in world coordinates (GK15 alone
 * misses jumps and kinks that fall between its nodes). Returns NAN when out of memory.
 * tolerance is absolute on the optical depth (1e-12 typical);
 * *error_estimate (may be NULL) receives the summed |K15 - G7| of accepted intervals. */
double fog_optical_depth_oracle(const fog_volume *volume, const transform_grid *grid,
                                const double camera[3], const double dir[3], double t_start,
                                double t_stop, double tolerance, double *error_estimate);

/* The fog's world box: x, z from the placement (corner origin_x, origin_z; W x H cells of
 * cell_size), y the profile's support; the oracle clips to it. */
void fog_box_oracle(const fog_volume *volume, double box_min[3], double box_max[3]);
/* K = extinction f(x, z) g(y) at world point p by the same brute-force B-spline sums;
 * 0 outside the box (on its faces: the value inside). */
double fog_extinction_oracle(const fog_volume *volume, const transform_grid *grid,
                             const double p[3]);

#endif
