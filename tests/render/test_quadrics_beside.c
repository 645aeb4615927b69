/* Quadric volumes beside another model's fog (fog_model_quadrics_beside, render/fog_models.h):
 * the CPU twins add them everywhere K is read, checked against what is known without them:
 *   - the optical depth of height fog with a sphere and a cylinder beside it is the height
 *     fog's closed form (written here from K e^{-(y - y0)/H}) plus the quadric reference's
 *     adaptive quadrature (tests/reference/quadric_reference.h), 1e-10 relative, on rays
 *     through, beside and past the volumes;
 *   - K at points is the height fog's plus the reference's;
 *   - T_s towards the sun (the height fog's closed form) adds the volumes' depth towards
 *     the sun, 1e-10;
 *   - the light's span reaches a volume past the model's own fog;
 *   - the sun's optical-depth volume holds the model alone (bit for bit the volume of the
 *     model without them: the volumes add their exact depth at each lookup instead);
 *   - the per-piece light is not taken beside them (the segments' mean, bit for bit). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "reference/quadric_reference.h"
#include "render/render.h"
#include "test_util.h"

static quadric_reference_volume to_reference(const fog_quadric *v) {
  quadric_reference_volume r = {.density = v->density, .edge = v->edge};
  memcpy(r.q, v->q, sizeof r.q);
  memcpy(r.lo, v->lo, sizeof r.lo);
  memcpy(r.hi, v->hi, sizeof r.hi);
  return r;
}

/* int_0^L k e^{-(y_c + t d_y - y0)/H} dt in closed form. */
static double height_depth(double k, double y0, double H, double y_c, double d_y, double L) {
  if (d_y == 0.0) return k * exp(-(y_c - y0) / H) * L;
  return k * exp(-(y_c - y0) / H) * H / d_y * (1.0 - exp(-d_y * L / H));
}

static void unit(double d[3]) {
  double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int a = 0; a < 3; a++) d[a] /= n;
}

