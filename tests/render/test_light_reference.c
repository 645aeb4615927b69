/* The sunlight reference (tests/reference/fog_light_reference.h) against what is known
 * without it: the identity S1 = 1 - tau of the unshadowed in-scatter, closed forms in a
 * homogeneous slab (sun overhead and oblique) and in height fog (T_s, and S for vertical rays
 * under an overhead sun), the shadowed fogmap S against a brute-force midpoint sum on
 * fog_oracle.c, and the optical depths against fog_oracle.c and the height fog's closed
 * form. Prints the worst error of each group and the time of one shadowed S on a
 * 64 x 64 fogmap. */
#include <math.h>
#include <stdio.h>
#include <time.h>

#include "reference/fog_light_reference.h"
#include "reference/fog_oracle.h"
#include "render/fog_field.h"
#include "test_util.h"
#include "transform/transform.h"

static void unit(double d[3]) {
  double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int i = 0; i < 3; i++) d[i] /= n;
}

static void aim(const double from[3], const double to[3], double d[3]) {
  for (int i = 0; i < 3; i++) d[i] = to[i] - from[i];
  unit(d);
}

/* A size x size grid at spacing 1 whose first coefficient sits `margin` samples outside
 * the box corner u = -1/2: random-ish in [0.2, 1.0], or `constant` everywhere if > 0. */
static transform_grid make_grid(int size, int degree, double margin, double constant) {
  transform_grid g;
  fog_error err;
  transform_grid_create(&g, size, size, &err);
  g.degree = degree;
  g.spacing = 1.0;
  g.origin_u = -0.5 - margin;
  g.origin_v = -0.5 - margin;
  for (int j = 0; j < size; j++)
    for (int i = 0; i < size; i++)
      g.coefficients[j * size + i] =
          constant > 0 ? (float)constant
                       : (float)(0.6 + 0.4 * sin(1.3 * i + 0.7 * j * j + 0.3 * degree));
  return g;
}

/* 6 x 6 cells of 2 at (10, -5): x in [10, 22], z in [-5, 7]. */
static fog_volume small_volume(fog_profile profile) {
  return (fog_volume){.map_width = 6, .map_height = 6, .origin_x = 10.0, .origin_z = -5.0,
                      .cell_size = 2.0, .extinction = 0.15, .profile = profile};
}

static const fog_profile exp_profile = {.kind = FOG_PROFILE_EXPONENTIAL, .y_floor = 0.0,
                                        .y0 = 2.0, .scale_height = 3.0, .y_top = 20.0};

/* ---- 1. identity S1 = 1 - tau, and the depths against independent values ---- */

static double worst_identity, worst_depth;

static void identity(const char *what, const light_ref_medium *m, const double o[3],
                     const double d[3], double t_surf) {
  double tau, s1 = light_ref_sun_inscatter(m, o, d, t_surf, NULL, 0, 1e-10, &tau);
  double e = fabs(s1 - (1.0 - tau));
  if (e > worst_identity) worst_identity = e;
  CHECK(e <= 1e-9, "%s: S1 %.15g, 1 - tau %.15g: %.2e", what, s1, 1.0 - tau, e);
  CHECK(s1 > 1e-3, "%s: the ray should see fog (S1 %.3g)", what, s1);
}

static void fogmap_depth(const char *what, const fog_volume *v, const transform_grid *g,
                         const double o[3], const double d[3], double t_surf) {
  light_ref_medium m = light_ref_fogmap(v, g);
  double ref = light_ref_optical_depth(&m, o, d, 0.0, t_surf, 1e-13);
  double oracle = fog_optical_depth_oracle(v, g, o, d, 0.0, t_surf, 1e-13, NULL);
  double e = fabs(ref - oracle);
  if (e > worst_depth) worst_depth = e;
  CHECK(e <= 1e-11, "%s: depth %.15g, fog_oracle %.15g: %.2e", what, ref, oracle, e);
}

