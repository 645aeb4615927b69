/* The 2.5D wavelet-fogmap fog model K(x, y, z) = extinction * f(x, z) * g(y)
 * (Giroud & Biri 2010, docs/integral.md), its exact optical depth along a ray (CPU, double;
 * fog_integral_cpu.c), an independent adaptive-quadrature oracle (tests/reference/fog_oracle.h, outside the
 * shipped library) and the
 * LOD-by-distance variants. The GLSL twin is render/shaders/fog_integral.glsl: same
 * function names, same equation references, line by line.
 *
 * Placement (world: Y up, the map spans X and Z). f is a transform_grid in fine-fogmap
 * sample units (u, v) (see transform/transform.h). The fog's box in (u, v) is
 * [-1/2, W-1/2] x [-1/2, H-1/2] for a W x H fogmap; its corner (u, v) = (-1/2, -1/2) sits
 * at world (origin_x, origin_z) and one fine sample is cell_size world units:
 *     u = (X - origin_x) / cell_size - 1/2,   v = (Z - origin_z) / cell_size - 1/2.
 * Vertically the box spans the profile's support [y_bottom, y_top] (fog_profile_extent).
 *
 * Knots (where the piecewise polynomial breaks): with x = (u - origin_u)/spacing the
 * centred B-spline phi_d(x - i) breaks at x - i = +-(d+1)/2, ..., so the knot lines of a
 * degree-d grid are the integers for odd d and the half-integers for even d. Knot cell c
 * is [c - 1/2, c + 1/2] (even d) or [c, c + 1] (odd d); inside it the d+1 coefficients
 * c - d/2 ... c - d/2 + d (integer division) are non-zero, and along a ray f is a
 * polynomial in t of degree <= 2d (degree d in each of x and z, both linear in t).
 *
 * Vertical profiles g(y) (all >= 0; zero outside [y_bottom, y_top]):
 *   FOG_PROFILE_SLAB        g = 1 on [y_floor, y_top].
 *   FOG_PROFILE_EXPONENTIAL g = 1 on [y_floor, y0], exp(-(y - y0)/scale_height) on
 *                           [y0, y_top] (ground fog with an exponential top; y_top cuts
 *                           the tail so the box is finite: choose y_top - y0 ~ 10 H).
 *   FOG_PROFILE_BSPLINE     g = sum_k b_k phi_p((y - origin)/spacing - k), centred
 *                           B-spline of degree p = 0..3 (e.g. fitted from a VDB), support
 *                           [origin - (p+1)/2 spacing, origin + (count-1+(p+1)/2) spacing].
 *
 * Exactness (docs/integral.md): the ray is cut at every knot line of f (2D DDA, Amanatides & Woo
 * 1987), at every knot of a B-spline profile, at y0 of the exponential profile, and at
 * the box. On each piece the integrand is a polynomial of degree 2d + p in t, integrated
 * exactly by Gauss-Legendre with d + p/2 + 1 nodes; or p(t) e^{a t} with p of degree 2d,
 * integrated in closed form (fog_exp_moments_closed) for |a| * half_length >= 1 and by
 * the moments' power series (fog_exp_moments_series) below, where the closed form cancels
 * (8-node Gauss-Legendre, fog_exp_moments_quadrature, is the tested alternative: as
 * accurate there, but it needs f at 8 nodes instead of 2d+1: 3x the fetches on the GPU).
 *
 * Camera-relative: every function takes the camera position and subtracts it from the
 * fog's placement first, in double, so a 50 km ray keeps its precision (and the GPU gets
 * small float numbers). Ray parameters t are world distances along a unit direction. */
#ifndef FOGPIPE_RENDER_FOG_FIELD_H
#define FOGPIPE_RENDER_FOG_FIELD_H

#include <stdbool.h>

#include "transform/transform.h"

#define FOG_PROFILE_MAX_COEFFICIENTS 64
/* Below this |a| * half_length the exponential moments switch from the closed form to
 * their power series (both sides agree to ~1e-15 there; test_integral_exp_switch.c). */
#define FOG_EXP_SWITCH 1.0

typedef enum fog_profile_kind {
  FOG_PROFILE_SLAB = 0,
  FOG_PROFILE_EXPONENTIAL,
  FOG_PROFILE_BSPLINE,
} fog_profile_kind;

typedef struct fog_profile {
  fog_profile_kind kind;
  double y_floor, y_top;   /* slab and exponential: vertical extent */
  double y0, scale_height; /* exponential: start of the decay, its scale height H > 0 */
  /* B-spline: count <= FOG_PROFILE_MAX_COEFFICIENTS coefficients b_k of degree 0..3. */
  int count, degree;
  const double *coefficients;
  double origin, spacing;
} fog_profile;

