/* transform_plan: sizes, boundary rules and scratch of one transform configuration,
 * and the 2D passes (rows, strips of columns) built from the 1D lifting kernels. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "transform/transform_plan.h"

float *transform_alloc_floats(size_t count) {
  if (count > (SIZE_MAX - 64) / sizeof(float)) return NULL; /* the byte count would wrap */
  size_t bytes = (count * sizeof(float) + 63) / 64 * 64; /* aligned_alloc: a multiple */
  return aligned_alloc(64, bytes ? bytes : 64);
}

int transform_basis_degree(transform_basis basis) {
  return basis == TRANSFORM_HAAR ? 0 : basis == TRANSFORM_LINEAR ? 1 : 2;
}

transform_basis transform_basis_of_degree(int degree) {
  return degree == 0 ? TRANSFORM_HAAR : degree == 2 ? TRANSFORM_QUADRATIC : TRANSFORM_LINEAR;
}

static int max_levels_1d(int n, transform_boundary boundary) {
  int j = 0;
  while (n >= 2 && (boundary != TRANSFORM_PERIODIC || n % 2 == 0)) {
    n = n / 2 + n % 2; /* (n + 1) / 2 overflowed at INT_MAX and looped for ever */
    j++;
  }
  return j;
}

int transform_max_levels(int width, int height, transform_boundary boundary) {
  int a = max_levels_1d(width, boundary), b = max_levels_1d(height, boundary);
  return a < b ? a : b;
}

static const char *basis_name(transform_basis b) {
  return b == TRANSFORM_HAAR ? "haar" : b == TRANSFORM_LINEAR ? "linear" : "quadratic";
}

/* Lengths and ghost rules of one dimension, level J down to 0. */
static int plan_dimension(transform_plan *p, int n, int *len, level_rules *rules, fog_error *err) {
  const transform_desc *d = &p->desc;
  len[p->levels] = n;
  rules[p->levels] = ghost_rules_finest(d->basis, d->boundary, n);
  for (int l = p->levels; l >= 1; l--) {
    len[l - 1] = len[l] / 2 + len[l] % 2;
    if (ghost_rules_coarsen(d->basis, d->boundary, len[l], &rules[l], &rules[l - 1])) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
               "internal: singular boundary rule at level %d (length %d)", l, len[l]);
      return 1;
    }
  }
  return 0;
}

static int plan_make(transform_plan **out, const transform_desc *desc, fog_error *err) {
  *out = NULL;
  transform_desc d = *desc;
  if (d.width <= 0 || d.height <= 0) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fogmap size %dx%d: both must be positive", d.width,
             d.height);
    return 1;
  }
  if ((unsigned)d.basis > TRANSFORM_QUADRATIC)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "unknown basis");
  if ((unsigned)d.boundary > TRANSFORM_PERIODIC)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "unknown boundary mode");
  if ((unsigned)d.decomposition > TRANSFORM_STANDARD)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "unknown decomposition");
  if (d.threads < 0 || d.threads > 2)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "threads must be 0, 1 or 2");
  if (d.levels < 0) return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "levels must be >= 0");
  int jmax = transform_max_levels(d.width, d.height, d.boundary);
  if (d.levels > jmax) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "%dx%d is too small for %d levels%s: the largest J that fits is %d", d.width, d.height,
             d.levels,
             d.boundary == TRANSFORM_PERIODIC
                 ? " in periodic mode (every level needs an even width and height)"
                 : "",
             jmax);
    return 1;
  }
  transform_plan *p = calloc(1, sizeof *p);
  if (!p) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for a transform plan");
  p->desc = d;
  p->levels = d.levels;
  p->threads = d.threads == 2 ? 2 : 1;
  size_t nl = (size_t)d.levels + 1;
  p->len_w = calloc(nl, sizeof(int));
  p->len_h = calloc(nl, sizeof(int));
  p->rules_w = calloc(nl, sizeof(level_rules));
  p->rules_h = calloc(nl, sizeof(level_rules));
  int ok = p->len_w && p->len_h && p->rules_w && p->rules_h;
  if (ok && (plan_dimension(p, d.width, p->len_w, p->rules_w, err) ||
             plan_dimension(p, d.height, p->len_h, p->rules_h, err))) {
    transform_plan_destroy(p);
    return 1;
  }
  size_t longest = (size_t)(d.width > d.height ? d.width : d.height);
  for (int t = 0; ok && t < p->threads; t++) {
    transform_scratch *s = &p->scratch[t];
    s->row = malloc(sizeof(float) * (2 * longest + 16));
    s->strip = malloc(sizeof(float) * (size_t)TRANSFORM_STRIP * ((size_t)d.height + 2));
    s->ghost = malloc(sizeof(float) * 2 * TRANSFORM_STRIP);
    ok = s->row && s->strip && s->ghost;
  }
  for (int t = 0; ok && t < p->threads; t++) { /* each thread streams its own rows */
    transform_scratch *s = &p->scratch[t];
    s->ring = malloc(sizeof(float) * 17 * (size_t)d.width); /* + a ghost row */
    s->ring_ghost = malloc(sizeof(float) * (size_t)d.width);
    ok = s->ring && s->ring_ghost;
  }
  if (ok) {
    transform_scratch *s = &p->scratch[0];
    size_t half = (size_t)p->len_w[d.levels > 0 ? d.levels - 1 : 0] *
                  (size_t)p->len_h[d.levels > 0 ? d.levels - 1 : 0];
    s->level = malloc(sizeof(float) * (half ? half : 1));
    s->level2 = malloc(sizeof(float) * (half ? half : 1));
    ok = s->level && s->level2;
  }
  if (ok && p->threads == 2) ok = !transform_workers_start(p);
  if (!ok) {
    transform_plan_destroy(p);
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for a transform plan");
  }
  *out = p;
  return 0;
}

