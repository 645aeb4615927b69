/* Double-precision reference for the single scattering of a point or spot lamp in a
 * participating medium, written apart from the renderer it checks (header-only, test use).
 *
 * Along the view ray x(t) = o + t d (d unit), t in [0, t_end], the in-scattered radiance is
 *
 *   L = a I  int_0^t_end  tau(t) K(x) p(c) T(x) S(x) / (|x - s|^2 + r^2)  dt
 *
 *   K(x)    extinction per world unit (caller's callback), a the scattering albedo,
 *   s, I, r lamp position, scalar intensity, softening radius (falloff 1/(dist^2 + r^2)),
 *   tau(t)  = exp(-int_0^t K(x(t')) dt')                   camera -> point,
 *   T(x)    = exp(-int_0^|s-x| K(x + u w) du), w = (s-x)/|s-x|   point -> lamp,
 *   p(c)    Henyey-Greenstein (1 - g^2) / (4 pi (1 + g^2 - 2 g c)^1.5),
 *           c = dot(normalize(s - x), d)  (c = +1 at a point between camera and lamp),
 *   S(x)    1 for a point lamp; for a spot smoothstep(cos_outer, cos_inner,
 *           dot(axis, normalize(x - s))).
 *
 * Method. Every integral is an adaptive Gauss-Kronrod G7/K15 rule with global error control
 * (the segment of largest |K15 - G7| is bisected until the summed |K15 - G7| meets the
 * target), an explicit fixed-size segment array (no allocation, no recursion), a bisection
 * depth limit, and an initial partition into pieces no longer than max_step.
 *   - Outer (t): the interval is cut at the ray's closest point to the lamp t_c, and at
 *     t_c +- h 4^k and t_c +- w 4^k (h the lamp's distance from the line, w = sqrt(h^2 + r^2)),
 *     so the 1/((t - t_c)^2 + w^2) peak and the phase function's variation over ~h are
 *     resolved by construction; for a spot, also at the ray's crossings of the inner and outer
 *     cones (where the smoothstep's second derivative jumps). Target: |error| <= tol |L|.
 *   - tau: the optical depth along the view ray is integrated once, adaptively, over
 *     [0, t_end]; its accepted segments (sorted) with their cumulative depths form a table.
 *     tau(t) = exp(-(cum(segment start) + int_start^t K)) or from the segment's end, whichever is
 *     nearer, the partial integral adaptive again (normally a single K15 on a piece of an
 *     already-resolved segment).
 *   - T: a fresh adaptive integral from x to the lamp at every outer node.
 *   Nested depths are held to 0.01 tol absolute (0.01 tol relative when the depth exceeds 1),
 *   which bounds the relative error of tau and T by 0.01 tol max(1, depth).
 * The |K15 - G7| estimate is very pessimistic for smooth integrands (it is the error of G7),
 * so the real error is normally orders of magnitude below the tolerance.
 *
 * max_step: the longest piece the rule may accept without subdividing, on each of the three
 * integrals. Adaptive quadrature can step over a feature narrower than its nodes see; set
 * max_step to about 1/4 of the narrowest feature of K (e.g. a Gaussian's radius / 4). <= 0: no
 * cap. Cost grows like (length / max_step)^2 (outer pieces times nested pieces per node):
 * ~30-70 ms for an 18-unit ray at max_step 0.175 against ~2-4 ms without a cap. Each
 * integral may start with at most LAMP_REF_MAX_SEGMENTS / 2 pieces (1024 by default); past
 * that the pieces are lengthened and info.converged is false (define LAMP_REF_MAX_SEGMENTS
 * larger before including this header for finer caps).
 *
 * Stack: about 3 * LAMP_REF_MAX_SEGMENTS * 40 bytes (~250 KB at the default 2048) per
 * lamp_ref_inscatter call. Thread-safe (no mutable globals). */
#ifndef FOGPIPE_TESTS_RENDER_LAMP_REFERENCE_H
#define FOGPIPE_TESTS_RENDER_LAMP_REFERENCE_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "reference/gauss_kronrod.h"

