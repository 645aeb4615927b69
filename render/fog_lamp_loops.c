/* Upper bounds of the loop iterations the lamps' in-scatter and the view ray run in one pixel
 * (fog_pass.h, fog_pass_lamp_loop_bound, fog_pass_view_loop_bound), counted as Mesa's llvmpipe
 * counts them against its per-shader budget (gl_util_loop_cap): every iteration of every loop,
 * and one more for each time a loop is entered (the pass that finds its exit). Loops of
 * constant count are counted too, though the compiler may unroll them (the bound errs high),
 * except the 3 nodes of a noise cell, a small loop of constant count the compiler unrolls
 * (counted, they made the bound refuse noisy volumes that test_render_fog_models draws right).
 * Each term follows the loops of fog_lamps.glsl, fog_light.glsl and fog_models.glsl. */
#include <math.h>

#include "render/fog_pass.h"

/* fog_quadric_weighted_turbulence over the (at most 5) stretches of one volume along a
 * segment no longer than `len`: per stretch and octave a DDA over the octave's texel cells
 * (its entries and exits: 3 cells and a pass more than the stretch's length crosses, |d|_1
 * <= sqrt 3 texels a unit length), the stretches' lengths summing to at most len; each cell's
 * 3 nodes a loop of constant count (unrolled). */
static double noise_walks(const fog_perlin *perlin, double len) {
  const int octaves = perlin->desc.octaves;
  double loops = 5.0 * (octaves + 1);
  for (int i = 0; i < octaves; i++)
    loops += 5.0 * (3 + 1) + len * sqrt(3.0) * fog_perlin_octave_scale(perlin, i);
  return loops;
}

/* Perlin fog's walks along a view ray cross, per octave, the texel cells a ray crosses in
 * the fog's box (at most its diagonal long, |d|_1 <= sqrt 3 texels a unit length: 3 cells
 * and a pass more); each piece's height cuts are a loop of their own, at least 1 a piece
 * and 2 more for each scale height the ray climbs (at most the box's height). A texel as
 * fine as perlin_feature = 1 over a 20 km box came to 10^6, past llvmpipe's cap, and the
 * walks stopped short silently: 63 % of the fog missing on long rays. */
static void perlin_cells(const fog_pass_params *p, double *cells, double *climb) {
  const fog_perlin *perlin = p->model_perlin;
  double diagonal = 0;
  for (int a = 0; a < 3; a++) {
    const double extent = perlin->desc.hi[a] - perlin->desc.lo[a];
    diagonal += extent * extent;
  }
  *cells = 0;
  for (int i = 0; i < perlin->desc.octaves; i++)
    *cells += sqrt(diagonal) * sqrt(3.0) * fog_perlin_octave_scale(perlin, i) + 4;
  *climb = 2.0 * (perlin->desc.hi[1] - perlin->desc.lo[1]) / p->model_scale_height;
}

/* The view ray's depth (fog_perlin_octave_depth): octave by octave, a piece a cell, each
 * its cuts' loop and exit pass. */
static double perlin_walks(const fog_pass_params *p) {
  double cells, climb;
  perlin_cells(p, &cells, &climb);
  const int octaves = p->model_perlin->desc.octaves;
  return octaves + 1 + octaves * (1 + climb) + 3 * cells;
}

/* The sun's mean per piece (fog_perlin_sun_mean): one walk over every octave's planes, a
 * piece between any two; per piece three loops over the octaves (the next plane, the cells,
 * the step) and its cuts; per cut the nodes, each a loop over the octaves, and the piece's
 * light (the nodes, each over the nodes, then the nodes again: fog_piece_light's mean).
 * Counted from the review of the first bound: the
 * shipped perlin_fog.ini at perlin_feature = 20 passed the view walk's bound and drew the
 * sun's mean cut short. */
static double perlin_sun_walk(const fog_pass_params *p) {
  double cells, climb;
  perlin_cells(p, &cells, &climb);
  const double octave_loop = p->model_perlin->desc.octaves + 1;
  const double nodes = (p->shadow_nodes > 0 ? p->shadow_nodes : 1) + 1;
  const double cuts = cells + climb;
  return 1 + cells * (3 * octave_loop + 1) +
         cuts * (1 + nodes * octave_loop + nodes * nodes + nodes);
}

/* The volumes' extinction at a point (fog_quadric_extinction_at) and their depth along a
 * segment no longer than any of their boxes' diagonals (fog_quadric_optical_depth_from:
 * per volume its 5 stretches, and with noise their turbulence). */
/* The volumes the draw reads (none without their array: fog_pass_check_model refuses it). */
static int quadric_count(const fog_pass_params *p) {
  return p->model_quadrics ? p->model_quadric_count : 0;
}