static void fogmap_identity(int degree) {
  fog_volume v = small_volume(exp_profile);
  transform_grid g = make_grid(8, degree, 1.0, 0.0);
  light_ref_medium m = light_ref_fogmap(&v, &g);
  double o[3], d[3], p[3];
  /* From outside, through, to the sky. */
  o[0] = 0, o[1] = 5, o[2] = 0, p[0] = 18, p[1] = 3, p[2] = 2;
  aim(o, p, d);
  identity("fogmap through", &m, o, d, HUGE_VAL);
  fogmap_depth("fogmap through", &v, &g, o, d, HUGE_VAL);
  /* Starting inside. */
  o[0] = 15, o[1] = 1, o[2] = 1, d[0] = 0.3, d[1] = 0.1, d[2] = 0.8;
  unit(d);
  identity("fogmap inside", &m, o, d, HUGE_VAL);
  fogmap_depth("fogmap inside", &v, &g, o, d, HUGE_VAL);
  /* A surface inside the fog. */
  o[0] = 5, o[1] = 8, o[2] = -10, p[0] = 16, p[1] = 1, p[2] = 2;
  aim(o, p, d);
  double dist = sqrt((p[0] - o[0]) * (p[0] - o[0]) + (p[1] - o[1]) * (p[1] - o[1]) +
                     (p[2] - o[2]) * (p[2] - o[2]));
  identity("fogmap surface", &m, o, d, 0.8 * dist);
  fogmap_depth("fogmap surface", &v, &g, o, d, 0.8 * dist);
  /* Inside, up to the sky. */
  o[0] = 12, o[1] = 1, o[2] = 0, d[0] = 0.2, d[1] = 1, d[2] = 0.1;
  unit(d);
  identity("fogmap inside to the sky", &m, o, d, HUGE_VAL);
  fogmap_depth("fogmap inside to the sky", &v, &g, o, d, HUGE_VAL);
  /* Down from above to the ground y = 0. */
  o[0] = 14, o[1] = 30, o[2] = 2, d[0] = 0.1, d[1] = -1, d[2] = 0.05;
  unit(d);
  identity("fogmap down", &m, o, d, -30.0 / d[1]);
  fogmap_depth("fogmap down", &v, &g, o, d, -30.0 / d[1]);
  transform_grid_destroy(&g);
}

/* int_0^L k e^{-(y_c + t d_y - y0)/H} dt, the closed form (d_y != 0; L = inf for d_y > 0). */
static double height_depth(const light_ref_height *h, double y_c, double d_y, double length) {
  double k_c = h->extinction * exp(-(y_c - h->y0) / h->scale_height);
  if (isinf(length)) return k_c * h->scale_height / d_y;
  return k_c * h->scale_height / d_y * -expm1(-d_y * length / h->scale_height);
}

static void height_case(const char *what, const light_ref_medium *m, const light_ref_height *h,
                        double y_c, double dx, double dy, double t_surf) {
  double o[3] = {3.0, y_c, -7.0}, d[3] = {dx, dy, 0.4};
  unit(d);
  identity(what, m, o, d, t_surf);
  if (d[1] == 0.0 && isinf(t_surf)) return;
  double ref = light_ref_optical_depth(m, o, d, 0.0, t_surf, 1e-13);
  double exact = d[1] == 0.0 ? h->extinction * exp(-(y_c - h->y0) / h->scale_height) * t_surf
                             : height_depth(h, y_c, d[1], t_surf);
  double e = fabs(ref - exact) / exact;
  if (e > worst_depth) worst_depth = e;
  CHECK(e <= 1e-12, "%s: depth %.15g, closed form %.15g: relative %.2e", what, ref, exact, e);
}

static void height_identity(void) {
  light_ref_height h = {.extinction = 0.02, .y0 = 0.0, .scale_height = 50.0};
  light_ref_medium m = light_ref_height_medium(&h);
  height_case("height up to the sky", &m, &h, 10.0, 0.3, 0.9, HUGE_VAL);
  height_case("height level, surface", &m, &h, 5.0, 1.0, 0.0, 300.0);
  height_case("height down to the ground", &m, &h, 200.0, 0.2, -0.7, 200.0 / 0.7 * 1.1);
  height_case("height low rise to the sky", &m, &h, -20.0, 1.0, 0.05, HUGE_VAL);
  height_case("height level to the sky", &m, &h, 30.0, 1.0, 0.0, HUGE_VAL);
}

/* ---- 2. homogeneous slab: K = 0.1 in x, z in [-50, 50], y in [0, 10] ---- */

enum { SLAB_TOP = 10 };
static const double slab_k = 0.1;

static double slab_density(const light_ref_medium *m, const double p[3]) {
  for (int a = 0; a < 3; a++)
    if (p[a] < m->box_min[a] || p[a] > m->box_max[a]) return 0.0;
  return slab_k;
}

static double worst_slab;

static void slab_check(const char *what, double got, double exact) {
  double e = fabs(got - exact);
  if (e > worst_slab) worst_slab = e;
  CHECK(e <= 1e-9, "%s: %.15g, closed form %.15g: %.2e", what, got, exact, e);
}