int main(void) {
  const double centre[3] = {-60, 80, -100}, base[3] = {120, 0, -60};
  const fog_quadric q[2] = {fog_quadric_sphere(centre, 70, 0.02, 0.5),
                            fog_quadric_cylinder(base, 30, 160, 0.03, 0.0)};
  const quadric_reference_volume ref[2] = {to_reference(&q[0]), to_reference(&q[1])};
  const double k = 0.01, y0 = 0.0, H = 25.0;
  const fog_model m = {.kind = FOG_MODEL_HEIGHT, .extinction = k, .y0 = y0, .scale_height = H,
                       .quadrics = q, .quadric_count = 2};
  CHECK(fog_model_quadrics_beside(&m), "the height fog's quadrics are not beside it");

  /* depth */
  static const double rays[6][7] = {{0, 120, 400, -60, -40, -500, 900},
                                    {0, 120, 400, 120, -60, -460, 700},
                                    {-60, 80, -100, 1, 0.1, 0.2, 300},
                                    {300, 50, 300, -0.4, 0.05, -1, 2000},
                                    {120, 10, -60, 0, 1, 0, 500},
                                    {-400, 300, 0, 1, -0.3, -0.2, 1e4}};
  double worst_depth = 0.0;
  for (int r = 0; r < 6; r++) {
    const double *o = rays[r];
    double d[3] = {rays[r][3], rays[r][4], rays[r][5]};
    unit(d);
    const double L = rays[r][6];
    double want = height_depth(k, y0, H, o[1], d[1], L) +
                  quadric_reference_optical_depth(ref, 2, o, d, L);
    double got = fog_model_optical_depth(&m, o, d, L);
    worst_depth = fmax(worst_depth, fabs(got - want) / want);
  }
  printf("depth beside the height fog: worst relative %.2e\n", worst_depth);
  CHECK(worst_depth <= 1e-10, "depth off by %.3e", worst_depth);

  /* K at points */
  double worst_k = 0.0;
  for (int i = 0; i < 200; i++) {
    double p[3] = {-150 + 1.7 * i, 5 + 0.8 * i, -160 + 0.9 * i};
    double want = k * exp(-(p[1] - y0) / H) + quadric_reference_extinction(ref, 2, p);
    worst_k = fmax(worst_k, fabs(fog_light_extinction_at(&m, p) - want));
  }
  CHECK(worst_k <= 1e-15, "K off by %.3e", worst_k);

  /* T_s: the height fog's closed form plus the volumes' depth towards the sun */
  fog_sun_shadow sun = {.sun = {0.3, 0.5, -0.4}};
  unit(sun.sun);
  double worst_sun = 0.0;
  for (int i = 0; i < 40; i++) {
    double p[3] = {-200 + 10 * i, 20 + 2 * i, -240 + 6 * i};
    double want = k * H * exp(-(p[1] - y0) / H) / sun.sun[1] +
                  quadric_reference_optical_depth(ref, 2, p, sun.sun, HUGE_VAL);
    double got = fog_sun_optical_depth(&m, FOG_SUN_SHADOW_HEIGHT, &sun, p);
    worst_sun = fmax(worst_sun, fabs(got - want) / want);
  }
  printf("depth towards the sun: worst relative %.2e\n", worst_sun);
  CHECK(worst_sun <= 1e-10, "towards the sun off by %.3e", worst_sun);

  /* the light's span: a ray through a volume past the RBF fog's reach */
  const fog_rbf g = {.centre = {0, 0, 0}, .radius = 10, .density = 0.05};
  const fog_model rbf = {.kind = FOG_MODEL_RBF, .rbfs = &g, .rbf_count = 1, .quadrics = q,
                         .quadric_count = 2};
  const double o[3] = {0, 80, 400}, d[3] = {-60.0 / 500, 0, -1};
  double t0, t1, dn[3] = {d[0], d[1], d[2]};
  unit(dn);
  /* the sphere's chord on the ray (~433.6..573.6): the lamps' span holds it (from the
   * camera on); the sun's too, and no more: the ray passes 80 above the Gaussian, past its
   * cull radius, so the sun's span is the volumes' box alone */
  double v[3] = {centre[0] - o[0], centre[1] - o[1], centre[2] - o[2]};
  const double tc = v[0] * dn[0] + v[1] * dn[1] + v[2] * dn[2];
  const double half = sqrt(70.0 * 70.0 - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - tc * tc));
  CHECK(fog_light_span(&rbf, o, dn, HUGE_VAL, &t0, &t1) && t0 <= tc - half && t1 >= tc + half,
        "the lamps' span %g..%g: expected it to hold the sphere's chord %g..%g", t0, t1,
        tc - half, tc + half);
  CHECK(fog_sun_span(&rbf, o, dn, HUGE_VAL, &t0, &t1) && t0 <= tc - half && t1 >= tc + half &&
            t0 > 400,
        "the sun's span %g..%g: expected the sphere's chord %g..%g and the box", t0, t1,
        tc - half, tc + half);

  /* the sun's volume holds the model alone */
  fog_sun_shadow with = {0}, alone = {0};
  const fog_model lone = fog_model_alone(&rbf);
  fog_error err = {0};
  const fog_sun_shadow_desc desc = {.across = 16, .along = 16};
  const double towards[3] = {0.6, 0.8, 0.0};
  CHECK(fog_sun_shadow_create(&with, &desc, &err) == 0 &&
            fog_sun_shadow_create(&alone, &desc, &err) == 0 &&
            fog_sun_shadow_compute(&with, &rbf, towards, 1, &err) == 0 &&
            fog_sun_shadow_compute(&alone, &lone, towards, 1, &err) == 0,
        "sun volumes: %s", err.message);
  CHECK(with.optical_depth && alone.optical_depth &&
            !memcmp(with.optical_depth, alone.optical_depth, sizeof(float) * 16 * 16 * 16),
        "the sun's volume holds the quadrics beside the model");
  /* the mean: per piece is not taken beside them (segments either way) */
  fog_light_rule pieces = {.steps = 8, .nodes = 2, .pieces = true}, segments = pieces;
  segments.pieces = false;
  double a = fog_sun_mean_light(&rbf, FOG_SUN_SHADOW_VOLUME, &with, pieces, HUGE_VAL, o, dn,
                                HUGE_VAL, NULL, NULL);
  double b = fog_sun_mean_light(&rbf, FOG_SUN_SHADOW_VOLUME, &with, segments, HUGE_VAL, o, dn,
                                HUGE_VAL, NULL, NULL);
  CHECK(a == b && a > 0.0 && a < 1.0, "the mean per piece %g, by segments %g", a, b);
  fog_sun_shadow_destroy(&with);
  fog_sun_shadow_destroy(&alone);
  return test_finish("test_quadrics_beside");
}
