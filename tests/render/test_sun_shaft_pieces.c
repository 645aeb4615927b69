/* V, the sun's visibility past the scene, in the per-piece means (fog_sun_mean_light with
 * rule.pieces, render/fog_sun_shadow.h; fog_shaft_visible in fog_light.glsl): linear
 * between steps x shaft_samples points of the ray's fog span. Perlin fog (its per-piece
 * walk), a shadow edge: the plane x = e, the sun reaching x < e only, so that the exact
 * in-scatter is the reference's S up to the edge (tests/reference: adaptive quadrature,
 * nothing of the walk):
 *   - every ray and edge within the line's bound: V's linear ramp over the points around
 *     the edge moves at most K_max dv / 2 of light (dv the points' spacing), plus the
 *     nodes' quadrature;
 *   - halving dv halves the worst error;
 *   - a fan of neighbouring rays (pixels) across one edge: the error varies smoothly from
 *     ray to ray with the line, as it does not with V at the pieces' nodes, whose places
 *     follow the fog's texel planes (the jagged bands of configs/perlin_fog.ini's hill
 *     shadows): the fan's total variation of the error is checked 5x smaller (10x measured). */
#include <math.h>
#include <stdio.h>

#include "reference/fog_light_reference.h"
#include "reference/perlin_reference.h"
#include "render/render.h"
#include "test_util.h"

typedef struct edge {
  double x; /* the sun reaches x < edge */
} edge;

static double lit_before(const void *user, const double p[3]) {
  return p[0] < ((const edge *)user)->x ? 1.0 : 0.0;
}

typedef struct setup {
  fog_perlin perlin;
  fog_perlin_medium medium;
  fog_model model;
  light_ref_medium ref;
} setup;

static double mean_of(const setup *s, int steps, int samples, const double o[3],
                      const double d[3], double edge_x) {
  const fog_light_rule rule = {.steps = steps, .nodes = 2, .pieces = true,
                               .shaft_samples = samples};
  edge e = {edge_x};
  return fog_sun_mean_light(&s->model, FOG_SUN_SHADOW_NONE, NULL, rule, HUGE_VAL, o, d,
                            HUGE_VAL, lit_before, &e);
}

/* The exact mean: S up to the edge over S of the whole ray (= 1 - tau). */
static double reference_mean(const setup *s, const double o[3], const double d[3],
                             double edge_x) {
  const double all = light_ref_sun_inscatter(&s->ref, o, d, HUGE_VAL, NULL, 0, 1e-11, NULL);
  const double t_edge = (edge_x - o[0]) / d[0];
  if (t_edge <= 0) return 0.0;
  return light_ref_sun_inscatter(&s->ref, o, d, t_edge, NULL, 0, 1e-11, NULL) / all;
}

/* max K along the ray's stretch in the box, sampled finely; and 1 - tau. */
static double largest_extinction(const setup *s, const double o[3], const double d[3]) {
  double k = 0.0;
  for (double t = 0.0; t < 400.0; t += 0.01) {
    double p[3];
    for (int a = 0; a < 3; a++) p[a] = o[a] + t * d[a];
    k = fmax(k, fog_perlin_extinction_at(&s->perlin, &s->medium, p));
  }
  return k;
}

/* The fog's span along x: the box [-128, 128] from o[0] = -140. */
static double span_of(const double o[3], const double d[3]) {
  return (128.0 - o[0]) / d[0] - (-128.0 - o[0]) / d[0];
}

