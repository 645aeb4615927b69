/* Lamps in the fog, the CPU twin of fog_lamps.glsl (render/fog_lamp.h): sample for sample
 * what the shader takes, in double. */
#include "render/fog_lamp.h"

#include <math.h>

#include "render/fog_light.h"
#include "render/fog_sun_shadow.h"

/* A visibility callback bound to one lamp (NULL: V = 1). */
typedef struct fog_lamp_visibility {
  fog_lamp_visibility_fn visible;
  const void *user;
  int lamp;
} fog_lamp_visibility;

/* Gauss-Legendre, 4 nodes on [-1, 1]. */
static const double gl4_x[4] = {-0.86113631159405258, -0.33998104358485626,
                                0.33998104358485626, 0.86113631159405258};
static const double gl4_w[4] = {0.34785484513745386, 0.65214515486254614,
                                0.65214515486254614, 0.34785484513745386};

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void fog_lamps_pack(const fog_lamps *lamps, const double camera[3], double intensity_scale,
                    fog_lamp_uniforms *out) {
  for (int i = 0; i < lamps->count && i < FOG_MAX_LAMPS; i++) {
    const fog_lamp *l = &lamps->lamp[i];
    const bool spot = l->kind == FOG_LAMP_SPOT;
    for (int a = 0; a < 3; a++) {
      out->position[i][a] = (float)(l->position[a] - camera[a]);
      out->intensity[i][a] = (float)(intensity_scale * l->intensity[a]);
      out->axis[i][a] = spot ? (float)l->axis[a] : 0.0f;
    }
    out->axis[i][3] = spot ? 1.0f : 0.0f;
    out->cone[i][0] = spot ? (float)l->cos_outer : 0.0f;
    out->cone[i][1] = spot ? (float)(1.0 / (l->cos_inner - l->cos_outer)) : 0.0f;
    out->cone[i][2] = (float)(l->radius * l->radius);
  }
}

bool fog_lamps_have_spot(const fog_lamps *lamps) {
  for (int i = 0; i < lamps->count; i++)
    if (lamps->lamp[i].kind == FOG_LAMP_SPOT) return true;
  return false;
}

bool fog_lamps_equal(const fog_lamps *a, const fog_lamps *b) {
  if (a->count != b->count) return false;
  for (int i = 0; i < a->count && i < FOG_MAX_LAMPS; i++) {
    const fog_lamp *p = &a->lamp[i], *q = &b->lamp[i];
    if (p->kind != q->kind || p->radius != q->radius || p->cos_inner != q->cos_inner ||
        p->cos_outer != q->cos_outer)
      return false;
    for (int c = 0; c < 3; c++)
      if (p->position[c] != q->position[c] || p->intensity[c] != q->intensity[c] ||
          p->axis[c] != q->axis[c])
        return false;
  }
  return true;
}

double fog_lamp_spot(const fog_lamp *lamp, const double x[3]) {
  if (lamp->kind != FOG_LAMP_SPOT) return 1.0;
  double v[3] = {x[0] - lamp->position[0], x[1] - lamp->position[1], x[2] - lamp->position[2]};
  double len = sqrt(dot3(v, v));
  if (!(len > 0.0)) return 1.0;
  double c = dot3(v, lamp->axis) / len;
  double u = (c - lamp->cos_outer) / (lamp->cos_inner - lamp->cos_outer);
  u = fmin(fmax(u, 0.0), 1.0);
  return u * u * (3.0 - 2.0 * u); /* smoothstep */
}

/* Optical depth from the camera along the ray at the ends of `steps` equal segments of
 * [t0, t0 + steps dt]: table[k] at t0 + k dt, by the midpoint rule. */
static void depth_table(const fog_model *m, const double o[3], const double d[3], double t0,
                        double dt, int steps, double *table) {
  table[0] = 0.0;
  for (int k = 0; k < steps; k++) {
    double t = t0 + (k + 0.5) * dt, p[3];
    for (int a = 0; a < 3; a++) p[a] = o[a] + t * d[a];
    table[k + 1] = table[k] + fog_light_extinction_at(m, p) * dt;
  }
}

