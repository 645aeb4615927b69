/* The lamp in-scatter reference (lamp_reference.h) against what is known without it:
 *   0. the G7/K15 rule integrates polynomials of degree 13 / 22 exactly;
 *   1. homogeneous fog, isotropic phase, r -> 0: the closed form of Sun, Ramamoorthi,
 *      Narasimhan & Nayar 2005 (re-derived below), for lamps ahead, beside and behind, near
 *      and far ends; and, for any g and r, the same integral after the substitution
 *      t = t_c + w tan(theta) that removes the falloff peak (homogeneous fog only);
 *   2. exact identities: K = 0 or a = 0 gives 0, L is linear in I;
 *   3. the no-attenuation limit (K = 1e-12): closed form with atan;
 *   4. Gaussian-sum fog: optical depths and T against the erf closed form, and L against a
 *      brute-force composite Simpson sum (2e5 intervals) with closed-form tau and T;
 *   5. spots: cone containing the lit ray = point lamp; cone away = 0; cone edges crossing
 *      the ray against brute-force Simpson;
 *   6. a lamp 1e-3 from the ray with r = 1e-2: the atan limit and the theta substitution;
 *   7. visibility: a wall filling the plane z = 0 with the lamp before it; a ray through the
 *      wall's shadow is lit only past z = 0, so L with V equals L without V over the whole
 *      ray minus L without V over its shadowed start (exact), and a wall with a slit lets
 *      through what the same identity gives for the slit's stretch.
 * Prints the worst error of each group and the time per ray. Everything here is written
 * independently of the header: own adaptive Simpson, own phase and spot functions. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <time.h>

#include "lamp_reference.h"
#include "test_util.h"

#define PI 3.14159265358979323846

static double rel_err(double x, double ref) {
  return ref == 0.0 ? fabs(x) : fabs(x - ref) / fabs(ref);
}

static void unit3(double v[3]) {
  double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int i = 0; i < 3; i++) v[i] /= n;
}
static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double hg(double g, double c) {
  return (1.0 - g * g) / (4.0 * PI * pow(1.0 + g * g - 2.0 * g * c, 1.5));
}

static uint64_t rng = 0x2545F4914F6CDD1Dull;
static double uniform(double a, double b) { /* xorshift64* */
  rng ^= rng >> 12;
  rng ^= rng << 25;
  rng ^= rng >> 27;
  return a + (b - a) * (double)((rng * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

/* ---- media with closed-form optical depths ---- */

typedef struct homogeneous {
  double k;
} homogeneous;
static double homogeneous_k(const void *u, const double p[3]) {
  (void)p;
  return ((const homogeneous *)u)->k;
}
static double homogeneous_depth(const void *u, const double a[3], const double dir[3],
                                double len) {
  return ((const homogeneous *)u)->k * len;
}

/* K(x) = base + sum c_i exp(-|x - b_i|^2 / rho_i^2). */
typedef struct gaussians {
  double base;
  int n;
  double c[4], rho[4], b[4][3];
} gaussians;
static double gaussians_k(const void *u, const double p[3]) {
  const gaussians *g = (const gaussians *)u;
  double k = g->base;
  for (int i = 0; i < g->n; i++) {
    double q[3] = {p[0] - g->b[i][0], p[1] - g->b[i][1], p[2] - g->b[i][2]};
    k += g->c[i] * exp(-dot3(q, q) / (g->rho[i] * g->rho[i]));
  }
  return k;
}
/* erf(x2) - erf(x1) for x1 <= x2 without cancellation. */
static double erf_diff(double x1, double x2) {
  if (x1 > 0.0) return erfc(x1) - erfc(x2);
  if (x2 < 0.0) return erfc(-x2) - erfc(-x1);
  return erf(x2) - erf(x1);
}
/* Along a + u dir: |x - b|^2 = (u - u0)^2 + q^2 with u0 = dir.(b - a), q the perpendicular
 * distance, so int_0^L c e^{-|x-b|^2/rho^2} du = c e^{-q^2/rho^2} rho sqrt(pi)/2
 * [erf((L - u0)/rho) - erf(-u0/rho)]. */
static double gaussians_depth(const void *u, const double a[3], const double dir[3], double len) {
  const gaussians *g = (const gaussians *)u;
  double od = g->base * len;
  for (int i = 0; i < g->n; i++) {
    double q[3] = {g->b[i][0] - a[0], g->b[i][1] - a[1], g->b[i][2] - a[2]};
    double u0 = dot3(q, dir);
    double perp[3] = {q[0] - u0 * dir[0], q[1] - u0 * dir[1], q[2] - u0 * dir[2]};
    double rho = g->rho[i];
    od += g->c[i] * exp(-dot3(perp, perp) / (rho * rho)) * rho * sqrt(PI) * 0.5 *
          erf_diff(-u0 / rho, (len - u0) / rho);
  }
  return od;
}

typedef struct exact_medium {
  double (*k)(const void *user, const double p[3]);
  double (*depth)(const void *user, const double a[3], const double dir[3], double len);
  const void *user;
} exact_medium;

/* ---- own adaptive Simpson (absolute tolerance eps) ---- */

typedef double (*fn1)(const void *ctx, double x);
static double asimpson_rec(fn1 f, const void *ctx, double a, double b, double fa, double fm,
                           double fb, double whole, double eps, int depth) {
  double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  double flm = f(ctx, lm), frm = f(ctx, rm);
  double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
  double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  double delta = left + right - whole;
  /* stop at the tolerance, at the depth limit, or where the estimate reaches roundoff */
  if (depth <= 0 || fabs(delta) <= 15.0 * eps || fabs(delta) <= 1e-14 * fabs(left + right))
    return left + right + delta / 15.0;
  return asimpson_rec(f, ctx, a, m, fa, flm, fm, left, 0.5 * eps, depth - 1) +
         asimpson_rec(f, ctx, m, b, fm, frm, fb, right, 0.5 * eps, depth - 1);
}
static double asimpson(fn1 f, const void *ctx, double a, double b, double eps) {
  /* start from 16 pieces so that no feature hides between the first nodes */
  double sum = 0.0;
  for (int i = 0; i < 16; i++) {
    double x0 = a + (b - a) * i / 16.0, x1 = a + (b - a) * (i + 1) / 16.0;
    double f0 = f(ctx, x0), f1 = f(ctx, x1), fm = f(ctx, 0.5 * (x0 + x1));
    sum += asimpson_rec(f, ctx, x0, x1, f0, fm, f1, (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1),
                        eps / 16.0, 40);
  }
  return sum;
}

/* ---- check 1: Sun et al. 2005 ----
 * Camera at o, lamp at distance D_sv, gamma the angle between d and the direction to the lamp.
 * Homogeneous K, p = 1/(4 pi), r = 0, point lamp:
 *   L = a I K/(4 pi) int_0^D e^{-K t} e^{-K d(t)} / d(t)^2 dt,
 *   d(t)^2 = (t - t_c)^2 + h^2,  t_c = D_sv cos(gamma),  h = D_sv sin(gamma).
 * Put t - t_c = h tan(theta): dt / d^2 = dtheta / h, d = h / cos(theta), and
 *   K t + K d = K t_c + K h (tan(theta) + sec(theta)) = K t_c + K h tan(pi/4 + theta/2).
 * With xi = pi/4 + theta/2 (dtheta = 2 dxi): t = 0 gives theta = gamma - pi/2, xi = gamma/2;
 * t = D gives xi_1 = pi/4 + atan((D - t_c)/h)/2. Hence
 *   L = A0 [F(A1, xi_1) - F(A1, gamma/2)],  F(u, v) = int_0^v exp(-u tan(xi)) dxi,
 *   A0 = a I K e^{-T_sv cos(gamma)} / (2 pi D_sv sin(gamma)),  A1 = T_sv sin(gamma),
 *   T_sv = K D_sv, and xi_1 = pi/4 + atan((T_vp - T_sv cos gamma)/(T_sv sin gamma))/2, T_vp = K D:
 * exactly eqs. of Sun et al. 2005 (their beta = K, the 1/(4 pi) phase folded into A0). */
static double sun_integrand(const void *ctx, double xi) {
  return exp(-*(const double *)ctx * tan(xi));
}
static double sun_airlight(double k, double albedo, double intensity, double dsv, double gamma,
                           double dist) {
  double tsv = k * dsv, tvp = k * dist;
  double a0 = albedo * intensity * k * exp(-tsv * cos(gamma)) / (2.0 * PI * dsv * sin(gamma));
  double a1 = tsv * sin(gamma);
  double xi1 = PI / 4.0 + 0.5 * atan((tvp - tsv * cos(gamma)) / (tsv * sin(gamma)));
  return a0 * asimpson(sun_integrand, &a1, 0.5 * gamma, xi1, 1e-17);
}

/* Homogeneous fog, any g and r: t = t_c + w tan(theta), w = sqrt(h^2 + r^2), so
 * dt / (d^2 + r^2) = dtheta / w and the integrand K p(c) e^{-K t - K d} / w is smooth in theta;
 * c = dot(s - x, d)/d = (t_c - t)/d. */
typedef struct theta_ctx {
  double k, g, tc, h, w;
} theta_ctx;
static double theta_integrand(const void *vc, double th) {
  const theta_ctx *c = (const theta_ctx *)vc;
  double u = c->w * tan(th); /* t - t_c */
  double dist = sqrt(u * u + c->h * c->h);
  return c->k * hg(c->g, -u / dist) * exp(-c->k * (c->tc + u) - c->k * dist) / c->w;
}
static double theta_inscatter(double k, double albedo, double g, const lamp_ref_lamp *lamp,
                              const double o[3], const double d[3], double t_end) {
  double q[3] = {lamp->position[0] - o[0], lamp->position[1] - o[1], lamp->position[2] - o[2]};
  double tc = dot3(q, d);
  double perp[3] = {q[0] - tc * d[0], q[1] - tc * d[1], q[2] - tc * d[2]};
  theta_ctx c = {k, g, tc, sqrt(dot3(perp, perp)), 0.0};
  c.w = sqrt(c.h * c.h + lamp->radius * lamp->radius);
  double th0 = atan(-tc / c.w), th1 = atan((t_end - tc) / c.w);
  /* split at theta = 0 (the closest point), a coarse pass for the scale, then to 1e-14 */
  double v = 0.0, eps = 1e-300;
  for (int pass = 0; pass < 2; pass++) {
    if (th0 < 0.0 && th1 > 0.0)
      v = asimpson(theta_integrand, &c, th0, 0.0, eps) +
          asimpson(theta_integrand, &c, 0.0, th1, eps);
    else
      v = asimpson(theta_integrand, &c, th0, th1, eps);
    eps = 1e-14 * fabs(v);
  }
  return albedo * lamp->intensity * v;
}

/* No attenuation (tau = T = 1), isotropic: L = a I K/(4 pi) int dt/((t - t_c)^2 + w^2)
 *   = a I K/(4 pi w) [atan((t_end - t_c)/w) - atan(-t_c/w)]. */
static double thin_inscatter(double k, double albedo, const lamp_ref_lamp *lamp,
                             const double o[3], const double d[3], double t_end) {
  double q[3] = {lamp->position[0] - o[0], lamp->position[1] - o[1], lamp->position[2] - o[2]};
  double tc = dot3(q, d);
  double perp[3] = {q[0] - tc * d[0], q[1] - tc * d[1], q[2] - tc * d[2]};
  double w = sqrt(dot3(perp, perp) + lamp->radius * lamp->radius);
  return albedo * lamp->intensity * k / (4.0 * PI * w) *
         (atan((t_end - tc) / w) - atan(-tc / w));
}

/* Own spot factor. */
static double spot_s(const lamp_ref_lamp *lamp, const double x[3]) {
  if (!lamp->spot) return 1.0;
  double v[3] = {x[0] - lamp->position[0], x[1] - lamp->position[1], x[2] - lamp->position[2]};
  double c = dot3(lamp->axis, v) / sqrt(dot3(v, v));
  double u = fmin(1.0, fmax(0.0, (c - lamp->cos_outer) / (lamp->cos_inner - lamp->cos_outer)));
  return u * u * (3.0 - 2.0 * u);
}

/* Brute force: composite Simpson with n intervals, closed-form tau and T. */
static double brute_inscatter(const exact_medium *em, double albedo, double g,
                              const lamp_ref_lamp *lamp, const double o[3], const double d[3],
                              double t_end, int n) {
  double sum = 0.0, step = t_end / n;
  for (int i = 0; i <= n; i++) {
    double t = step * i;
    double x[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
    double v[3] = {lamp->position[0] - x[0], lamp->position[1] - x[1], lamp->position[2] - x[2]};
    double dist = sqrt(dot3(v, v));
    double w[3] = {v[0] / dist, v[1] / dist, v[2] / dist};
    double f = exp(-em->depth(em->user, o, d, t)) * em->k(em->user, x) * hg(g, dot3(w, d)) *
               exp(-em->depth(em->user, x, w, dist)) * spot_s(lamp, x) /
               (dist * dist + lamp->radius * lamp->radius);
    sum += f * (i == 0 || i == n ? 1.0 : (i & 1) ? 4.0 : 2.0);
  }
  return albedo * lamp->intensity * sum * step / 3.0;
}

static lamp_ref_lamp point_lamp(double x, double y, double z, double intensity, double radius) {
  lamp_ref_lamp l;
  memset(&l, 0, sizeof l);
  l.position[0] = x, l.position[1] = y, l.position[2] = z;
  l.intensity = intensity;
  l.radius = radius;
  return l;
}

static double run(const lamp_ref_medium *m, const lamp_ref_lamp *lamp, const double o[3],
                  const double d[3], double t_end, const char *what) {
  lamp_ref_info info;
  double v = lamp_ref_inscatter_ex(m, lamp, o, d, t_end, &info);
  CHECK(info.converged, "%s: not converged (%d segments)", what, info.segments);
  return v;
}

/* ---- 0 ---- */
static double power_fn(void *ctx, double t) { return pow(t, *(int *)ctx); }
static void rule_check(void) {
  double worst = 0.0;
  for (int k = 0; k <= 22; k++) {
    double v, e;
    lamp_ref__gk15(power_fn, &k, 0.0, 1.0, &v, &e);
    double kr = rel_err(v, 1.0 / (k + 1));
    if (k <= 13) CHECK(e < 1e-15, "G7 vs K15 differ on x^%d: %.3e", k, e); /* e = |K - G| */
    if (kr > worst) worst = kr;
  }
  CHECK(worst < 1e-14, "K15 on x^k, k <= 22: %.3e", worst);
  printf("0. GK15 on x^0..x^22 over [0,1]: worst rel %.2e (G7 = K15 to 1e-15 up to x^13)\n", worst);
}

/* ---- 1 ---- */
static void sun_check(void) {
  homogeneous hom = {0.25};
  lamp_ref_medium m = {homogeneous_k, &hom, 0.8, 0.0, 0.0, 1e-9, NULL, NULL};
  double o[3] = {1.0, -2.0, 0.5}, d[3] = {0.3, -0.5, 0.8}, n[3] = {0.8, 0.0, -0.3};
  unit3(d);
  double dn = dot3(n, d);
  for (int i = 0; i < 3; i++) n[i] -= dn * d[i];
  unit3(n);
  const double gammas[] = {10.0, 30.0, 90.0, 150.0, 175.0}; /* degrees */
  const double dsvs[] = {1.5, 4.0, 12.0};
  const double ends[] = {1.0, 8.0, 60.0};
  double worst = 0.0, worst_r0 = 0.0, worst_theta = 0.0;
  for (int ig = 0; ig < 5; ig++)
    for (int is = 0; is < 3; is++)
      for (int ie = 0; ie < 3; ie++) {
        double gamma = gammas[ig] * PI / 180.0, dsv = dsvs[is], t_end = ends[ie];
        lamp_ref_lamp lamp = point_lamp(0, 0, 0, 2.0, 1e-6 * dsv);
        for (int k = 0; k < 3; k++)
          lamp.position[k] = o[k] + dsv * (cos(gamma) * d[k] + sin(gamma) * n[k]);
        double ref = sun_airlight(hom.k, m.albedo, lamp.intensity, dsv, gamma, t_end);
        double v = run(&m, &lamp, o, d, t_end, "sun");
        double e = rel_err(v, ref);
        CHECK(e < 1e-7, "Sun et al.: gamma %g Dsv %g D %g: %.15g vs %.15g (%.2e)", gammas[ig],
              dsv, t_end, v, ref, e);
        if (e > worst) worst = e;
        /* r -> 0: the O(r^2 / h^2) softening error goes, the quadrature error stays. */
        lamp.radius = 1e-9 * dsv;
        e = rel_err(run(&m, &lamp, o, d, t_end, "sun r 1e-9"), ref);
        CHECK(e < 1e-12, "Sun et al., r 1e-9 Dsv: gamma %g Dsv %g D %g: %.2e", gammas[ig], dsv,
              t_end, e);
        if (e > worst_r0) worst_r0 = e;
        /* The same geometry with g and a large r, against the theta substitution. */
        lamp_ref_medium mg = m;
        mg.phase_g = ig & 1 ? 0.7 : -0.4;
        lamp.radius = 0.3;
        double vg = run(&mg, &lamp, o, d, t_end, "theta");
        double rg = theta_inscatter(hom.k, m.albedo, mg.phase_g, &lamp, o, d, t_end);
        e = rel_err(vg, rg);
        CHECK(e < 1e-8, "theta: gamma %g Dsv %g D %g g %g: %.15g vs %.15g (%.2e)", gammas[ig],
              dsv, t_end, mg.phase_g, vg, rg, e);
        if (e > worst_theta) worst_theta = e;
      }
  printf("1. homogeneous K %.2f, g 0, r 1e-6 Dsv vs Sun et al. 2005 closed form "
         "(45 geometries, gamma 10..175 deg, Dsv 1.5..12, D 1..60): worst rel %.2e "
         "(r 1e-9 Dsv: %.2e)\n", hom.k, worst, worst_r0);
  printf("1b. same with g 0.7 / -0.4, r 0.3 vs theta-substituted Simpson: worst rel %.2e\n",
         worst_theta);
}

/* ---- 2 ---- */
static void identity_check(void) {
  homogeneous zero = {0.0}, hom = {0.4};
  lamp_ref_medium m = {homogeneous_k, &zero, 0.9, 0.5, 0.0, 1e-9, NULL, NULL};
  double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
  lamp_ref_lamp lamp = point_lamp(3.0, 0.5, 0.0, 5.0, 0.01);
  double v0 = run(&m, &lamp, o, d, 10.0, "K = 0");
  CHECK(v0 == 0.0, "K = 0: %.3e", v0);
  m.user = &hom;
  double v1 = run(&m, &lamp, o, d, 10.0, "I");
  lamp.intensity = 12.5;
  double v2 = run(&m, &lamp, o, d, 10.0, "2.5 I");
  double lin = rel_err(v2, 2.5 * v1);
  CHECK(lin < 1e-15, "linear in I: %.17g vs 2.5 * %.17g (%.2e)", v2, v1, lin);
  m.albedo = 0.0;
  double va = run(&m, &lamp, o, d, 10.0, "a = 0");
  CHECK(va == 0.0, "a = 0: %.3e", va);
  printf("2. K = 0 -> %.1e, a = 0 -> %.1e, L(2.5 I) / (2.5 L(I)) - 1 = %.2e\n", v0, va, lin);
}

/* ---- 3 ---- */
static void thin_check(void) {
  homogeneous hom = {1e-12};
  lamp_ref_medium m = {homogeneous_k, &hom, 0.7, 0.0, 0.0, 1e-9, NULL, NULL};
  double worst = 0.0;
  for (int i = 0; i < 40; i++) {
    double o[3] = {uniform(-5, 5), uniform(-5, 5), uniform(-5, 5)};
    double d[3] = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    unit3(d);
    double t_end = uniform(0.5, 30.0);
    double tl = uniform(-5.0, 35.0), off = pow(10.0, uniform(-2.0, 1.0));
    lamp_ref_lamp lamp = point_lamp(o[0] + tl * d[0] + off * 0.6, o[1] + tl * d[1] - off * 0.8,
                                    o[2] + tl * d[2], 1.0, pow(10.0, uniform(-4.0, -1.0)));
    /* the offset (0.6, -0.8, 0) is partly along d: the closed form finds h itself */
    double v = run(&m, &lamp, o, d, t_end, "thin");
    double ref = thin_inscatter(hom.k, m.albedo, &lamp, o, d, t_end);
    double e = rel_err(v, ref);
    CHECK(e < 1e-9, "thin %d: %.15g vs %.15g (%.2e)", i, v, ref, e);
    if (e > worst) worst = e;
  }
  printf("3. K = 1e-12 (no attenuation) vs atan closed form, 40 random rays "
         "(h <~ 1e-2..10, r 1e-4..1e-1): worst rel %.2e\n", worst);
}

/* ---- 4 ---- */
static gaussians test_gaussians(void) {
  gaussians g = {0.02, 3, {0.8, 0.3, 0.15}, {0.7, 1.5, 3.0},
                 {{-3.0, 0.5, 0.0}, {1.0, -0.8, 0.4}, {4.0, 1.5, -1.0}}};
  return g;
}
static void gaussian_check(void) {
  gaussians g = test_gaussians();
  lamp_ref_medium m = {gaussians_k, &g, 0.85, 0.4, 0.7 / 4.0, 1e-9, NULL, NULL};
  double worst_od = 0.0, worst_t = 0.0;
  for (int i = 0; i < 40; i++) {
    double a[3] = {uniform(-8, 8), uniform(-3, 3), uniform(-3, 3)};
    double dir[3] = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    unit3(dir);
    double len = uniform(0.2, 25.0);
    double ref = gaussians_depth(&g, a, dir, len), od = lamp_ref_optical_depth(&m, a, dir, len);
    double e = rel_err(od, ref);
    CHECK(e < 1e-10, "optical depth %d: %.15g vs %.15g (%.2e)", i, od, ref, e);
    if (e > worst_od) worst_od = e;
    lamp_ref_lamp lamp = point_lamp(a[0] + len * dir[0], a[1] + len * dir[1],
                                    a[2] + len * dir[2], 1.0, 0.01);
    double tr = lamp_ref_transmittance_to_lamp(&m, &lamp, a);
    e = rel_err(tr, exp(-ref));
    CHECK(e < 1e-10, "T %d: %.15g vs %.15g (%.2e)", i, tr, exp(-ref), e);
    if (e > worst_t) worst_t = e;
  }
  printf("4a. Gaussian fog optical depth vs erf closed form (40 segments, tol 1e-9): worst rel "
         "%.2e; T to the lamp: worst rel %.2e\n", worst_od, worst_t);

  exact_medium em = {gaussians_k, gaussians_depth, &g};
  double o[3] = {-8.0, 0.3, -0.2}, d[3] = {1.0, 0.05, 0.02};
  unit3(d);
  const double lamps[3][3] = {{0.5, 1.8, 0.3}, {-3.5, -0.6, 1.0}, {12.0, 0.4, 2.0}};
  double worst = 0.0, worst_nocap = 0.0;
  for (int i = 0; i < 3; i++) {
    lamp_ref_lamp lamp = point_lamp(lamps[i][0], lamps[i][1], lamps[i][2], 3.0, 0.05);
    lamp_ref_info info;
    clock_t c0 = clock();
    double v = lamp_ref_inscatter_ex(&m, &lamp, o, d, 18.0, &info);
    double ms = 1e3 * (double)(clock() - c0) / CLOCKS_PER_SEC;
    CHECK(info.converged, "gaussian %d not converged", i);
    double ref = brute_inscatter(&em, m.albedo, m.phase_g, &lamp, o, d, 18.0, 200000);
    double e = rel_err(v, ref);
    CHECK(e < 1e-6, "gaussian in-scatter %d: %.15g vs Simpson %.15g (%.2e)", i, v, ref, e);
    if (e > worst) worst = e;
    lamp_ref_medium nocap = m;
    nocap.max_step = 0.0;
    c0 = clock();
    double vn = run(&nocap, &lamp, o, d, 18.0, "gaussian no cap");
    double ms_nocap = 1e3 * (double)(clock() - c0) / CLOCKS_PER_SEC;
    double en = rel_err(vn, ref);
    if (en > worst_nocap) worst_nocap = en;
    printf("   lamp %d: L %.12e, est. rel error %.1e, %d outer segments, %lld K calls, %.1f ms "
           "(max_step 0: %.1f ms)\n", i, v, info.error_estimate / v, info.segments,
           info.extinction_calls, ms, ms_nocap);
  }
  printf("4b. Gaussian fog, g 0.4, max_step 0.175: L vs composite Simpson (2e5 intervals, erf "
         "tau and T), 3 lamps: worst rel %.2e (max_step 0: %.2e)\n", worst, worst_nocap);
}

/* ---- 5 ---- */
static void spot_check(void) {
  homogeneous hom = {0.3};
  lamp_ref_medium m = {homogeneous_k, &hom, 0.75, 0.5, 0.0, 1e-9, NULL, NULL};
  double o[3] = {-6.0, 0.0, 0.0}, d[3] = {1.0, 0.0, 0.0};
  lamp_ref_lamp point = point_lamp(0.0, 2.0, 0.0, 4.0, 0.02);
  lamp_ref_lamp spot = point;
  spot.spot = true;
  spot.axis[1] = -1.0; /* down at the ray: the ray's points lie within 71.6 deg of the axis */
  spot.cos_inner = cos(85.0 * PI / 180.0);
  spot.cos_outer = cos(89.0 * PI / 180.0);
  double vp = run(&m, &point, o, d, 12.0, "point"), vs = run(&m, &spot, o, d, 12.0, "spot");
  double e_full = rel_err(vs, vp);
  CHECK(e_full < 1e-10, "spot containing the ray: %.15g vs point %.15g (%.2e)", vs, vp, e_full);
  spot.axis[1] = 1.0; /* away: every point is >= 108 deg off the axis */
  spot.cos_inner = cos(40.0 * PI / 180.0);
  spot.cos_outer = cos(60.0 * PI / 180.0);
  double v_away = run(&m, &spot, o, d, 12.0, "spot away");
  CHECK(fabs(v_away) < 1e-15 * vp, "spot away: %.3e", v_away);
  /* Cone edges crossing the ray (tilted axis): vs brute force. */
  exact_medium em = {homogeneous_k, homogeneous_depth, &hom};
  double axis[3] = {0.3, -1.0, 0.1};
  unit3(axis);
  for (int i = 0; i < 3; i++) spot.axis[i] = axis[i];
  spot.cos_inner = cos(20.0 * PI / 180.0);
  spot.cos_outer = cos(40.0 * PI / 180.0);
  double v_edge = run(&m, &spot, o, d, 12.0, "spot edge");
  double ref = brute_inscatter(&em, m.albedo, m.phase_g, &spot, o, d, 12.0, 200000);
  double e_edge = rel_err(v_edge, ref);
  CHECK(e_edge < 1e-8, "spot edges: %.15g vs Simpson %.15g (%.2e)", v_edge, ref, e_edge);
  double ref_point = brute_inscatter(&em, m.albedo, m.phase_g, &point, o, d, 12.0, 200000);
  double e_point = rel_err(vp, ref_point);
  CHECK(e_point < 1e-8, "point: %.15g vs Simpson %.15g (%.2e)", vp, ref_point, e_point);
  printf("5. spot with the ray inside the inner cone vs point lamp: rel %.2e; cone pointing "
         "away: %.1e; cone edges across the ray vs Simpson: rel %.2e (point vs Simpson %.2e)\n",
         e_full, v_away, e_edge, e_point);
}

/* ---- 6 ---- */
static void near_check(void) {
  double o[3] = {0.5, -1.0, 2.0}, d[3] = {0.6, 0.64, -0.48};
  unit3(d);
  double n[3] = {0.8, -0.6, 0.2};
  double dn = dot3(n, d);
  for (int i = 0; i < 3; i++) n[i] -= dn * d[i];
  unit3(n);
  homogeneous thin = {1e-12}, hom = {0.3};
  double worst_thin = 0.0, worst_theta = 0.0, lo = 0.0, hi = 0.0;
  /* lamp mid-ray, near either end, just behind the camera, and beyond a ray that stops short */
  const double tls[] = {4.0, 0.0005, 9.9995, -0.01, 4.0};
  const double ends[] = {10.0, 10.0, 10.0, 10.0, 3.5};
  for (int i = 0; i < 5; i++)
    for (int on_ray = 0; on_ray <= 1; on_ray++) {
      double t_end = ends[i], tl = tls[i], h = on_ray ? 0.0 : 1e-3;
      lamp_ref_lamp lamp = point_lamp(0, 0, 0, 1.0, 1e-2);
      for (int k = 0; k < 3; k++) lamp.position[k] = o[k] + tl * d[k] + h * n[k];
      lamp_ref_medium m = {homogeneous_k, &thin, 0.6, 0.0, 0.0, 1e-9, NULL, NULL};
      double v = run(&m, &lamp, o, d, t_end, "near thin");
      double e = rel_err(v, thin_inscatter(thin.k, m.albedo, &lamp, o, d, t_end));
      CHECK(e < 1e-9, "near thin t_l %g h %g: %.2e", tl, h, e);
      if (e > worst_thin) worst_thin = e;
      if (on_ray) continue; /* c jumps at t_c when h = 0: no smooth theta integrand */
      m.user = &hom;
      for (int s = -1; s <= 1; s += 2) {
        m.phase_g = 0.8 * s;
        double vg = run(&m, &lamp, o, d, t_end, "near theta");
        double rg = theta_inscatter(hom.k, m.albedo, m.phase_g, &lamp, o, d, t_end);
        e = rel_err(vg, rg);
        CHECK(e < 1e-8, "near t_l %g g %g: %.15g vs %.15g (%.2e)", tl, m.phase_g, vg, rg, e);
        if (e > worst_theta) worst_theta = e;
        if (i == 4) *(s < 0 ? &lo : &hi) = vg;
      }
    }
  /* The ray stops 0.5 short of the lamp, which every point sees straight ahead (c = 1 to
   * 2e-6): the ratio is p(0.8, 1) / p(-0.8, 1) = (1.8 / 0.2^2) / (0.2 / 1.8^2) = 729. */
  double ratio = hi / lo;
  CHECK(fabs(ratio / 729.0 - 1.0) < 1e-4, "forward peak: L(g 0.8) / L(g -0.8) = %.6f", ratio);
  printf("6. lamp 1e-3 from the ray (and on it), r 1e-2, lamp mid-ray, near the ends, just behind, "
         "beyond the end: K 1e-12 vs atan closed form: worst rel %.2e; K 0.3, g +-0.8 vs theta "
         "substitution: worst rel %.2e; lamp ahead: L(g 0.8) / L(g -0.8) = %.3f (729)\n",
         worst_thin, worst_theta, ratio);
}

/* V of section 7: a wall in the plane z = 0, open where |x| < slit (slit 0: no opening),
 * the lamp on the side z > 0. */
static bool wall_visible(const void *u, const double x[3], const double lamp[3]) {
  const double slit = *(const double *)u;
  if ((x[2] > 0) == (lamp[2] > 0)) return true;
  const double f = lamp[2] / (lamp[2] - x[2]); /* where the segment meets z = 0 */
  const double cross = lamp[0] + f * (x[0] - lamp[0]);
  return fabs(cross) < slit;
}

static void visibility_check(void) {
  const double hom = 0.05, no_slit = 0.0, slit = 0.5;
  lamp_ref_medium plain = {homogeneous_k, &hom, 0.8, 0.3, 0.0, 1e-10, NULL, NULL};
  lamp_ref_medium walled = plain, slitted = plain;
  walled.visible = wall_visible, walled.visible_user = &no_slit;
  slitted.visible = wall_visible, slitted.visible_user = &slit;
  const lamp_ref_lamp lamp = point_lamp(0.3, 1.0, 2.0, 100.0, 0.2);
  double worst = 0, worst_slit = 0;
  for (int k = 0; k < 6; k++) {
    /* from behind the wall (z < 0) through it at a slant */
    double o[3] = {uniform(-3, 3), uniform(-2, 2), -uniform(3, 8)}, d[3] = {uniform(-0.3, 0.3),
                   uniform(-0.3, 0.3), 1.0};
    unit3(d);
    const double t_wall = -o[2] / d[2], t_end = t_wall + uniform(2, 10);
    const double whole = run(&plain, &lamp, o, d, t_end, "7. visibility"), start = run(&plain, &lamp, o, d, t_wall, "7. visibility");
    worst = fmax(worst, rel_err(run(&walled, &lamp, o, d, t_end, "7. visibility"), whole - start));
    /* the slit's stretches behind the wall: the segment from x(t) to the lamp meets z = 0 at
     * x = c where L2 x0(t) + (c - L0) x2(t) - c L2 = 0, linear in t; the roots for c = -+
     * slit cut [0, t_wall] into pieces lit or dark throughout (V at a piece's middle) */
    double want = whole - start, cuts[4] = {0.0, t_wall, t_wall, t_wall};
    for (int e = 0; e < 2; e++) {
      const double c = e ? slit : -slit, *L = lamp.position;
      const double t = -(L[2] * o[0] + (c - L[0]) * o[2] - c * L[2]) /
                       (L[2] * d[0] + (c - L[0]) * d[2]);
      if (t > 0 && t < t_wall) cuts[1 + e] = t;
    }
    if (cuts[1] > cuts[2]) {
      const double swap = cuts[1];
      cuts[1] = cuts[2], cuts[2] = swap;
    }
    for (int piece = 0; piece < 3; piece++) {
      const double mid = 0.5 * (cuts[piece] + cuts[piece + 1]);
      const double x[3] = {o[0] + mid * d[0], o[1] + mid * d[1], o[2] + mid * d[2]};
      if (cuts[piece] < cuts[piece + 1] && wall_visible(&slit, x, lamp.position))
        want += run(&plain, &lamp, o, d, cuts[piece + 1], "7. visibility") -
                run(&plain, &lamp, o, d, cuts[piece], "7. visibility");
    }
    worst_slit = fmax(worst_slit, rel_err(run(&slitted, &lamp, o, d, t_end, "7. visibility"), want));
  }
  printf("7. visibility: a wall %.2e, a wall with a slit %.2e (relative, 6 rays)\n", worst,
         worst_slit);
  CHECK(worst < 1e-8, "reference with V off the identity by %.2e", worst);
  CHECK(worst_slit < 1e-6, "reference with a slit off by %.2e", worst_slit);
}

int main(void) {
  clock_t c0 = clock();
  visibility_check();
  rule_check();
  sun_check();
  identity_check();
  thin_check();
  gaussian_check();
  spot_check();
  near_check();
  printf("total CPU time %.2f s\n", (double)(clock() - c0) / CLOCKS_PER_SEC);
  return test_finish("test_lamp_reference");
}
