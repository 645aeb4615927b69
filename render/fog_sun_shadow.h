/* The fog's shadow on itself: T_s(p) = exp(-int_0^inf K(p + s w_sun) ds), the sunlight
 * left at p after the fog between p and the sun (docs/light.md).
 *
 * Stored as an optical-depth volume in the sun's frame: axes e0, e1 across the sunlight
 * and e2 = -w_sun along it, a box fitted around the model's fog. Each column (i, j) is one
 * ray of sunlight, entering on the box's sun-side face; its samples k hold the exact
 * optical depth from there to the sample (the model's CPU twin, fog_models.h, walked
 * segment by segment so a column costs one walk): beyond the box on the sun side there is
 * no fog, so that is the optical depth towards the sun. Between samples the renderer
 * interpolates trilinearly: the only approximation, charted against resolution.
 *
 * Samples sit on the box's faces and edges (sample k of n at k / (n - 1) of the extent),
 * so the interpolation is exact at the faces. Models whose fog has no bound (homogeneous,
 * height, RBFs over a homogeneous base) get no volume: fog_sun_shadow_kind says how their
 * T_s is found instead. */
#ifndef FOGPIPE_RENDER_FOG_SUN_SHADOW_H
#define FOGPIPE_RENDER_FOG_SUN_SHADOW_H

#include <stdbool.h>

#include "render/fog_models.h"
#include "transform/fog_error.h"

/* How the fog pass finds T_s for a model (the shader variant's FOG_SUN_SHADOW). */
typedef enum fog_sun_shadow_kind {
  FOG_SUN_SHADOW_NONE = 0, /* T_s = 1: self-shadowing off */
  FOG_SUN_SHADOW_VOLUME,   /* the optical-depth volume below (bounded fog) */
  FOG_SUN_SHADOW_HEIGHT,   /* height fog, closed form: K H e^{-(y - y0)/H} / w_y */
  FOG_SUN_SHADOW_OPAQUE,   /* T_s = 0: the fog towards the sun never ends (a homogeneous
                              fog, a sun at or below the horizon over height fog) */
} fog_sun_shadow_kind;

/* The volume's resolution: columns across the sunlight and samples along it. */
typedef struct fog_sun_shadow_desc {
  int across; /* >= 2: columns per side */
  int along;  /* >= 2: samples per column */
} fog_sun_shadow_desc;

#define FOG_SUN_SHADOW_MAX_SIZE 512

typedef struct fog_sun_shadow {
  int size[3];          /* across, across, along */
  double origin[3];     /* world position of sample (0, 0, 0) */
  double axis[3][3];    /* unit e0, e1, e2 (= -w_sun) */
  double extent[3];     /* world length of the box along each axis (> 0) */
  double sun[3];        /* w_sun it was computed for */
  int level;            /* the fogmap: the pyramid level its columns walked */
  float *optical_depth; /* size[0] size[1] size[2], i fastest, then j, then k */
} fog_sun_shadow;

/* How a model's T_s is found for the unit direction sun_dir towards the sun: from the model
 * alone (quadrics beside it add their exact depth in fog_sun_optical_depth). NONE for a sun
 * wholly below the horizon (fog_sun_above_horizon 0), which lights nothing. */
fog_sun_shadow_kind fog_sun_shadow_kind_of(const fog_model *model, const double sun_dir[3]);

/* The model's own fog lies inside [lo, hi] (false: it has no bound; quadrics beside it are
 * not counted). For RBFs: 6 radii around each centre, where a Gaussian has fallen to e^-36. */
bool fog_model_bounds(const fog_model *model, double lo[3], double hi[3]);

/* Allocates the volume (size from desc, checked) for fog_sun_shadow_compute. */
int fog_sun_shadow_create(fog_sun_shadow *shadow, const fog_sun_shadow_desc *desc, fog_error *err);
void fog_sun_shadow_destroy(fog_sun_shadow *shadow);

/* Fits the box to the model's bounds in the frame of sun_dir (unit, towards the sun) and
 * fills every sample. The model must have bounds (fog_sun_shadow_kind_of gives VOLUME).
 * threads >= 1 share the columns. */
int fog_sun_shadow_compute(fog_sun_shadow *shadow, const fog_model *model, const double sun_dir[3],
                           int threads, fog_error *err);

/* Trilinear interpolation of the optical depth towards the sun at world point p, as the
 * GL lookup does it (the CPU twin): across the sunlight the volume fades to 0 in the half
 * sample outside its box (no fog there), along it the end samples hold. */
double fog_sun_shadow_depth_at(const fog_sun_shadow *shadow, const double p[3]);

/* The texture-coordinate map of the GL lookup: tex = M (p - origin) + offset, M row a =
 * e_a (n_a - 1) / (n_a extent_a), offset_a = 0.5 / n_a. */
void fog_sun_shadow_tex_map(const fog_sun_shadow *shadow, double m[3][3], double offset[3]);