static void slab_scatter(const char *what, const light_ref_medium *m, double ox, double oy,
                         double oz, double dx, double dy, double dz, double t_surf,
                         const double sun[3], double exact) {
  double o[3] = {ox, oy, oz}, d[3] = {dx, dy, dz};
  unit(d);
  slab_check(what, light_ref_sun_inscatter(m, o, d, t_surf, sun, 1, 1e-10, NULL), exact);
}

static void slab_cases(const light_ref_medium *m) {
  const double k = slab_k, top = SLAB_TOP, up[3] = {0, 1, 0}, oblique[3] = {0.6, 0.8, 0.0};
  const double ys[3] = {0.5, 3.0, 9.9};
  for (int i = 0; i < 3; i++) {
    double p[3] = {1.0, ys[i], -2.0};
    slab_check("slab T_s, sun overhead", light_ref_sun_transmittance(m, p, up, 1e-12),
               exp(-k * (top - ys[i])));
    slab_check("slab T_s, sun oblique", light_ref_sun_transmittance(m, p, oblique, 1e-12),
               exp(-k * (top - ys[i]) / 0.8));
  }
  /* Horizontal at height y: T_s = e^{-K (top - y)} all along, so S = T_s (1 - e^{-K L}). */
  slab_scatter("slab horizontal inside", m, -20, 4, 3, 1, 0, 0, 30.0, up,
               exp(-k * 6) * -expm1(-k * 30));
  slab_scatter("slab horizontal through", m, -80, 7, 0, 1, 0, 0, HUGE_VAL, up,
               exp(-k * 3) * -expm1(-k * 100));
  slab_scatter("slab horizontal, oblique sun", m, 0, 4, -20, 0, 0, 1, 30.0, oblique,
               exp(-k * 6 / 0.8) * -expm1(-k * 30));
  /* Down from above: at depth s below the top tau = T_s = e^{-K s}, so
   * S = int_0^Y K e^{-2 K s} ds = (1 - e^{-2 K Y}) / 2 for a path of Y in the slab. */
  slab_scatter("slab down to the floor", m, 1, 15, 2, 0, -1, 0, HUGE_VAL, up,
               -expm1(-2 * k * 10) / 2);
  slab_scatter("slab down to a surface", m, 1, 15, 2, 0, -1, 0, 10.0, up,
               -expm1(-2 * k * 5) / 2);
  /* Obliquely down, d_y = -0.8: at path length s in the slab the depth below the top is
   * 0.8 s, so S = int_0^L K e^{-1.8 K s} ds = (1 - e^{-1.8 K L}) / 1.8, L = 10/0.8. */
  slab_scatter("slab oblique down", m, 0, 12, 0, 0.6, -0.8, 0, HUGE_VAL, up,
               -expm1(-1.8 * k * 12.5) / 1.8);
  /* Up from y = 2: tau = e^{-K u}, T_s = e^{-K (8 - u)}: the integrand is K e^{-8 K}. */
  slab_scatter("slab up", m, 0, 2, 0, 0, 1, 0, HUGE_VAL, up, k * 8 * exp(-8 * k));
}

/* The same slab as a fogmap: constant coefficients (partition of unity: f = c in the box)
 * and the slab profile, K = extinction c in x [10, 22], z [-5, 7], y [0, 10]. */
static void fogmap_slab(int degree) {
  fog_profile slab = {.kind = FOG_PROFILE_SLAB, .y_floor = 0.0, .y_top = 10.0};
  fog_volume v = small_volume(slab);
  transform_grid g = make_grid(8, degree, 1.0, 0.5);
  light_ref_medium m = light_ref_fogmap(&v, &g);
  double k = v.extinction * 0.5, up[3] = {0, 1, 0};
  slab_scatter("fogmap slab horizontal", &m, 12, 4, 1, 1, 0, 0, 8.0, up,
               exp(-k * 6) * -expm1(-k * 8));
  slab_scatter("fogmap slab down", &m, 15, 25, 1, 0, -1, 0, HUGE_VAL, up,
               -expm1(-2 * k * 10) / 2);
  transform_grid_destroy(&g);
}

/* ---- 3. height fog: T_s = exp(-K H e^{-(y - y0)/H} / w_y), and S under an overhead sun ---- */

static double worst_height_ts, worst_height_s;