static void within_bound(const setup *s) {
  double worst_ratio[3] = {0, 0, 0}, worst[3] = {0, 0, 0}, worst_nodes = 0;
  const int samples[3] = {4, 8, 16};
  for (int r = 0; r < 4; r++) {
    double o[3] = {-140.0, 3.0 + 4.0 * r, -30.0 + 17.0 * r}, d[3] = {1.0, 0.004 * r, 0.11};
    double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int a = 0; a < 3; a++) d[a] /= n;
    const double all = light_ref_sun_inscatter(&s->ref, o, d, HUGE_VAL, NULL, 0, 1e-11, NULL);
    const double k_max = largest_extinction(s, o, d);
    for (int i = 0; i < 23; i++) {
      const double x = -110.0 + 10.03 * i;
      const double want = reference_mean(s, o, d, x);
      for (int m = 0; m < 3; m++) {
        const double dv = span_of(o, d) / (8.0 * samples[m]);
        const double bound = k_max * dv / 2.0 / all + 1e-6;
        const double error = fabs(mean_of(s, 8, samples[m], o, d, x) - want);
        worst[m] = fmax(worst[m], error);
        worst_ratio[m] = fmax(worst_ratio[m], error / bound);
      }
      worst_nodes = fmax(worst_nodes, fabs(mean_of(s, 8, 1, o, d, x) - want));
    }
  }
  printf("per piece, a shadow edge against the reference (4 rays x 23 edges): V at the nodes "
         "%.2e; the line of 8 x 4 / 8 / 16 points %.2e / %.2e / %.2e (worst of error / bound: "
         "%.2f %.2f %.2f)\n", worst_nodes, worst[0], worst[1], worst[2], worst_ratio[0],
         worst_ratio[1], worst_ratio[2]);
  for (int m = 0; m < 3; m++)
    CHECK(worst_ratio[m] <= 1.0, "%d points a segment: error %.2f of the bound", samples[m],
          worst_ratio[m]);
  CHECK(worst[2] < 0.75 * worst[1] && worst[1] < 0.75 * worst[0],
        "halving dv does not shrink the error: %.3e %.3e %.3e", worst[0], worst[1], worst[2]);
}

/* 240 neighbouring rays 0.05 units apart in z, slanting through the fog's texel planes, one
 * edge: the sum over the fan of |error(r + 1) - error(r)|, for V at the nodes ([0]) and the
 * line of 8 x 8 points ([1]). */
static void smooth_across_pixels(const setup *s) {
  double total[2] = {0, 0}, previous[2] = {0, 0}, worst[2] = {0, 0};
  for (int r = 0; r < 240; r++) {
    double o[3] = {-140.0, 7.0, -20.0 + 0.05 * r}, d[3] = {1.0, 0.01, 0.23 + 0.0004 * r};
    double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int a = 0; a < 3; a++) d[a] /= n;
    const double want = reference_mean(s, o, d, 13.7);
    for (int v = 0; v < 2; v++) {
      const double error = mean_of(s, 8, v ? 8 : 1, o, d, 13.7) - want;
      if (r > 0) total[v] += fabs(error - previous[v]);
      previous[v] = error;
      worst[v] = fmax(worst[v], fabs(error));
    }
  }
  printf("a fan of 240 rays across one edge: the error's total variation %.2e with V at the "
         "nodes (worst %.2e), %.2e with the line of 64 points (worst %.2e)\n", total[0],
         worst[0], total[1], worst[1]);
  CHECK(total[1] < 0.2 * total[0], "the line's error is no smoother across the fan: %.3e vs "
        "%.3e", total[1], total[0]);
}

int main(void) {
  static setup s;
  fog_error err = {0};
  fog_perlin_desc desc = fog_perlin_desc_default();
  if (fog_perlin_create(&s.perlin, &desc, &err)) {
    CHECK(0, "perlin: %s", err.message);
    return test_finish("test_sun_shaft_pieces");
  }
  s.medium = (fog_perlin_medium){.extinction = 0.05, .y0 = 2.0, .scale_height = 6.0,
                                 .time = 1.5, .integral = FOG_PERLIN_EXACT};
  s.model = (fog_model){.kind = FOG_MODEL_PERLIN, .perlin = &s.perlin, .extinction = 0.05,
                        .y0 = 2.0, .scale_height = 6.0, .time = 1.5,
                        .perlin_integral = FOG_PERLIN_EXACT};
  s.ref = light_ref_perlin_medium(&s.perlin, &s.medium);
  within_bound(&s);
  smooth_across_pixels(&s);
  fog_perlin_destroy(&s.perlin);
  return test_finish("test_sun_shaft_pieces");
}
