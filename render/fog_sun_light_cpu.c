/* The CPU twin of fog_light.glsl, in double (render/fog_sun_shadow.h): T_s at a point and
 * the tau K-weighted mean of T_s along a view ray, sample for sample as the shader takes
 * them, so the GL pass can be checked against it pixel by pixel. */
#include <math.h>

#include "render/fog_rbf_tiles.h"
#include "render/fog_sun_shadow.h"

/* The quadrics beside the model: their exact depth from p towards the sun. */
static double beside_towards_sun(const fog_model *m, const fog_sun_shadow *volume,
                                 const double p[3]) {
  if (!fog_model_quadrics_beside(m)) return 0.0;
  const fog_quadric_noise noise = fog_model_quadric_noise(m);
  return fog_quadric_optical_depth(m->quadrics, m->quadric_count, &noise, p, volume->sun,
                                   HUGE_VAL);
}

double fog_sun_optical_depth(const fog_model *m, fog_sun_shadow_kind kind,
                             const fog_sun_shadow *volume, const double p[3]) {
  switch (kind) {
    case FOG_SUN_SHADOW_VOLUME:
      return fog_sun_shadow_depth_at(volume, p) + beside_towards_sun(m, volume, p);
    case FOG_SUN_SHADOW_HEIGHT: /* K H e^{-(y - y0)/H} / w_y */
      return m->extinction * m->scale_height * exp(-(p[1] - m->y0) / m->scale_height) /
                 volume->sun[1] +
             beside_towards_sun(m, volume, p);
    case FOG_SUN_SHADOW_OPAQUE:
      return HUGE_VAL;
    default:
      return 0.0;
  }
}

/* K at p, as the shadow mean samples it: the fogmap's approximation the light reads
 * (lit_slot: A_J for either LOD method, A_0 at mu <= 0), the volume trilinear, the analytic
 * models pointwise. */
static double model_extinction_at(const fog_model *m, const double p[3]);

double fog_light_extinction_at(const fog_model *m, const double p[3]) {
  double k = model_extinction_at(m, p);
  const fog_quadric_noise noise = fog_model_quadric_noise(m);
  if (fog_model_quadrics_beside(m))
    k += fog_quadric_extinction_at(m->quadrics, m->quadric_count, &noise, p);
  return k;
}

/* The fogmap's approximation the light reads: A_J, the fog itself, for either LOD method
 * (the sum of details at mu = 1 draws A_0 + D_1..D_J = A_J); A_0 at mu <= 0, where the
 * pass draws A_0 alone (fog_pass.c, one-grid draws). */
static int lit_slot(const fog_model *m) { return m->lod->mu <= 0.0 ? 0 : m->lod->levels; }

static double model_extinction_at(const fog_model *m, const double p[3]) {
  switch (m->kind) {
    case FOG_MODEL_FOGMAP: {
      int slot = lit_slot(m);
      return fog_extinction_point(m->volume, &m->lod->approx[slot], p);
    }
    case FOG_MODEL_VOLUME:
      return fog_grid3d_extinction_at(m->grid3d, p);
    case FOG_MODEL_HEIGHT:
      return m->extinction * exp(-(p[1] - m->y0) / m->scale_height);
    case FOG_MODEL_QUADRIC: {
      const fog_quadric_noise noise = fog_model_quadric_noise(m);
      return fog_quadric_extinction_at(m->quadrics, m->quadric_count, &noise, p);
    }
    case FOG_MODEL_PERLIN: {
      fog_perlin_medium medium = fog_model_perlin_medium(m);
      return m->perlin ? fog_perlin_extinction_at(m->perlin, &medium, p) : 0.0;
    }
    case FOG_MODEL_LINEAR:
    case FOG_MODEL_EXP2: {
      double r = sqrt((p[0] - m->eye[0]) * (p[0] - m->eye[0]) +
                      (p[1] - m->eye[1]) * (p[1] - m->eye[1]) +
                      (p[2] - m->eye[2]) * (p[2] - m->eye[2]));
      return m->kind == FOG_MODEL_LINEAR ? fog_linear_extinction(m->fog_start, m->fog_end, r)
                                         : fog_exp2_extinction(m->extinction, r);
    }
    default: {
      double k = m->extinction;
      for (int i = 0; i < m->rbf_count; i++) {
        double r2 = 0.0;
        for (int a = 0; a < 3; a++)
          r2 += (p[a] - m->rbfs[i].centre[a]) * (p[a] - m->rbfs[i].centre[a]);
        k += m->rbfs[i].density * exp(-r2 / (m->rbfs[i].radius * m->rbfs[i].radius));
      }
      return k;
    }
  }
}

