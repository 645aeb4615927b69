/* The GL fog pass: per pixel, the exact optical depth of the 2.5D fogmap model
 * (render/fog_field.h; shaders fog_integral.glsl + fog_pass_fs.glsl) with LOD by distance,
 * and the blend L = tau L(P) + L_fog (1 - tau) (Giroud & Biri eq. 4).
 *
 * Lifecycle (needs a current GL 4.3+ context, render/gl_context.h):
 *   fog_pass_create()                       compiles the default variant; every other
 *                                           variant (one per draw configuration: fetch,
 *                                           integrator, degree, profile, LOD, resolution)
 *                                           on its first draw, then kept (JIT ~0.1-0.6 s
 *                                           on llvmpipe: warm up before timing)
 *   fog_pass_upload_grid() / _upload_lod()  coefficient grids -> R32F textures; call again
 *                                           when they change (same size: glTexSubImage2D
 *                                           into the existing texture, no reallocation)
 *   fog_pass_draw()                         per frame; never allocates (after the first
 *                                           draw of a variant)
 *   fog_pass_destroy()
 *
 * Drawing: bind a framebuffer whose draw buffer 0 takes the composited colour (RGBA16F or
 * RGBA32F), draw buffer 1 the transmittance tau (R32F) and, if it has one, draw buffer 2 the
 * in-scattered radiance (RGBA32F: colour = tau surface + in-scatter), e.g. a gl_target with
 * color_formats {GL_RGBA32F, GL_R32F, GL_RGBA32F}; fog_pass_draw sets the viewport to width x height
 * and draws one full-screen triangle. Inputs: the surface colour texture (linear RGBA) and
 * the surface DISTANCE texture (R32F: Euclidean distance from the camera along the pixel's
 * ray to the first surface; anything >= 1e29, e.g. SCENE_SKY_DISTANCE, means none). Both
 * are read with texelFetch at the same pixel, so they must be width x height.
 *
 * Grid slots: A_l in slot l (l = 0..J), D_l in slot J + l (l = 1..J); a single grid is
 * slot 0 with levels = 0. At most FOG_PASS_MAX_GRIDS slots (J <= FOG_MAX_LEVELS). All slots
 * of one draw share the degree of slot 0. A draw needs only the slots its LOD method reads:
 * switching reads slots 0..J, the sum of details slots 0 and J+1..2J. LOD draws read the
 * slots copied into one 2D array texture (refreshed on the first LOD draw after an upload).
 * Each sampler has a texture unit of its own (fog_pass.c, enum fog_pass_unit). */
#ifndef FOGPIPE_RENDER_FOG_PASS_H
#define FOGPIPE_RENDER_FOG_PASS_H

#include <GL/glcorearb.h>

#include "render/camera.h"
#include "render/fog_field.h"
#include "render/fog_lamp.h"
#include "render/fog_light.h"
#include "render/fog_models.h"
#include "render/fog_sun_shadow.h"
#include "render/lamp_shadow_map.h"
#include "render/sun_shadow_map.h"
#include "transform/fog_error.h"
#include "transform/transform.h"

#define FOG_PASS_MAX_GRIDS 16
_Static_assert(2 * FOG_MAX_LEVELS + 1 <= FOG_PASS_MAX_GRIDS,
               "a pyramid of FOG_MAX_LEVELS levels needs 2J + 1 grid slots");

typedef enum fog_fetch {
  FOG_FETCH_MANUAL = 0, /* texelFetch + the B-spline cell weights in float: exact */
  FOG_FETCH_HARDWARE,   /* GL_LINEAR filtering (degree 1; degree 2 by two fetches per
                           axis); weights quantised by the hardware */
} fog_fetch;

typedef enum fog_integrator {
  FOG_INTEGRATOR_EXACT = 0, /* the knot-cell walk with Gauss-Legendre per piece; the
                               analytic models' closed forms */
  FOG_INTEGRATOR_MARCH,     /* uniform ray marching, march_steps midpoint samples (analytic
                               models: to the surface, or for the sky to where the fog ends,
                               fog_models.glsl) */
  FOG_INTEGRATOR_FROXEL,    /* the engines' froxel grid (params.froxel, docs/light.md): a
                               benchmark baseline, the sun and the ambient light only */
} fog_integrator;

/* FOG_INTEGRATOR_FROXEL's view-frustum grid (Wronski 2014, Hillaire 2015): columns x rows
 * cells across the image, `slices` along each cell's centre ray, exponentially spaced
 * between near_distance and far_distance (distances along the ray). One sample of the fog
 * and its light per cell (at the slice's middle), accumulated front to back with the
 * energy-conserving slice integral, then looked up per pixel (trilinear). No fog before
 * near_distance or past far_distance. */
typedef struct fog_froxel_grid {
  int columns, rows, slices;
  double near_distance, far_distance; /* 0 < near < far */
} fog_froxel_grid;

