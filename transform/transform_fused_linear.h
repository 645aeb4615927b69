/* The fused CDF 5/3 forward level, written once for one SIMD width and included by
 * transform_fused.c once per width (FL_V floats per vector, FL_NAME(x) names the
 * functions, FL_TARGET their target attribute; the masks FL_EVEN/FL_ODD,
 * FL_SHIFT(prev, o): the vector (prev[FL_V-1], o[0], ..., o[FL_V-2]), and
 * FL_NEXT(a, b): (a[1], ..., a[FL_V-1], b[0])).
 * Not a header to include elsewhere: it has no include guard on purpose, and it
 * undefines its FL_ parameters at its end, ready for the next width.
 *
 * GCC vector extensions, not intrinsics: the same source compiles for any target and
 * gcc picks the shuffles (SSE2 shufps, AVX2 vpermps, AVX-512 vpermt2ps). Every float
 * operation is the one of the scalar code in the same order (and -std=c11 keeps
 * contraction off), so all widths give the same bits. FL_NAME(row) is transform_rows'
 * row lifting; the level (FL_NAME(level), below) does the column step first. */

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

/* x_n of an even-length row: the coarse level's right rule on the even samples. */
static inline float FL_NAME(width_ghost)(const float *x, const float *ghost_w,
                                         const int *ghost_i, int ghost_n) {
  float g = 0.0f;
  for (int t = 0; t < ghost_n && t < 4; t++) g += ghost_w[t] * x[2 * ghost_i[t]];
  return g;
}