static double depth_at(const double *table, int steps, double t0, double dt, double t) {
  double u = (t - t0) / dt;
  int k = (int)floor(u);
  k = k < 0 ? 0 : (k > steps - 1 ? steps - 1 : k);
  double f = fmin(fmax(u - k, 0.0), 1.0);
  return table[k] + f * (table[k + 1] - table[k]);
}

/* The analytic models' optical depths are closed forms (fog_models.h): tau and T exact. */
static bool exact_depths(const fog_model *m) {
  return m->kind == FOG_MODEL_HOMOGENEOUS || m->kind == FOG_MODEL_HEIGHT ||
         m->kind == FOG_MODEL_RBF || m->kind == FOG_MODEL_QUADRIC;
}

/* The integrand's factors besides K at world point x of the ray (at t): tau p S T over
 * the falloff, with the closed-form depths (FOG_LAMP_FOGSHOP's sample). */
static double lamp_factor_exact(const fog_model *m, const fog_lamp *lamp, double g,
                                const double o[3], const double d[3], double t) {
  double x[3], to_lamp[3];
  for (int a = 0; a < 3; a++) x[a] = o[a] + t * d[a], to_lamp[a] = lamp->position[a] - x[a];
  double dist = sqrt(dot3(to_lamp, to_lamp)), shadow = 0.0;
  double cos_theta = dist > 0.0 ? dot3(to_lamp, d) / dist : 1.0;
  if (dist > 0.0) {
    double w[3] = {to_lamp[0] / dist, to_lamp[1] / dist, to_lamp[2] / dist};
    shadow = fog_model_optical_depth(m, x, w, dist);
  }
  return exp(-fog_model_optical_depth(m, o, d, t) - shadow) * fog_phase_hg(g, cos_theta) *
         fog_lamp_spot(lamp, x) / (dist * dist + lamp->radius * lamp->radius);
}

/* What one lamp's pieces share: the lamp, the ray, the angle variable's t_s and h', the
 * camera's depth table over [t0, t0 + steps dt], and V (NULL: 1). */
typedef struct lamp_ray {
  const fog_model *m;
  const fog_lamp *lamp;
  const fog_lamp_method *method;
  double g;
  const double *o, *d;
  double t0, dt, ts, hp;
  const double *table;
  bool base_only; /* the RBF model's homogeneous base alone, K, tau and T, no V
                     (FOG_LAMP_FOGSHOP's base term: Sun et al.'s airlight of a homogeneous
                     medium, which the Gaussians do not shadow) */
  const fog_lamp_visibility *vis;
} lamp_ray;

/* The angle of node n of the piece [phi_a, phi_b]. */
static double lamp_node(double phi_a, double phi_b, int n) {
  return phi_a + 0.5 * (1.0 + gl4_x[n]) * (phi_b - phi_a);
}

/* The integrand tau K p S T (V apart) at the 4 nodes of [phi_a, phi_b] where need[n]
 * (fog_lamp_node_values; 0 elsewhere). */