/* Empty-space skipping of the fogmap's exact walk (render/fog_occupancy.h). */
typedef enum fog_skip {
  FOG_SKIP_EMPTY = 0, /* jump blocks of exact zeros: the same integral bit for bit; only
                         where at least FOG_SKIP_MIN_EMPTY_SHARE of the grids' blocks are
                         empty (below that, the walk without skipping is faster) */
  FOG_SKIP_BELOW,     /* jump blocks whose bound of |f| is <= skip_below (each of the J + 1
                         grids the sum of details adds: <= skip_below / (J + 1)): |delta
                         optical depth| <= skip_below * extinction * g_max * (ray length in
                         the box); the volume: its voxels' values as uploaded, g_max 1 */
  FOG_SKIP_NONE,      /* walk every knot cell (the bench's comparison) */
} fog_skip;

/* How the exact walks run: settings that trade nothing or a stated bound for speed. */
typedef struct fog_walk_settings {
  /* Early termination at opacity: the exact walks (the fogmap's single grid and LOD
   * switching, the volume's DDA) and the shadowed light's mean stop once the transmittance
   * falls below this, i.e. once the optical depth passes t_max = -ln(cutoff). The pixel then
   * reports tau_partial <= cutoff where the whole ray gives tau <= tau_partial, so
   * |delta tau| <= cutoff, and the blend L = tau L(P) + (1 - tau) L_fog moves by at most
   * cutoff * max |L(P) - L_fog| (docs/integral.md, Early termination). 0: never stop (whole
   * rays). The product's default is FOG_PASS_TRANSMITTANCE_CUTOFF ([render]
   * transmittance_cutoff). The sum of details (signed bands) and the marchers always
   * integrate whole rays. */
  double transmittance_cutoff;
  fog_skip skip;             /* FOG_MODEL_FOGMAP's exact walk */
  float skip_below;          /* FOG_SKIP_BELOW: the bound of |f| (grid units) below which a
                                block counts as empty; >= 0 */
} fog_walk_settings;

/* The benches' and the preview's marching sample count (fog_pass_params.march_steps). */
#define FOG_PASS_MARCH_STEPS 64
/* fog_pass_params.shaft_samples: at most (a variant's key holds it in 5 bits) */
#define FOG_PASS_MAX_SHAFT_SAMPLES 16

