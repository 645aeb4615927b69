/* The view ray's sunlight mean (fog_sun_mean_light, render/fog_sun_shadow.h) with one and
 * with two samples a segment, against the independent reference (tests/reference/
 * fog_light_reference.h: adaptive Gauss-Kronrod along the view ray, T_s by nested adaptive
 * quadrature towards the sun), on height fog under a low sun (T_s in closed form: the mean's
 * own quadrature is the only approximation), 12 view rays:
 *   - both converge to the reference;
 *   - the midpoint is second order, the two Gauss nodes fourth: the error falls ~4x and
 *     ~16x per doubling of the segments (observed orders checked);
 *   - at equal samples (N midpoints vs N/2 segments of two nodes) the two nodes err less;
 *   - a signed extinction (a wavelet approximation's ringing: here a Gaussian of negative
 *     density beside a positive one) keeps the mean a mean: within [0, 1] on every ray,
 *     the sunlit Gaussian's light where the other is in shadow (the signed weights nearly
 *     cancelled and made it 70 on one of fit's views);
 *   - V apart from T_s at shaft_samples points a segment converges to the exact mean of a
 *     shadow edge inside a segment, within the segment's share over 2M. */
#include <math.h>
#include <stdio.h>

#include "reference/fog_light_reference.h"
#include "render/render.h"
#include "test_util.h"

enum { RAYS = 12, LEVELS = 5 };

/* The sun reaches x < 0 only. */
static double west_lit(const void *user, const double p[3]) {
  (void)user;
  return p[0] < 0.0 ? 1.0 : 0.0;
}

/* +c at x = -20 and -c (1 - 1e-7) at x = +20 on the x axis: K's integral along the axis is
 * ~0, so signed weights would cancel; the lit one is the positive one. */
static void signed_extinction(void) {
  const fog_rbf g[2] = {{.centre = {-20, 0, 0}, .radius = 4, .density = 0.02},
                        {.centre = {20, 0, 0}, .radius = 4, .density = -0.02 * (1 - 1e-7)}};
  const fog_model m = {.kind = FOG_MODEL_RBF, .rbfs = g, .rbf_count = 2};
  double worst = 0.0;
  for (int r = 0; r < 9; r++) {
    const double o[3] = {-60, 0.3 * (r - 4), 0};
    const double d[3] = {1, 0, 0};
    for (int nodes = 1; nodes <= 2; nodes++) {
      double mean = fog_sun_mean_light(&m, FOG_SUN_SHADOW_NONE, NULL,
                                       (fog_light_rule){.steps = 64, .nodes = nodes}, HUGE_VAL,
                                       o, d, 120.0, west_lit, NULL);
      CHECK(mean >= 0.0 && mean <= 1.0 + 1e-12, "ray %d, %d node(s): mean %g, not in [0, 1]",
            r, nodes, mean);
      worst = fmax(worst, fabs(mean - 1.0));
    }
  }
  printf("signed K: the mean is the lit Gaussian's light within %.2e\n", worst);
  CHECK(worst < 1e-9, "the mean %.3e from the lit Gaussian's 1", worst);
}

/* A very dense soft-edged sphere (up to 1e6 per unit) met steeply inside a segment, lit
 * for x < 0. Its optical depth from the edge (x ~ -30) to x = 0 is ~1e3 x density: the
 * tau K weight beyond x = 0 is e^{-1e4} or less, so the exact mean is 1 to rounding.
 * - K linear through the two nodes, extrapolated back to the segment's start, gave a
 *   negative depth to the first node (-1350), e^1350 overflowed and 0 x inf made the mean
 *   NaN (a lit render of such a quadric wrote NaN);
 * - both nodes' weights K e^{-d} (d from the segment's start) underflowed to 0 once the
 *   segment was ~745 deep (in the shader's float, ~90): the mean was 0, dense fog drew no
 *   sunlight where all of it was lit. */
