/* An upper bound of the loop iterations the lamps' in-scatter runs in one pixel
 * (fog_pass.h, fog_pass_lamp_loop_bound), counted as Mesa's llvmpipe counts them against
 * its per-shader budget (gl_util_loop_cap): every iteration of every loop, and one more
 * for each time a loop is entered (the pass that finds its exit). Loops of constant count
 * are counted too, though the compiler may unroll them, so the bound errs high. Each term
 * follows the loops of fog_lamps.glsl and fog_models.glsl. */
#include <math.h>

#include "render/fog_pass.h"

/* fog_quadric_weighted_turbulence over a stretch of length len: per octave a DDA over its
 * texel cells (at most len |d| s + 3 of them, |d|_1 <= sqrt 3), each with its 3 nodes. */
static double noise_walk(const fog_perlin *perlin, double len) {
  double loops = perlin->desc.octaves + 1;
  for (int i = 0; i < perlin->desc.octaves; i++) {
    double cells = len * sqrt(3.0) * fog_perlin_octave_scale(perlin, i) + 3;
    loops += (cells + 1) * (1 + 4);
  }
  return loops;
}

/* The volumes' extinction at a point (fog_quadric_extinction_at) and their depth along a
 * segment no longer than any of their boxes' diagonals (fog_quadric_optical_depth_from). */
static double quadric_point(const fog_pass_params *p, bool noise) {
  int q = p->model_quadric_count;
  return q + 1 + (noise ? 2 + p->model_perlin->desc.octaves + 1 : 0);
}
static double quadric_segment(const fog_pass_params *p, bool noise) {
  double loops = p->model_quadric_count + 1;
  for (int i = 0; i < p->model_quadric_count; i++) {
    const fog_quadric *v = &p->model_quadrics[i];
    double diagonal = 0;
    for (int a = 0; a < 3; a++) diagonal += (v->hi[a] - v->lo[a]) * (v->hi[a] - v->lo[a]);
    loops += 6 + (noise && v->noise > 0 ? 5 * noise_walk(p->model_perlin, sqrt(diagonal)) : 0);
  }
  return loops;
}

/* K at a point (fog_lamp_extinction) and, for the models with closed-form depths, one
 * segment's depth (fog_lamp_segment_depth). */
static double point_loops(const fog_pass_params *p, bool noise) {
  double loops = 0;
  if (p->model == FOG_MODEL_RBF) loops += p->model_rbf_count + 1; /* at most every Gaussian */
  if (p->model == FOG_MODEL_PERLIN) loops += p->model_perlin->desc.octaves + 1;
  if (p->model_quadric_count > 0) loops += quadric_point(p, noise);
  return loops;
}
static double segment_loops(const fog_pass_params *p, bool noise) {
  double loops = 0;
  if (p->model == FOG_MODEL_RBF) loops += p->model_rbf_count + 1;
  if (p->model_quadric_count > 0) loops += quadric_segment(p, noise);
  return loops;
}

static bool exact_depths(fog_model_kind m) {
  return m == FOG_MODEL_HOMOGENEOUS || m == FOG_MODEL_HEIGHT || m == FOG_MODEL_RBF ||
         m == FOG_MODEL_QUADRIC;
}

double fog_pass_lamp_loop_bound(const fog_pass_params *p) {
  const fog_lamps *lamps = &p->lamps;
  if (lamps->count <= 0) return 0;
  const fog_lamp_method *m = &lamps->method;
  const bool noise = p->model_perlin && p->model_quadric_count > 0 &&
                     fog_quadric_noisy(p->model_quadrics, p->model_quadric_count);
  const bool exact = exact_depths(p->model);
  const double point = point_loops(p, noise), segment = segment_loops(p, noise);
  /* T from a point to the lamp: the closed form, or the walk of shadow_steps */
  const double shadow = exact ? segment : m->shadow_steps + 1 + m->shadow_steps * point;
  /* the 4 nodes of a piece (their loop, K, tau from the camera, T) and with the shadow
   * cubes the nodes' V, the lit flags and the edges' bisections */
  const double node = point + (exact ? segment : 0) + shadow;
  const double piece = 1 + 5 + 4 * node +
                       (p->lamp_shadows ? 5 + 5 + 6 * (FOG_LAMP_EDGE_BISECTIONS + 1) : 0);
  const double pieces = m->angle_pieces + m->span_pieces + 1; /* and the cut at the closest */
  double per_lamp = 0, table = 0;
  switch (m->integral) {
  case FOG_LAMP_ANGLE:
    per_lamp = pieces * piece + 1;
    if (!exact) table = m->depth_steps + 1 + m->depth_steps * point;
    break;
  case FOG_LAMP_FOGSHOP: /* the base's angle integral (both depths), then every Gaussian */
    per_lamp = pieces * (1 + 5 + 4 * 2 * segment) + 1 +
               (p->model_rbf_count + 1) * (1 + 2 * segment);
    break;
  case FOG_LAMP_MARCH:
    per_lamp = (m->march_steps + 1) * (1 + point + shadow);
    break;
  }
  /* the surfaces' light dimmed by the fog between each lamp and the surface */
  const double surfaces = p->surface_lamps ? lamps->count + 1 + lamps->count * shadow : 0;
  return lamps->count + 1 + table + lamps->count * per_lamp + surfaces;
}