typedef struct fog_pass_params {
  fog_model_kind model;      /* FOG_MODEL_FOGMAP (default) or an analytic model */
  double model_extinction;   /* FOG_MODEL_HOMOGENEOUS / _HEIGHT: K (at y0), per world unit */
  double model_y0, model_scale_height; /* FOG_MODEL_HEIGHT: K e^{-(y - y0)/H}; H > 0 */
  /* FOG_MODEL_LINEAR: the factor's distances from the camera, 0 <= start < end (FOG_MODEL_EXP2
   * reads model_extinction, the factor's density). */
  double model_fog_start, model_fog_end;
  /* FOG_MODEL_RBF: model_extinction is the base; these Gaussians (at most FOG_MAX_RBFS,
   * radius > 0, density >= 0) are read at each draw. */
  const fog_rbf *model_rbfs;
  int model_rbf_count;
  /* FOG_MODEL_QUADRIC: these volumes (at most FOG_MAX_QUADRICS; density >= 0, edge >= 0, a
   * box lo <= hi), read at each draw. Any other model: volumes beside its fog, their
   * extinction added (fog_model_quadrics_beside: the depth, the light, the lamps; the sun's
   * mean by segments, not per piece). */
  const fog_quadric *model_quadrics;
  int model_quadric_count;
  /* FOG_MODEL_PERLIN: the octaves (uploaded with fog_pass_upload_perlin), the animation time
   * in seconds and the integral; model_extinction, model_y0 and model_scale_height are its
   * height fog's. FOG_MODEL_QUADRIC (or quadrics beside the Perlin fog) with noise: the
   * octaves and the time of the volumes' turbulence (required: NULL is refused). */
  const fog_perlin *model_perlin;
  double model_time;
  fog_perlin_integral model_perlin_integral;
  /* FOG_MODEL_VOLUME (the grid of fog_pass_upload_grid3d) with FOG_INTEGRATOR_MARCH: the
   * step in world units (> 0); the exact integrator needs none. Its exact walk reads the
   * cells' corners (FOG_FETCH_MANUAL: exact on any GL) or samples with the hardware's
   * trilinear filter (FOG_FETCH_HARDWARE: float weights on llvmpipe, 8-bit on GPUs); the
   * march always samples with the filter. */
  double model_grid3d_step;
  const fog_volume *volume;  /* FOG_MODEL_FOGMAP: placement and profile (required) */
  int levels;                /* J: slots 0..J approximations, J+1..2J details; 0: one grid */
  fog_lod_method lod_method;
  double mu;                 /* LOD parameter in [0, 1]; levels = 0 ignores it */
  float fog_colour[3];       /* L_fog, linear: the ambient in-scatter L_amb */
  /* Sunlight scattered in the fog (render/fog_light.h): albedo 0 is eq. 4 exactly. A
   * zero-initialised sun has albedo 0. */
  fog_sun sun;
  /* Point and spot lights (render/fog_lamp.h), in-scattered with the sun's albedo and
   * phase function; count 0: none. */
  fog_lamps lamps;
  /* The fog's shadow on itself, T_s (render/fog_sun_shadow.h, fog_light.glsl): how it is
   * found for this model and sun (fog_sun_shadow_kind_of; FOG_SUN_SHADOW_NONE: T_s = 1, the
   * unshadowed identity); _VOLUME reads the volume of fog_pass_upload_sun_shadow. The view
   * ray's tau K-weighted mean of T_s is taken over shadow_steps segments (>= 1 unless
   * NONE). */
  fog_sun_shadow_kind self_shadow;
  int shadow_steps;
  int shadow_nodes; /* samples per segment: 1 the midpoint, 2 two Gauss-Legendre nodes
                       (fog_sun_mean_transmittance); per piece with shadow_pieces */
  bool shadow_pieces; /* FOG_MODEL_PERLIN, _VOLUME, _FOGMAP: the mean per piece of the exact walk */
  int shaft_samples;  /* with shafts, by segments: V's mean over this many points a segment
                         (fog_light_rule.shaft_samples), 1 .. FOG_PASS_MAX_SHAFT_SAMPLES */
  /* Optional (0: none): an RGBA texture of the surfaces' sun-lit share of their colour
   * (scene pass attachment 2, width x height); the fog's shadow takes (1 - T_s(P)) of it. */
  GLuint surface_sun;
  /* Optional (0: none): the scene pass's attachment 3 (rgb the lamps' share of the colour,
   * a the packed normal); with lamps, the fog between each lamp and the surface dims it
   * (fog_lamps.glsl, fog_lamps_surface; no CPU twin: test_lamp_surface checks it against
   * the analytic transmittance of homogeneous fog). */
  GLuint surface_lamps;
  /* Optional (NULL: none): the scene pass's sun shadow map (scene_pass_sun_shadow): V in
   * the view ray's mean, light shafts (shadow_steps >= 1 then too). */
  const sun_shadow_map *shafts;
  /* Optional (NULL: none): the lamps' shadow cubes (scene_pass_lamp_shadows, rendered for
   * these lamps in this order): V_i in the lamps' in-scatter (their shafts) and on the
   * surfaces they light. */
  const lamp_shadow_maps *lamp_shadows;
  fog_fetch fetch;
  fog_integrator integrator;
  fog_froxel_grid froxel;    /* FOG_INTEGRATOR_FROXEL: the grid */
  fog_walk_settings walk;    /* early termination, empty-space skipping */
  int march_steps;           /* FOG_INTEGRATOR_MARCH: samples a ray, >= 1 (every model but the
                                volume, which steps by model_grid3d_step); FOG_PASS_MARCH_STEPS
                                is the benches' usual choice */
  int march_jitter;          /* non-zero: per-pixel jittered sample positions */
  unsigned frame;            /* jitter seed */
  /* 0 or 1: the fog at full resolution (render, record: the reference). 2 or 4: the walk
   * runs at (width/D) x (height/D) (rounded up; each sample traces the ray of full-
   * resolution pixel k D + D/2 to that pixel's surface distance), then a joint bilateral
   * upsampling guided by the full-resolution surface distance (fog_pass_fs.glsl with FOG_UPSAMPLE) blends
   * at full resolution: ~D^2 less walk work, edges of surfaces stay sharp, the smooth fog is
   * interpolated (docs/integral.md, Performance: measured error). Every model (the
   * froxel baseline ignores it). The pass keeps a (width/D) x (height/D)
   * RGBA32F target of its own (created on first use, again when the size changes) and
   * restores the caller's draw framebuffer. */
  int resolution_divisor;
} fog_pass_params;

/* The CPU twin's rule for the pass's mean (fog_sun_mean_light). */
static inline fog_light_rule fog_pass_light_rule(const fog_pass_params *p) {
  return (fog_light_rule){.steps = p->shadow_steps, .nodes = p->shadow_nodes,
                          .pieces = p->shadow_pieces, .shaft_samples = p->shaft_samples};
}

#define FOG_PASS_TRANSMITTANCE_CUTOFF 1e-4
/* The optical depth where a walk with that cut-off stops: -ln(cutoff), or HUGE_VAL for 0. */
double fog_pass_depth_limit(double transmittance_cutoff);
/* FOG_SKIP_EMPTY's switch (docs/integral.md, Empty space): on llvmpipe the skipping walk
 * cost 1.44x the plain one on a fogmap with no empty block and gained 1.29x on the
 * Mantaflow ground fog with 52 % of its blocks empty. */