transform_plan *transform_plan_create(const transform_desc *desc, fog_error *err) {
  transform_plan *plan;
  return plan_make(&plan, desc, err) ? NULL : plan;
}

void transform_plan_destroy(transform_plan *p) {
  if (!p) return;
  transform_workers_stop(p);
  for (int t = 0; t < 2; t++) {
    free(p->scratch[t].row);
    free(p->scratch[t].strip);
    free(p->scratch[t].ghost);
    free(p->scratch[t].ring);
    free(p->scratch[t].ring_ghost);
    free(p->scratch[t].level);
    free(p->scratch[t].level2);
  }
  free(p->zero_band);
  free(p->len_w);
  free(p->len_h);
  free(p->rules_w);
  free(p->rules_h);
  free(p);
}

const transform_desc *transform_plan_desc(const transform_plan *p) { return &p->desc; }

const char *transform_basis_name(transform_basis basis) { return basis_name(basis); }

void transform_level_size(const transform_plan *p, int level, int *width, int *height) {
  *width = p->len_w[level];
  *height = p->len_h[level];
}

void transform_band_rect(const transform_plan *p, int l, transform_orientation o, int *x,
                         int *y, int *w, int *h) {
  int w0 = p->len_w[l - 1], h0 = p->len_h[l - 1], w1 = p->len_w[l], h1 = p->len_h[l];
  *x = o == TRANSFORM_DETAIL_Y ? 0 : w0;
  *w = o == TRANSFORM_DETAIL_Y ? w0 : w1 - w0;
  *y = o == TRANSFORM_DETAIL_X ? 0 : h0;
  *h = o == TRANSFORM_DETAIL_X ? h0 : h1 - h0;
}

/* ---- the 2D passes ---- */

/* The lifting step of level l along one axis (its lengths and boundary rules). */
static lifting_step step_along(const transform_plan *p, const int *len,
                               const level_rules *rules, int l) {
  return (lifting_step){.basis = p->desc.basis,
                        .periodic = p->desc.boundary == TRANSFORM_PERIODIC,
                        .n = len[l],
                        .fine = &rules[l],
                        .coarse = &rules[l - 1]};
}

static lifting_step step_w(const transform_plan *p, int l) {
  return step_along(p, p->len_w, p->rules_w, l);
}

static lifting_step step_h(const transform_plan *p, int l) {
  return step_along(p, p->len_h, p->rules_h, l);
}

/* Direct forward row steps for the two short filters: the lifting steps fused into
 * one loop per channel reading the interleaved row (stride-2 loads vectorise), the
 * same float operations in the same order as the planar kernels in lifting.c. */
