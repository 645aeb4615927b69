/* Quadric fog volumes (fog_models.h, FOG_MODEL_QUADRIC): the CPU twin's exact optical depth
 * against the independent reference (tests/reference/quadric_reference.h: adaptive
 * Gauss-Kronrod on the pointwise extinction, its breaks found by bisection on Q, never by
 * solving the quadratic), and the shapes against their documented equations.
 *   - shapes: Q = 0 on the surface the config's numbers describe, -1 at the core, the box
 *     the shape's bounds (docs/config.md);
 *   - random scenes of 1-8 volumes (every shape and rotated general quadrics, hard and soft
 *     edges, cones and hyperboloids whose a < 0), rays through them, grazing them, from
 *     inside, along the axes, finite and to infinity: |delta| <= 1e-9 (1 + depth);
 *   - the cases the roots must get right: a tangent ray (0), a ray with a = 0 (vertical in
 *     a cylinder: Q constant along it), a ray lying in a box face, a camera at the core;
 *   - the pointwise extinction (the march's and the light's integrand) equals the reference's.
 */
#include <math.h>
#include <stdio.h>

#include "reference/quadric_reference.h"
#include "render/fog_models.h"
#include "fog_test_scene.h"
#include "test_util.h"

static quadric_reference_volume to_reference(const fog_quadric *v) {
  quadric_reference_volume r = {.density = v->density, .edge = v->edge};
  for (int k = 0; k < 10; k++) r.q[k] = v->q[k];
  for (int a = 0; a < 3; a++) r.lo[a] = v->lo[a], r.hi[a] = v->hi[a];
  return r;
}

static void unit(double d[3]) {
  double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int a = 0; a < 3; a++) d[a] /= n;
}

/* The shapes' equations as docs/config.md states them, evaluated directly. */
static void check_shapes(void) {
  double worst = 0.0;
  for (int trial = 0; trial < 200; trial++) {
    double c[3] = {fog_test_range(-500, 500), fog_test_range(-50, 200), fog_test_range(-500, 500)};
    double r = fog_test_range(1, 100), h = fog_test_range(1, 300), u[3];
    double rx[3] = {fog_test_range(1, 100), fog_test_range(1, 100), fog_test_range(1, 100)};
    for (int a = 0; a < 3; a++) u[a] = fog_test_range(-1, 1);
    unit(u);
    fog_quadric s = fog_quadric_sphere(c, r, 1, 0), e = fog_quadric_ellipsoid(c, rx, 1, 0);
    fog_quadric cy = fog_quadric_cylinder(c, r, h, 1, 0), co = fog_quadric_cone(c, r, h, 1, 0);
    double on_sphere[3], on_ellipsoid[3];
    for (int a = 0; a < 3; a++) on_sphere[a] = c[a] + r * u[a], on_ellipsoid[a] = c[a] + rx[a] * u[a];
    /* the cylinder's wall and the cone's at height y: radius r and r (1 - (y - Y)/h) */
    double y = c[1] + fog_test_range(0, h), phi = fog_test_range(0, 6.283185307179586);
    double rc = r * (1.0 - (y - c[1]) / h);
    double wall[3] = {c[0] + r * cos(phi), y, c[2] + r * sin(phi)};
    double slant[3] = {c[0] + rc * cos(phi), y, c[2] + rc * sin(phi)};
    double apex[3] = {c[0], c[1] + h, c[2]};
    /* Q's terms are of the size (|c| / r)^2: its rounding is relative to that */
    double extent = (fabs(c[0]) + fabs(c[1]) + fabs(c[2])) / fmin(fmin(r, h), fmin(rx[0], fmin(rx[1], rx[2])));
    double scale = 1.0 + extent * extent;
    double errors[] = {fog_quadric_value(&s, on_sphere), fog_quadric_value(&s, c) + 1.0,
                       fog_quadric_value(&e, on_ellipsoid), fog_quadric_value(&e, c) + 1.0,
                       fog_quadric_value(&cy, wall), fog_quadric_value(&co, slant),
                       fog_quadric_value(&co, apex), fog_quadric_value(&co, c) + 1.0,
                       fog_quadric_value(&cy, (double[3]){c[0], y, c[2]}) + 1.0};
    for (size_t k = 0; k < sizeof errors / sizeof errors[0]; k++)
      worst = fmax(worst, fabs(errors[k]) / scale);
    for (int a = 0; a < 3; a++) {
      worst = fmax(worst, fabs(s.lo[a] - (c[a] - r)) + fabs(s.hi[a] - (c[a] + r)));
      worst = fmax(worst, fabs(e.lo[a] - (c[a] - rx[a])) + fabs(e.hi[a] - (c[a] + rx[a])));
    }
    worst = fmax(worst, fabs(cy.lo[1] - c[1]) + fabs(cy.hi[1] - (c[1] + h)) +
                            fabs(co.lo[0] - (c[0] - r)) + fabs(co.hi[2] - (c[2] + r)));
  }
  printf("shapes: Q on the documented surfaces, -1 at the core, the boxes: worst %.2e\n", worst);
  CHECK(worst <= 1e-14, "shapes: %.3e", worst);
}