#ifndef LAMP_REF_MAX_SEGMENTS
#define LAMP_REF_MAX_SEGMENTS 2048 /* segments per adaptive integral */
#endif
#define LAMP_REF_MAX_BREAKS 192 /* outer breakpoints; well under LAMP_REF_MAX_SEGMENTS / 4 */
#define LAMP_REF_MAX_DEPTH 52   /* bisections of one initial piece */
#define LAMP_REF_PI 3.14159265358979323846

typedef double (*lamp_ref_extinction_fn)(const void *user, const double p[3]);

typedef struct lamp_ref_lamp {
  double position[3];
  double intensity;
  double radius; /* > 0: falloff 1 / (dist^2 + radius^2) */
  bool spot;
  double axis[3]; /* unit, spot only: the direction the spot shines */
  double cos_inner, cos_outer; /* spot only, cos_inner > cos_outer */
} lamp_ref_lamp;

typedef struct lamp_ref_medium {
  lamp_ref_extinction_fn extinction; /* K(x) >= 0 per world unit */
  const void *user;
  double albedo;    /* a */
  double phase_g;   /* Henyey-Greenstein g, |g| < 1 */
  double max_step;  /* longest piece accepted unsplit (see above); <= 0: no cap */
  double tolerance; /* relative target of L (and of lamp_ref_optical_depth); <= 0: 1e-9 */
  /* V(x): whether the lamp at `lamp` sees world point x past the scene's surfaces (exact ray
   * casts, 1 or 0); NULL: always. Where V jumps along the view ray the integrand does too:
   * V is sampled at LAMP_REF_SHADOW_SAMPLES equal steps of [0, t_end] and each change is
   * bisected to the last bit and made an outer break (a shadow narrower than a step between
   * samples can be missed: size the samples to the scene). */
  bool (*visible)(const void *user, const double x[3], const double lamp[3]);
  const void *visible_user;
} lamp_ref_medium;

#ifndef LAMP_REF_SHADOW_SAMPLES
#define LAMP_REF_SHADOW_SAMPLES 4096
#endif

typedef struct lamp_ref_info {
  double error_estimate;      /* absolute, on L: a I sum |K15 - G7| of the outer rule */
  bool converged;             /* every integral met its target within the segment budget */
  int segments;               /* outer segments used */
  long long extinction_calls; /* K evaluations */
} lamp_ref_info;

/* ---------------------------------------------------------------- internals ---------- */

typedef double (*lamp_ref__fn)(void *ctx, double t);

typedef struct lamp_ref__segment {
  double a, b, value, error;
  int depth;
} lamp_ref__segment;

static inline double lamp_ref__dot(const double u[3], const double v[3]) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

static inline double lamp_ref__tolerance(const lamp_ref_medium *m) {
  double tol = m->tolerance > 0.0 ? m->tolerance : 1e-9;
  return tol < 1e-13 ? 1e-13 : tol;
}

static inline double lamp_ref__inner_tolerance(const lamp_ref_medium *m) {
  double tol = 0.01 * lamp_ref__tolerance(m);
  return tol < 4e-15 ? 4e-15 : tol;
}

/* 15-point Kronrod rule with its embedded 7-point Gauss rule on [a, b] (QUADPACK's qk15,
 * tests/reference/gauss_kronrod.h); error = |K15 - G7|. */
static inline void lamp_ref__gk15(lamp_ref__fn f, void *ctx, double a, double b, double *value,
                                  double *error) {
  double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double fc = f(ctx, c);
  double rk = wgk[7] * fc, rg = wg[3] * fc;
  for (int j = 0; j < 7; j++) {
    double dx = h * xgk[j];
    double s = f(ctx, c - dx) + f(ctx, c + dx);
    rk += wgk[j] * s;
    if (j & 1) rg += wg[j >> 1] * s; /* G7 nodes are the odd Kronrod nodes */
  }
  *value = rk * h;
  *error = fabs((rk - rg) * h);
}

