/* The fused CDF 5/3 forward level, written once for one SIMD width and included by
 * transform_fused.c once per width (FL_V floats per vector, FL_NAME(x) names the
 * functions, FL_TARGET their target attribute; the masks FL_EVEN/FL_ODD, and
 * FL_SHIFT(prev, o): the vector (prev[FL_V-1], o[0], ..., o[FL_V-2])).
 * Not a header to include elsewhere: it has no include guard on purpose, and it
 * undefines its FL_ parameters at its end, ready for the next width.
 *
 * GCC vector extensions, not intrinsics: the same source compiles for any target and
 * gcc picks the shuffles (SSE2 shufps, AVX2 vpermps, AVX-512 vpermt2ps). Every float
 * operation is the one of the scalar code in the same order (and -std=c11 keeps
 * contraction off), so all widths give the same bits as transform_rows plus the
 * two-pass columns' interior. */

typedef float FL_NAME(vf) __attribute__((vector_size(4 * FL_V)));
typedef int FL_NAME(vi) __attribute__((vector_size(4 * FL_V)));

/* Row lifting of one input row x (length n >= 4) to y = [lo*e | hi*o] (the layout
 * transform_rows writes): the steps of transform_plan.c's row_forward_linear. The
 * vector part: outputs k .. k+FL_V-1 of both halves from four loads, the even/odd split
 * being two shuffles of two loads, x_2k+2 the even lanes one pair further, and o_k-1
 * the lanes of o shifted by one with the previous vector's last lane (`prev`). */
#define FL_ODD_AT(x, k) ((x)[2 * (k) + 1] - 0.5f * ((x)[2 * (k)] + (x)[2 * (k) + 2]))
FL_TARGET static inline __attribute__((always_inline)) void FL_NAME(lift)(
    const float *restrict x, int k, FL_NAME(vf) *prev, FL_NAME(vf) *lw, FL_NAME(vf) *hg,
    float lo, float hi) {
  typedef FL_NAME(vf) vf;
  typedef FL_NAME(vi) vi;
  vf a, b, c, e2;
  const float *xk = x + 2 * (size_t)k;
  __builtin_memcpy(&a, xk, sizeof a);
  __builtin_memcpy(&b, xk + FL_V, sizeof b);
  __builtin_memcpy(&c, xk + 2, sizeof c);
  __builtin_memcpy(&e2, xk + 2 + FL_V, sizeof e2);
  vf ev = __builtin_shuffle(a, b, (vi)FL_EVEN);
  vf od = __builtin_shuffle(a, b, (vi)FL_ODD);
  vf e1 = __builtin_shuffle(c, e2, (vi)FL_EVEN);
  vf o = od - 0.5f * (ev + e1);
  vf om = FL_SHIFT(*prev, o);
  *lw = lo * (ev + 0.25f * (om + o));
  *hg = hi * o;
  *prev = o;
}

/* Outputs k < row_vector_end(n) are done by vectors (their loads reach x[2(k+FL_V)+1],
 * inside the row); none when the row is too short for one vector. */
static inline int FL_NAME(row_vector_end)(int n) {
  int m = (n + 1) / 2, d = n / 2, inner = d < m - 1 ? d : m - 1;
  int kv = inner < (n - 2) / 2 ? inner : (n - 2) / 2;
  return kv >= FL_V ? kv : 0;
}

/* The scalar rest of a row: outputs kv on (the right end), and the left end (outputs 0
 * of both halves, which the vectors, when there are any, gave the same values). */
FL_TARGET static inline __attribute__((always_inline)) void FL_NAME(row_tail)(
    int n, const float *restrict x, float *restrict y, float lo, float hi,
    const float *ghost_w, const int *ghost_i, int ghost_n, int kv) {
  int m = (n + 1) / 2, d = n / 2;
  int inner = d < m - 1 ? d : m - 1; /* o_k with x_2k+2 inside the row */
  float *restrict low = y, *restrict high = y + m;
  for (int k = kv > 1 ? kv : 1; k < inner; k++) {
    float om = FL_ODD_AT(x, k - 1), o = FL_ODD_AT(x, k);
    low[k] = lo * (x[2 * k] + 0.25f * (om + o));
    high[k] = hi * o;
  }
  float o_last; /* o_d-1 */
  if (d == m) { /* even n: x_n is a ghost of the coarse level's right rule */
    float g = 0.0f;
    for (int t = 0; t < ghost_n && t < 4; t++) g += ghost_w[t] * x[2 * ghost_i[t]];
    o_last = x[2 * d - 1] - 0.5f * (x[2 * d - 2] + g);
    high[d - 1] = hi * o_last;
    low[d - 1] = lo * (x[2 * d - 2] + 0.25f * (FL_ODD_AT(x, d - 2) + o_last));
  } else {
    o_last = FL_ODD_AT(x, d - 1);
    low[m - 1] = lo * (x[n - 1] + 0.25f * 2.0f * o_last);
  }
  float o0 = d > 1 ? FL_ODD_AT(x, 0) : o_last; /* o_-1 = o_0 (symmetric) */
  high[0] = hi * o0;
  if (!(d == m && d - 1 == 0)) low[0] = lo * (x[0] + 0.25f * (o0 + o0));
}