static void lamp_node_values(const lamp_ray *r, double phi_a, double phi_b, const bool need[4],
                             double f[4]) {
  const fog_model *m = r->m;
  const fog_lamp *lamp = r->lamp;
  const fog_lamp_method *method = r->method;
  const double *o = r->o, *d = r->d;
  for (int n = 0; n < 4; n++) {
    f[n] = 0.0;
    if (!need[n]) continue;
    double t = r->ts + r->hp * tan(lamp_node(phi_a, phi_b, n)), x[3], to_lamp[3];
    for (int a = 0; a < 3; a++) x[a] = o[a] + t * d[a];
    double spot = fog_lamp_spot(lamp, x);
    if (!(spot > 0.0)) continue;
    double k = r->base_only ? m->extinction : fog_light_extinction_at(m, x);
    if (!(k > 0.0)) continue;
    for (int a = 0; a < 3; a++) to_lamp[a] = lamp->position[a] - x[a];
    double dist = sqrt(dot3(to_lamp, to_lamp));
    double cos_theta = dist > 0.0 ? dot3(to_lamp, d) / dist : 1.0;
    double depth, shadow = 0.0;
    if (r->base_only) { /* Sun et al.'s homogeneous medium: the base alone */
      depth = m->extinction * fmax(t, 0.0);
      shadow = m->extinction * dist;
    } else if (exact_depths(m)) {
      depth = fog_model_optical_depth(m, o, d, t);
      if (dist > 0.0) {
        double w[3] = {to_lamp[0] / dist, to_lamp[1] / dist, to_lamp[2] / dist};
        shadow = fog_model_optical_depth(m, x, w, dist);
      }
    } else {
      /* the classic factors' depth from the camera is the factor itself (a table would
       * miss its fall to 0 at the linear fog's end, where K grows without bound); their
       * shadow rays are marched, as in GLSL, where a segment's closed form cancels */
      depth = fog_model_about_eye(m) ? fog_model_optical_depth(m, o, d, t)
                                  : depth_at(r->table, method->depth_steps, r->t0, r->dt, t);
      /* T: midpoint steps from x to the lamp */
      double ds = dist / method->shadow_steps;
      for (int j = 0; j < method->shadow_steps; j++) {
        double f = (j + 0.5) / method->shadow_steps, q[3];
        for (int a = 0; a < 3; a++) q[a] = x[a] + f * to_lamp[a];
        shadow += fog_light_extinction_at(m, q) * ds;
      }
    }
    double tau = exp(-depth);
    /* at the linear fog's end (K infinite, tau 0, rounding either way) no light comes back */
    if (tau == 0.0 || !(k < HUGE_VAL)) continue;
    f[n] = tau * k * fog_phase_hg(r->g, cos_theta) * spot * exp(-shadow);
  }
}

/* One piece with V given at its nodes (fog_lamp_piece): 4 nodes of f V, times dphi / 2. */
static double lamp_piece(const lamp_ray *r, double phi_a, double phi_b, const double visible[4]) {
  if (!(phi_b > phi_a)) return 0.0;
  bool need[4];
  double f[4], sum = 0.0;
  for (int n = 0; n < 4; n++) need[n] = visible[n] > 0.0;
  lamp_node_values(r, phi_a, phi_b, need, f);
  for (int n = 0; n < 4; n++) sum += gl4_w[n] * f[n] * visible[n];
  return 0.5 * (phi_b - phi_a) * sum;
}

/* V at angle phi (the callback's). */
static double lamp_visible_at(const lamp_ray *r, double phi) {
  double t = r->ts + r->hp * tan(phi), x[3];
  for (int a = 0; a < 3; a++) x[a] = r->o[a] + t * r->d[a];
  return r->vis->visible(r->vis->user, r->vis->lamp, x);
}

static void lamp_node_visibility(const lamp_ray *r, double phi_a, double phi_b, double v[4]) {
  for (int n = 0; n < 4; n++) v[n] = lamp_visible_at(r, lamp_node(phi_a, phi_b, n));
}

void fog_lamp_lagrange_integrals(double u0, double u1, double out[4]) {
  for (int n = 0; n < 4; n++) {
    /* L_n = prod_{m != n} (u - x_m) / (x_n - x_m), expanded into powers of u */
    double c[4] = {1.0, 0.0, 0.0, 0.0}, den = 1.0;
    int degree = 0;
    for (int m = 0; m < 4; m++) {
      if (m == n) continue;
      for (int j = ++degree; j >= 0; j--) c[j] = (j > 0 ? c[j - 1] : 0.0) - gl4_x[m] * c[j];
      den *= gl4_x[n] - gl4_x[m];
    }
    double sum = 0.0, p0 = u0, p1 = u1;
    for (int j = 0; j < 4; j++, p0 *= u0, p1 *= u1) sum += c[j] * (p1 - p0) / (j + 1);
    out[n] = sum / den;
  }
}