/* The last low output of an odd-length row n: o_d mirrors to o_d-1. */
static inline float FL_NAME(odd_last_low)(const float *x, int n, float lo) {
  return lo * (x[n - 1] + 0.25f * 2.0f * FL_ODD_AT(x, n / 2 - 1));
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
    float g = FL_NAME(width_ghost)(x, ghost_w, ghost_i, ghost_n);
    o_last = x[2 * d - 1] - 0.5f * (x[2 * d - 2] + g);
    high[d - 1] = hi * o_last;
    low[d - 1] = lo * (x[2 * d - 2] + 0.25f * (FL_ODD_AT(x, d - 2) + o_last));
  } else {
    o_last = FL_ODD_AT(x, d - 1);
    low[m - 1] = FL_NAME(odd_last_low)(x, n, lo);
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

/* ---- the level, columns first ----
 * The level is a column lifting and a row lifting of the same samples. The two commute
 * (linear steps along different axes, boundary rules included), so the level runs the
 * column step first, straight from the input rows, and lifts the two rows it gives along
 * x while they are still in registers: per pair k of fine rows, the column predict
 * o_k = x_2k+1 - (x_2k + x_2k+2)/2 and update e_k = x_2k + (o_k-1 + o_k)/4, then the
 * row lifting of e_k (output row k: LL | HL) and of o_k (output row m + k: LH | HH).
 * Only o_k is stored (a row buffer, for e_k+1) besides the output: 1.5 stores per input
 * vector, against 2.5 when rows were lifted into a ring first and the columns read them
 * back (docs/transform.md: the store port was the limit). The scales of both steps are
 * applied once, as their products (lo, hi of the column step times those of the row).
 * The scalar code at the rows' ends and the vectors do the same operations in the same
 * order, so the bits do not depend on the SIMD width or on where the buffers sit. */

/* The column step at column i of pair k: o_k (also written to oc) and e_k; op is o_k-1,
 * unread when `first` (k = 0: o_-1 is o_0 itself). */
FL_TARGET static inline __attribute__((always_inline)) void FL_NAME(column)(
    const float *restrict x0, const float *restrict x1, const float *restrict x2,
    const float *restrict op, float *restrict oc, int i, int first, FL_NAME(vf) *e,
    FL_NAME(vf) *o) {
  typedef FL_NAME(vf) vf;
  vf a, b, c, p;
  __builtin_memcpy(&a, x0 + i, sizeof a);
  __builtin_memcpy(&b, x1 + i, sizeof b);
  __builtin_memcpy(&c, x2 + i, sizeof c);
  vf v = b - 0.5f * (a + c);
  if (first)
    p = v;
  else
    __builtin_memcpy(&p, op + i, sizeof p);
  __builtin_memcpy(oc + i, &v, sizeof v);
  *e = a + 0.25f * (p + v);
  *o = v;
}

/* The scalar twin at column i (e_k into e[i]). */
static inline float FL_NAME(column_e)(const float *x0, const float *x1, const float *x2,
                                      const float *op, float *oc, int i, int first) {
  float v = x1[i] - 0.5f * (x0[i] + x2[i]);
  oc[i] = v;
  return x0[i] + 0.25f * ((first ? v : op[i]) + v);
}

/* Row lifting of outputs kc .. kc+FL_V-1 of one row held in registers: va, vb the row's
 * columns 2kc .. 2kc+2FL_V-1, vn from column 2kc+2FL_V on (its lane 0 is x_2k+2 of the
 * last output); the steps of FL_NAME(lift). */
FL_TARGET static inline __attribute__((always_inline)) void FL_NAME(lift_registers)(
    FL_NAME(vf) va, FL_NAME(vf) vb, FL_NAME(vf) vn, FL_NAME(vf) *prev, float *restrict low,
    float *restrict high, float lo, float hi) {
  typedef FL_NAME(vf) vf;
  typedef FL_NAME(vi) vi;
  vf ev = __builtin_shuffle(va, vb, (vi)FL_EVEN);
  vf od = __builtin_shuffle(va, vb, (vi)FL_ODD);
  vf e1 = FL_NEXT(ev, vn);
  vf o = od - 0.5f * (ev + e1);
  vf om = FL_SHIFT(*prev, o);
  *prev = o;
  vf lw = lo * (ev + 0.25f * (om + o)), hg = hi * o;
  __builtin_memcpy(low, &lw, sizeof lw);
  __builtin_memcpy(high, &hg, sizeof hg);
}

/* The first column after output k's group, x_2k+2 of its last output: column c of the
 * e and o rows, or past the row's end (even width, last output) the width rule's ghost. */
static inline float FL_NAME(next_column)(const float *x0, const float *x1, const float *x2,
                                         const float *op, float *oc, int c, int w, int first,
                                         const float ghost_eo[2], float *o) {
  if (c >= w) {
    *o = ghost_eo[1];
    return ghost_eo[0];
  }
  float e = FL_NAME(column_e)(x0, x1, x2, op, oc, c, first);
  *o = oc[c];
  return e;
}

/* Outputs [0, kv) of pair k by vectors, FL_V at a time, for both rows: e_k into row `le`
 * (LL | HL, scales fe_l, fe_h), o_k into row `lo_row` (LH | HH, scales fo_l, fo_h); `mw`
 * is the low half's length; FL_V <= kv. A group needs the next group's first column for
 * its x_2k+2: loaded with the next group's vector while that fits in the row
 * (kc + FL_V <= kv_load), then computed alone (FL_NAME(next_column)); where kv is not a
 * whole number of groups, a last group overlaps the one before. */
FL_TARGET static inline __attribute__((always_inline)) void FL_NAME(pair_vectors)(
    const float *restrict x0, const float *restrict x1, const float *restrict x2,
    const float *restrict op, float *restrict oc, int first, int w, const float ghost_eo[2],
    int kv, int kv_load, float *restrict le, float *restrict lo_row, int mw, float fe_l,
    float fe_h, float fo_l, float fo_h) {
  typedef FL_NAME(vf) vf;
  vf ea, oa, eb, ob, en, on;
  float ne, no;
  int kc = 0;
  FL_NAME(column)(x0, x1, x2, op, oc, 0, first, &ea, &oa);
  /* o_-1 = o_0 (symmetric): the first group's prev holds o_0 */
  vf prev_e = (vf){0} + (ea[1] - 0.5f * (ea[0] + ea[2]));
  vf prev_o = (vf){0} + (oa[1] - 0.5f * (oa[0] + oa[2]));
  for (; kc + FL_V <= kv_load; kc += FL_V) {
    FL_NAME(column)(x0, x1, x2, op, oc, 2 * kc + FL_V, first, &eb, &ob);
    FL_NAME(column)(x0, x1, x2, op, oc, 2 * kc + 2 * FL_V, first, &en, &on);
    FL_NAME(lift_registers)(ea, eb, en, &prev_e, le + kc, le + mw + kc, fe_l, fe_h);
    FL_NAME(lift_registers)(oa, ob, on, &prev_o, lo_row + kc, lo_row + mw + kc, fo_l, fo_h);
    ea = en;
    oa = on;
  }
  /* at most one more whole group: kc + FL_V > kv_load = (w - FL_V)/2 gives kc + 2FL_V > kv */
  if (kc + FL_V <= kv) {
    FL_NAME(column)(x0, x1, x2, op, oc, 2 * kc + FL_V, first, &eb, &ob);
    ne = FL_NAME(next_column)(x0, x1, x2, op, oc, 2 * kc + 2 * FL_V, w, first, ghost_eo, &no);
    FL_NAME(lift_registers)(ea, eb, (vf){0} + ne, &prev_e, le + kc, le + mw + kc, fe_l, fe_h);
    FL_NAME(lift_registers)(oa, ob, (vf){0} + no, &prev_o, lo_row + kc, lo_row + mw + kc, fo_l,
                            fo_h);
    kc += FL_V;
  }
  if (kc < kv) { /* overlapping the group before, so oc holds its columns */
    kc = kv - FL_V;
    float c[3];
    for (int t = 0; t < 3; t++) c[t] = FL_NAME(column_e)(x0, x1, x2, op, oc, 2 * kc - 2 + t, first);
    prev_e = (vf){0} + (c[1] - 0.5f * (c[0] + c[2]));
    prev_o = (vf){0} + FL_ODD_AT(oc, kc - 1);
    ne = FL_NAME(next_column)(x0, x1, x2, op, oc, 2 * kv, w, first, ghost_eo, &no);
    FL_NAME(column)(x0, x1, x2, op, oc, 2 * kc, first, &ea, &oa);
    FL_NAME(column)(x0, x1, x2, op, oc, 2 * kc + FL_V, first, &eb, &ob);
    FL_NAME(lift_registers)(ea, eb, (vf){0} + ne, &prev_e, le + kc, le + mw + kc, fe_l, fe_h);
    FL_NAME(lift_registers)(oa, ob, (vf){0} + no, &prev_o, lo_row + kc, lo_row + mw + kc, fo_l,
                            fo_h);
  }
}

/* Output rows k in [k0, k1) of the level (fine rows 2k, 2k+1, 2k+2; a range past 0
 * starts from o_k0-1, computed first). Scratch: two o rows (o_k-1, o_k), the e row's
 * scalar columns, and `ghost` (x_n of even n, from the coarse right rule). */
FL_TARGET static void FL_NAME(level)(const transform_plan *p, int l, const float *src,
                                     size_t src_stride, float *ring, float *dst,
                                     size_t dst_stride, float *ghost, int k0, int k1) {
  int n = p->len_h[l], m = (n + 1) / 2, d = n / 2, w = p->len_w[l], mw = (w + 1) / 2;
  float lo = lifting_scale_low(TRANSFORM_LINEAR), hi = lifting_scale_high(TRANSFORM_LINEAR);
  float fe_l = lo * lo, fe_h = hi * lo, fo_l = lo * hi, fo_h = hi * hi;
  const ghost_rule *rho = &p->rules_h[l - 1].right, *rw = &p->rules_w[l - 1].right;
  float gw[4] = {0};
  int gmin = w;
  for (int t = 0; t < rw->count; t++) {
    gw[t] = (float)rw->weight[t];
    if (2 * rw->index[t] < gmin) gmin = 2 * rw->index[t];
  }
  /* outputs [0, kv) are vectors: every interior one, and for even w the last too (its
   * x_2k+2 is the width rule's ghost; odd w ends with a mirrored low output); the groups
   * that load the next group's columns end at kv_load */
  int kv = w / 2, kv_load = (w - FL_V) / 2;
  if (kv < FL_V || gmin < w - FL_V) kv = 0; /* the rule's columns: in the last vector */
  /* scratch rows a multiple of 16 floats apart, at the input's offset within a 64-byte
   * line where the ring has room: the vectors' o loads and stores (two of the ten loads
   * and six stores per group) then split lines only where the input's loads do */
  size_t ws = (size_t)w;
  {
    size_t wr = ((size_t)w + 15) & ~(size_t)15;
    size_t want = ((uintptr_t)src / sizeof(float)) % 16;
    size_t have = ((uintptr_t)ring / sizeof(float)) % 16, shift = (want + 16 - have) % 16;
    if (3 * wr + shift <= 17 * (size_t)w && (uintptr_t)src % sizeof(float) == 0)
      ws = wr, ring += shift;
  }
  float *obuf[2] = {ring, ring + ws}, *e = ring + 2 * ws;
  if (k0 > 0) { /* o_k0-1 */
    const float *restrict x0 = src + (size_t)(2 * k0 - 2) * src_stride;
    const float *restrict x1 = x0 + src_stride, *restrict x2 = x1 + src_stride;
    float *restrict o = obuf[(k0 - 1) & 1];
    for (int i = 0; i < w; i++) o[i] = x1[i] - 0.5f * (x0[i] + x2[i]);
  }
  for (int k = k0; k < k1; k++) {
    const float *x0 = src + (size_t)(2 * k) * src_stride;
    float *oc = obuf[k & 1];
    const float *op = k > 0 ? obuf[(k - 1) & 1] : NULL;
    float *le = dst + (size_t)k * dst_stride;
    if (k >= d) { /* odd n, last even row: o_m-1 mirrors to o_m-2 */
      for (int i = 0; i < w; i++) e[i] = x0[i] + 0.25f * (op[i] + op[i]);
      FL_NAME(row)(w, e, le, fe_l, fe_h, gw, rw->index, rw->count);
      continue;
    }
    const float *x1 = x0 + src_stride, *x2 = x1 + src_stride;
    if (2 * k + 2 >= n) { /* even n: x_n from the coarse level's right rule */
      for (int i = 0; i < w; i++) ghost[i] = 0.0f;
      for (int t = 0; t < rho->count; t++) {
        const float *restrict row = src + (size_t)(2 * rho->index[t]) * src_stride;
        float c = (float)rho->weight[t];
        for (int i = 0; i < w; i++) ghost[i] += c * row[i];
      }
      x2 = ghost;
    }
    float *lo_row = dst + (size_t)(m + k) * dst_stride;
    int first = k == 0;
    if (!kv) { /* too narrow for a group: all scalar */
      for (int i = 0; i < w; i++) e[i] = FL_NAME(column_e)(x0, x1, x2, op, oc, i, first);
      FL_NAME(row_tail)(w, e, le, fe_l, fe_h, gw, rw->index, rw->count, 0);
      FL_NAME(row_tail)(w, oc, lo_row, fo_l, fo_h, gw, rw->index, rw->count, 0);
      continue;
    }
    /* the row's last FL_V columns first: e there for the width rule's ghost (even w) or
     * the mirrored last low output (odd w) */
    {
      FL_NAME(vf) et, ot;
      FL_NAME(column)(x0, x1, x2, op, oc, w - FL_V, first, &et, &ot);
      __builtin_memcpy(e + w - FL_V, &et, sizeof et);
    }
    float ghost_eo[2] = {0.0f, 0.0f}; /* x_w of the e and o rows (even w) */
    if (w % 2 == 0) {
      ghost_eo[0] = FL_NAME(width_ghost)(e, gw, rw->index, rw->count);
      ghost_eo[1] = FL_NAME(width_ghost)(oc, gw, rw->index, rw->count);
    }
    if (first && fe_l == 1.0f) /* literal scales: gcc drops x * 1 */
      FL_NAME(pair_vectors)(x0, x1, x2, op, oc, 1, w, ghost_eo, kv, kv_load, le, lo_row, mw,
                            1.0f, fe_h, fo_l, fo_h);
    else if (first)
      FL_NAME(pair_vectors)(x0, x1, x2, op, oc, 1, w, ghost_eo, kv, kv_load, le, lo_row, mw,
                            fe_l, fe_h, fo_l, fo_h);
    else if (fe_l == 1.0f)
      FL_NAME(pair_vectors)(x0, x1, x2, op, oc, 0, w, ghost_eo, kv, kv_load, le, lo_row, mw,
                            1.0f, fe_h, fo_l, fo_h);
    else
      FL_NAME(pair_vectors)(x0, x1, x2, op, oc, 0, w, ghost_eo, kv, kv_load, le, lo_row, mw,
                            fe_l, fe_h, fo_l, fo_h);
    if (w % 2) { /* odd w: the last low output, the vectors' only missing one */
      le[mw - 1] = FL_NAME(odd_last_low)(e, w, fe_l);
      lo_row[mw - 1] = FL_NAME(odd_last_low)(oc, w, fo_l);
    }
  }
}
#undef FL_ODD_AT
#undef FL_V
#undef FL_NAME
#undef FL_TARGET
#undef FL_EVEN
#undef FL_ODD
#undef FL_SHIFT
#undef FL_NEXT