/* The stretch of the ray that holds fog (fog_light_span, fog_sun_span): the box, the
 * volume's support, the height fog, homogeneous fog and an RBF base up to an optical depth
 * of FOG_LIGHT_SPAN_DEPTH (the rest weighs < e^-20), the RBFs (chords: the chords of their
 * cull spheres in front of o; else from o to their reach, 6 radii), the quadrics' boxes;
 * the classic factors from the eye (o = eye): the linear fog's [start, end], the exp2 fog
 * to FOG_LIGHT_SPAN_DEPTH. */
static bool model_light_span(const fog_model *m, const double o[3], const double d[3],
                             double t_surface, bool chords, double *t0, double *t1);

static bool light_span(const fog_model *m, const double o[3], const double d[3],
                       double t_surface, bool chords, double *t0, double *t1) {
  bool some = model_light_span(m, o, d, t_surface, chords, t0, t1);
  double lo[3], hi[3], a, b;
  if (!fog_model_quadrics_beside(m) ||
      !fog_quadric_bounds(m->quadrics, m->quadric_count, lo, hi))
    return some;
  for (int c = 0; c < 3; c++) lo[c] -= o[c], hi[c] -= o[c];
  if (!fog_slab_entry_exit(lo, hi, d, &a, &b)) return some;
  a = fmax(a, 0.0), b = fmin(b, t_surface);
  if (!(a < b && b < 1e29)) return some;
  /* the union's hull: the two stretches and what lies between */
  if (some) a = fmin(a, *t0), b = fmax(b, *t1);
  *t0 = a, *t1 = b;
  return true;
}

bool fog_light_span(const fog_model *m, const double o[3], const double d[3],
                    double t_surface, double *t0, double *t1) {
  return light_span(m, o, d, t_surface, false, t0, t1);
}

bool fog_sun_span(const fog_model *m, const double o[3], const double d[3], double t_surface,
                  double *t0, double *t1) {
  return light_span(m, o, d, t_surface, true, t0, t1);
}