static void row_forward_linear_interior(int begin, int end, const float *restrict x,
                                       float *restrict low, float *restrict high, float lo,
                                       float hi) {
  /* o_k-1 is recomputed rather than carried, so iterations are independent (vectorised) */
  for (int k = begin; k < end; k++) {
    float om = x[2 * k - 1] - 0.5f * (x[2 * k - 2] + x[2 * k]);
    float o = x[2 * k + 1] - 0.5f * (x[2 * k] + x[2 * k + 2]);
    low[k] = lo * (x[2 * k] + 0.25f * (om + o));
    high[k] = hi * o;
  }
}

/* x_n beyond an even row's end: a ghost of the coarse level's right rule, or x_0 when
 * periodic. */
static inline float right_ghost(const lifting_step *st, const float *x) {
  if (st->periodic) return x[0];
  float g = 0.0f;
  const ghost_rule *r = &st->coarse->right;
  for (int t = 0; t < r->count; t++) g += (float)r->weight[t] * x[2 * r->index[t]];
  return g;
}

static void row_forward_linear(const lifting_step *st, const float *restrict x,
                               float *restrict out, float lo, float hi) {
  int n = st->n, m = (n + 1) / 2, d = n / 2;
  int inner = d < m - 1 ? d : m - 1; /* o_k with x_2k+2 inside the row */
#define ODD(k) (x[2 * (k) + 1] - 0.5f * (x[2 * (k)] + x[2 * (k) + 2]))
  float *restrict high = out + m;
  row_forward_linear_interior(1, inner, x, out, high, lo, hi);
  float o_last; /* o_d-1 */
  if (d == m) { /* even n: x_n is a ghost of the coarse level's right rule */
    const float g = right_ghost(st, x);
    o_last = x[2 * d - 1] - 0.5f * (x[2 * d - 2] + g);
    high[d - 1] = hi * o_last;
    out[d - 1] = lo * (x[2 * d - 2] + 0.25f * (ODD(d - 2) + o_last));
  } else {
    o_last = ODD(d - 1);
    out[m - 1] = lo * (x[n - 1] + 0.25f * 2.0f * o_last);
  }
  float o0 = d == 1 ? o_last : ODD(0);
  high[0] = hi * o0;
  if (!(d == m && d - 1 == 0)) {
    float left = st->periodic ? o_last : o0;
    out[0] = lo * (x[0] + 0.25f * (left + o0));
  }
#undef ODD
}

static void row_forward_haar_halves(int d, const float *restrict x, float *restrict low,
                                    float *restrict high, float lo, float hi) {
  for (int k = 0; k < d; k++) {
    float o = x[2 * k + 1] - x[2 * k];
    low[k] = lo * (x[2 * k] + 0.5f * o);
    high[k] = hi * o;
  }
}

static void row_forward_haar(const lifting_step *st, const float *restrict x,
                             float *restrict out, float lo, float hi) {
  int n = st->n, m = (n + 1) / 2, d = n / 2;
  row_forward_haar_halves(d, x, out, out + m, lo, hi);
  if (m > d) out[m - 1] = lo * x[n - 1];
}

/* Direct inverse row steps (Haar, CDF 5/3): read [c | d], write the interleaved row,
 * the same float operations as the planar kernels' inverse. `in` must not alias `x`. */