FL_TARGET static inline __attribute__((always_inline)) void FL_NAME(row)(
    int n, const float *restrict x, float *restrict y, float lo, float hi,
    const float *ghost_w, const int *ghost_i, int ghost_n) {
  typedef FL_NAME(vf) vf;
  int m = (n + 1) / 2, kv = FL_NAME(row_vector_end)(n);
  if (kv) {
    /* from k = 0: lane FL_V-1 of prev is o_0, the symmetric o_-1 */
    vf prev = (vf){0} + FL_ODD_AT(x, 0), lw, hg;
    float *restrict yl = y, *restrict yh = y + m;
    int k = 0;
    /* unrolled twice: the loop's bookkeeping is a fifth of its instructions */
#pragma GCC unroll 2
    for (; k + FL_V <= kv; k += FL_V) {
      FL_NAME(lift)(x, k, &prev, &lw, &hg, lo, hi);
      __builtin_memcpy(yl + k, &lw, sizeof lw);
      __builtin_memcpy(yh + k, &hg, sizeof hg);
    }
    if (k < kv) { /* the last vector overlaps the previous one */
      k = kv - FL_V;
      prev = (vf){0} + FL_ODD_AT(x, k - 1);
      FL_NAME(lift)(x, k, &prev, &lw, &hg, lo, hi);
      __builtin_memcpy(yl + k, &lw, sizeof lw);
      __builtin_memcpy(yh + k, &hg, sizeof hg);
    }
  }
  FL_NAME(row_tail)(n, x, y, lo, hi, ghost_w, ghost_i, ghost_n, kv);
}

/* Column step of fused iteration k over whole ring rows: o = x_2k+1 - (e0 + e1)/2
 * (kept in the ring for the next update), written out as high = hi*o and
 * low = lo*(e0 + (om + o)/4). It also prefetches the two input rows the next
 * iteration lifts (next0, next1: one 64-byte line of each per 16 outputs, so the whole
 * row over the sweep): this loop only writes the output and the row lifting only reads
 * the input, and each input row starts a fresh 4 KiB page at 1024 floats, where the
 * hardware prefetcher starts over; fetched here, the reads overlap these writes
 * (measured on the AVX-512 machine: the 1024^2 fused level 7-10% faster). */
FL_TARGET static inline __attribute__((always_inline)) void FL_NAME(col_vector)(
    int i, const float *restrict e0, const float *restrict e1, const float *restrict om,
    float *restrict o, float *restrict low, float *restrict high, float lo, float hi,
    int first) {
  typedef FL_NAME(vf) vf;
  vf a, b, c, v;
  __builtin_memcpy(&a, e0 + i, sizeof a);
  __builtin_memcpy(&b, e1 + i, sizeof b);
  __builtin_memcpy(&v, o + i, sizeof v);
  v = v - 0.5f * (a + b);
  if (first)
    c = v;
  else
    __builtin_memcpy(&c, om + i, sizeof c);
  __builtin_memcpy(o + i, &v, sizeof v);
  vf hg = hi * v, lw = lo * (a + 0.25f * (c + v));
  __builtin_memcpy(high + i, &hg, sizeof hg);
  __builtin_memcpy(low + i, &lw, sizeof lw);
}

FL_TARGET static inline __attribute__((always_inline)) void FL_NAME(col)(
    int w, const float *restrict e0, const float *restrict e1, const float *restrict om,
    float *restrict o, float *restrict low, float *restrict high, float lo, float hi,
    int first, const float *next0, const float *next1) {
  /* scalar up to the first 64-byte boundary of the output row: the vectors' stores
   * (and, with the ring placed to match, their loads) then never split a cache line */
  int i = 0, head = (int)((16 - ((uintptr_t)low / sizeof(float)) % 16) % 16);
  for (; i < head && i < w; i++) {
    float v = o[i] - 0.5f * (e0[i] + e1[i]);
    o[i] = v;
    high[i] = hi * v;
    low[i] = lo * (e0[i] + 0.25f * ((first ? v : om[i]) + v));
  }
#pragma GCC unroll 2
  for (; i + 16 <= w; i += 16) { /* 16 floats: one cache line per row */
    __builtin_prefetch(next0 + i, 0, 3);
    __builtin_prefetch(next1 + i, 0, 3);
    for (int j = 0; j < 16; j += FL_V)
      FL_NAME(col_vector)(i + j, e0, e1, om, o, low, high, lo, hi, first);
  }
  for (; i + FL_V <= w; i += FL_V)
    FL_NAME(col_vector)(i, e0, e1, om, o, low, high, lo, hi, first);
  for (; i < w; i++) {
    float v = o[i] - 0.5f * (e0[i] + e1[i]);
    o[i] = v;
    high[i] = hi * v;
    low[i] = lo * (e0[i] + 0.25f * ((first ? v : om[i]) + v));
  }
}

/* Output rows k in [k0, k1) of the level: rows lifted into the ring as they are needed,
 * then the column predict and update of fine rows 2k, 2k+1, 2k+2 (see linear_level;
 * a range past 0 starts from o_k0-1, as linear_warm_up). */