static bool model_light_span(const fog_model *m, const double o[3], const double d[3],
                             double t_surface, bool chords, double *t0, double *t1) {
  *t0 = 0.0;
  *t1 = t_surface;
  switch (m->kind) {
    case FOG_MODEL_FOGMAP: {
      double a, b;
      if (!fog_box_entry_exit(m->volume, o, d, &a, &b)) return false;
      *t0 = fmax(a, 0.0), *t1 = fmin(b, t_surface);
      break;
    }
    case FOG_MODEL_VOLUME: {
      double u0[3], du[3], ulo[3], uhi[3], a, b;
      volume_grid_index_of(m->grid3d, o, u0);
      for (int c = 0; c < 3; c++) {
        du[c] = 0.0;
        for (int k = 0; k < 3; k++) du[c] += m->grid3d->index_from_world[c][k] * d[k];
        ulo[c] = -1.0 - u0[c], uhi[c] = m->grid3d->dim[c] - u0[c];
      }
      if (!fog_slab_entry_exit(ulo, uhi, du, &a, &b)) return false;
      *t0 = fmax(a, 0.0), *t1 = fmin(b, t_surface);
      break;
    }
    case FOG_MODEL_HEIGHT: {
      const double depth = FOG_LIGHT_SPAN_DEPTH, H = m->scale_height;
      double k0 = m->extinction * exp((m->y0 - o[1]) / H), dy = d[1], reach;
      if (fabs(dy) < 1e-6) {
        reach = depth / k0;
      } else {
        double q = depth * dy / (k0 * H);
        reach = q >= 1.0 ? (dy > 0 ? fmax(m->y0 - o[1] + 36.0 * H, 0.0) / dy : HUGE_VAL)
                         : -H / dy * log1p(-q); /* 1 - q loses a small q */
      }
      *t1 = fmin(t_surface, reach);
      break;
    }
    case FOG_MODEL_LINEAR:
      /* nothing before start; opaque from end on (from the eye: the ray's own distances) */
      *t0 = fmax(m->fog_start, 0.0), *t1 = fmin(t_surface, m->fog_end);
      break;
    case FOG_MODEL_EXP2: /* (a t)^2 reaches FOG_LIGHT_SPAN_DEPTH at sqrt(depth) / a */
      *t1 = fmin(t_surface, m->extinction > 0 ? sqrt(FOG_LIGHT_SPAN_DEPTH) / m->extinction : 0.0);
      break;
    case FOG_MODEL_QUADRIC:
    case FOG_MODEL_PERLIN: {
      double lo[3], hi[3], a, b;
      if (!fog_model_bounds(m, lo, hi)) return false;
      for (int c = 0; c < 3; c++) lo[c] -= o[c], hi[c] -= o[c];
      if (!fog_slab_entry_exit(lo, hi, d, &a, &b)) return false;
      *t0 = fmax(a, 0.0), *t1 = fmin(b, t_surface);
      break;
    }
    case FOG_MODEL_RBF:
      if (m->extinction == 0 && chords) {
        /* The sun's mean over Gaussians alone: the stretch of the ray inside their cull
         * spheres (fog_rbf_cull_radius) in front of o, as the GL's tile lists hold them.
         * Past its chord a Gaussian adds at most c r (sqrt(pi)/2) e^{-R^2/r^2} (erfc x <=
         * e^{-x^2}) of optical depth, half the tiles' bound, and the sun's light there at
         * most that share; from the camera to the farthest Gaussian, the mean's segments
         * fell mostly on empty air. (Not the lamps': a lamp's 1/d^2 near a Gaussian's tail
         * can make light of depth under the bound.) */
        double a = HUGE_VAL, b = 0.0;
        for (int i = 0; i < m->rbf_count; i++) {
          const double R = fog_rbf_cull_radius(&m->rbfs[i], m->rbf_count);
          double v[3], tc = 0.0, h2 = 0.0;
          for (int c = 0; c < 3; c++) v[c] = m->rbfs[i].centre[c] - o[c], tc += v[c] * d[c];
          for (int c = 0; c < 3; c++) h2 += (v[c] - tc * d[c]) * (v[c] - tc * d[c]);
          if (!(R > 0) || !(R * R - h2 > 0)) continue;
          const double half_chord = sqrt(R * R - h2);
          if (!(tc + half_chord > 0)) continue; /* behind o */
          a = fmin(a, tc - half_chord), b = fmax(b, tc + half_chord);
        }
        *t0 = fmax(a, 0.0), *t1 = fmin(b, t_surface);
      } else if (m->extinction == 0) {
        /* from o to the farthest Gaussian's reach (the lamps') */
        double reach = 0.0;
        for (int i = 0; i < m->rbf_count; i++) {
          double along = 0.0;
          for (int a = 0; a < 3; a++) along += (m->rbfs[i].centre[a] - o[a]) * d[a];
          reach = fmax(reach, along + 6.0 * m->rbfs[i].radius);
        }
        *t1 = fmin(t_surface, reach);
      } else { /* a base never ends: as homogeneous fog below */
        *t1 = fmin(t_surface, m->extinction > 0 ? FOG_LIGHT_SPAN_DEPTH / m->extinction : 0.0);
      }
      break;
    default: {
      /* homogeneous fog and an RBF base never end: up to an optical depth of
       * FOG_LIGHT_SPAN_DEPTH from the camera (the base alone reaches it there) */
      double reach = m->extinction > 0 ? FOG_LIGHT_SPAN_DEPTH / m->extinction : 0.0;
      *t1 = fmin(t_surface, reach);
    }
  }
  return *t0 < *t1 && *t1 < 1e29;
}