/* Global adaptive G7/K15 of f over [breaks[0], breaks[nbreaks-1]] (breaks sorted), each
 * [breaks[k], breaks[k+1]] first cut into equal pieces no longer than max_step (if > 0).
 * Stops when sum |K15 - G7| <= rel * max(floor_scale, |integral|). Clears *ok if the target
 * was not met (segment budget, depth limit) or max_step could not be honoured. */
static inline double lamp_ref__integrate(lamp_ref__fn f, void *ctx, const double *breaks,
                                         int nbreaks, double max_step, double rel,
                                         double floor_scale, lamp_ref__segment *ws, int cap,
                                         int *nseg_out, double *error_out, bool *ok) {
  int n = 0;
  double total = 0.0, total_err = 0.0;
  double pieces = 0.0;
  for (int k = 0; k + 1 < nbreaks; k++) {
    double len = breaks[k + 1] - breaks[k];
    if (len > 0.0) pieces += max_step > 0.0 ? ceil(len / max_step) : 1.0;
  }
  double budget = (double)(cap / 2), shrink = 1.0;
  if (pieces > budget) {
    shrink = budget / pieces;
    *ok = false;
  }
  for (int k = 0; k + 1 < nbreaks; k++) {
    double b0 = breaks[k], len = breaks[k + 1] - b0;
    if (!(len > 0.0)) continue;
    double np = max_step > 0.0 ? floor(ceil(len / max_step) * shrink) : 1.0;
    int m = np < 1.0 ? 1 : (int)np;
    int room = cap - n - (nbreaks - 2 - k); /* leave one segment for every later interval */
    if (m > room) {
      m = room;
      *ok = false;
    }
    for (int i = 0; i < m; i++) {
      lamp_ref__segment *s = &ws[n++];
      s->a = b0 + len * i / m;
      s->b = i + 1 == m ? breaks[k + 1] : b0 + len * (i + 1) / m;
      s->depth = 0;
      lamp_ref__gk15(f, ctx, s->a, s->b, &s->value, &s->error);
      total += s->value;
      total_err += s->error;
    }
  }
  for (;;) {
    double target = rel * fmax(floor_scale, fabs(total));
    if (total_err <= target) { /* re-sum exactly before accepting (running sums drift) */
      total = total_err = 0.0;
      for (int i = 0; i < n; i++) total += ws[i].value, total_err += ws[i].error;
      if (total_err <= rel * fmax(floor_scale, fabs(total))) break;
    }
    int worst = -1;
    double worst_err = -1.0;
    for (int i = 0; i < n; i++) {
      const lamp_ref__segment *s = &ws[i];
      if (s->error > worst_err && s->depth < LAMP_REF_MAX_DEPTH) {
        double mid = 0.5 * (s->a + s->b);
        if (mid > s->a && mid < s->b) worst = i, worst_err = s->error;
      }
    }
    if (worst < 0 || n >= cap) {
      *ok = false;
      break;
    }
    lamp_ref__segment *s = &ws[worst], *r = &ws[n++];
    double mid = 0.5 * (s->a + s->b);
    total -= s->value;
    total_err -= s->error;
    r->a = mid;
    r->b = s->b;
    r->depth = ++s->depth;
    s->b = mid;
    lamp_ref__gk15(f, ctx, s->a, s->b, &s->value, &s->error);
    lamp_ref__gk15(f, ctx, r->a, r->b, &r->value, &r->error);
    total += s->value + r->value;
    total_err += s->error + r->error;
  }
  total = total_err = 0.0;
  for (int i = 0; i < n; i++) total += ws[i].value, total_err += ws[i].error;
  if (nseg_out) *nseg_out = n;
  if (error_out) *error_out = total_err;
  return total;
}

/* K along the line origin + t dir. */
typedef struct lamp_ref__line {
  const lamp_ref_medium *m;
  double origin[3], dir[3];
  long long *calls;
} lamp_ref__line;