static void height_sun(void) {
  light_ref_height h = {.extinction = 0.02, .y0 = 5.0, .scale_height = 50.0};
  light_ref_medium m = light_ref_height_medium(&h);
  const double ys[4] = {-100.0, 5.0, 37.0, 400.0}, wy[3] = {1.0, 0.5, 0.05};
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 3; j++) {
      double p[3] = {-12.0, ys[i], 40.0}, w[3] = {0.3, wy[j], -0.2};
      w[0] = 0.6 * sqrt(1 - wy[j] * wy[j]), w[2] = -0.8 * sqrt(1 - wy[j] * wy[j]);
      double exact = exp(-h.extinction * h.scale_height * exp(-(ys[i] - h.y0) / h.scale_height) /
                         wy[j]);
      double got = light_ref_sun_transmittance(&m, p, w, 1e-13);
      double e = fabs(got / exact - 1.0);
      if (e > worst_height_ts) worst_height_ts = e;
      CHECK(e <= 1e-10, "height T_s at y %g, w_y %g: %.15g, closed form %.15g: relative %.2e",
            ys[i], wy[j], got, exact, e);
    }
  /* Vertical rays, sun overhead. With w(y) = K H e^{-(y - y0)/H}, T_s = e^{-w} and the
   * depth from the camera at y_c down to y is w - w_c, so looking down to the ground y_g
   * S = int_{w_c}^{w_g} e^{-(w - w_c)} e^{-w} dw = e^{w_c} (e^{-2 w_c} - e^{-2 w_g}) / 2;
   * looking up, tau = e^{-(w_c - w)} and S = int_0^{w_c} e^{-w_c} dw = w_c e^{-w_c}. */
  const double up[3] = {0, 1, 0}, down[3] = {0, -1, 0}, cams[3] = {-60.0, 20.0, 150.0};
  for (int i = 0; i < 3; i++) {
    double o[3] = {2.0, cams[i], 1.0}, y_g = -80.0;
    double w_c = h.extinction * h.scale_height * exp(-(cams[i] - h.y0) / h.scale_height);
    double w_g = h.extinction * h.scale_height * exp(-(y_g - h.y0) / h.scale_height);
    double s_up = light_ref_sun_inscatter(&m, o, up, HUGE_VAL, up, 1, 1e-10, NULL);
    double e = fabs(s_up - w_c * exp(-w_c));
    if (e > worst_height_s) worst_height_s = e;
    CHECK(e <= 1e-9, "height S up from %g: %.15g, closed form %.15g: %.2e", cams[i], s_up,
          w_c * exp(-w_c), e);
    if (cams[i] <= y_g) continue;
    double s_down = light_ref_sun_inscatter(&m, o, down, cams[i] - y_g, up, 1, 1e-10, NULL);
    double exact = exp(w_c) * (exp(-2 * w_c) - exp(-2 * w_g)) / 2;
    e = fabs(s_down - exact);
    if (e > worst_height_s) worst_height_s = e;
    CHECK(e <= 1e-9, "height S down from %g: %.15g, closed form %.15g: %.2e", cams[i], s_down,
          exact, e);
  }
}

/* ---- 4. the shadowed fogmap S against a brute-force sum built on fog_oracle.c ---- */

/* Midpoint sum of tau K T_s over [a, b] in n steps, tau and T_s from fog_oracle.c's optical
 * depth (a different quadrature and nesting: running increments between the midpoints). */