/* Where the fog sits and how thick it is; the grid f is passed separately so the LOD
 * variants can integrate several grids over the same box. */
typedef struct fog_volume {
  int map_width, map_height; /* fine fogmap size W x H: the box [-1/2, W-1/2] x [-1/2, H-1/2] */
  double origin_x, origin_z; /* world position of the box corner (u, v) = (-1/2, -1/2) */
  double cell_size;          /* world size of one fine sample: > 0 */
  double extinction;         /* extinction per world unit for f = g = 1: >= 0 (0: no fog) */
  fog_profile profile;
} fog_volume;

/* LOD by distance (docs/integral.md). approx[0..levels] are A_0 .. A_J, detail[0..levels-1] are
 * the deconstructed detail grids D_1 .. D_J (detail[l-1] is D_l), all over the same box.
 * d_l = ||OP|| mu^l, where ||OP|| is the distance to the first surface or, when the ray
 * leaves the fog's box first, to the box exit. */
typedef enum fog_lod_method {
  FOG_LOD_SUM_OF_DETAILS = 0, /* paper: A_0 on [0, ||OP||] + D_l on [0, d_l] */
  FOG_LOD_SWITCH,             /* ours: A_l on (d_{l+1}, d_l], A_J on [0, d_J], A_0 beyond d_1 */
} fog_lod_method;

/* The one level cap: pyramids of at most J = FOG_MAX_LEVELS levels, everywhere (the GL fog
 * pass holds the 2J + 1 grids in FOG_PASS_MAX_GRIDS slots; configs, the pipeline and the
 * renderer clamp to it; the GLSL gets it from fog_constants.glsl). */
#define FOG_MAX_LEVELS 7

/* A view of a pyramid for integration: approx[0..J], detail[0..J-1] = D_1..D_J. */
typedef struct fog_lod {
  int levels; /* J >= 0 */
  const transform_grid *approx;
  const transform_grid *detail;
  double mu; /* in [0, 1] */
} fog_lod;

/* One pyramid's grids, owned, indexed as the transform makes them (its density pyramid,
 * transform_density_pyramid: levels clamped at 0, A_J the fogmap itself): approx[l] = A_l
 * for l = 0..levels, detail[l] = D_l for l = 1..levels
 * (detail[0] unused; none at all unless has_details: approximation switching does not
 * read them). The simulation's steps, a fogmap's or a VDB frame's pyramid alike. */
typedef struct fog_pyramid {
  int levels, degree;
  bool has_details;
  transform_grid approx[FOG_MAX_LEVELS + 1];
  transform_grid detail[FOG_MAX_LEVELS + 1];
} fog_pyramid;

/* The pyramid of a density map (width x height samples, rows of width) in the B-spline basis
 * of degree (0..2) with `levels` levels (0..FOG_MAX_LEVELS, and at most what the map's size
 * allows: transform_max_levels): the approximations A_0..A_J and the deconstructed details
 * D_1..D_J as grids (transform/). Errors in err (sizes, memory); *pyramid is then empty. */
int fog_pyramid_create(fog_pyramid *pyramid, const float *density, int width, int height,
                       int degree, int levels, transform_boundary boundary, fog_error *err);
void fog_pyramid_destroy(fog_pyramid *pyramid);
/* The pyramid as a fog_lod (detail from D_1) at LOD parameter mu. */
fog_lod fog_pyramid_lod(const fog_pyramid *pyramid, double mu);

/* The vertical extent [y_bottom, y_top] of the profile's support. */
void fog_profile_extent(const fog_profile *profile, double *y_bottom, double *y_top);
/* The fog's box in world coordinates. */
void fog_volume_box(const fog_volume *volume, double box_min[3], double box_max[3]);

/* Ray against the fog's box (camera-relative; dir need not be axis-free, zeros allowed):
 * returns 1 and the parameter interval [*t_enter, *t_exit] (t_enter may be negative when
 * the camera is inside), or 0 when the line misses the box. */
/* Slab test (Kay & Kajiya) of the line t dir against the box [lo, hi], both relative to the
 * line's origin; dir components may be 0. Non-zero when the line meets the box, with the
 * parameters of entry and exit (either may be negative). */
int fog_slab_entry_exit(const double lo[3], const double hi[3], const double dir[3],
                        double *t_enter, double *t_exit);
