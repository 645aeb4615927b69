/* One forward level of the non-standard transform in a single streaming pass: each
 * input row is lifted along x into a small ring of rows (L1/L2 resident), the column
 * lifting steps run on those ring rows as soon as their neighbours exist (every inner
 * loop is a whole row: contiguous, vectorised), and every output row is written once,
 * already at its final place and scale. Memory traffic is one read of the level and
 * one write, as for a memcpy; the two-pass version (rows, then strips of columns)
 * moves the data twice. Same lifting steps and boundary rules as the two-pass columns,
 * the same coefficients to float rounding (tests/transform/test_fused_matches_two_pass.c;
 * Haar's bits agree, the quadratic's step 3 sums its terms in another order, ~7e-7). The
 * CDF 5/3 level in SIMD (transform_fused_linear.h) runs the other way round, column step
 * first, without a ring. */
#include <stdint.h>
#include <string.h>

#include "transform/transform_plan.h"

#define RING 16 /* fine rows in flight; the widest window (bior3.3) spans 8 */

typedef struct stream {
  const transform_plan *p;
  int thread, l, w, n, loaded; /* fine rows < loaded are in the ring */
  const float *src;
  size_t src_stride;
  float *ring;
} stream;

static float *slot(const stream *s, int fine_row) {
  return s->ring + (size_t)(fine_row % RING) * (size_t)s->w;
}

/* Lift input rows along x until fine row `upto` is in the ring. */
static void load_until(stream *s, int upto) {
  if (upto > s->n - 1) upto = s->n - 1;
  while (s->loaded <= upto) {
    int r = s->loaded++;
    transform_rows(s->p, s->thread, 1, s->l, s->l - 1, s->src + (size_t)r * s->src_stride,
                   slot(s, r), 0, 0, 1);
  }
}

/* rule over rows of the ring: fine rows = 2 * coarse index (even channel) */
static void rule_rows(const stream *s, const ghost_rule *r, int fine_step, int fine_offset,
                      float *restrict out) {
  int w = s->w;
  for (int i = 0; i < w; i++) out[i] = 0.0f;
  for (int t = 0; t < r->count; t++) {
    const float *restrict row = slot(s, fine_step * r->index[t] + fine_offset);
    float k = (float)r->weight[t];
    for (int i = 0; i < w; i++) out[i] += k * row[i];
  }
}

int transform_fused_supported(const transform_plan *p, int l) {
  if (p->desc.two_pass) return 0;
  if (p->desc.boundary != TRANSFORM_SYMMETRIC || p->desc.decomposition != TRANSFORM_NONSTANDARD)
    return 0;
  int n = p->len_h[l], m = (n + 1) / 2;
  if (n < 8) return 0;
  /* the ring holds only a window: the rules must reference rows near their own end */
  const ghost_rule *right = &p->rules_h[l - 1].right, *left = &p->rules_h[l].left;
  for (int t = 0; t < right->count; t++)
    if (right->index[t] < m - 2) return 0;
  for (int t = 0; t < left->count; t++)
    if (left->index[t] > 1) return 0;
  return 1;
}

static void linear_row_step(int w, const float *restrict e0, const float *restrict e1,
                            const float *restrict om, float *restrict o, float *restrict low,
                            float *restrict high, float lo, float hi) {
  for (int i = 0; i < w; i++) {
    float v = o[i] - 0.5f * (e0[i] + e1[i]);
    o[i] = v;
    high[i] = hi * v;
    low[i] = lo * (e0[i] + 0.25f * (om[i] + v));
  }
}

/* o_k0-1 (predicted, in the ring) for a range starting at k0 > 0: fine rows 2k0-2 ..
 * 2k0 lifted along x, then the column predict of linear_level (same operations) */
static void linear_warm_up(stream *s, int k0) {
  s->loaded = 2 * k0 - 2;
  load_until(s, 2 * k0);
  float *restrict o = slot(s, 2 * k0 - 1);
  const float *restrict e0 = slot(s, 2 * k0 - 2), *restrict e1 = slot(s, 2 * k0);
  for (int i = 0; i < s->w; i++) o[i] = o[i] - 0.5f * (e0[i] + e1[i]);
}