static inline double lamp_ref__line_extinction(void *vl, double t) {
  const lamp_ref__line *l = (const lamp_ref__line *)vl;
  double p[3] = {l->origin[0] + t * l->dir[0], l->origin[1] + t * l->dir[1],
                 l->origin[2] + t * l->dir[2]};
  (*l->calls)++;
  return l->m->extinction(l->m->user, p);
}

static inline double lamp_ref__depth(const lamp_ref_medium *m, const double a[3],
                                     const double dir[3], double t0, double t1, double rel,
                                     double floor_scale, lamp_ref__segment *ws, int cap,
                                     long long *calls, bool *ok) {
  if (!(t1 > t0)) return 0.0;
  lamp_ref__line line = {m, {a[0], a[1], a[2]}, {dir[0], dir[1], dir[2]}, calls};
  double breaks[2] = {t0, t1};
  return lamp_ref__integrate(lamp_ref__line_extinction, &line, breaks, 2, m->max_step, rel,
                             floor_scale, ws, cap, NULL, NULL, ok);
}

/* T(x) with the nested tolerance: |error of the depth| <= rel max(1, depth). */
static inline double lamp_ref__transmittance(const lamp_ref_medium *m, const lamp_ref_lamp *lamp,
                                             const double x[3], lamp_ref__segment *ws, int cap,
                                             long long *calls, bool *ok) {
  double v[3] = {lamp->position[0] - x[0], lamp->position[1] - x[1], lamp->position[2] - x[2]};
  double dist = sqrt(lamp_ref__dot(v, v));
  if (!(dist > 0.0)) return 1.0;
  double w[3] = {v[0] / dist, v[1] / dist, v[2] / dist};
  return exp(-lamp_ref__depth(m, x, w, 0.0, dist, lamp_ref__inner_tolerance(m), 1.0, ws, cap,
                              calls, ok));
}

/* ------------------------------------------------------------ public pieces ---------- */

/* Henyey-Greenstein phase function (per steradian), |g| < 1. */
static inline double lamp_ref_phase_hg(double g, double c) {
  double base = 1.0 + g * g - 2.0 * g * c;
  return (1.0 - g * g) / (4.0 * LAMP_REF_PI * base * sqrt(base));
}

/* The spot factor S at x (1 for a point lamp; 1 on the lamp itself, a set of measure 0). */
static inline double lamp_ref_spot_factor(const lamp_ref_lamp *lamp, const double x[3]) {
  if (!lamp->spot) return 1.0;
  double v[3] = {x[0] - lamp->position[0], x[1] - lamp->position[1], x[2] - lamp->position[2]};
  double dist = sqrt(lamp_ref__dot(v, v));
  if (!(dist > 0.0)) return 1.0;
  double cosang = lamp_ref__dot(lamp->axis, v) / dist;
  double u = (cosang - lamp->cos_outer) / (lamp->cos_inner - lamp->cos_outer);
  u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
  return u * u * (3.0 - 2.0 * u);
}

/* Optical depth int_0^length K(a + u dir) du (dir unit), to the medium's relative tolerance. */
static inline double lamp_ref_optical_depth(const lamp_ref_medium *m, const double a[3],
                                            const double dir[3], double length) {
  lamp_ref__segment ws[LAMP_REF_MAX_SEGMENTS];
  long long calls = 0;
  bool ok = true;
  return lamp_ref__depth(m, a, dir, 0.0, length, lamp_ref__tolerance(m), 0.0, ws,
                         LAMP_REF_MAX_SEGMENTS, &calls, &ok);
}

/* T(x): transmittance from x to the lamp, exactly as the in-scatter integrand uses it
 * (depth to 0.01 tol absolute, or relative above depth 1). */
static inline double lamp_ref_transmittance_to_lamp(const lamp_ref_medium *m,
                                                    const lamp_ref_lamp *lamp,
                                                    const double x[3]) {
  lamp_ref__segment ws[LAMP_REF_MAX_SEGMENTS];
  long long calls = 0;
  bool ok = true;
  return lamp_ref__transmittance(m, lamp, x, ws, LAMP_REF_MAX_SEGMENTS, &calls, &ok);
}