/* A piece with V known at its ends and nodes (fog_lamp_piece_shadowed): lit bit 0 the start,
 * 1-4 the nodes, 5 the end; a piece an edge crosses integrates the cubic through f's nodes
 * over its lit stretches. */
static double lamp_piece_shadowed(const lamp_ray *r, double phi_a, double phi_b, unsigned lit,
                                  const double visible[4]) {
  const bool some = visible[0] > 0.0 || visible[1] > 0.0 || visible[2] > 0.0 || visible[3] > 0.0;
  if (lit == 63u || (lit == 0u && some)) return lamp_piece(r, phi_a, phi_b, visible);
  if (lit == 0u) return 0.0;
  static const bool all[4] = {true, true, true, true};
  double f[4], w[4];
  lamp_node_values(r, phi_a, phi_b, all, f);
  const double dphi = phi_b - phi_a;
  double start = -1.0, before_at = phi_a, total = 0.0;
  for (int k = 1; k <= 5; k++) {
    double at = k == 5 ? phi_b : lamp_node(phi_a, phi_b, k - 1);
    bool before = (lit >> (k - 1)) & 1u, now = (lit >> k) & 1u;
    if (now != before) {
      double lo = before_at, hi = at;
      for (int b = 0; b < FOG_LAMP_EDGE_BISECTIONS; b++) {
        double mid = 0.5 * (lo + hi);
        if ((lamp_visible_at(r, mid) >= 0.5) == before) lo = mid; else hi = mid;
      }
      double edge = 2.0 * (0.5 * (lo + hi) - phi_a) / dphi - 1.0;
      if (before) {
        fog_lamp_lagrange_integrals(start, edge, w);
        for (int n = 0; n < 4; n++) total += f[n] * w[n];
      }
      start = edge;
    }
    before_at = at;
  }
  if (lit & 32u) {
    fog_lamp_lagrange_integrals(start, 1.0, w);
    for (int n = 0; n < 4; n++) total += f[n] * w[n];
  }
  return 0.5 * dphi * total;
}

/* The angles phi (t = ts + hp tan phi) where the ray o + t d crosses a spot's cones
 * cos = cos_outer and cos = cos_inner (fog_lamp_cone_cuts in GLSL): the smoothstep's kinks,
 * and the edges of a beam narrower than a piece's nodes (an outer half-angle of 2 degrees
 * fell between them: the beam drawn dashed). With w = t d - s (s the lamp from o, a the
 * axis), (w.a)^2 = c^2 |w|^2 is A t^2 + 2 B t + E = 0, A = alpha^2 - c^2,
 * B = c^2 ts - alpha beta, E = beta^2 - c^2 |s|^2 (alpha = d.a, beta = s.a); a root counts
 * where w.a has c's sign (the cone, not its mirror). Its discriminant
 * B^2 - A E = c^2 (|beta d - alpha s|^2 - c^2 h^2), h the lamp's distance from the ray's
 * line, from the two vectors' lengths: as B^2 - A E it cancelled in float for a ray grazing
 * the cone near the lamp (2 ulps of B^2 left, the cuts inside the beam's sliver); this way
 * it still loses ~1/sin^2 of the half-angle (u2 = h2 - (a.(s x d))^2), so below half a
 * degree the tolerance below also cuts rays that miss the beam at their grazing point
 * (harmless: a piece boundary more, counted in the loop bound). A grazing ray whose
 * discriminant rounds a little below 0 is cut at the grazing point. HUGE_VAL for none, and
 * for a point lamp. */
