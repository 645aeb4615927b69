/* Lamps in the fog: point and spot lights, single scattering (docs/light.md, Lamps).
 *
 * The in-scatter of one lamp (position s, intensity I, radius r) along a view ray
 * x(t) = o + t d over the fog's span [t0, t1] is
 *
 *   L = a I int tau(t) K(x) p(theta) T(x) S(x) / (|x - s|^2 + r^2) dt
 *
 * with tau the transmittance from the camera, T the transmittance from x to the lamp, p
 * Henyey-Greenstein with cos theta = d . (s - x)/|s - x| (the sun's convention) and S the
 * spot's cone (1 for a point lamp). The radius softens the inverse square so a lamp inside
 * the fog stays finite. With t_s the ray's closest point to the lamp, h its distance and
 * h' = sqrt(h^2 + r^2), the substitution t = t_s + h' tan phi turns dt / (|x - s|^2 + r^2)
 * into dphi / h' exactly (the angle variable of Sun et al. 2005, Fogshop eq. 14-17):
 * the 1/d^2 peak of the halo becomes a bounded integrand on [phi0, phi1], integrated with
 * Gauss-Legendre nodes on pieces of the angle (fog_lamp_method). That is what Fogshop's one
 * sample per Gaussian (its eq. 11) cannot do when a bright lamp sits close to the fog.
 *
 * tau(t) and T at a node: for the analytic models (homogeneous, height, RBFs) their closed
 * forms, exact; for the fogmap and the volume, tau from the optical depth tabulated once per
 * ray at the ends of depth_steps equal segments of the span (midpoint rule), interpolated
 * linearly between, and T by shadow_steps midpoint steps from the node to the lamp. The CPU
 * twin below takes every sample the shader takes, in double. */
#ifndef FOGPIPE_RENDER_FOG_LAMP_H
#define FOGPIPE_RENDER_FOG_LAMP_H

#include "render/fog_models.h"

#define FOG_MAX_LAMPS 16
/* With shadow cubes (or a visibility callback), a piece of the angle integral that a
 * shadow's edge crosses is cut there: V is known at the piece's ends and its 4 nodes; an
 * edge between two of those on different sides of V = 1/2 is found by
 * FOG_LAMP_EDGE_BISECTIONS bisections, and the rest of the integrand (smooth) is integrated
 * over the lit stretches as the cubic through its 4 nodes (fog_lamp_lagrange_integrals):
 * no more samples of the expensive integrand than an uncut piece. */
#define FOG_LAMP_EDGE_BISECTIONS 10
/* The optical-depth table's most segments (a GLSL array per pixel). */
#define FOG_LAMP_MAX_DEPTH_STEPS 64

typedef enum fog_lamp_kind {
  FOG_LAMP_POINT = 0, /* all round */
  FOG_LAMP_SPOT,      /* a cone round axis, with a smooth edge */
} fog_lamp_kind;

typedef struct fog_lamp {
  fog_lamp_kind kind;
  double position[3];  /* world */
  double intensity[3]; /* radiant intensity per channel (colour x intensity), linear */
  double radius;       /* > 0: the falloff is 1 / (d^2 + radius^2) */
  double axis[3];      /* FOG_LAMP_SPOT: unit, the direction it shines */
  /* FOG_LAMP_SPOT: cosines of the cone's half-angles, cos_inner >= cos_outer +
   * FOG_SPOT_MIN_COSINE_GAP: full light inside the inner cone, none outside the outer,
   * smoothstep between. */
  double cos_inner, cos_outer;
} fog_lamp;

/* Which integral: ours (above), or Fogshop's approximation for Gaussian fog (Zhou et al.
 * 2007, eq. 11): each Gaussian's share is its own optical depth along the ray (erf) times
 * the rest of the integrand (tau, the phase, T, the cone, the falloff) taken once, at the
 * projection of its centre on the ray, with tau and T the exact closed forms; the
 * homogeneous base's airlight as Sun et al.'s, in the base alone (the Gaussians do not
 * shadow it: no shafts), here by the angle integral. FOG_MODEL_RBF only: the bench's and the
 * tests' comparison. */
typedef enum fog_lamp_integral {
  FOG_LAMP_ANGLE = 0,
  FOG_LAMP_FOGSHOP,
  FOG_LAMP_MARCH, /* uniform ray marching: march_steps midpoint samples of the span, tau
                     summed along them, T as the angle integral's (the bench's baseline) */
} fog_lamp_integral;