/* The CPU twins of fog_light.glsl (render/fog_sun_light_cpu.c), in double. */
/* K at world point p as the light's samples read it: the fogmap's finest approximation
 * the draw reads (switching: A_J; the sum of details: A_0), zero outside its box; the volume
 * trilinear; the analytic models pointwise; plus the quadrics beside the model. */
double fog_light_extinction_at(const fog_model *model, const double p[3]);
/* Where the fog never ends (height fog, homogeneous fog, an RBF base) the light's span stops
 * at this optical depth from the camera: the rest weighs < e^-20 (2e-9). */
#define FOG_LIGHT_SPAN_DEPTH 20.0
/* The stretch [t0, t1] of the ray o + t d up to t_surface that holds fog, finite (the
 * lamps' span; fog_light_span in GLSL): the box, the volume's support, the quadrics' boxes,
 * from o to the RBFs' reach (6 radii), the endless models to FOG_LIGHT_SPAN_DEPTH, joined
 * with the boxes of the quadrics beside the model; false where it is empty. */
bool fog_light_span(const fog_model *model, const double o[3], const double d[3],
                    double t_surface, double *t0, double *t1);
/* The same for the sun's mean (fog_sun_span in GLSL), but RBFs without a base: the hull of
 * the chords of their cull spheres (fog_rbf_cull_radius) in front of o. */
bool fog_sun_span(const fog_model *model, const double o[3], const double d[3],
                  double t_surface, double *t0, double *t1);
/* Optical depth towards the sun at world point p for a model's kind (volume: for _VOLUME
 * the volume, for _HEIGHT only its sun). With _VOLUME and _HEIGHT the quadrics beside the
 * model add their exact depth towards volume->sun (the volume holds the model alone). */
double fog_sun_optical_depth(const fog_model *model, fog_sun_shadow_kind kind,
                             const fog_sun_shadow *volume, const double p[3]);
/* How the view ray's mean of T_s V is taken (docs/light.md): `steps` equal segments of
 * `nodes` samples, or with `pieces` (Perlin fog, the volume, the fogmap; not with quadrics
 * beside them) per piece of the exact walk with `nodes` Gauss nodes each (steps unused). */
/* The segments' pieces (fog_sun_mean_light, fog_light.glsl): one whose optical depth
 * exceeds this is cut where its estimated depth reaches it, at most steps cuts a ray (the
 * shader's constant too). */
#define FOG_SUN_PIECE_MAX_DEPTH 1.0

typedef struct fog_light_rule {
  int steps;   /* >= 1 */
  int nodes;   /* segments: 1 or 2; pieces: 1 .. FOG_PIECE_MAX_NODES */
  bool pieces;
  /* Segments: V, the sun's visibility, as the mean of this many equally spaced points of
   * the segment (V is 0 or 1 along a ray, with edges a segment cannot follow: the shafts
   * of thin obstacles alias into ghost copies at the nodes); 1 or less: V at the nodes
   * with T_s. Per piece: V linear between steps x shaft_samples equally spaced points of
   * the ray's fog span, the nodes reading it (at the nodes alone, pinned to the fog's
   * cells, the shadows' edges followed the cells' outlines). */
  int shaft_samples;
} fog_light_rule;

/* The tau K-weighted mean of T_s along the ray o + t d up to t_surface: `steps` equal
 * segments of the ray's fog span, each weighing e^{-D} (1 - e^{-dD}) (D the depth before it,
 * dD its own) and seeing T_s at `nodes` points, stopping past depth_limit; 1 where the ray
 * holds no fog. nodes 1: K and T_s at the midpoint, dD = K dt. nodes 2: at the two
 * Gauss-Legendre nodes m -+ dt/(2 sqrt 3), dD = dt (K_a + K_b)/2, the segment's T_s the
 * nodes' weighted by K e^{-d} (d the depth from the segment's start to the node, K linear
 * through the nodes): fourth order in dt where the midpoint is second. The sun's in-scatter
 * is then a L_sun p(theta) mean (1 - tau). */
double fog_sun_mean_transmittance(const fog_model *model, fog_sun_shadow_kind kind,
                                  const fog_sun_shadow *volume, fog_light_rule rule,
                                  double depth_limit, const double o[3], const double d[3],
                                  double t_surface);
/* The same mean of T_s V, V(p) in [0, 1] the sun's visibility past the scene at world point
 * p (the shadow map's twin or exact ray casts): light shafts. visible NULL: V = 1. */
typedef double (*fog_sun_visibility_fn)(const void *user, const double p[3]);
double fog_sun_mean_light(const fog_model *model, fog_sun_shadow_kind kind,
                          const fog_sun_shadow *volume, fog_light_rule rule,
                          double depth_limit,
                          const double o[3], const double d[3], double t_surface,
                          fog_sun_visibility_fn visible, const void *user);

#endif