static void linear_level(stream *s, float *dst, size_t dst_stride, float *ghost, int k0,
                         int k1) {
  int n = s->n, m = (n + 1) / 2, d = n / 2, w = s->w;
  float lo = lifting_scale_low(TRANSFORM_LINEAR), hi = lifting_scale_high(TRANSFORM_LINEAR);
  const ghost_rule *rho = &s->p->rules_h[s->l - 1].right;
  if (k0 > 0) linear_warm_up(s, k0);
  /* iteration k: predict o_k = x_2k+1 - (x_2k + x_2k+2)/2 and, in the same loop, update
   * e_k = x_2k + (o_k-1 + o_k)/4; both written out at once, o_k kept for e_k+1 */
  for (int k = k0; k < k1; k++) {
    load_until(s, 2 * k + 2);
    const float *restrict e0 = slot(s, 2 * k);
    float *restrict low = dst + (size_t)k * dst_stride;
    if (k < d) {
      float *restrict o = slot(s, 2 * k + 1);
      const float *restrict e1;
      if (2 * k + 2 < n) {
        e1 = slot(s, 2 * k + 2);
      } else {
        rule_rows(s, rho, 2, 0, ghost);
        e1 = ghost;
      }
      float *restrict high = dst + (size_t)(m + k) * dst_stride;
      if (k > 0) {
        linear_row_step(w, e0, e1, slot(s, 2 * k - 1), o, low, high, lo, hi);
      } else { /* o_-1 is o_0 itself */
        for (int i = 0; i < w; i++) {
          float v = o[i] - 0.5f * (e0[i] + e1[i]);
          o[i] = v;
          high[i] = hi * v;
          low[i] = lo * (e0[i] + 0.25f * (v + v));
        }
      }
    } else { /* odd n, last even row: o_m-1 mirrors to o_m-2 */
      const float *restrict om = slot(s, 2 * k - 1);
      for (int i = 0; i < w; i++) low[i] = lo * (e0[i] + 0.25f * (om[i] + om[i]));
    }
  }
}

/* The CDF 5/3 level in explicit SIMD (transform_fused_linear.h) at three widths: the
 * portable SSE2 one (x86-64 baseline, and any other gcc target) and, chosen at run time
 * on x86-64 CPUs that have them, AVX2 and AVX-512 ones. All give the same bits. Build
 * with -DFOGPIPE_FUSED_MAX_V=4 (or 8) to measure the baseline (or AVX2) path alone.
 * Compilers without __builtin_shuffle (clang) use the scalar-loop linear_level above
 * (rows first: the same coefficients to float rounding, not the same bits). */
#ifndef FOGPIPE_FUSED_MAX_V
#define FOGPIPE_FUSED_MAX_V 16
#endif
#if defined(__GNUC__) && !defined(__clang__)
#define FUSED_SIMD 1
#define FL_V 4
#define FL_NAME(x) fl4_##x
#define FL_TARGET
#define FL_EVEN {0, 2, 4, 6}
#define FL_ODD {1, 3, 5, 7}
/* two shufps; gcc's lowering of the one-shuffle form takes six instructions */
#define FL_SHIFT(a, b) \
  __builtin_shuffle(__builtin_shuffle(a, b, (vi){3, 3, 4, 4}), b, (vi){0, 2, 5, 6})
#define FL_NEXT(a, b) __builtin_shuffle(a, b, (vi){1, 2, 3, 4})
#include "transform/transform_fused_linear.h" /* undefines its FL_ parameters */

#if defined(__x86_64__) && FOGPIPE_FUSED_MAX_V > 4
#define FUSED_DISPATCH 1
#define FL_V 8
#define FL_NAME(x) fl8_##x
#define FL_TARGET __attribute__((target("avx2")))
#define FL_EVEN {0, 2, 4, 6, 8, 10, 12, 14}
#define FL_ODD {1, 3, 5, 7, 9, 11, 13, 15}
#define FL_SHIFT(a, b) __builtin_shuffle(a, b, (vi){7, 8, 9, 10, 11, 12, 13, 14})
#define FL_NEXT(a, b) __builtin_shuffle(a, b, (vi){1, 2, 3, 4, 5, 6, 7, 8})
#include "transform/transform_fused_linear.h" /* undefines its FL_ parameters */
#define FL_V 16
#define FL_NAME(x) fl16_##x
#define FL_TARGET __attribute__((target("avx512f")))
#define FL_EVEN {0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30}
#define FL_ODD {1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31}
#define FL_SHIFT(a, b) \
  __builtin_shuffle(a, b, (vi){15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30})
#define FL_NEXT(a, b) \
  __builtin_shuffle(a, b, (vi){1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16})