static void steep_dense_fog(void) {
  double worst = 0.0;
  for (double density = 10.0; density <= 1e6; density *= 10.0) {
    const fog_quadric v = fog_quadric_sphere((double[3]){0, 0, 0}, 30, density, 1.0);
    const fog_model m = {.kind = FOG_MODEL_QUADRIC, .quadrics = &v, .quadric_count = 1};
    for (int r = 0; r < 9; r++)
      for (int nodes = 1; nodes <= 2; nodes++) {
        const double o[3] = {-60, 1.5 * r, 0}, d[3] = {1, 0, 0};
        double mean = fog_sun_mean_light(&m, FOG_SUN_SHADOW_NONE, NULL,
                                         (fog_light_rule){.steps = 8, .nodes = nodes},
                                         HUGE_VAL, o, d, 120.0, west_lit, NULL);
        CHECK(fabs(mean - 1.0) < 1e-9, "sphere of density %g, ray %d, %d node(s): mean %.9g, "
              "expected 1 (all the weight lies lit, in front of x = 0)", density, r, nodes,
              mean);
        worst = isnan(mean) ? mean : fmax(worst, fabs(mean - 1.0));
      }
  }
  printf("dense sphere (density 10 .. 1e6): the mean within %.2e of 1\n", worst);
}

/* The sun reaches x < *edge only: a shadow edge inside a segment, off every node. */
static double lit_before_edge(const void *user, const double p[3]) {
  return p[0] < *(const double *)user ? 1.0 : 0.0;
}

/* V apart from T_s ([light] shaft_samples): thin homogeneous fog (K dt = 0.0015: tau K
 * nearly even across a segment) along x from -60 for 120 units, lit up to x = edge,
 * 8 segments of two nodes. The exact tau K-weighted mean of V is
 * (1 - e^{-K (60 + edge)}) / (1 - e^{-K 120}). At the nodes (shaft_samples 1) the segment
 * [45, 60] holding the edge counts as half lit (one node each side); with M points its lit
 * part is known to 1/(2M) of its length, so the mean errs by at most that segment's share
 * of the weight over 2M, plus its share times K dt for tau K's slope. At -3.3 (78 % of the
 * segment lit) the nodes' error is large; at -6.15 (59 %) 4, 8 and 16 points differ (at 78 %
 * they all count 75 % lit: a cap of 4 points passed there). */
static void shaft_samples_converge(double edge) {
  const double K = 1e-4, dt = 15.0, o[3] = {-60, 0, 0}, d[3] = {1, 0, 0};
  const fog_model m = {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = K};
  const double exact = -expm1(-K * (60.0 + edge)) / -expm1(-K * 120.0);
  const double share = (exp(-K * 45.0) - exp(-K * 60.0)) / -expm1(-K * 120.0);
  double at_nodes = 0.0, at_4 = 0.0;
  for (int samples = 1; samples <= 16; samples *= 2) {
    const fog_light_rule rule = {.steps = 8, .nodes = 2, .shaft_samples = samples};
    const double mean = fog_sun_mean_light(&m, FOG_SUN_SHADOW_NONE, NULL, rule, HUGE_VAL, o, d,
                                           120.0, lit_before_edge, &edge);
    const double error = fabs(mean - exact), bound = share / (2.0 * samples) + share * K * dt;
    printf("shafts, edge at x %.2f: %2d point%s a segment: mean %.6f, exact %.6f, error %.2e "
           "(bound %.2e)\n", edge, samples, samples == 1 ? " " : "s", mean, exact, error, bound);
    if (samples == 1) {
      at_nodes = error;
      if (edge > -4.0)
        CHECK(error > 0.2 * share, "at the nodes the edge's segment should be half lit: %g",
              error);
    } else {
      CHECK(error <= bound, "edge %.2f, %d points: error %.3e, bound %.3e", edge, samples,
            error, bound);
    }
    if (samples == 4) at_4 = error;
    if (samples == 16 && edge > -4.0) CHECK(error < 0.25 * at_nodes, "16 points: %.3e", error);
    if (samples == 16 && edge < -4.0)
      CHECK(error < 0.5 * at_4, "edge %.2f: 16 points err %.3e, 4 points %.3e: no gain",
            edge, error, at_4);
  }
}