double fog_sun_mean_transmittance(const fog_model *m, fog_sun_shadow_kind kind,
                                  const fog_sun_shadow *volume, fog_light_rule rule,
                                  double depth_limit, const double o[3], const double d[3],
                                  double t_surface) {
  return fog_sun_mean_light(m, kind, volume, rule, depth_limit, o, d, t_surface, NULL, NULL);
}

/* V for the per-piece walks (fog_shaft_visible in fog_light.glsl): linear between
 * steps x shaft_samples equally spaced points of the ray's fog span, the pieces' nodes
 * reading it. The points follow the span, not the fog's cells: V at the nodes, pinned to
 * the cells' planes, drew the cells' outlines into the shadows as jagged bands. The nodes
 * come in increasing t, so each point is looked up about once. */
typedef struct shaft_line {
  int count;    /* points; 0: V at the nodes */
  double t0, dv; /* the span's start, the points' spacing */
  long k;       /* the points k and k + 1 held in lo and hi (-2: none yet) */
  double lo, hi;
} shaft_line;

/* T_s V at a point, for the per-piece walks. */
typedef struct sun_light_user {
  const fog_model *m;
  fog_sun_shadow_kind kind;
  const fog_sun_shadow *volume;
  fog_sun_visibility_fn visible;
  const void *user;
  const double *o, *d;
  shaft_line line;
} sun_light_user;

static double shaft_point(const sun_light_user *u, long k) {
  const double t = u->line.t0 + (k + 0.5) * u->line.dv;
  double p[3];
  for (int a = 0; a < 3; a++) p[a] = u->o[a] + t * u->d[a];
  return u->visible(u->user, p);
}

static double shaft_visible(sun_light_user *u, const double p[3]) {
  shaft_line *line = &u->line;
  double t = 0.0, dd = 0.0;
  for (int a = 0; a < 3; a++) t += (p[a] - u->o[a]) * u->d[a], dd += u->d[a] * u->d[a];
  const double x = fmin(fmax((t / dd - line->t0) / line->dv - 0.5, 0.0), line->count - 1.0);
  const long k = (long)x < line->count - 2 ? (long)x : line->count - 2;
  if (k != line->k) {
    line->lo = k == line->k + 1 ? line->hi : shaft_point(u, k);
    line->hi = shaft_point(u, k + 1);
    line->k = k;
  }
  return line->lo + (line->hi - line->lo) * (x - (double)k);
}

static double sun_light_point(const void *user, const double p[3]) {
  sun_light_user *u = (sun_light_user *)user; /* the walk's user: this call's own state */
  const double v = !u->visible ? 1.0 : u->line.count > 0 ? shaft_visible(u, p)
                                                         : u->visible(u->user, p);
  return exp(-fog_sun_optical_depth(u->m, u->kind, u->volume, p)) * v;
}

/* T_s V at the ray's point t. */
static double sun_light_at(const fog_model *m, fog_sun_shadow_kind kind,
                           const fog_sun_shadow *volume, const double o[3], const double d[3],
                           double t, fog_sun_visibility_fn visible, const void *user) {
  double p[3];
  for (int a = 0; a < 3; a++) p[a] = o[a] + t * d[a];
  return exp(-fog_sun_optical_depth(m, kind, volume, p)) * (visible ? visible(user, p) : 1.0);
}