#include "transform/transform_fused_linear.h" /* undefines its FL_ parameters */
#endif
#endif /* FUSED_SIMD */

#ifdef FUSED_SIMD
static void linear_level_simd(const transform_plan *p, int l, const float *src,
                              size_t src_stride, float *ring, float *dst, size_t dst_stride,
                              float *ghost, int k0, int k1) {
#ifdef FUSED_DISPATCH
  if (FOGPIPE_FUSED_MAX_V >= 16 && __builtin_cpu_supports("avx512f")) {
    fl16_level(p, l, src, src_stride, ring, dst, dst_stride, ghost, k0, k1);
    return;
  }
  if (__builtin_cpu_supports("avx2")) {
    fl8_level(p, l, src, src_stride, ring, dst, dst_stride, ghost, k0, k1);
    return;
  }
#endif
  fl4_level(p, l, src, src_stride, ring, dst, dst_stride, ghost, k0, k1);
}
#endif

static void haar_level(stream *s, float *dst, size_t dst_stride, int k0, int k1) {
  int n = s->n, m = (n + 1) / 2, d = n / 2, w = s->w;
  float hi = lifting_scale_high(TRANSFORM_HAAR);
  s->loaded = 2 * k0; /* rows are independent pairs */
  for (int k = k0; k < k1; k++) {
    load_until(s, 2 * k + 1);
    const float *restrict e = slot(s, 2 * k);
    float *restrict lo_out = dst + (size_t)k * dst_stride;
    if (k < d) {
      const float *restrict o = slot(s, 2 * k + 1);
      float *restrict hi_out = dst + (size_t)(m + k) * dst_stride;
      for (int i = 0; i < w; i++) {
        float v = o[i] - e[i];
        hi_out[i] = hi * v;
        lo_out[i] = e[i] + 0.5f * v;
      }
    } else {
      memcpy(lo_out, e, sizeof(float) * (size_t)w);
    }
  }
}

/* Iteration k runs step 1 on e_k, step 2 on o_k-1, step 3 on e_k-2. For output rows
 * [k0, k1), step 3 needs o_k0-1 .. o_k1 final, so a range past 0 starts one iteration
 * early (from raw row 2k0-3) and steps 2 without writing o_k0-1; each range ends with
 * step 2 on o_k1, kept in the ring only. */
static void quadratic_level(stream *s, float *dst, size_t dst_stride, float *ghost, int k0,
                            int k1) {
  int n = s->n, m = (n + 1) / 2, d = n / 2, w = s->w;
  float lo = lifting_scale_low(TRANSFORM_QUADRATIC), hi = lifting_scale_high(TRANSFORM_QUADRATIC);
  const float third = (float)(1.0 / 3.0), a = (float)(3.0 / 36.0), b = (float)(16.0 / 36.0);
  const ghost_rule *rho = &s->p->rules_h[s->l - 1].right;
  const ghost_rule *left = &s->p->rules_h[s->l].left;
  int k_first = k0 > 0 ? k0 - 1 : 0, k_last = k1 + 1 < m + 1 ? k1 + 1 : m + 1;
  s->loaded = k_first > 0 ? 2 * k_first - 1 : 0;
  for (int k = k_first; k <= k_last; k++) {
    load_until(s, k == 0 ? 1 : 2 * k);
    if (k < m) { /* step 1: e_k -= o_k-1 / 3 (k = 0: the fine level's left ghost) */
      float *restrict e = slot(s, 2 * k);
      if (k == 0) {
        rule_rows(s, left, 1, 0, ghost);
        for (int i = 0; i < w; i++) e[i] -= third * ghost[i];
      } else {
        const float *restrict o = slot(s, 2 * k - 1);
        for (int i = 0; i < w; i++) e[i] -= third * o[i];
      }
    }
    int j = k - 1; /* step 2: o_j -= (9 e_j + 3 e_j+1)/8, written out */
    if (j >= k_first && j < d) {
      float *restrict o = slot(s, 2 * j + 1);
      const float *restrict e0 = slot(s, 2 * j);
      const float *restrict e1;
      if (j + 1 < m) {
        e1 = slot(s, 2 * j + 2);
      } else {
        rule_rows(s, rho, 2, 0, ghost);
        e1 = ghost;
      }
      if (j >= k0 && j < k1) {
        float *restrict out = dst + (size_t)(m + j) * dst_stride;
        for (int i = 0; i < w; i++) {
          float v = o[i] - (1.125f * e0[i] + 0.375f * e1[i]);
          o[i] = v;
          out[i] = hi * v;
        }
      } else { /* a neighbour's row: needed final, written by the neighbour */
        for (int i = 0; i < w; i++) o[i] = o[i] - (1.125f * e0[i] + 0.375f * e1[i]);
      }
    }
    int q = k - 2; /* step 3: e_q += (3 o_q-1 + 16 o_q - 3 o_q+1)/36, written out */
    if (q >= k0 && q < k1) {
      const float *restrict e = slot(s, 2 * q);
      float *restrict out = dst + (size_t)q * dst_stride;
      const float *om = q >= 1 ? slot(s, 2 * q - 1) : NULL;
      const float *o0 = q < d ? slot(s, 2 * q + 1) : NULL;
      const float *op = q + 1 < d ? slot(s, 2 * q + 3) : NULL;
      if (om && o0 && op) {
        for (int i = 0; i < w; i++) out[i] = lo * (e[i] + a * (om[i] - op[i]) + b * o0[i]);
      } else { /* ends: missing odd rows are zero */
        for (int i = 0; i < w; i++) {
          float v = e[i];
          if (om) v += a * om[i];
          if (o0) v += b * o0[i];
          if (op) v -= a * op[i];
          out[i] = lo * v;
        }
      }
    }
  }
}