/* ---------------------------------------------------------------- in-scatter ---------- */

typedef struct lamp_ref__scene {
  const lamp_ref_medium *m;
  const lamp_ref_lamp *lamp;
  lamp_ref__line view;              /* o + t d */
  const lamp_ref__segment *table;   /* the view-ray depth's segments, sorted by a */
  const double *cum;                /* cum[i]: depth from 0 to table[i].a; cum[n]: total */
  int ntable;
  lamp_ref__segment *inner;         /* workspace of the nested integrals */
  long long calls;
  bool ok;
} lamp_ref__scene;

/* Optical depth along the view ray from 0 to t, from the table. */
static inline double lamp_ref__view_depth(lamp_ref__scene *sc, double t) {
  int lo = 0, hi = sc->ntable - 1;
  while (lo < hi) {
    int mid = (lo + hi + 1) / 2;
    if (sc->table[mid].a <= t) lo = mid; else hi = mid - 1;
  }
  const lamp_ref__segment *s = &sc->table[lo];
  double rel = lamp_ref__inner_tolerance(sc->m), floor_scale = fmax(1.0, sc->cum[sc->ntable]);
  if (t - s->a <= s->b - t)
    return sc->cum[lo] + lamp_ref__depth(sc->m, sc->view.origin, sc->view.dir, s->a, t, rel,
                                         floor_scale, sc->inner, LAMP_REF_MAX_SEGMENTS,
                                         &sc->calls, &sc->ok);
  return sc->cum[lo + 1] - lamp_ref__depth(sc->m, sc->view.origin, sc->view.dir, t, s->b, rel,
                                           floor_scale, sc->inner, LAMP_REF_MAX_SEGMENTS,
                                           &sc->calls, &sc->ok);
}