static double quadric_point(const fog_pass_params *p, bool noise) {
  int q = quadric_count(p);
  return q + 1 + (noise ? 2 + p->model_perlin->desc.octaves + 1 : 0);
}
static double quadric_segment(const fog_pass_params *p, bool noise) {
  double loops = quadric_count(p) + 1;
  for (int i = 0; i < quadric_count(p); i++) {
    const fog_quadric *v = &p->model_quadrics[i];
    double diagonal = 0;
    for (int a = 0; a < 3; a++) diagonal += (v->hi[a] - v->lo[a]) * (v->hi[a] - v->lo[a]);
    loops += 6 + (noise && v->noise > 0 ? noise_walks(p->model_perlin, sqrt(diagonal)) : 0);
  }
  return loops;
}

/* K at a point (fog_lamp_extinction, fog_light_extinction: over RBF fog the Gaussians of
 * the pixel's screen tile, at most `gaussians`) and, for the models with closed-form
 * depths, one segment's depth (fog_lamp_segment_depth: every Gaussian). */
static double point_loops(const fog_pass_params *p, bool noise, int gaussians) {
  double loops = 0;
  if (p->model == FOG_MODEL_RBF) loops += gaussians + 1;
  if (p->model == FOG_MODEL_PERLIN && p->model_perlin) loops += p->model_perlin->desc.octaves + 1;
  if (quadric_count(p) > 0) loops += quadric_point(p, noise);
  return loops;
}
static double segment_loops(const fog_pass_params *p, bool noise) {
  double loops = 0;
  if (p->model == FOG_MODEL_RBF) loops += p->model_rbf_count + 1;
  if (quadric_count(p) > 0) loops += quadric_segment(p, noise);
  return loops;
}

/* Whether the draw has noise inside its volumes (the octaves given). */
static bool noisy(const fog_pass_params *p) {
  return p->model_perlin && quadric_count(p) > 0 &&
         fog_quadric_noisy(p->model_quadrics, quadric_count(p));
}

static bool exact_depths(fog_model_kind m) {
  return m == FOG_MODEL_HOMOGENEOUS || m == FOG_MODEL_HEIGHT || m == FOG_MODEL_RBF ||
         m == FOG_MODEL_QUADRIC;
}

double fog_pass_lamp_loop_bound(const fog_pass_params *p) {
  const fog_lamps *lamps = &p->lamps;
  /* as the pass draws them: in the fog with albedo > 0 and not by the froxel baseline, on
   * the surfaces with their attachment; the cubes serving the lamps there */
  const bool in_fog = lamps->count > 0 && p->sun.albedo > 0 &&
                      p->integrator != FOG_INTEGRATOR_FROXEL;
  const bool on_surfaces = lamps->count > 0 && p->surface_lamps != 0;
  if (!in_fog && !on_surfaces) return 0;
  const bool cubes = p->lamp_shadows && p->lamp_shadows->count >= lamps->count;
  const fog_lamp_method *m = &lamps->method;
  const bool noise = noisy(p);
  const bool exact = exact_depths(p->model);
  const double point = point_loops(p, noise, p->model_rbf_count),
               segment = segment_loops(p, noise);
  /* T from a point to the lamp: the closed form, or the walk of shadow_steps */
  const double shadow = exact ? segment : m->shadow_steps + 1 + m->shadow_steps * point;
  /* the 4 nodes of a piece (their loop, K, tau from the camera, T) and with the shadow
   * cubes the nodes' V, the lit flags and the edges' bisections. A loop's last pass, the
   * one that finds its exit, runs its body masked, and every loop nested in it once more:
   * EXIT_PASS_SITES for those a piece's and a lamp's last passes hold. */
  enum { EXIT_PASS_SITES = 16 };
  const double node = point + (exact ? segment : 0) + shadow;
  const double piece = 1 + 5 + 4 * node + EXIT_PASS_SITES +
                       (cubes ? 5 + 5 + 6 * (FOG_LAMP_EDGE_BISECTIONS + 1) : 0);
  /* and the cut at the closest point; a spot's 4 at its cones' crossings, found by two
   * loops of two roots (fog_lamp_cone_cuts: unrolled, counted as if not) */
  const bool spots = fog_lamps_have_spot(lamps);
  const double pieces = m->angle_pieces + m->span_pieces + 1 + (spots ? 4 : 0);
  const double cone_loops = spots ? 2 + 1 + 2 * (2 + 1) : 0;
  double per_lamp = 0, table = 0;
  switch (m->integral) {
  case FOG_LAMP_ANGLE:
    per_lamp = pieces * piece + 1 + EXIT_PASS_SITES + cone_loops;
    if (!exact && p->model != FOG_MODEL_LINEAR && p->model != FOG_MODEL_EXP2) /* their factor */
      table = m->depth_steps + 1 + m->depth_steps * point;
    break;
  case FOG_LAMP_FOGSHOP: /* the base's angle integral (both depths), then every Gaussian */
    per_lamp = pieces * (1 + 5 + 4 * 2 * segment) + 1 + cone_loops +
               (p->model_rbf_count + 1) * (1 + 2 * segment);
    break;
  case FOG_LAMP_MARCH:
    per_lamp = (m->march_steps + 1) * (1 + point + shadow);
    break;
  }
  /* the surfaces' light dimmed by the fog between each lamp and the surface */
  const double surfaces = on_surfaces ? lamps->count + 1 + lamps->count * shadow : 0;
  if (!in_fog) return surfaces;
  /* the lamps' span along the ray: over RBF fog its reach loops over the tile's Gaussians */
  const double span = p->model == FOG_MODEL_RBF ? p->model_rbf_count + 1 : 0;
  return lamps->count + 1 + EXIT_PASS_SITES + span + table + lamps->count * per_lamp +
         surfaces;
}