static void lamp_cone_cuts(const fog_lamp *lamp, const double s[3], const double d[3],
                           double ts, double hp, const double h[3], double cuts[4]) {
  for (int k = 0; k < 4; k++) cuts[k] = HUGE_VAL;
  if (lamp->kind != FOG_LAMP_SPOT) return;
  const double alpha = dot3(d, lamp->axis), beta = dot3(s, lamp->axis), sigma = dot3(s, s);
  double u[3];
  for (int k = 0; k < 3; k++) u[k] = beta * d[k] - alpha * s[k];
  const double u2 = dot3(u, u), h2 = dot3(h, h);
  for (int cone = 0; cone < 2; cone++) {
    const double c = cone ? lamp->cos_inner : lamp->cos_outer, c2 = c * c;
    const double a = alpha * alpha - c2, b = c2 * ts - alpha * beta, e = beta * beta - c2 * sigma;
    const double disc = c2 * (u2 - c2 * h2);
    if (!(disc >= -1e-4 * c2 * u2)) continue;
    const double q = -(b + copysign(sqrt(fmax(disc, 0.0)), b));
    const double roots[2] = {a != 0.0 ? q / a : HUGE_VAL, q != 0.0 ? e / q : HUGE_VAL};
    for (int k = 0; k < 2; k++) {
      const double t = roots[k];
      if (isfinite(t) && (t * alpha - beta) * c >= 0.0)
        cuts[2 * cone + k] = atan((t - ts) / hp);
    }
  }
}

/* One lamp, per unit a I, over [t0, t1] with the camera's depth table. */
static double lamp_unit(const fog_model *m, const fog_lamp *lamp, const fog_lamp_method *method,
                        double g, const double o[3], const double d[3], double t0, double t1,
                        const double *table, bool base_only, const fog_lamp_visibility *vis) {
  double s[3] = {lamp->position[0] - o[0], lamp->position[1] - o[1], lamp->position[2] - o[2]};
  double ts = dot3(s, d), hv[3];
  for (int a = 0; a < 3; a++) hv[a] = s[a] - ts * d[a];
  double hp = sqrt(dot3(hv, hv) + lamp->radius * lamp->radius);
  const lamp_ray r = {.m = m, .lamp = lamp, .method = method, .g = g, .o = o, .d = d, .t0 = t0,
                      .dt = (t1 - t0) / method->depth_steps, .ts = ts, .hp = hp,
                      .table = table, .base_only = base_only, .vis = vis};
  double phi0 = atan((t0 - ts) / hp), phi1 = atan((t1 - ts) / hp), total = 0.0;
  /* The pieces: the union of angle_pieces equal steps of phi (the halo) and span_pieces
   * equal steps of t (the fog far from the lamp, which phi compresses), merged in order,
   * and cuts at phi = 0, the closest point, where the direction to the lamp turns (for a
   * lamp on the ray the phase function jumps there), at a spot's cone crossings, and where
   * the ray crosses a quadric volume's surface (K's steps and kinks: a hard-edged sphere
   * lit by a lamp drew rings, as under the sun; fog_sun_mean_light). */
  const int na = method->angle_pieces, nt = method->span_pieces;
  double phi_a = phi0, cuts[5 + FOG_QUADRIC_MAX_CUTS];
  lamp_cone_cuts(lamp, s, d, ts, hp, hv, cuts);
  cuts[4] = 0.0;
  int cut_count = 5;
  if (m->quadrics && m->quadric_count > 0 && !base_only) {
    const int n = fog_quadric_cuts(m->quadrics, m->quadric_count, o, d, t0, t1, cuts + 5);
    for (int k = 0; k < n; k++) cuts[5 + k] = atan((cuts[5 + k] - ts) / hp);
    cut_count += n;
  }
  const bool shadowed = vis && !base_only;
  bool lit_a = shadowed && lamp_visible_at(&r, phi0) >= 0.5; /* V at the piece's start */
  for (int ia = 1, it = 1; ia <= na || it <= nt;) {
    double next_a = ia <= na ? phi0 + ia * (phi1 - phi0) / na : HUGE_VAL;
    double next_t = it <= nt ? atan((t0 + it * (t1 - t0) / nt - ts) / hp) : HUGE_VAL;
    double phi_b = next_a <= next_t ? next_a : next_t, next_cut = HUGE_VAL;
    for (int k = 0; k < cut_count; k++)
      if (cuts[k] > phi_a && cuts[k] < next_cut) next_cut = cuts[k];
    if (next_cut < phi_b) {
      phi_b = next_cut;
    } else if (next_a <= next_t) {
      ia++;
    } else {
      it++;
    }
    if (shadowed && phi_b > phi_a) { /* with V at the nodes and the end, any edge is found */
      double v[4];
      lamp_node_visibility(&r, phi_a, phi_b, v);
      bool lit_b = lamp_visible_at(&r, phi_b) >= 0.5;
      unsigned lit = (lit_a ? 1u : 0u) | (lit_b ? 32u : 0u);
      for (int n = 0; n < 4; n++) lit |= v[n] >= 0.5 ? 2u << n : 0u;
      total += lamp_piece_shadowed(&r, phi_a, phi_b, lit, v);
      lit_a = lit_b;
    } else {
      static const double unshadowed[4] = {1.0, 1.0, 1.0, 1.0};
      total += lamp_piece(&r, phi_a, phi_b, unshadowed);
    }
    phi_a = phi_b;
  }
  return total / hp;
}