/* A general quadric: diag(1/a^2, s/b^2, 1/c^2) rotated by random angles and moved, s = +1
 * (ellipsoid), -1 (hyperboloid of one sheet, or a cone with k = 0), in a random box. */
static fog_quadric random_general(double density, double edge) {
  double ang[3] = {fog_test_range(0, 3.14159), fog_test_range(0, 3.14159),
                   fog_test_range(0, 3.14159)};
  double rot[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int axis = 0; axis < 3; axis++) { /* rot = R_axis rot */
    int i = (axis + 1) % 3, j = (axis + 2) % 3;
    double cs = cos(ang[axis]), sn = sin(ang[axis]);
    for (int col = 0; col < 3; col++) {
      double a = rot[i][col], b = rot[j][col];
      rot[i][col] = cs * a - sn * b, rot[j][col] = sn * a + cs * b;
    }
  }
  double sign = fog_test_uniform() < 0.5 ? 1.0 : -1.0, k = fog_test_uniform() < 0.3 ? 0.0 : 1.0;
  double w[3] = {1 / pow(fog_test_range(5, 40), 2), sign / pow(fog_test_range(5, 40), 2),
                 1 / pow(fog_test_range(5, 40), 2)};
  double m[3][3] = {{0}}, c[3] = {fog_test_range(-30, 30), fog_test_range(-30, 30),
                                  fog_test_range(-30, 30)};
  for (int i = 0; i < 3; i++) /* M = R^T diag(w) R */
    for (int j = 0; j < 3; j++)
      for (int a = 0; a < 3; a++) m[i][j] += rot[a][i] * w[a] * rot[a][j];
  double mc[3] = {0};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) mc[i] += m[i][j] * c[j];
  /* Q = (x - c)^T M (x - c) - k */
  fog_quadric v = {.q = {m[0][0], m[1][1], m[2][2], 2 * m[0][1], 2 * m[1][2], 2 * m[0][2],
                         -2 * mc[0], -2 * mc[1], -2 * mc[2],
                         c[0] * mc[0] + c[1] * mc[1] + c[2] * mc[2] - k},
                   .density = density, .edge = edge};
  for (int a = 0; a < 3; a++) {
    v.lo[a] = c[a] - fog_test_range(10, 60);
    v.hi[a] = c[a] + fog_test_range(10, 60);
  }
  return v;
}

static fog_quadric random_volume(void) {
  double c[3] = {fog_test_range(-40, 40), fog_test_range(-20, 20), fog_test_range(-40, 40)};
  double density = fog_test_range(0.005, 0.2);
  double edge = fog_test_uniform() < 0.3 ? 0.0 : fog_test_range(0.05, 1.0);
  switch ((int)(fog_test_uniform() * 5)) {
    case 0: return fog_quadric_sphere(c, fog_test_range(3, 40), density, edge);
    case 1:
      return fog_quadric_ellipsoid(c, (double[3]){fog_test_range(3, 40), fog_test_range(3, 40),
                                                  fog_test_range(3, 40)}, density, edge);
    case 2: return fog_quadric_cylinder(c, fog_test_range(3, 30), fog_test_range(5, 80), density, edge);
    case 3: return fog_quadric_cone(c, fog_test_range(3, 30), fog_test_range(5, 80), density, edge);
    default: return random_general(density, edge);
  }
}

static double worst_error = 0.0;

static void compare(const fog_quadric *v, int n, const double o[3], const double d[3],
                    double length, const char *what) {
  quadric_reference_volume ref[FOG_MAX_QUADRICS];
  for (int i = 0; i < n; i++) ref[i] = to_reference(&v[i]);
  double want = quadric_reference_optical_depth(ref, n, o, d, length);
  double got = fog_quadric_optical_depth(v, n, NULL, o, d, length);
  double error = fabs(got - want) / (1.0 + want);
  worst_error = fmax(worst_error, error);
  CHECK(error <= 1e-9, "%s: twin %.17g, reference %.17g", what, got, want);
}

static void check_random_scenes(void) {
  int rays = 0;
  for (int scene = 0; scene < 300; scene++) {
    fog_quadric v[8];
    int n = 1 + (int)(fog_test_uniform() * 8);
    for (int i = 0; i < n; i++) v[i] = random_volume();
    for (int r = 0; r < 40; r++, rays++) {
      double o[3], d[3], target[3];
      int kind = r % 4;
      const fog_quadric *aim = &v[r % n];
      for (int a = 0; a < 3; a++) {
        /* a point inside the aimed volume's box, from outside or from inside it */
        target[a] = fog_test_range(aim->lo[a], aim->hi[a]);
        o[a] = kind == 1 ? fog_test_range(aim->lo[a], aim->hi[a]) : fog_test_range(-300, 300);
      }
      for (int a = 0; a < 3; a++) d[a] = target[a] - o[a];
      if (kind == 2) d[0] = d[2] = 0.0, d[1] = 1.0;                     /* along an axis */
      if (kind == 3) d[r % 3] = 0.0;                                      /* in a plane */
      unit(d);
      double length = r % 3 == 0 ? HUGE_VAL : fog_test_range(1, 600);
      compare(v, n, o, d, length, "random scene");
    }
  }
  printf("random scenes: %d rays, max |twin - reference| / (1 + depth) %.2e\n", rays, worst_error);
}