double fog_pass_loop_bound(const fog_pass_params *p, int tile_gaussians) {
  return fog_pass_lamp_loop_bound(p) + fog_pass_view_loop_bound(p, tile_gaussians);
}

/* The sun's mean along the view ray (fog_light.glsl): by segments, or per piece of the
 * model's own walk. */
static bool sun_mean(const fog_pass_params *p) {
  return p->self_shadow == FOG_SUN_SHADOW_VOLUME || p->self_shadow == FOG_SUN_SHADOW_HEIGHT ||
         (p->self_shadow == FOG_SUN_SHADOW_NONE && p->shafts);
}
static bool sun_pieces(const fog_pass_params *p) {
  const bool beside = p->model != FOG_MODEL_QUADRIC && quadric_count(p) > 0;
  return (p->model == FOG_MODEL_PERLIN || p->model == FOG_MODEL_VOLUME ||
          p->model == FOG_MODEL_FOGMAP) && p->shadow_pieces && !beside;
}

/* Perlin fog's own walks along the view ray: its exact depth, and the sun's mean per piece
 * (which runs under either integrator). */
static double perlin_fog_walks(const fog_pass_params *p) {
  if (p->model != FOG_MODEL_PERLIN || !p->model_perlin) return 0;
  double loops = 0;
  if (p->integrator != FOG_INTEGRATOR_MARCH && p->model_perlin_integral == FOG_PERLIN_EXACT)
    loops += perlin_walks(p);
  if (sun_mean(p) && sun_pieces(p)) loops += perlin_sun_walk(p);
  return loops;
}

double fog_pass_turbulence_loop_bound(const fog_pass_params *p) {
  double loops = perlin_fog_walks(p);
  if (p->integrator == FOG_INTEGRATOR_MARCH) return loops;
  for (int i = 0; noisy(p) && i < quadric_count(p); i++) {
    const fog_quadric *v = &p->model_quadrics[i];
    double diagonal = 0;
    for (int a = 0; a < 3; a++) diagonal += (v->hi[a] - v->lo[a]) * (v->hi[a] - v->lo[a]);
    if (v->noise > 0) loops += noise_walks(p->model_perlin, sqrt(diagonal));
  }
  return loops;
}

double fog_pass_view_loop_bound(const fog_pass_params *p, int tile_gaussians) {
  const bool noise = noisy(p);
  const bool beside = p->model != FOG_MODEL_QUADRIC && quadric_count(p) > 0;
  /* the RBFs' exact integral and reach over the tile's list */
  double loops = p->model == FOG_MODEL_RBF ? 2.0 * (tile_gaussians + 1) : 0;
  /* the walks of the view ray itself: Perlin fog's octaves and the sun's mean per piece
   * with them; exact, the quadric volumes' stretches and their noise (quadric_segment: the
   * noise walks once, not again through fog_pass_turbulence_loop_bound) */
  loops += perlin_fog_walks(p);
  if (p->integrator != FOG_INTEGRATOR_MARCH && quadric_count(p) > 0)
    loops += quadric_segment(p, noise);
  /* marching (the volume's step, `volume_step`; the benches' march_steps): its samples,
   * the volume's at most 16384 a ray (fog_grid3d_optical_depth_march), each a K */
  if (p->integrator == FOG_INTEGRATOR_MARCH)
    loops += p->model == FOG_MODEL_VOLUME
                 ? 16384 + 1
                 : (p->march_steps + 1.0) * (1 + point_loops(p, noise, tile_gaussians));
  /* the sun's mean by segments (fog_light.glsl; the per-piece means walk with the view
   * ray): K at each node, and towards the sun the quadrics beside in closed form */
  const bool march = sun_mean(p), pieces = sun_pieces(p);
  if (march && !pieces) {
    const double node = point_loops(p, noise, tile_gaussians) +
                        (beside ? quadric_segment(p, noise) : 0);
    loops += p->shadow_steps + 1 + (double)p->shadow_steps * p->shadow_nodes * node;
    /* V's points a segment: a loop of their own */
    if (p->shafts && p->shaft_samples > 1) loops += (double)p->shadow_steps * (p->shaft_samples + 1);
  }
  return loops;
}