FL_TARGET static void FL_NAME(level)(const transform_plan *p, int l, const float *src,
                                     size_t src_stride, float *ring, float *dst,
                                     size_t dst_stride, float *ghost, int k0, int k1) {
  int n = p->len_h[l], m = (n + 1) / 2, d = n / 2, w = p->len_w[l];
  float lo = lifting_scale_low(TRANSFORM_LINEAR), hi = lifting_scale_high(TRANSFORM_LINEAR);
  const ghost_rule *rho = &p->rules_h[l - 1].right, *rw = &p->rules_w[l - 1].right;
  float gw[4] = {0};
  for (int t = 0; t < rw->count; t++) gw[t] = (float)rw->weight[t];
  /* 8 ring rows: the window spans 4, the right rule reaches 2 rows further back.
   * Where the ring (17 rows of w) has room, its rows are a multiple of 16 floats apart
   * and start at the same offset within a 64-byte line as the output rows, so that the
   * column steps (FL_NAME(col), from its first aligned output) load and store whole
   * cache lines: at 1024^2 on the AVX-512 machine the level is ~10% faster than with
   * rows that split lines (malloc'd outputs sit 16 bytes past a line). */
  size_t ws = (size_t)w;
  {
    size_t wr = ((size_t)w + 15) & ~(size_t)15;
    size_t want = ((uintptr_t)dst / sizeof(float)) % 16;
    size_t have = ((uintptr_t)ring / sizeof(float)) % 16, shift = (want + 16 - have) % 16;
    if (8 * wr + shift <= 17 * (size_t)w && (uintptr_t)dst % sizeof(float) == 0)
      ws = wr, ring += shift;
  }
#define SLOT(r) (ring + (size_t)((r) % 8) * ws)
  /* lo is 1 for CDF 5/3: the literal lets gcc drop the multiplications (x * 1 == x) */
#define LOAD(r)                                                                             \
  do {                                                                                      \
    if (lo == 1.0f)                                                                         \
      FL_NAME(row)(w, src + (size_t)(r) * src_stride, SLOT(r), 1.0f, hi, gw, rw->index,      \
                   rw->count);                                                              \
    else                                                                                    \
      FL_NAME(row)(w, src + (size_t)(r) * src_stride, SLOT(r), lo, hi, gw, rw->index,        \
                   rw->count);                                                              \
  } while (0)
  if (k0 == 0) {
    LOAD(0);
  } else {
    LOAD(2 * k0 - 2);
    LOAD(2 * k0 - 1);
    LOAD(2 * k0);
    float *restrict o = SLOT(2 * k0 - 1);
    const float *restrict e0 = SLOT(2 * k0 - 2), *restrict e1 = SLOT(2 * k0);
    for (int i = 0; i < w; i++) o[i] = o[i] - 0.5f * (e0[i] + e1[i]);
  }
  for (int k = k0; k < k1; k++) {
    const float *restrict e0 = SLOT(2 * k);
    float *restrict low = dst + (size_t)k * dst_stride;
    if (k < d) {
      float *restrict high = dst + (size_t)(m + k) * dst_stride;
      LOAD(2 * k + 1);
      float *restrict o = SLOT(2 * k + 1);
      const float *restrict e1;
      if (2 * k + 2 < n) {
        LOAD(2 * k + 2);
        e1 = SLOT(2 * k + 2);
      } else {
        for (int i = 0; i < w; i++) ghost[i] = 0.0f;
        for (int t = 0; t < rho->count; t++) {
          const float *restrict row = SLOT(2 * rho->index[t]);
          float c = (float)rho->weight[t];
          for (int i = 0; i < w; i++) ghost[i] += c * row[i];
        }
        e1 = ghost;
      }
      /* the input rows the next iteration lifts (the last row past the end) */
      const float *next0 = src + (size_t)(2 * k + 3 < n ? 2 * k + 3 : n - 1) * src_stride;
      const float *next1 = src + (size_t)(2 * k + 4 < n ? 2 * k + 4 : n - 1) * src_stride;
      if (k > 0 && lo == 1.0f)
        FL_NAME(col)(w, e0, e1, SLOT(2 * k - 1), o, low, high, 1.0f, hi, 0, next0, next1);
      else if (k > 0)
        FL_NAME(col)(w, e0, e1, SLOT(2 * k - 1), o, low, high, lo, hi, 0, next0, next1);
      else /* o_-1 is o_0 itself */
        FL_NAME(col)(w, e0, e1, NULL, o, low, high, lo, hi, 1, next0, next1);
    } else { /* odd n, last even row: o_m-1 mirrors to o_m-2 */
      const float *restrict om = SLOT(2 * k - 1);
      for (int i = 0; i < w; i++) low[i] = lo * (e0[i] + 0.25f * (om[i] + om[i]));
    }
  }
#undef LOAD
#undef SLOT
}
#undef FL_ODD_AT
#undef FL_V
#undef FL_NAME
#undef FL_TARGET
#undef FL_EVEN
#undef FL_ODD
#undef FL_SHIFT