static void check_cases(void) {
  double c[3] = {1, 2, 3};
  fog_quadric s = fog_quadric_sphere(c, 2.0, 0.3, 0.0);
  /* tangent: the line x = 3 (distance 2) along z */
  double o[3] = {3, 2, -50}, d[3] = {0, 0, 1};
  double t = fog_quadric_optical_depth(&s, 1, NULL, o, d, HUGE_VAL);
  printf("tangent ray: %.3e\n", t);
  CHECK(fabs(t) <= 1e-12, "tangent ray: %g", t);
  /* through the centre: 0.3 * 4; from the centre: 0.3 * 2 */
  double oc[3] = {1, 2, -50};
  CHECK(fabs(fog_quadric_optical_depth(&s, 1, NULL, oc, d, HUGE_VAL) - 1.2) <= 1e-13, "sphere chord");
  CHECK(fabs(fog_quadric_optical_depth(&s, 1, NULL, c, d, HUGE_VAL) - 0.6) <= 1e-13, "from the centre");
  /* a = 0: a vertical ray in an upright cylinder sees Q constant: density over the height */
  fog_quadric cy = fog_quadric_cylinder((double[3]){0, 0, 0}, 5, 20, 0.1, 0.5);
  double up[3] = {0, 1, 0}, below[3] = {1, -40, 1};
  double k = 0.1 * fmin(1.0, (1.0 - 2.0 / 25.0) / 0.5); /* Q = 2/25 - 1 at x = z = 1 */
  compare(&cy, 1, below, up, HUGE_VAL, "a = 0");
  CHECK(fabs(fog_quadric_optical_depth(&cy, 1, NULL, below, up, HUGE_VAL) - 20 * k) <= 1e-12,
        "a = 0: %.17g vs %.17g", fog_quadric_optical_depth(&cy, 1, NULL, below, up, HUGE_VAL), 20 * k);
  /* a ray lying in the cylinder's top face (the closed box keeps it) */
  double face[3] = {-50, 20, 0}, along_x[3] = {1, 0, 0};
  compare(&cy, 1, face, along_x, HUGE_VAL, "ray in a box face");
  /* the double cone x^2 + z^2 = y^2 in [-2, 2]^3 along x = 0.5 (a < 0 along y): 3 density */
  fog_quadric cone = {.q = {1, -1, 1, 0, 0, 0, 0, 0, 0, 0}, .lo = {-2, -2, -2},
                      .hi = {2, 2, 2}, .density = 1.0};
  double oy[3] = {0.5, -5, 0};
  CHECK(fabs(fog_quadric_optical_depth(&cone, 1, NULL, oy, up, HUGE_VAL) - 3.0) <= 1e-13, "double cone");
  /* soft sphere, edge 1: K = c (1 - r^2) on the diameter: c 4/3 */
  fog_quadric soft = fog_quadric_sphere((double[3]){0, 0, 0}, 1, 0.6, 1.0);
  double ox[3] = {-3, 0, 0};
  CHECK(fabs(fog_quadric_optical_depth(&soft, 1, NULL, ox, along_x, HUGE_VAL) - 0.8) <= 1e-14,
        "soft sphere: %.17g", fog_quadric_optical_depth(&soft, 1, NULL, ox, along_x, HUGE_VAL));
}

static void check_extinction(void) {
  double worst = 0.0;
  for (int scene = 0; scene < 100; scene++) {
    fog_quadric v[6];
    quadric_reference_volume ref[6];
    for (int i = 0; i < 6; i++) v[i] = random_volume(), ref[i] = to_reference(&v[i]);
    for (int k = 0; k < 200; k++) {
      double p[3] = {fog_test_range(-80, 80), fog_test_range(-60, 60), fog_test_range(-80, 80)};
      double want = quadric_reference_extinction(ref, 6, p);
      worst = fmax(worst, fabs(fog_quadric_extinction_at(v, 6, NULL, p) - want) / (1.0 + want));
    }
  }
  printf("pointwise extinction vs the reference: %.2e\n", worst);
  CHECK(worst <= 1e-13, "pointwise extinction: %.3e", worst);
}

int main(void) {
  char message[256];
  CHECK(quadric_reference_self_test(message, sizeof message) == 0, "reference: %s", message);
  check_shapes();
  check_cases();
  check_random_scenes();
  check_extinction();
  return test_finish("test_integral_quadric");
}