/* x_2k and x_2k+1 of the interior in one loop (an interleaved store pair, which gcc
 * vectorises; e_k+1 recomputed, not carried, so iterations are independent); the same
 * expressions as the scalar ends in row_inverse_linear, so the same bits. Cloned for
 * AVX-512 and AVX2, picked at load time (ifunc), the default build staying portable. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
static void row_inverse_linear_interior(int begin, int end, const float *restrict c,
                                        const float *restrict dd, float *restrict x,
                                        float ilo, float ihi) {
  for (int k = begin; k < end; k++) {
    float e = ilo * c[k] + -0.25f * (ihi * dd[k - 1] + ihi * dd[k]);
    float e_next = ilo * c[k + 1] + -0.25f * (ihi * dd[k] + ihi * dd[k + 1]);
    x[2 * k] = e;
    x[2 * k + 1] = ihi * dd[k] - -0.5f * (e + e_next);
  }
}

static void row_inverse_linear(const lifting_step *st, const float *restrict in,
                               float *restrict x, float ilo, float ihi) {
  int n = st->n, m = (n + 1) / 2, d = n / 2;
  const float *restrict c = in, *restrict dd = in + m;
  int both = m < d ? m : d;
  int inner = d < m - 1 ? d : m - 1; /* x_2k+1 with x_2k+2 inside the row */
  /* interior k: e_k and e_k+1 both of the plain form, x_2k+1 inside */
  int kv = both - 1 < inner ? both - 1 : inner;
  if (kv > 1) row_inverse_linear_interior(1, kv, c, dd, x, ilo, ihi);
  int rest = kv > 1 ? kv : 1;
  /* e_k = c_k/lo - (o_k-1 + o_k)/4, o = d/hi recomputed (independent iterations) */
  for (int k = rest; k < both; k++)
    x[2 * k] = ilo * c[k] + -0.25f * (ihi * dd[k - 1] + ihi * dd[k]);
  float o0 = ihi * dd[0], olast = ihi * dd[d - 1];
  x[0] = ilo * c[0] + -0.25f * ((st->periodic ? olast : o0) + o0);
  if (m > d) x[n - 1] = ilo * c[m - 1] + -0.25f * 2.0f * olast;
  /* x_2k+1 = o_k + (e_k + e_k+1)/2 */
  if (inner > 0) x[1] = ihi * dd[0] - -0.5f * (x[0] + x[2]);
  for (int k = rest; k < inner; k++) x[2 * k + 1] = ihi * dd[k] - -0.5f * (x[2 * k] + x[2 * k + 2]);
  if (d == m) {
    const float g = right_ghost(st, x);
    x[2 * d - 1] = olast - -0.5f * (x[2 * d - 2] + g);
  }
}

static void row_inverse_haar(const lifting_step *st, const float *restrict in,
                             float *restrict x, float ilo, float ihi) {
  int n = st->n, m = (n + 1) / 2, d = n / 2;
  const float *restrict c = in, *restrict dd = in + m;
  for (int k = 0; k < d; k++) {
    float o = ihi * dd[k];
    float e = ilo * c[k] - 0.5f * o;
    x[2 * k] = e;
    x[2 * k + 1] = o + e;
  }
  if (m > d) x[n - 1] = ilo * c[m - 1];
}

/* Rows [r0, r1): split (forward) or merge (inverse) levels `from` .. `to` of the row
 * direction, reading src and writing dst (same stride; may be equal). Forward runs
 * from = top level down to `to`; inverse from `from` up to `to`. */