void transform_fused_forward_level(const transform_plan *p, int thread, int l,
                                   const float *src, size_t src_stride, float *dst,
                                   size_t dst_stride, int k0, int k1) {
  transform_scratch *sc = (transform_scratch *)&p->scratch[thread];
  stream s = {.p = p, .thread = thread, .l = l, .w = p->len_w[l], .n = p->len_h[l],
              .loaded = 0, .src = src, .src_stride = src_stride, .ring = sc->ring};
  switch (p->desc.basis) {
    case TRANSFORM_HAAR: haar_level(&s, dst, dst_stride, k0, k1); break;
    case TRANSFORM_LINEAR:
#ifdef FUSED_SIMD
      if (s.w >= 4) {
        linear_level_simd(p, l, src, src_stride, sc->ring, dst, dst_stride, sc->ring_ghost, k0,
                          k1);
        break;
      }
#endif
      linear_level(&s, dst, dst_stride, sc->ring_ghost, k0, k1);
      break;
    case TRANSFORM_QUADRATIC: quadratic_level(&s, dst, dst_stride, sc->ring_ghost, k0, k1); break;
  }
}

/* ---- one inverse level in a single streaming pass (Haar and CDF 5/3) ----
 * Reads the level's composite rows — row r < h_{l-1}: [A_{l-1} row r | band X row r],
 * row r >= h_{l-1}: [band Y | band XY] — scales them into the ring, undoes the column
 * steps as soon as the neighbours exist, merges each finished fine row along x and
 * writes it once. `low` NULL means a zero A_{l-1} (deconstructed details). */

typedef struct inverse_stream {
  const transform_plan *p;
  int thread, l, w, n, m, loaded; /* composite rows < loaded are in the ring */
  const float *low, *coef;
  size_t low_stride, coef_stride;
  float *ring;
  float scale_low, scale_high; /* 1/lo, 1/hi */
} inverse_stream;

static float *islot(const inverse_stream *s, int k) { /* composite row k */
  return s->ring + (size_t)(k % RING) * (size_t)s->w;
}

/* composite rows 0..k of the low half and m..m+k of the high half, scaled */
static void iload_until(inverse_stream *s, int k) {
  int w0 = s->p->len_w[s->l - 1], d = s->n - s->m;
  if (k > s->m - 1) k = s->m - 1;
  while (s->loaded <= k) {
    int r = s->loaded++;
    float *restrict e = islot(s, 2 * r);
    const float *restrict band = s->coef + (size_t)r * s->coef_stride;
    if (s->low) {
      const float *restrict lowrow = s->low + (size_t)r * s->low_stride;
      for (int i = 0; i < w0; i++) e[i] = s->scale_low * lowrow[i];
    } else {
      for (int i = 0; i < w0; i++) e[i] = 0.0f;
    }
    for (int i = w0; i < s->w; i++) e[i] = s->scale_low * band[i];
    if (r < d) {
      float *restrict o = islot(s, 2 * r + 1);
      const float *restrict high = s->coef + (size_t)(s->m + r) * s->coef_stride;
      for (int i = 0; i < s->w; i++) o[i] = s->scale_high * high[i];
    }
  }
}