/* How the in-scatter integral is taken (see above); every count >= 1. */
typedef struct fog_lamp_method {
  fog_lamp_integral integral;
  /* The integral's pieces, 4 Gauss-Legendre nodes each in phi: the union of angle_pieces
   * equal steps of the angle (resolving the halo near the lamp) and span_pieces equal steps
   * of the ray's fog span (resolving the fog far from it, where phi compresses t). */
  int angle_pieces;
  int span_pieces;
  int depth_steps;  /* tau's table (<= FOG_LAMP_MAX_DEPTH_STEPS) */
  int shadow_steps; /* T's march towards the lamp */
  int march_steps;  /* FOG_LAMP_MARCH: samples along the span (>= 1) */
} fog_lamp_method;

/* The product's defaults ([light] lamp_angle_pieces, lamp_span_pieces, lamp_depth_steps,
 * lamp_shadow_steps). */
#define FOG_LAMP_ANGLE_PIECES 8
#define FOG_LAMP_SPAN_PIECES 8
#define FOG_LAMP_DEPTH_STEPS 32
#define FOG_LAMP_SHADOW_STEPS 8

/* The least cos_inner - cos_outer of a spot: the shaders take the cosines as float, in
 * which 1 - cos of a 0.01 degree cone is 0 (the beam vanished on the GPU where the CPU drew
 * it) and a 0.05 degree one is a few ulps (its edge 17 % off); at 1e-5 (an outer
 * half-angle of 0.26 degrees about an inner 0) the float cosine's rounding is 1 % of the
 * ramp. */
#define FOG_SPOT_MIN_COSINE_GAP 1e-5

typedef struct fog_lamps {
  fog_lamp lamp[FOG_MAX_LAMPS];
  int count; /* 0: no lamps */
  fog_lamp_method method;
} fog_lamps;

/* The same lamps: the count, and each lamp's kind, position, intensity, radius and cone
 * (field by field, not the bytes; the method is not compared). */
bool fog_lamps_equal(const fog_lamps *a, const fog_lamps *b);
/* Whether a spot is among the lamps (its pieces are cut at its cones: the pass's variant
 * and its loop bound ask the same). */
bool fog_lamps_have_spot(const fog_lamps *lamps);

/* The lamps as the shaders take them (fog_lamps.glsl, scene_surface_fs.glsl): positions
 * relative to the camera (subtracted in double), intensity x scale, the spot's axis with
 * w 1 (0: a point lamp), and (cos_outer, 1/(cos_inner - cos_outer), radius^2). */
typedef struct fog_lamp_uniforms {
  float position[FOG_MAX_LAMPS][3], intensity[FOG_MAX_LAMPS][3], axis[FOG_MAX_LAMPS][4],
      cone[FOG_MAX_LAMPS][3];
} fog_lamp_uniforms;
void fog_lamps_pack(const fog_lamps *lamps, const double camera[3], double intensity_scale,
                    fog_lamp_uniforms *out);

/* S: the spot's cone at world point x (1 for a point lamp). */
double fog_lamp_spot(const fog_lamp *lamp, const double x[3]);


/* The CPU twin of fog_lamps.glsl: the lamps' in-scattered radiance of the ray o + t d
 * (d unit) up to t_surface, per channel, for albedo a and Henyey-Greenstein g. */
void fog_lamps_inscatter(const fog_model *model, const fog_lamps *lamps, double albedo,
                         double phase_g, const double o[3], const double d[3],
                         double t_surface, double out[3]);

/* V_i(x) in [0, 1]: lamp i's visibility past the scene's surfaces at world point x (the
 * shadow cubes' twin, or exact ray casts). */
typedef double (*fog_lamp_visibility_fn)(const void *user, int lamp, const double x[3]);
/* The same with each lamp's V in the integrand (its shafts); visible NULL: V = 1. Fogshop's
 * approximation takes no V (the paper's airlight has none). */
void fog_lamps_inscatter_shadowed(const fog_model *model, const fog_lamps *lamps, double albedo,
                                  double phase_g, const double o[3], const double d[3],
                                  double t_surface, fog_lamp_visibility_fn visible,
                                  const void *user, double out[3]);

/* The integrals over [u0, u1] of the Lagrange polynomials through the 4 Gauss-Legendre nodes
 * on [-1, 1] (over [-1, 1]: the weights). */
void fog_lamp_lagrange_integrals(double u0, double u1, double out[4]);

/* One lamp's share, without the factor a I (per unit intensity): for tests and the bench. */
double fog_lamp_inscatter_unit(const fog_model *model, const fog_lamp *lamp,
                               const fog_lamp_method *method, double phase_g,
                               const double o[3], const double d[3], double t_surface);

#endif