void transform_rows(const transform_plan *p, int thread, int forward, int top, int bottom,
                    const float *src, float *dst, size_t stride, int r0, int r1) {
  transform_scratch *s = (transform_scratch *)&p->scratch[thread];
  float lo = lifting_scale_low(p->desc.basis), hi = lifting_scale_high(p->desc.basis);
  float ilo = 1.0f / lo, ihi = 1.0f / hi;
  for (int r = r0; r < r1; r++) {
    const float *in = src + (size_t)r * stride;
    float *restrict x = dst + (size_t)r * stride;
    if (forward) {
      for (int l = top; l > bottom; l--) {
        lifting_step st = step_w(p, l);
        int n = st.n, m = (n + 1) / 2, d = n / 2;
        float *restrict e = s->row, *restrict o = s->row + m + 4;
        const float *restrict xi = (l == top) ? in : x;
        if (p->desc.basis != TRANSFORM_QUADRATIC && n >= 4) {
          if (xi == x) { /* in place: lift from a copy */
            float *copy = s->row + n + 8;
            memcpy(copy, x, sizeof(float) * (size_t)n);
            xi = copy;
          }
          if (p->desc.basis == TRANSFORM_LINEAR)
            row_forward_linear(&st, xi, x, lo, hi);
          else
            row_forward_haar(&st, xi, x, lo, hi);
          continue;
        }
        for (int k = 0; k < d; k++) e[k] = xi[2 * k], o[k] = xi[2 * k + 1];
        if (m > d) e[m - 1] = xi[n - 1];
        lifting_forward(&st, e, o, 1, s->ghost);
        for (int k = 0; k < m; k++) x[k] = lo * e[k];
        for (int k = 0; k < d; k++) x[m + k] = hi * o[k];
      }
      if (top == bottom && in != x) memcpy(x, in, sizeof(float) * (size_t)p->len_w[top]);
    } else {
      int direct = p->desc.basis != TRANSFORM_QUADRATIC && top == bottom + 1 && in != x &&
                   p->len_w[top] >= 4;
      if (direct) { /* one level, out of place: straight from the input row */
        lifting_step st = step_w(p, top);
        if (p->desc.basis == TRANSFORM_LINEAR)
          row_inverse_linear(&st, in, x, ilo, ihi);
        else
          row_inverse_haar(&st, in, x, ilo, ihi);
        continue;
      }
      if (in != x) memcpy(x, in, sizeof(float) * (size_t)p->len_w[top]);
      for (int l = bottom + 1; l <= top; l++) {
        lifting_step st = step_w(p, l);
        int n = st.n, m = (n + 1) / 2, d = n / 2;
        if (p->desc.basis != TRANSFORM_QUADRATIC && n >= 4) { /* in place: from a copy */
          float *copy = s->row + n + 8;
          memcpy(copy, x, sizeof(float) * (size_t)n);
          if (p->desc.basis == TRANSFORM_LINEAR)
            row_inverse_linear(&st, copy, x, ilo, ihi);
          else
            row_inverse_haar(&st, copy, x, ilo, ihi);
          continue;
        }
        float *restrict e = s->row, *restrict o = s->row + m + 4;
        for (int k = 0; k < m; k++) e[k] = ilo * x[k];
        for (int k = 0; k < d; k++) o[k] = ihi * x[m + k];
        lifting_inverse(&st, e, o, 1, s->ghost);
        for (int k = 0; k < d; k++) x[2 * k] = e[k], x[2 * k + 1] = o[k];
        if (m > d) x[n - 1] = e[m - 1];
      }
    }
  }
}

/* Columns [c0, c1) in strips of TRANSFORM_STRIP, levels as transform_rows; in place. */
void transform_columns(const transform_plan *p, int thread, int forward, int top, int bottom,
                       float *base, size_t stride, int c0, int c1) {
  transform_scratch *s = (transform_scratch *)&p->scratch[thread];
  float lo = lifting_scale_low(p->desc.basis), hi = lifting_scale_high(p->desc.basis);
  float ilo = 1.0f / lo, ihi = 1.0f / hi;
  for (int c = c0; c < c1; c += TRANSFORM_STRIP) {
    int L = c1 - c < TRANSFORM_STRIP ? c1 - c : TRANSFORM_STRIP;
    for (int step = 0; step < top - bottom; step++) {
      int l = forward ? top - step : bottom + 1 + step;
      lifting_step st = step_h(p, l);
      int n = st.n, m = (n + 1) / 2;
      float *restrict e = s->strip, *restrict o = s->strip + (size_t)m * L;
      if (forward) {
        for (int k = 0; k < n; k++) {
          float *restrict dstc = (k % 2 ? o : e) + (size_t)(k / 2) * L;
          const float *restrict srcc = base + (size_t)k * stride + c;
          for (int i = 0; i < L; i++) dstc[i] = srcc[i];
        }
        lifting_forward(&st, e, o, L, s->ghost);
        for (int k = 0; k < n; k++) {
          const float *restrict srcc = k < m ? e + (size_t)k * L : o + (size_t)(k - m) * L;
          float w = k < m ? lo : hi;
          float *restrict dstc = base + (size_t)k * stride + c;
          for (int i = 0; i < L; i++) dstc[i] = w * srcc[i];
        }
      } else {
        for (int k = 0; k < n; k++) {
          float *restrict dstc = k < m ? e + (size_t)k * L : o + (size_t)(k - m) * L;
          float w = k < m ? ilo : ihi;
          const float *restrict srcc = base + (size_t)k * stride + c;
          for (int i = 0; i < L; i++) dstc[i] = w * srcc[i];
        }
        lifting_inverse(&st, e, o, L, s->ghost);
        for (int k = 0; k < n; k++) {
          const float *restrict srcc = (k % 2 ? o : e) + (size_t)(k / 2) * L;
          float *restrict dstc = base + (size_t)k * stride + c;
          for (int i = 0; i < L; i++) dstc[i] = srcc[i];
        }
      }
    }
  }
}