/* The outer integrand without the constant factor a I. */
static inline double lamp_ref__integrand(void *vsc, double t) {
  lamp_ref__scene *sc = (lamp_ref__scene *)vsc;
  const lamp_ref_lamp *lamp = sc->lamp;
  const double *o = sc->view.origin, *d = sc->view.dir;
  double x[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
  double s = lamp_ref_spot_factor(lamp, x);
  if (s == 0.0) return 0.0;
  if (sc->m->visible && !sc->m->visible(sc->m->visible_user, x, lamp->position)) return 0.0;
  sc->calls++;
  double k = sc->m->extinction(sc->m->user, x);
  if (k == 0.0) return 0.0;
  double v[3] = {lamp->position[0] - x[0], lamp->position[1] - x[1], lamp->position[2] - x[2]};
  double dist2 = lamp_ref__dot(v, v), dist = sqrt(dist2);
  double c = dist > 0.0 ? lamp_ref__dot(v, d) / dist : 1.0;
  double p = lamp_ref_phase_hg(sc->m->phase_g, c);
  double transmit = lamp_ref__transmittance(sc->m, lamp, x, sc->inner, LAMP_REF_MAX_SEGMENTS,
                                            &sc->calls, &sc->ok);
  double tau = exp(-lamp_ref__view_depth(sc, t));
  return tau * k * p * transmit * s / (dist2 + lamp->radius * lamp->radius);
}

static inline void lamp_ref__sort(double *v, int n) { /* insertion sort, n small */
  for (int i = 1; i < n; i++) {
    double x = v[i];
    int j = i;
    for (; j > 0 && v[j - 1] > x; j--) v[j] = v[j - 1];
    v[j] = x;
  }
}

static inline void lamp_ref__add_break(double *br, int *n, double t, double t_end) {
  if (t > 0.0 && t < t_end && *n < LAMP_REF_MAX_BREAKS) br[(*n)++] = t;
}

/* Roots in t of dot(axis, x(t) - s)^2 = c0^2 |x(t) - s|^2: the ray's crossings of the cone
 * cos = c0 (and of its mirror cone, harmless extra breakpoints). */
static inline void lamp_ref__cone_breaks(const lamp_ref_lamp *lamp, const double o[3],
                                         const double d[3], double c0, double t_end, double *br,
                                         int *n) {
  double q[3] = {o[0] - lamp->position[0], o[1] - lamp->position[1], o[2] - lamp->position[2]};
  double al = lamp_ref__dot(lamp->axis, q), be = lamp_ref__dot(lamp->axis, d);
  double qa = be * be - c0 * c0, qb = 2.0 * (al * be - c0 * c0 * lamp_ref__dot(q, d));
  double qc = al * al - c0 * c0 * lamp_ref__dot(q, q);
  if (fabs(qa) < 1e-14) {
    if (qb != 0.0) lamp_ref__add_break(br, n, -qc / qb, t_end);
    return;
  }
  double disc = qb * qb - 4.0 * qa * qc;
  if (disc < 0.0) return;
  double qq = -0.5 * (qb + copysign(sqrt(disc), qb));
  lamp_ref__add_break(br, n, qq / qa, t_end);
  if (qq != 0.0) lamp_ref__add_break(br, n, qc / qq, t_end);
}

/* The view ray's points where V jumps (lamp_ref_medium.visible): each change between
 * samples, bisected until the bracket is one ulp wide. */
static inline void lamp_ref__shadow_breaks(const lamp_ref_medium *m, const lamp_ref_lamp *lamp,
                                           const double o[3], const double d[3], double t_end,
                                           double *br, int *n) {
  if (!m->visible) return;
  const int samples = LAMP_REF_SHADOW_SAMPLES;
  bool before = false;
  for (int i = 0; i <= samples; i++) {
    double t = t_end * i / samples, x[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
    bool now = m->visible(m->visible_user, x, lamp->position);
    if (i > 0 && now != before) {
      double a = t_end * (i - 1) / samples, b = t;
      for (int k = 0; k < 80 && b - a > 0.0; k++) {
        double c = 0.5 * (a + b);
        if (c <= a || c >= b) break;
        double y[3] = {o[0] + c * d[0], o[1] + c * d[1], o[2] + c * d[2]};
        if (m->visible(m->visible_user, y, lamp->position) == before) a = c; else b = c;
      }
      lamp_ref__add_break(br, n, 0.5 * (a + b), t_end);
    }
    before = now;
  }
}

/* Outer breakpoints: 0, t_end, the closest point t_c, t_c +- h 4^k up to w, t_c +- w 4^k
 * beyond, the spot's cone crossings and V's jumps; sorted, without duplicates. */
static inline int lamp_ref__outer_breaks(const lamp_ref_medium *medium,
                                         const lamp_ref_lamp *lamp, const double o[3],
                                         const double d[3], double t_end, double *br) {
  int n = 0;
  lamp_ref__shadow_breaks(medium, lamp, o, d, t_end, br, &n);
  double q[3] = {lamp->position[0] - o[0], lamp->position[1] - o[1], lamp->position[2] - o[2]};
  double tc = lamp_ref__dot(q, d);
  double perp[3] = {q[0] - tc * d[0], q[1] - tc * d[1], q[2] - tc * d[2]};
  double h = sqrt(lamp_ref__dot(perp, perp));
  double w = sqrt(h * h + lamp->radius * lamp->radius);
  double span = t_end + fabs(tc);
  lamp_ref__add_break(br, &n, tc, t_end);
  double e = (h > 1e-12 * w && h < w) ? h : w;
  if (!(e > 1e-12 * span)) e = 1e-12 * span;
  for (; e < span; e *= 4.0) {
    lamp_ref__add_break(br, &n, tc - e, t_end);
    lamp_ref__add_break(br, &n, tc + e, t_end);
  }
  if (lamp->spot) {
    lamp_ref__cone_breaks(lamp, o, d, lamp->cos_outer, t_end, br, &n);
    lamp_ref__cone_breaks(lamp, o, d, lamp->cos_inner, t_end, br, &n);
  }
  br[n++] = 0.0;
  br[n++] = t_end;
  lamp_ref__sort(br, n);
  int m = 0;
  for (int i = 0; i < n; i++)
    if (m == 0 || br[i] > br[m - 1]) br[m++] = br[i];
  return m;
}

static inline void lamp_ref__sort_segments(lamp_ref__segment *s, int n) { /* shell sort by a */
  for (int gap = n / 2; gap > 0; gap /= 2)
    for (int i = gap; i < n; i++) {
      lamp_ref__segment x = s[i];
      int j = i;
      for (; j >= gap && s[j - gap].a > x.a; j -= gap) s[j] = s[j - gap];
      s[j] = x;
    }
}

typedef struct lamp_ref__workspace {
  lamp_ref__segment outer[LAMP_REF_MAX_SEGMENTS];
  lamp_ref__segment table[LAMP_REF_MAX_SEGMENTS];
  lamp_ref__segment inner[LAMP_REF_MAX_SEGMENTS];
  double cum[LAMP_REF_MAX_SEGMENTS + 1];
  double breaks[LAMP_REF_MAX_BREAKS + 2];
} lamp_ref__workspace;

/* In-scattered radiance of the lamp along o + t d, t in [0, t_end] (d unit, t_end finite);
 * info (may be NULL) receives the error estimate and whether every integral converged. */
static inline double lamp_ref_inscatter_ex(const lamp_ref_medium *m, const lamp_ref_lamp *lamp,
                                           const double o[3], const double d[3], double t_end,
                                           lamp_ref_info *info) {
  if (info) memset(info, 0, sizeof *info), info->converged = true;
  if (!(t_end > 0.0) || m->albedo == 0.0 || lamp->intensity == 0.0) return 0.0;
  lamp_ref__workspace ws;
  lamp_ref__scene sc;
  memset(&sc, 0, sizeof sc);
  sc.m = m;
  sc.lamp = lamp;
  sc.ok = true;
  sc.view.m = m;
  sc.view.calls = &sc.calls;
  for (int i = 0; i < 3; i++) sc.view.origin[i] = o[i], sc.view.dir[i] = d[i];
  sc.inner = ws.inner;

  /* The table of the view ray's optical depth. */
  double ends[2] = {0.0, t_end};
  int n = 0;
  lamp_ref__integrate(lamp_ref__line_extinction, &sc.view, ends, 2, m->max_step,
                      lamp_ref__inner_tolerance(m), 1.0, ws.table, LAMP_REF_MAX_SEGMENTS, &n,
                      NULL, &sc.ok);
  lamp_ref__sort_segments(ws.table, n);
  ws.cum[0] = 0.0;
  for (int i = 0; i < n; i++) ws.cum[i + 1] = ws.cum[i] + ws.table[i].value;
  sc.table = ws.table;
  sc.cum = ws.cum;
  sc.ntable = n;

  /* The outer integral. */
  int nb = lamp_ref__outer_breaks(m, lamp, o, d, t_end, ws.breaks);
  int nseg = 0;
  double err = 0.0;
  double v = lamp_ref__integrate(lamp_ref__integrand, &sc, ws.breaks, nb, m->max_step,
                                 lamp_ref__tolerance(m), 0.0, ws.outer, LAMP_REF_MAX_SEGMENTS,
                                 &nseg, &err, &sc.ok);
  double scale = m->albedo * lamp->intensity;
  if (info) {
    info->error_estimate = fabs(scale) * err;
    info->converged = sc.ok;
    info->segments = nseg;
    info->extinction_calls = sc.calls;
  }
  return scale * v;
}

static inline double lamp_ref_inscatter(const lamp_ref_medium *m, const lamp_ref_lamp *lamp,
                                        const double o[3], const double d[3], double t_end) {
  return lamp_ref_inscatter_ex(m, lamp, o, d, t_end, NULL);
}

#endif