static double brute_force_s(const fog_volume *v, const transform_grid *g, const double o[3],
                            const double d[3], double a, double b, const double sun[3], int n) {
  double h = (b - a) / n, s = 0.0, depth = 0.0, prev = a;
  for (int i = 0; i < n; i++) {
    double t = a + (i + 0.5) * h, p[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
    depth += fog_optical_depth_oracle(v, g, o, d, prev, t, 1e-14, NULL);
    prev = t;
    double k = fog_extinction_oracle(v, g, p);
    if (k > 0.0)
      s += exp(-depth) * k * h *
           exp(-fog_optical_depth_oracle(v, g, p, sun, 0.0, HUGE_VAL, 1e-14, NULL));
  }
  return s;
}

static double worst_brute;

static void fogmap_sun(int degree) {
  fog_volume v = small_volume(exp_profile);
  transform_grid g = make_grid(8, degree, 1.0, 0.0);
  light_ref_medium m = light_ref_fogmap(&v, &g);
  double sun[3] = {0.5, 0.6, -0.3}, p[3] = {14.0, 1.5, 2.0};
  unit(sun);
  double got = light_ref_sun_transmittance(&m, p, sun, 1e-13);
  double exact = exp(-fog_optical_depth_oracle(&v, &g, p, sun, 0.0, HUGE_VAL, 1e-13, NULL));
  CHECK(fabs(got - exact) <= 1e-12, "fogmap T_s %.15g, fog_oracle %.15g", got, exact);
  /* Shadowing only removes light: S < S1; S converges as tol shrinks. */
  double o[3] = {0, 5, 0}, q[3] = {18, 3, 2}, d[3], tau;
  aim(o, q, d);
  double s1 = light_ref_sun_inscatter(&m, o, d, HUGE_VAL, sun, 0, 1e-10, &tau);
  double s = light_ref_sun_inscatter(&m, o, d, HUGE_VAL, sun, 1, 1e-10, NULL);
  double s_fine = light_ref_sun_inscatter(&m, o, d, HUGE_VAL, sun, 1, 1e-12, NULL);
  CHECK(s < s1 && s > 0.0, "fogmap S %.15g vs S1 %.15g", s, s1);
  CHECK(fabs(s - s_fine) <= 1e-10, "fogmap S at tol 1e-10 %.15g, 1e-12 %.15g", s, s_fine);
  /* The midpoint sum's error is c h^2 + O(h^3) (kinks at the knots): Richardson of n and
   * 2n steps over the ray's stretch in the box (x from 10 to 22) leaves ~1e-11. */
  double a = 10.0 / d[0], b = 22.0 / d[0];
  double m1 = brute_force_s(&v, &g, o, d, a, b, sun, 2000);
  double m2 = brute_force_s(&v, &g, o, d, a, b, sun, 4000);
  double e = fabs((4.0 * m2 - m1) / 3.0 - s_fine);
  if (e > worst_brute) worst_brute = e;
  CHECK(e <= 1e-9, "fogmap degree %d S %.15g, brute force %.15g: %.2e", degree, s_fine,
        (4.0 * m2 - m1) / 3.0, e);
  printf("fogmap 6x6 degree %d shadowed: S %.12f (S1 %.12f); tol 1e-10 vs 1e-12 %.2e; "
         "vs brute force %.2e\n", degree, s_fine, s1, fabs(s - s_fine), e);
  transform_grid_destroy(&g);
}

static void timing(int degree) {
  fog_profile profile = {.kind = FOG_PROFILE_EXPONENTIAL, .y_floor = 0.0, .y0 = 3.0,
                         .scale_height = 4.0, .y_top = 40.0};
  fog_volume v = {.map_width = 64, .map_height = 64, .origin_x = 0.0, .origin_z = 0.0,
                  .cell_size = 2.5, .extinction = 0.05, .profile = profile};
  transform_grid g = make_grid(68, degree, 2.0, 0.0);
  light_ref_medium m = light_ref_fogmap(&v, &g);
  double sun[3] = {0.47, 0.57, 0.67}, o[3] = {-10, 20, -10}, q[3] = {150, 2, 130}, d[3];
  unit(sun); /* 35 degrees up */
  aim(o, q, d);
  enum { CALLS = 4 };
  double s = 0.0, s1 = 0.0, tau;
  clock_t start = clock();
  for (int i = 0; i < CALLS; i++)
    s = light_ref_sun_inscatter(&m, o, d, HUGE_VAL, sun, 1, 1e-9, NULL);
  double ms = 1e3 * (double)(clock() - start) / CLOCKS_PER_SEC / CALLS;
  s1 = light_ref_sun_inscatter(&m, o, d, HUGE_VAL, sun, 0, 1e-9, &tau);
  CHECK(s > 0.0 && s < s1, "64x64 degree %d: S %.15g S1 %.15g", degree, s, s1);
  CHECK(fabs(s1 - (1.0 - tau)) <= 1e-9, "64x64 degree %d: S1 %.15g 1 - tau %.15g", degree, s1,
        1.0 - tau);
  printf("64x64 fogmap degree %d, shadowed, tol 1e-9: S %.12f (S1 %.12f): %.1f ms per call\n",
         degree, s, s1, ms);
  transform_grid_destroy(&g);
}

int main(void) {
  for (int degree = 0; degree <= 2; degree++) fogmap_identity(degree);
  height_identity();
  printf("identity |S1 - (1 - tau)|: worst %.2e\n", worst_identity);
  printf("optical depth vs fog_oracle (abs) / height closed form (rel): worst %.2e\n",
         worst_depth);

  light_ref_medium slab = {.density = slab_density,
                           .box_min = {-50, 0, -50},
                           .box_max = {50, SLAB_TOP, 50}};
  slab_cases(&slab);
  fogmap_slab(1);
  fogmap_slab(2);
  printf("homogeneous slab, T_s and S closed forms: worst %.2e\n", worst_slab);

  height_sun();
  printf("height fog T_s closed form: worst relative %.2e; S (sun overhead): worst %.2e\n",
         worst_height_ts, worst_height_s);

  fogmap_sun(1);
  fogmap_sun(2);
  timing(1);
  timing(2);
  return test_finish("test_light_reference");
}