/* FOG_LAMP_FOGSHOP (fog_lamp.h): the base by the angle integral, each Gaussian sampled at
 * its centre's projection on the ray (clamped to the span) times its own optical depth. */
static double lamp_unit_fogshop(const fog_model *m, const fog_lamp *lamp,
                                const fog_lamp_method *method, double g, const double o[3],
                                const double d[3], double t0, double t1) {
  static const double half_sqrt_pi = 0.88622692545275801;
  double sum = m->extinction > 0.0 ? lamp_unit(m, lamp, method, g, o, d, t0, t1, NULL, true, NULL) : 0.0;
  for (int i = 0; i < m->rbf_count; i++) {
    const fog_rbf *b = &m->rbfs[i];
    double v[3], w[3];
    for (int a = 0; a < 3; a++) v[a] = b->centre[a] - o[a];
    double tc = dot3(v, d);
    for (int a = 0; a < 3; a++) w[a] = v[a] - tc * d[a];
    double inv_r = 1.0 / b->radius;
    double depth = b->density * exp(-dot3(w, w) * inv_r * inv_r) * b->radius * half_sqrt_pi *
                   fog_erf_difference((t0 - tc) * inv_r, (t1 - tc) * inv_r);
    if (!(depth > 0.0)) continue;
    sum += depth * lamp_factor_exact(m, lamp, g, o, d, fmin(fmax(tc, t0), t1));
  }
  return sum;
}

/* FOG_LAMP_MARCH: midpoint samples of t, tau summed along them (to each sample's middle),
 * T as lamp_unit's; the falloff sampled as it is (no angle variable). */
static double lamp_unit_march(const fog_model *m, const fog_lamp *lamp,
                              const fog_lamp_method *method, double g, const double o[3],
                              const double d[3], double t0, double t1,
                              const fog_lamp_visibility *vis) {
  const int n = method->march_steps;
  const double dt = (t1 - t0) / n;
  double before = 0.0, sum = 0.0;
  for (int i = 0; i < n; i++) {
    double t = t0 + (i + 0.5) * dt, x[3], to_lamp[3];
    for (int a = 0; a < 3; a++) x[a] = o[a] + t * d[a], to_lamp[a] = lamp->position[a] - x[a];
    double k = fog_light_extinction_at(m, x);
    double tau = exp(-(before + 0.5 * k * dt));
    before += k * dt;
    double lit = fog_lamp_spot(lamp, x);
    if (vis && lit > 0.0) lit *= vis->visible(vis->user, vis->lamp, x);
    if (!(k > 0.0) || !(lit > 0.0)) continue;
    double dist = sqrt(dot3(to_lamp, to_lamp)), shadow = 0.0;
    double cos_theta = dist > 0.0 ? dot3(to_lamp, d) / dist : 1.0;
    if (exact_depths(m)) {
      if (dist > 0.0) {
        double w[3] = {to_lamp[0] / dist, to_lamp[1] / dist, to_lamp[2] / dist};
        shadow = fog_model_optical_depth(m, x, w, dist);
      }
    } else {
      double ds = dist / method->shadow_steps;
      for (int j = 0; j < method->shadow_steps; j++) {
        double f = (j + 0.5) / method->shadow_steps, q[3];
        for (int a = 0; a < 3; a++) q[a] = x[a] + f * to_lamp[a];
        shadow += fog_light_extinction_at(m, q) * ds;
      }
    }
    sum += tau * k * fog_phase_hg(g, cos_theta) * lit * exp(-shadow) /
           (dist * dist + lamp->radius * lamp->radius);
  }
  return sum * dt;
}