int fog_box_entry_exit(const fog_volume *volume, const double camera[3], const double dir[3],
                       double *t_enter, double *t_exit);

/* The exact optical depth int_{t_start}^{t_stop} K(camera + t dir) dt (dir unit length),
 * clipped to the fog's box. t_start >= 0 normally 0; t_stop the distance to the first
 * surface (HUGE_VAL when there is none). */
double fog_optical_depth(const fog_volume *volume, const transform_grid *grid,
                         const double camera[3], const double dir[3], double t_start,
                         double t_stop);

/* The same with empty-space skipping (render/fog_occupancy.h): blocks of `occupancy`
 * (built from `grid`) whose bound is <= skip_below are jumped over. skip_below = 0: the
 * same value bit for bit (only blocks of exact zeros are skipped); above 0 the result
 * moves by at most skip_below * extinction * g_max * (length in the box). */
struct fog_occupancy;
double fog_optical_depth_skipping(const fog_volume *volume, const transform_grid *grid,
                                  const struct fog_occupancy *occupancy, float skip_below,
                                  const double camera[3], const double dir[3], double t_start,
                                  double t_stop);

/* The running optical depth from origin at t_k = k step, k = 0..n-1 (out[0] = 0): one walk
 * along the ray, its sum read at each t_k (what n calls of fog_optical_depth would give, at
 * the cost of one). */
void fog_optical_depth_samples(const fog_volume *volume, const transform_grid *grid,
                               const double origin[3], const double dir[3], double step, int n,
                               double out[]);

/* K at world point p: extinction f g inside the box, 0 outside (the marcher's integrand). */
double fog_extinction_point(const fog_volume *volume, const transform_grid *grid,
                            const double p[3]);

/* ||OP|| of the LOD rule: min(t_surface, box exit), 0 when the ray misses the box. */
double fog_lod_ray_length(const fog_volume *volume, const double camera[3], const double dir[3],
                          double t_surface);
/* Optical depth with LOD by distance, either method (same value for the same mu when
 * A_l = A_{l-1} + D_l holds exactly). */
double fog_optical_depth_lod(const fog_volume *volume, const fog_lod *lod, fog_lod_method method,
                             const double camera[3], const double dir[3], double t_surface);

/* Uniform ray marching, the alternative integrator the benchmark compares against (twin of
 * fog_optical_depth_march in fog_integral.glsl): the box part of [t_start, t_stop] cut into
 * `steps` equal steps, K sampled at t0 + (i + jitter) dt (jitter 0.5: midpoint rule). */
double fog_optical_depth_march(const fog_volume *volume, const transform_grid *grid,
                               const double camera[3], const double dir[3], double t_start,
                               double t_stop, int steps, double jitter);
/* LOD by distance with the marcher on every grid segment (as the shader's march variant). */
double fog_optical_depth_lod_march(const fog_volume *volume, const fog_lod *lod,
                                   fog_lod_method method, const double camera[3],
                                   const double dir[3], double t_surface, int steps,
                                   double jitter);
/* The shader's per-pixel jitter in [0, 1) for GL pixel (px, py_gl) (row 0 at the BOTTOM)
 * and frame: the same integer hash on both sides. */
double fog_march_jitter(unsigned px, unsigned py_gl, unsigned frame);

/* tau = exp(-optical depth), a depth below 0 taken as 0 (no fog: signed bands cancelling
 * below it make no light), and the blend L = tau L(P) + L_fog (1 - tau) (Giroud & Biri
 * eq. 4), per colour channel. */
double fog_transmittance(double optical_depth);
void fog_blend(double tau, const double surface[3], const double fog_colour[3], double out[3]);

/* The exponential moments J_k = int_{-1}^{1} s^k exp(c0 + b s) ds, k = 0..n (n <= 7), in
 * closed form (recurrence J_k = [s^k e^{c0+bs}/b] - k/b J_{k-1}, which cancels as b -> 0),
 * by the power series e^{c0} sum_j b^j/j! int s^{k+j} (20 terms: exact to ~1e-19 for
 * |b| < 1, no cancellation) and by 8-node Gauss-Legendre (O(b^{16-n}/(16-n)!));
 * fog_exp_moments picks closed form or series by |b| against FOG_EXP_SWITCH. */
void fog_exp_moments_closed(double c0, double b, int n, double moments[]);
void fog_exp_moments_series(double c0, double b, int n, double moments[]);
void fog_exp_moments_quadrature(double c0, double b, int n, double moments[]);
void fog_exp_moments(double c0, double b, int n, double moments[]);

#endif