#define FOG_SKIP_MIN_EMPTY_SHARE 0.25

typedef struct fog_pass fog_pass;

/* Compiles the default variant (manual fetch, exact). */
fog_pass *fog_pass_create(fog_error *err);
void fog_pass_destroy(fog_pass *pass);

/* The renderer's loop cap (render/gl_util.h, gl_util_loop_cap), probed by fog_pass_create:
 * 65535 iterations of all a shader's loops on llvmpipe, GL_UTIL_NO_LOOP_CAP on GPUs. A draw
 * whose bound (fog_pass_loop_bound: the lamps' loops and the view ray's own, an RBF tile's
 * Gaussians, marching, the sun's mean, Perlin and noise walks) passes it less
 * FOG_PASS_LOOP_RESERVE (the rest of the view ray's walk) is refused, with or without
 * lamps: past the cap the shader would end its loops early and draw wrong, without an
 * error. set_loop_cap replaces the probed value (tests and benchmarks: GL_UTIL_NO_LOOP_CAP
 * draws anything, as the GPUs do). */
#define FOG_PASS_LOOP_RESERVE 8192
long fog_pass_loop_cap(const fog_pass *pass);
void fog_pass_set_loop_cap(fog_pass *pass, long cap);
/* The most loop iterations a pixel's bound may reach on this pass: the cap less the
 * reserve (what the draw checks; callers that plan a draw ask the same). */
double fog_pass_loops_allowed(const fog_pass *pass);
/* An upper bound of the loop iterations one pixel of the lamps' in-scatter runs, counted as
 * llvmpipe counts them (render/fog_lamp_loops.c): 0 without lamps. */
double fog_pass_lamp_loop_bound(const fog_pass_params *params);
/* The same for the view ray's loops that grow with the draw's settings: over RBF fog the
 * Gaussians of the pixel's screen tile (at most tile_gaussians), marching's samples, and
 * the sun's mean along the ray (shadow_steps x shadow_nodes points of K). The pass adds it to the lamps' (over
 * RBF fog once the tiles are built). */
double fog_pass_view_loop_bound(const fog_pass_params *params, int tile_gaussians);
/* The part of both that is the turbulence's walks: Perlin fog's octaves along the view ray
 * and with its sun's mean per piece, and the noise of quadric volumes (what a larger
 * perlin_feature shortens). */
double fog_pass_turbulence_loop_bound(const fog_pass_params *params);
/* Both, what the draw compares with fog_pass_loops_allowed. */
double fog_pass_loop_bound(const fog_pass_params *params, int tile_gaussians);

/* Uploads grid into slot (0 .. FOG_PASS_MAX_GRIDS-1) as an R32F texture. Re-uploading a
 * grid of the same size reuses the texture (glTexSubImage2D). */
int fog_pass_upload_grid(fog_pass *pass, int slot, const transform_grid *grid, fog_error *err);
/* Uploads lod->approx[0..J] and lod->detail[0..J-1] into their slots. */
int fog_pass_upload_lod(fog_pass *pass, const fog_lod *lod, fog_error *err);
/* Uploads a pyramid: its approximations, and its details when it has them. */
int fog_pass_upload_pyramid(fog_pass *pass, const fog_pyramid *pyramid, fog_error *err);

/* Uploads the density grid of FOG_MODEL_VOLUME as an R32F 3D texture (hardware trilinear,
 * zero border) with its placement; a grid of the same size reuses the texture. */
int fog_pass_upload_grid3d(fog_pass *pass, const volume_grid_desc *grid, fog_error *err);

/* Uploads FOG_MODEL_PERLIN's octave textures (one R32F 3D texture, size x size x size
 * octaves); the same size reuses the texture. */
int fog_pass_upload_perlin(fog_pass *pass, const fog_perlin *perlin, fog_error *err);

/* Uploads the sun's optical-depth volume (render/fog_sun_shadow.h) as an R32F 3D texture
 * with its placement; the same size reuses the texture. */
int fog_pass_upload_sun_shadow(fog_pass *pass, const fog_sun_shadow *shadow, fog_error *err);

/* Draws the fog over the bound framebuffer (see above). width x height is the viewport and
 * the size of both surface textures. */
int fog_pass_draw(fog_pass *pass, const camera *cam, const fog_pass_params *params,
                  GLuint surface_colour, GLuint surface_distance, int width, int height,
                  fog_error *err);

/* Blocks until the GL has finished every command (glFinish): time a draw as
 * fog_pass_finish(); t0 = now; fog_pass_draw(...); fog_pass_finish(); t = now - t0. */
void fog_pass_finish(void);

#endif