double fog_lamp_inscatter_unit(const fog_model *m, const fog_lamp *lamp,
                               const fog_lamp_method *method, double g, const double o[3],
                               const double d[3], double t_surface) {
  double t0, t1, table[FOG_LAMP_MAX_DEPTH_STEPS + 1] = {0};
  if (!fog_light_span(m, o, d, t_surface, &t0, &t1)) return 0.0;
  if (method->integral == FOG_LAMP_FOGSHOP && m->kind == FOG_MODEL_RBF)
    return lamp_unit_fogshop(m, lamp, method, g, o, d, t0, t1);
  if (method->integral == FOG_LAMP_MARCH)
    return lamp_unit_march(m, lamp, method, g, o, d, t0, t1, NULL);
  if (!exact_depths(m) && !fog_model_about_eye(m)) /* the classic factors: their own */
    depth_table(m, o, d, t0, (t1 - t0) / method->depth_steps, method->depth_steps, table);
  return lamp_unit(m, lamp, method, g, o, d, t0, t1, table, false, NULL);
}

void fog_lamps_inscatter_shadowed(const fog_model *m, const fog_lamps *lamps, double albedo,
                                  double g, const double o[3], const double d[3],
                                  double t_surface, fog_lamp_visibility_fn visible,
                                  const void *user, double out[3]) {
  out[0] = out[1] = out[2] = 0.0;
  double t0, t1, table[FOG_LAMP_MAX_DEPTH_STEPS + 1] = {0};
  if (lamps->count == 0 || !(albedo > 0.0) || !fog_light_span(m, o, d, t_surface, &t0, &t1))
    return;
  const fog_lamp_method *method = &lamps->method;
  if (!exact_depths(m) && !fog_model_about_eye(m)) /* the classic factors: their own */
    depth_table(m, o, d, t0, (t1 - t0) / method->depth_steps, method->depth_steps, table);
  const bool fogshop = method->integral == FOG_LAMP_FOGSHOP && m->kind == FOG_MODEL_RBF;
  for (int i = 0; i < lamps->count; i++) {
    const fog_lamp_visibility vis = {visible, user, i}, *v = visible ? &vis : NULL;
    double unit = fogshop ? lamp_unit_fogshop(m, &lamps->lamp[i], method, g, o, d, t0, t1)
                  : method->integral == FOG_LAMP_MARCH
                      ? lamp_unit_march(m, &lamps->lamp[i], method, g, o, d, t0, t1, v)
                      : lamp_unit(m, &lamps->lamp[i], method, g, o, d, t0, t1, table, false, v);
    for (int c = 0; c < 3; c++) out[c] += albedo * lamps->lamp[i].intensity[c] * unit;
  }
}

void fog_lamps_inscatter(const fog_model *m, const fog_lamps *lamps, double albedo, double g,
                         const double o[3], const double d[3], double t_surface, double out[3]) {
  fog_lamps_inscatter_shadowed(m, lamps, albedo, g, o, d, t_surface, NULL, NULL, out);
}