static double extinction_on_ray(const fog_model *m, const double o[3], const double d[3],
                                double t) {
  double p[3];
  for (int a = 0; a < 3; a++) p[a] = o[a] + t * d[a];
  return fog_light_extinction_at(m, p);
}

double fog_sun_mean_light(const fog_model *m, fog_sun_shadow_kind kind,
                          const fog_sun_shadow *volume, fog_light_rule rule,
                          double depth_limit, const double o[3], const double d[3],
                          double t_surface, fog_sun_visibility_fn visible, const void *user) {
  if (kind == FOG_SUN_SHADOW_NONE && !visible) return 1.0;
  if (kind == FOG_SUN_SHADOW_OPAQUE) return 0.0;
  if (rule.pieces && !fog_model_quadrics_beside(m) && ((m->kind == FOG_MODEL_PERLIN && m->perlin) ||
                      (m->kind == FOG_MODEL_VOLUME && m->grid3d) ||
                      (m->kind == FOG_MODEL_FOGMAP && m->volume && m->lod))) {
    /* per piece of the exact walk: S over 1 - e^{-D} of the same walk */
    sun_light_user u = {m, kind, volume, visible, user, o, d, {.count = 0}};
    double t0, t1;
    if (visible && rule.shaft_samples > 1 && fog_sun_span(m, o, d, t_surface, &t0, &t1)) {
      const int count = rule.steps * rule.shaft_samples;
      u.line = (shaft_line){.count = count, .t0 = t0, .dv = (t1 - t0) / count, .k = -2};
    }
    double D, S;
    if (m->kind == FOG_MODEL_FOGMAP) {
      /* the approximation fog_light_extinction_at reads */
      int slot = lit_slot(m);
      S = fog_fogmap_light_integral(m->volume, &m->lod->approx[slot], o, d, t_surface,
                                    rule.nodes, depth_limit, sun_light_point, &u, &D);
    } else if (m->kind == FOG_MODEL_PERLIN) {
      fog_perlin_medium medium = fog_model_perlin_medium(m);
      S = fog_perlin_light_integral(m->perlin, &medium, o, d, t_surface, rule.nodes,
                                    depth_limit, sun_light_point, &u, &D);
    } else {
      S = fog_grid3d_light_integral(m->grid3d, o, d, t_surface, rule.nodes, depth_limit,
                                    sun_light_point, &u, &D);
    }
    return D > 0.0 ? S / -expm1(-D) : 1.0;
  }
  /* The mean of T_s V weighted by tau K. A negative K (a linear or quadratic wavelet
   * approximation's ringing, or an empty region's float rounding) weighs nothing: signed
   * weights that nearly cancel made this "mean" 70 on a ray through such a region. */
  const int steps = rule.steps, nodes = rule.nodes;
  double t0, t1;
  if (!fog_sun_span(m, o, d, t_surface, &t0, &t1)) return 1.0;
  /* the Gauss nodes' offset from the middle, in segments: 1/(2 sqrt 3) */
  const double g = 0.28867513459481288225;
  /* Segments are cut where the ray crosses a quadric volume's surface: K jumps or kinks
   * there, and two nodes cannot integrate a step. A hard-edged sphere thick enough to hold
   * its weight in the first few units past its edge drew concentric rings at 8 segments
   * (the nodes slid across the edge with the chord's length): across a fan of rays the
   * worst error fell from 0.49 to 4.5e-2 of 1 - tau once cut (test_quadric_cuts). */
  double cuts[FOG_QUADRIC_MAX_CUTS];
  const int cut_count = m->quadrics && m->quadric_count > 0
                            ? fog_quadric_cuts(m->quadrics, m->quadric_count, o, d, t0, t1, cuts)
                            : 0;
  double dt = (t1 - t0) / steps, before = 0.0, weights = 0.0, lit = 0.0, start = t0;
  /* V apart from T_s: its mean over the segment's shaft_samples points multiplies the
   * segment's T_s (the nodes then see T_s alone) */
  const int shaft_samples = visible && rule.shaft_samples > 1 ? rule.shaft_samples : 1;
  const fog_sun_visibility_fn node_visible = shaft_samples > 1 ? NULL : visible;
  /* A piece deeper than FOG_SUN_PIECE_MAX_DEPTH is cut where its estimated depth reaches
   * it, until it is not (at most steps cuts a ray, so past a depth of ~steps): thick fog's
   * weight lies in the first units past where it starts, and two nodes on a piece whose
   * e^{-D} falls by e^{-2} or more missed it (a thick sphere's lit side erred by 4.5e-2 at
   * 8 segments; cut so, 1.9e-2). The cut meets the piece's end as its depth falls to the
   * limit, so the mean stays continuous from ray to ray; halving instead jumped by 1.6e-2
   * between neighbouring rays (arcs of seams). Thin fog is never cut. */
  int deep_cuts = 0;
  for (int i = 0; i < steps && before < depth_limit;) {
    /* [start, end]: the rest of equal segment i up to the next cut */
    const double step_end = i + 1 < steps ? t0 + (i + 1) * dt : t1;
    double end = step_end;
    for (int c = 0; c < cut_count; c++)
      if (cuts[c] > start && cuts[c] < end) end = cuts[c];
    double len, mid, step_depth, ka = 0.0, kb = 0.0, light;
    for (;;) {
      len = end - start, mid = 0.5 * (start + end);
      if (nodes == 2) {
        ka = fmax(extinction_on_ray(m, o, d, mid - g * len), 0.0);
        kb = fmax(extinction_on_ray(m, o, d, mid + g * len), 0.0);
        step_depth = 0.5 * len * (ka + kb);
      } else {
        step_depth = fmax(extinction_on_ray(m, o, d, mid), 0.0) * len;
      }
      if (!(step_depth > FOG_SUN_PIECE_MAX_DEPTH) || deep_cuts >= steps) break;
      /* at least 1/64 of the piece: past K ~ 2e6 the cut 1/K on would round to nothing in
       * the shader's float, which would spend its cuts on empty pieces */
      end = start + len * fmax(FOG_SUN_PIECE_MAX_DEPTH / step_depth, 1.0 / 64.0), deep_cuts++;
    }
    if (end >= step_end) i++;
    start = end;
    if (nodes == 2) {
      const double ta = mid - g * len, tb = mid + g * len;
      /* The nodes weigh K e^{-d}, d the depth from the segment's start, K linear through
       * them: only their ratio counts, so each is taken relative to node a's,
       * K_a : K_b e^{-(d_b - d_a)} with d_b - d_a = g len (K_a + K_b) (the trapezoid between
       * them). Absolute weights underflowed together in a dense segment (d ~ 745; in the
       * shader's float, ~90) and its light became 0; the depth to node a, extrapolated
       * back, went negative on a steep K and overflowed. */
      double sa = ka, sb = kb * exp(-g * len * (ka + kb));
      double lb = sun_light_at(m, kind, volume, o, d, tb, node_visible, user);
      /* sa + sb = 0 with K_b > 0: node a holds no fog, node b all of the weight */
      light = sa + sb > 0.0
                  ? (sa * sun_light_at(m, kind, volume, o, d, ta, node_visible, user) +
                     sb * lb) / (sa + sb)
                  : lb;
    } else {
      light = sun_light_at(m, kind, volume, o, d, mid, node_visible, user);
    }
    if (shaft_samples > 1) {
      double seen = 0.0;
      for (int k = 0; k < shaft_samples; k++) {
        const double t = mid + ((k + 0.5) / shaft_samples - 0.5) * len;
        double p[3];
        for (int a = 0; a < 3; a++) p[a] = o[a] + t * d[a];
        seen += visible(user, p);
      }
      light *= seen / shaft_samples;
    }
    double w = exp(-before) * -expm1(-step_depth);
    weights += w;
    lit += w * light;
    before += step_depth;
  }
  return weights > 0.0 ? lit / weights : 1.0;
}