int main(void) {
  shaft_samples_converge(-3.3);
  shaft_samples_converge(-6.15);
  const double sun_dir_raw[3] = {0.8, 0.3, -0.5};
  double sun[3], n = 0;
  for (int a = 0; a < 3; a++) n += sun_dir_raw[a] * sun_dir_raw[a];
  for (int a = 0; a < 3; a++) sun[a] = sun_dir_raw[a] / sqrt(n);
  const fog_model m = {.kind = FOG_MODEL_HEIGHT, .extinction = 0.03, .y0 = 5.0,
                       .scale_height = 12.0};
  fog_sun_shadow volume = {.sun = {sun[0], sun[1], sun[2]}}; /* _HEIGHT reads its sun */
  light_ref_height h = {.extinction = m.extinction, .y0 = m.y0, .scale_height = m.scale_height};
  light_ref_medium medium = light_ref_height_medium(&h);
  /* errors[nodes - 1][level]: samples 4, 8, .., 64 (segments = samples / nodes) */
  double errors[2][LEVELS] = {{0}};
  for (int r = 0; r < RAYS; r++) {
    const double o[3] = {0.0, 2.0 + 3.0 * (r % 3), 0.0};
    double d[3] = {cos(0.5 * r), -0.02 - 0.015 * r, sin(0.5 * r)}, len = 0;
    for (int a = 0; a < 3; a++) len += d[a] * d[a];
    for (int a = 0; a < 3; a++) d[a] /= sqrt(len);
    const double t_surface = 150.0 + 40.0 * r;
    double ref_tau;
    double s_ref = light_ref_sun_inscatter(&medium, o, d, t_surface, sun, 1, 1e-12, &ref_tau);
    CHECK(s_ref == s_ref && s_ref > 1e-3, "ray %d: reference %g", r, s_ref);
    double tau = exp(-fog_model_optical_depth(&m, o, d, t_surface));
    for (int nodes = 1; nodes <= 2; nodes++)
      for (int l = 0; l < LEVELS; l++) {
        int segments = (4 << l) / nodes;
        fog_light_rule rule = {.steps = segments, .nodes = nodes};
        double mean = fog_sun_mean_light(&m, FOG_SUN_SHADOW_HEIGHT, &volume, rule, HUGE_VAL, o,
                                         d, t_surface, NULL, NULL);
        double e = fabs(mean * (1 - tau) - s_ref) / s_ref;
        errors[nodes - 1][l] = fmax(errors[nodes - 1][l], e);
      }
  }
  for (int l = 0; l < LEVELS; l++)
    printf("%2d samples: midpoints %.3e, two nodes %.3e (relative to S)\n", 4 << l,
           errors[0][l], errors[1][l]);
  /* the two nodes' order from the finest pair: at 4 to 16 samples pieces deeper than
   * FOG_SUN_PIECE_MAX_DEPTH are halved, which lowers those errors (the mean's own rule, not
   * the order's) */
  double order1 = log2(errors[0][LEVELS - 2] / errors[0][LEVELS - 1]),
         order2 = log2(errors[1][LEVELS - 2] / errors[1][LEVELS - 1]);
  printf("observed orders: midpoints %.2f, two nodes %.2f\n", order1, order2);
  CHECK(errors[0][LEVELS - 1] < 1e-3 && errors[1][LEVELS - 1] < 1e-5,
        "no convergence to the reference: %.3e, %.3e", errors[0][LEVELS - 1],
        errors[1][LEVELS - 1]);
  CHECK(order1 > 1.6 && order1 < 2.5, "midpoints: order %.2f, expected ~2", order1);
  CHECK(order2 > 3.3, "two nodes: order %.2f, expected ~4", order2);
  for (int l = 1; l < LEVELS; l++)
    CHECK(errors[1][l] < errors[0][l], "%d samples: two nodes %.3e not below midpoints %.3e",
          4 << l, errors[1][l], errors[0][l]);
  signed_extinction();
  steep_dense_fog();
  return test_finish("test_sun_mean_nodes");
}