int transform_fused_inverse_supported(const transform_plan *p, int l) {
  return p->desc.basis != TRANSFORM_QUADRATIC && transform_fused_supported(p, l);
}

static void emit_row(const inverse_stream *s, const float *fine, float *dst) {
  transform_rows(s->p, s->thread, 0, s->l, s->l - 1, fine, dst, 0, 0, 1);
}

/* Fine rows 2k, 2k+1 for k in [k0, k1): e_k needs o_k-1 and o_k, the odd row 2k+1 needs
 * e_k+1 too, so a range reads composite rows k0-1 .. k1 and finishes e_k1 unwritten. */
void transform_fused_inverse_level(const transform_plan *p, int thread, int l,
                                   const float *low, size_t low_stride, const float *coef,
                                   size_t coef_stride, float *dst, size_t dst_stride, int k0,
                                   int k1) {
  transform_scratch *sc = (transform_scratch *)&p->scratch[thread];
  int n = p->len_h[l], m = (n + 1) / 2, d = n / 2, w = p->len_w[l];
  transform_basis basis = p->desc.basis;
  inverse_stream s = {.p = p, .thread = thread, .l = l, .w = w, .n = n, .m = m,
                      .loaded = k0 > 0 ? k0 - 1 : 0, .low = low,
                      .coef = coef, .low_stride = low_stride, .coef_stride = coef_stride,
                      .ring = sc->ring, .scale_low = 1.0f / lifting_scale_low(basis),
                      .scale_high = 1.0f / lifting_scale_high(basis)};
  /* even rows live in ring slots 2k (scaled c, then final e), odd in 2k+1 (scaled d) */
  float *fine = sc->ring_ghost; /* one fine row before the merge along x */
  float *ghost = sc->ring + (size_t)(RING - 0) * (size_t)w; /* extra row after the ring */
  if (basis == TRANSFORM_HAAR) {
    s.loaded = k0;
    for (int k = k0; k < k1; k++) {
      iload_until(&s, k);
      float *restrict e = islot(&s, 2 * k);
      if (k < d) {
        const float *restrict o = islot(&s, 2 * k + 1);
        for (int i = 0; i < w; i++) e[i] -= 0.5f * o[i];
        emit_row(&s, e, dst + (size_t)(2 * k) * dst_stride);
        for (int i = 0; i < w; i++) fine[i] = o[i] + e[i];
        emit_row(&s, fine, dst + (size_t)(2 * k + 1) * dst_stride);
      } else {
        emit_row(&s, e, dst + (size_t)(2 * k) * dst_stride);
      }
    }
    return;
  }
  /* CDF 5/3: e_k -= (o_k-1 + o_k)/4 (o_-1 = o_0; odd n: o_m-1 = o_m-2), then
   * x_2k+1 = o_k + (e_k + e_k+1)/2 with e_m from the coarse right rule (even n) */
  const ghost_rule *rho = &p->rules_h[l - 1].right;
  for (int k = k0; k <= k1; k++) {
    if (k < m) { /* finish e_k */
      iload_until(&s, k + 1);
      float *restrict e = islot(&s, 2 * k);
      const float *restrict om = islot(&s, k > 0 ? 2 * k - 1 : 1);
      const float *restrict op = islot(&s, k < d ? 2 * k + 1 : 2 * k - 1);
      for (int i = 0; i < w; i++) e[i] += -0.25f * (om[i] + op[i]);
      if (k < k1) emit_row(&s, e, dst + (size_t)(2 * k) * dst_stride);
    }
    int j = k - 1; /* odd row 2j+1 once e_j and e_j+1 are final */
    if (j >= k0 && j < d) {
      const float *restrict o = islot(&s, 2 * j + 1);
      const float *restrict e0 = islot(&s, 2 * j);
      const float *restrict e1;
      if (j + 1 < m) {
        e1 = islot(&s, 2 * j + 2);
      } else {
        for (int i = 0; i < w; i++) ghost[i] = 0.0f;
        for (int t = 0; t < rho->count; t++) {
          const float *restrict row = islot(&s, 2 * rho->index[t]);
          float c = (float)rho->weight[t];
          for (int i = 0; i < w; i++) ghost[i] += c * row[i];
        }
        e1 = ghost;
      }
      for (int i = 0; i < w; i++) fine[i] = o[i] - -0.5f * (e0[i] + e1[i]);
      emit_row(&s, fine, dst + (size_t)(2 * j + 1) * dst_stride);
    }
  }
}
