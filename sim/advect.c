/* Semi-Lagrangian advection: bilinear, clamped cubic and MacCormack (see advect.h for
 * the references). One thread, no allocation; the departure point of a
 * cell is traced once and shared by every field advected in the same pass. */
#include "sim/advect.h"

#include <math.h>

/* A periodic sample position: the cell below/left (i0), the next one (i1, wrapped) and
 * the fraction t in [0, 1]. */
typedef struct axis_pos {
  int i0, i1;
  float t;
} axis_pos;

/* min/max by comparison: gcc compiles these to minss/maxss, whereas fminf/fmaxf (NaN
 * rules of C99 Annex F) become libm calls without -ffast-math — 8x slower advection. */
static inline float min_f(float a, float b) { return a < b ? a : b; }
static inline float max_f(float a, float b) { return a > b ? a : b; }

static inline axis_pos locate(float x, int n) {
  /* Bounded first: a non-finite or absurd position (which a sane velocity never gives)
   * must not reach the int conversion; fmaxf also maps NaN to the bound. */
  x = x > -1e6f ? x : -1e6f; /* NaN compares false: it becomes -1e6 */
  x = min_f(x, 1e6f);
  /* floor without a libm call (the portable build has no SSE4.1 roundss). */
  int i = (int)x;
  i -= x < (float)i;
  /* Exact: x and floor(x) share x's ulp grid below 2^23, so t is in [0, 1). */
  float t = x - (float)i;
  if ((unsigned)i >= (unsigned)n) { /* outside [0, n): wrap (rare unless near an edge) */
    i %= n;
    if (i < 0) i += n;
  }
  int i1 = i + 1;
  if (i1 == n) i1 = 0;
  return (axis_pos){i, i1, t};
}

static inline int wrap_prev(int i, int n) { return i == 0 ? n - 1 : i - 1; }
static inline int wrap_next(int i, int n) { return i + 1 == n ? 0 : i + 1; }

/* The four corner values of the bilinear cell around a position. */
typedef struct cell4 {
  float a, b, c, d; /* (i0,j0) (i1,j0) (i0,j1) (i1,j1) */
} cell4;

static inline cell4 fetch4(const float *f, int w, axis_pos px, axis_pos pz) {
  const float *r0 = f + (long)pz.i0 * w, *r1 = f + (long)pz.i1 * w;
  return (cell4){r0[px.i0], r0[px.i1], r1[px.i0], r1[px.i1]};
}

static inline float cell_min(cell4 c) { return min_f(min_f(c.a, c.b), min_f(c.c, c.d)); }
static inline float cell_max(cell4 c) { return max_f(max_f(c.a, c.b), max_f(c.c, c.d)); }

static inline float lerp(float a, float b, float t) { return a + t * (b - a); }

static inline float bilinear(cell4 c, float tx, float tz) {
  return lerp(lerp(c.a, c.b, tx), lerp(c.c, c.d, tx), tz);
}

/* Clamped to the cell's corners: for the cubic this is its limiter; for bilinear it only
 * removes the last-bit rounding of the convex combination, so "never above the old
 * maximum" holds exactly in float arithmetic, not just to an ulp per step. */
static inline float clamp_to_cell(float v, cell4 c) {
  return min_f(max_f(v, cell_min(c)), cell_max(c));
}

/* The 4x4 Catmull-Rom stencil around a sample: its rows, columns and weights, computed
 * once per cell and shared by every field of a fused pass. Catmull-Rom (Catmull & Rom
 * 1974) is the cubic Hermite with centred tangents (p2 - p0)/2, (p3 - p1)/2, written
 * here as its four basis weights at t (they sum to 1): third order where smooth. */
typedef struct cubic_stencil {
  int col[4];
  long row[4]; /* row offsets, z * width */
  float wx[4], wz[4];
} cubic_stencil;

static inline void catmull_rom_weights(float t, float *w) {
  const float t2 = t * t, t3 = t2 * t;
  w[0] = 0.5f * (-t3 + 2.0f * t2 - t);
  w[1] = 0.5f * (3.0f * t3 - 5.0f * t2 + 2.0f);
  w[2] = 0.5f * (-3.0f * t3 + 4.0f * t2 + t);
  w[3] = 0.5f * (t3 - t2);
}

static inline cubic_stencil make_stencil(int w, int h, axis_pos px, axis_pos pz) {
  cubic_stencil s;
  s.col[0] = wrap_prev(px.i0, w), s.col[1] = px.i0, s.col[2] = px.i1;
  s.col[3] = wrap_next(px.i1, w);
  s.row[0] = (long)wrap_prev(pz.i0, h) * w, s.row[1] = (long)pz.i0 * w;
  s.row[2] = (long)pz.i1 * w, s.row[3] = (long)wrap_next(pz.i1, h) * w;
  catmull_rom_weights(px.t, s.wx);
  catmull_rom_weights(pz.t, s.wz);
  return s;
}

/* Tensor-product Catmull-Rom. It overshoots near steep gradients; the caller clamps it
 * to the min/max of the 2x2 cell around the sample, which makes the scheme monotone (no
 * new extrema, never below 0). A Fritsch-Carlson limited Hermite (tangents zeroed at
 * extrema) was tried first and dropped: it pins peaks to grid nodes at small CFL
 * (docs/simulation.md). */
static inline float cubic_sample(const float *f, const cubic_stencil *s) {
  float v = 0.0f;
  for (int k = 0; k < 4; k++) {
    const float *row = f + s->row[k];
    const float r = s->wx[0] * row[s->col[0]] + s->wx[1] * row[s->col[1]] +
                    s->wx[2] * row[s->col[2]] + s->wx[3] * row[s->col[3]];
    v += s->wz[k] * r;
  }
  return v;
}

static inline float clamped_cubic(const float *f, int w, int h, axis_pos px, axis_pos pz) {
  cubic_stencil s = make_stencil(w, h, px, pz);
  return cubic_sample(f, &s);
}

float advect_sample_bilinear(const float *field, int width, int height, float x, float z) {
  axis_pos px = locate(x, width);
  axis_pos pz = locate(z, height);
  cell4 c = fetch4(field, width, px, pz);
  return clamp_to_cell(bilinear(c, px.t, pz.t), c);
}

float advect_sample_monotone_cubic(const float *field, int width, int height, float x,
                                   float z) {
  axis_pos px = locate(x, width);
  axis_pos pz = locate(z, height);
  cell4 c = fetch4(field, width, px, pz);
  return clamp_to_cell(clamped_cubic(field, width, height, px, pz), c);
}

/* Midpoint (RK2) trace from grid point (x, z) over time `sdt` (negative: forward in
 * time): x_mid = x - sdt/2 u(x), x_d = x - sdt u(x_mid). */
typedef struct trace_ctx {
  const float *vx, *vz;
  int w, h;
} trace_ctx;

static inline void trace(const trace_ctx *tc, int x, int z, long idx, float sdt, float *out_x,
                         float *out_z) {
  float mx = (float)x - 0.5f * sdt * tc->vx[idx];
  float mz = (float)z - 0.5f * sdt * tc->vz[idx];
  axis_pos px = locate(mx, tc->w);
  axis_pos pz = locate(mz, tc->h);
  float ux = bilinear(fetch4(tc->vx, tc->w, px, pz), px.t, pz.t);
  float uz = bilinear(fetch4(tc->vz, tc->w, px, pz), px.t, pz.t);
  *out_x = (float)x - sdt * ux;
  *out_z = (float)z - sdt * uz;
}

/* always_inline: the callers pass constant `count` and `cubic`, and each call site should
 * get its own specialised loop (gcc otherwise shares one clone with run-time flags). */
#define ADVECT_INLINE static inline __attribute__((always_inline))

/* One cell of a semi-Lagrangian pass with a fixed interpolator, recording its departure
 * point when `departures` is not NULL (MacCormack's limiter needs them). */
ADVECT_INLINE void semi_lagrangian_cell(const advect_pass *p, const trace_ctx *tc, int count,
                                        int cubic, const float *const *src,
                                        float *const *dst, float *departures, int x, int z) {
  const int w = p->width, h = p->height;
  long idx = (long)z * w + x;
  float dx, dz;
  trace(tc, x, z, idx, p->dt, &dx, &dz);
  if (departures) {
    departures[2 * idx] = dx;
    departures[2 * idx + 1] = dz;
  }
  axis_pos px = locate(dx, w);
  axis_pos pz = locate(dz, h);
  if (cubic) {
    const cubic_stencil st = make_stencil(w, h, px, pz);
    for (int f = 0; f < count; f++)
      dst[f][idx] = clamp_to_cell(cubic_sample(src[f], &st), fetch4(src[f], w, px, pz));
  } else {
    for (int f = 0; f < count; f++) {
      cell4 c = fetch4(src[f], w, px, pz);
      dst[f][idx] = clamp_to_cell(bilinear(c, px.t, pz.t), c);
    }
  }
}

ADVECT_INLINE void semi_lagrangian(const advect_pass *p, const trace_ctx *tc, int count,
                                   int cubic, const float *const *src, float *const *dst,
                                   float *departures) {
  for (int z = 0; z < p->height; z++)
    for (int x = 0; x < p->width; x++)
      semi_lagrangian_cell(p, tc, count, cubic, src, dst, departures, x, z);
}

/* MacCormack (Selle et al. 2008 eq. 5-7): phi_hat = A(phi) (the forward pass, done by
 * semi_lagrangian with departures recorded), phi_bar = A^R(phi_hat) (the same trace with
 * time reversed), phi_new = phi_hat + (phi - phi_bar)/2, clamped to the extrema of phi
 * around the departure point (their §4). One cell: */
ADVECT_INLINE void maccormack_cell(const advect_pass *p, const trace_ctx *tc, int count,
                                   int cubic, const float *const *src,
                                   const float *const *forward, float *const *dst,
                                   const float *departures, int x, int z) {
  const int w = p->width, h = p->height;
  long idx = (long)z * w + x;
  float ax, az;
  trace(tc, x, z, idx, -p->dt, &ax, &az);
  axis_pos rx = locate(ax, w);
  axis_pos rz = locate(az, h);
  axis_pos px = locate(departures[2 * idx], w);
  axis_pos pz = locate(departures[2 * idx + 1], h);
  cubic_stencil st;
  if (cubic) st = make_stencil(w, h, rx, rz);
  for (int f = 0; f < count; f++) {
    float back = cubic ? cubic_sample(forward[f], &st)
                       : bilinear(fetch4(forward[f], w, rx, rz), rx.t, rz.t);
    float v = forward[f][idx] + 0.5f * (src[f][idx] - back);
    dst[f][idx] = clamp_to_cell(v, fetch4(src[f], w, px, pz));
  }
}

ADVECT_INLINE void maccormack_correct(const advect_pass *p, const trace_ctx *tc, int count,
                                      int cubic, const float *const *src,
                                      const float *const *forward, float *const *dst,
                                      const float *departures) {
  for (int z = 0; z < p->height; z++)
    for (int x = 0; x < p->width; x++)
      maccormack_cell(p, tc, count, cubic, src, forward, dst, departures, x, z);
}

#if defined(__GNUC__) && defined(__x86_64__)
/* Every pass 8 cells at a time with AVX2 gathers (chosen at run time; the default build
 * stays portable). Every lane does the scalar code's operations in the same order (C11:
 * no contraction), so the bits are those of semi_lagrangian_cell and maccormack_cell,
 * which also take any group of 8 whose stencils wrap around the periodic edge (or whose
 * positions are far outside, which locate() wraps). */
#include <immintrin.h>
#define ADVECT_AVX2 1
#define AVX2 __attribute__((target("avx2"))) static inline

/* locate() for 8 positions: cell i and fraction t. Returns 0 if a lane's i is outside
 * [lo, hi], where the caller's stencil would wrap: the group then goes scalar. */
AVX2 int locate8(__m256 x, int lo, int hi, __m256i *i, __m256 *t) {
  x = _mm256_max_ps(x, _mm256_set1_ps(-1e6f)); /* x > -1e6 ? x : -1e6 (NaN: -1e6) */
  x = _mm256_min_ps(x, _mm256_set1_ps(1e6f));  /* x < 1e6 ? x : 1e6 */
  __m256i k = _mm256_cvttps_epi32(x);
  __m256 below = _mm256_cmp_ps(x, _mm256_cvtepi32_ps(k), _CMP_LT_OQ);
  k = _mm256_add_epi32(k, _mm256_castps_si256(below)); /* -1 where x < (float)k */
  *t = _mm256_sub_ps(x, _mm256_cvtepi32_ps(k));
  *i = k;
  __m256i out = _mm256_or_si256(_mm256_cmpgt_epi32(_mm256_set1_epi32(lo), k),
                                _mm256_cmpgt_epi32(k, _mm256_set1_epi32(hi)));
  return _mm256_testz_si256(out, out);
}

AVX2 __m256 lerp8(__m256 a, __m256 b, __m256 t) {
  return _mm256_add_ps(a, _mm256_mul_ps(t, _mm256_sub_ps(b, a)));
}

/* catmull_rom_weights for 8 fractions. */
AVX2 void catmull_rom8(__m256 t, __m256 w[4]) {
  const __m256 half = _mm256_set1_ps(0.5f);
  __m256 t2 = _mm256_mul_ps(t, t), t3 = _mm256_mul_ps(t2, t);
  __m256 m3 = _mm256_sub_ps(_mm256_setzero_ps(), t3); /* -t3 (exact) */
  w[0] = _mm256_mul_ps(half, _mm256_sub_ps(_mm256_add_ps(m3, _mm256_mul_ps(_mm256_set1_ps(2.0f), t2)), t));
  w[1] = _mm256_mul_ps(half, _mm256_add_ps(_mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(3.0f), t3),
                                                         _mm256_mul_ps(_mm256_set1_ps(5.0f), t2)),
                                           _mm256_set1_ps(2.0f)));
  w[2] = _mm256_mul_ps(half, _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(-3.0f), t3),
                                                         _mm256_mul_ps(_mm256_set1_ps(4.0f), t2)),
                                           t));
  w[3] = _mm256_mul_ps(half, _mm256_sub_ps(t3, t2));
}

/* Where 8 samples sit: the cell (row-major index of its low corner), the fractions, and
 * for the cubic the Catmull-Rom weights of both axes. */
typedef struct spot8 {
  __m256i cell;
  __m256 sx, sz, wx[4], wz[4];
} spot8;

/* locate() both axes of 8 positions for an interpolator that reads no wrapped cell:
 * cells 0 .. n-2 for the bilinear 2x2, 1 .. n-3 for the cubic's 4x4. 0 if one would. */
AVX2 int spot8_at(__m256 x, __m256 z, int w, int h, int cubic, spot8 *s) {
  __m256i ix, iz;
  if (!locate8(x, cubic, w - 2 - cubic, &ix, &s->sx) ||
      !locate8(z, cubic, h - 2 - cubic, &iz, &s->sz))
    return 0;
  s->cell = _mm256_add_epi32(_mm256_mullo_epi32(iz, _mm256_set1_epi32(w)), ix);
  if (cubic) {
    catmull_rom8(s->sx, s->wx);
    catmull_rom8(s->sz, s->wz);
  }
  return 1;
}

/* The cell's four corners of f (fetch4's a, b, c, d). */
AVX2 void corners8(const float *f, __m256i cell, int w, __m256 c[4]) {
  __m256i one = _mm256_set1_epi32(1), below = _mm256_add_epi32(cell, _mm256_set1_epi32(w));
  c[0] = _mm256_i32gather_ps(f, cell, 4);
  c[1] = _mm256_i32gather_ps(f, _mm256_add_epi32(cell, one), 4);
  c[2] = _mm256_i32gather_ps(f, below, 4);
  c[3] = _mm256_i32gather_ps(f, _mm256_add_epi32(below, one), 4);
}

/* f at 8 spots, unclamped: bilinear (the corners, which it returns in c) or the cubic's
 * 16 taps in cubic_sample's order (its 2x2 centre is the cell: returned in c too). */
AVX2 __m256 sample8(const float *f, const spot8 *s, int w, int cubic, __m256 c[4]) {
  if (!cubic) {
    corners8(f, s->cell, w, c);
    return lerp8(lerp8(c[0], c[1], s->sx), lerp8(c[2], c[3], s->sx), s->sz);
  }
  /* tap (row k, column j) at corner + k w + j, corner = cell - w - 1 */
  __m256i corner = _mm256_sub_epi32(s->cell, _mm256_set1_epi32(w + 1));
  __m256 v = _mm256_setzero_ps();
  for (int k = 0; k < 4; k++) {
    __m256i row = _mm256_add_epi32(corner, _mm256_set1_epi32(k * w));
    __m256 g[4];
    for (int j = 0; j < 4; j++)
      g[j] = _mm256_i32gather_ps(f, _mm256_add_epi32(row, _mm256_set1_epi32(j)), 4);
    __m256 r = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(s->wx[0], g[0]),
                                                         _mm256_mul_ps(s->wx[1], g[1])),
                                           _mm256_mul_ps(s->wx[2], g[2])),
                             _mm256_mul_ps(s->wx[3], g[3]));
    v = _mm256_add_ps(v, _mm256_mul_ps(s->wz[k], r));
    if (k == 1) c[0] = g[1], c[1] = g[2];
    if (k == 2) c[2] = g[1], c[3] = g[2];
  }
  return v;
}

/* clamp_to_cell: min_f/max_f are minps/maxps with the same operand order. */
AVX2 __m256 clamp8(__m256 v, const __m256 c[4]) {
  __m256 lo = _mm256_min_ps(_mm256_min_ps(c[0], c[1]), _mm256_min_ps(c[2], c[3]));
  __m256 hi = _mm256_max_ps(_mm256_max_ps(c[0], c[1]), _mm256_max_ps(c[2], c[3]));
  return _mm256_min_ps(_mm256_max_ps(v, lo), hi);
}

/* trace() for cells x .. x+7 of row z: their departure points, 0 if a lane's midpoint
 * cell would wrap. */
AVX2 int trace8(const trace_ctx *tc, int x, int z, long idx, float sdt, __m256 *dx,
                __m256 *dz) {
  const int w = tc->w;
  __m256 xf = _mm256_add_ps(_mm256_set1_ps((float)x), _mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7));
  __m256 zf = _mm256_set1_ps((float)z);
  __m256 half_sdt = _mm256_set1_ps(0.5f * sdt);
  __m256 mx = _mm256_sub_ps(xf, _mm256_mul_ps(half_sdt, _mm256_loadu_ps(tc->vx + idx)));
  __m256 mz = _mm256_sub_ps(zf, _mm256_mul_ps(half_sdt, _mm256_loadu_ps(tc->vz + idx)));
  spot8 mid;
  if (!spot8_at(mx, mz, w, tc->h, 0, &mid)) return 0;
  __m256 c[4];
  __m256 ux = sample8(tc->vx, &mid, w, 0, c), uz = sample8(tc->vz, &mid, w, 0, c);
  *dx = _mm256_sub_ps(xf, _mm256_mul_ps(_mm256_set1_ps(sdt), ux));
  *dz = _mm256_sub_ps(zf, _mm256_mul_ps(_mm256_set1_ps(sdt), uz));
  return 1;
}

/* semi_lagrangian, 8 cells at a time. */
__attribute__((target("avx2"), always_inline)) static inline void semi_lagrangian_avx2(
    const advect_pass *p, const trace_ctx *tc, int count, int cubic, const float *const *src,
    float *const *dst, float *departures) {
  const int w = p->width, h = p->height;
  for (int z = 0; z < h; z++) {
    int x = 0;
    for (; x + 8 <= w; x += 8) {
      long idx = (long)z * w + x;
      __m256 dx, dz, c[4];
      spot8 at;
      if (!trace8(tc, x, z, idx, p->dt, &dx, &dz) || !spot8_at(dx, dz, w, h, cubic, &at)) {
        for (int k = 0; k < 8; k++)
          semi_lagrangian_cell(p, tc, count, cubic, src, dst, departures, x + k, z);
        continue;
      }
      if (departures) { /* (dx, dz) interleaved */
        __m256 lo = _mm256_unpacklo_ps(dx, dz), hi = _mm256_unpackhi_ps(dx, dz);
        _mm256_storeu_ps(departures + 2 * idx, _mm256_permute2f128_ps(lo, hi, 0x20));
        _mm256_storeu_ps(departures + 2 * idx + 8, _mm256_permute2f128_ps(lo, hi, 0x31));
      }
      for (int f = 0; f < count; f++) {
        __m256 v = sample8(src[f], &at, w, cubic, c);
        _mm256_storeu_ps(dst[f] + idx, clamp8(v, c));
      }
    }
    for (; x < w; x++) semi_lagrangian_cell(p, tc, count, cubic, src, dst, departures, x, z);
  }
}

/* maccormack_correct, 8 cells at a time. */
__attribute__((target("avx2"), always_inline)) static inline void maccormack_correct_avx2(
    const advect_pass *p, const trace_ctx *tc, int count, int cubic, const float *const *src,
    const float *const *forward, float *const *dst, const float *departures) {
  const int w = p->width, h = p->height;
  for (int z = 0; z < h; z++) {
    int x = 0;
    for (; x + 8 <= w; x += 8) {
      long idx = (long)z * w + x;
      /* the departure points of the forward pass, de-interleaved */
      __m256 d0 = _mm256_loadu_ps(departures + 2 * idx);
      __m256 d1 = _mm256_loadu_ps(departures + 2 * idx + 8);
      __m256 ev = _mm256_shuffle_ps(d0, d1, _MM_SHUFFLE(2, 0, 2, 0));
      __m256 od = _mm256_shuffle_ps(d0, d1, _MM_SHUFFLE(3, 1, 3, 1));
      __m256 px = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(ev), _MM_SHUFFLE(3, 1, 2, 0)));
      __m256 pz = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(od), _MM_SHUFFLE(3, 1, 2, 0)));
      __m256 ax, az, c[4];
      spot8 back_at, dep;
      if (!trace8(tc, x, z, idx, -p->dt, &ax, &az) ||
          !spot8_at(ax, az, w, h, cubic, &back_at) || !spot8_at(px, pz, w, h, 0, &dep)) {
        for (int k = 0; k < 8; k++)
          maccormack_cell(p, tc, count, cubic, src, forward, dst, departures, x + k, z);
        continue;
      }
      for (int f = 0; f < count; f++) {
        __m256 back = sample8(forward[f], &back_at, w, cubic, c);
        __m256 v = _mm256_add_ps(_mm256_loadu_ps(forward[f] + idx),
                                 _mm256_mul_ps(_mm256_set1_ps(0.5f),
                                               _mm256_sub_ps(_mm256_loadu_ps(src[f] + idx), back)));
        corners8(src[f], dep.cell, w, c);
        _mm256_storeu_ps(dst[f] + idx, clamp8(v, c));
      }
    }
    for (; x < w; x++)
      maccormack_cell(p, tc, count, cubic, src, forward, dst, departures, x, z);
  }
}

/* The passes as functions of their own (the scheme's interpolator a constant in each). */
#define ADVECT_AVX2_PASS(name, cubic)                                                       \
  __attribute__((target("avx2"))) static void name(                                        \
      const advect_pass *p, const trace_ctx *tc, int count, const float *const *src,       \
      float *const *dst, float *departures) {                                               \
    semi_lagrangian_avx2(p, tc, count, cubic, src, dst, departures);                        \
  }
ADVECT_AVX2_PASS(semi_lagrangian_cubic_avx2, 1)
ADVECT_AVX2_PASS(semi_lagrangian_bilinear_avx2, 0)
#undef ADVECT_AVX2_PASS
#define ADVECT_AVX2_CORRECT(name, cubic)                                                    \
  __attribute__((target("avx2"))) static void name(                                        \
      const advect_pass *p, const trace_ctx *tc, int count, const float *const *src,       \
      const float *const *forward, float *const *dst, const float *departures) {           \
    maccormack_correct_avx2(p, tc, count, cubic, src, forward, dst, departures);            \
  }
ADVECT_AVX2_CORRECT(maccormack_correct_cubic_avx2, 1)
ADVECT_AVX2_CORRECT(maccormack_correct_bilinear_avx2, 0)
#undef ADVECT_AVX2_CORRECT
#undef AVX2
#endif

/* Whether the AVX2 passes run (the CPU has AVX2 and the caller did not ask for the
 * portable loop). */
static int use_avx2(const advect_pass *p) {
#ifdef ADVECT_AVX2
  return !p->portable && __builtin_cpu_supports("avx2");
#else
  (void)p;
  return 0;
#endif
}

static void run_count(const advect_pass *p, const trace_ctx *tc, int count,
                      const float *const *src, float *const *dst) {
  const int avx2 = use_avx2(p);
  (void)avx2; /* unused where there is no AVX2 path */
  switch (p->scheme) {
    case ADVECT_MONOTONE_CUBIC:
#ifdef ADVECT_AVX2
      if (avx2) {
        semi_lagrangian_cubic_avx2(p, tc, count, src, dst, 0);
        return;
      }
#endif
      semi_lagrangian(p, tc, count, 1, src, dst, 0);
      return;
    case ADVECT_MACCORMACK:
    case ADVECT_MACCORMACK_BILINEAR: {
      const long n = (long)p->width * p->height;
      float *forward[4];
      const long stride = n + ADVECT_ARRAY_PAD;
      for (int f = 0; f < count; f++) forward[f] = p->scratch + f * stride;
      float *departures = p->scratch + count * stride;
      const float *const *fwd = (const float *const *)forward;
      /* Separate calls with a constant `cubic` so each pass is compiled for its
       * interpolator. */
      const int cubic = p->scheme == ADVECT_MACCORMACK;
#ifdef ADVECT_AVX2
      if (avx2) {
        if (cubic) {
          semi_lagrangian_cubic_avx2(p, tc, count, src, forward, departures);
          maccormack_correct_cubic_avx2(p, tc, count, src, fwd, dst, departures);
        } else {
          semi_lagrangian_bilinear_avx2(p, tc, count, src, forward, departures);
          maccormack_correct_bilinear_avx2(p, tc, count, src, fwd, dst, departures);
        }
        return;
      }
#endif
      if (cubic) {
        semi_lagrangian(p, tc, count, 1, src, forward, departures);
        maccormack_correct(p, tc, count, 1, src, fwd, dst, departures);
      } else {
        semi_lagrangian(p, tc, count, 0, src, forward, departures);
        maccormack_correct(p, tc, count, 0, src, fwd, dst, departures);
      }
      return;
    }
    case ADVECT_BILINEAR:
    default:
#ifdef ADVECT_AVX2
      if (avx2) {
        semi_lagrangian_bilinear_avx2(p, tc, count, src, dst, 0);
        return;
      }
#endif
      semi_lagrangian(p, tc, count, 0, src, dst, 0);
      return;
  }
}

long advect_scratch_floats(int width, int height, int count) {
  const long n = (long)width * height;
  return count * (n + ADVECT_ARRAY_PAD) + 2 * n;
}

void advect_fields(const advect_pass *pass, int count, const float *const *sources,
                   float *const *destinations) {
  const trace_ctx tc = {pass->velocity_x, pass->velocity_z, pass->width, pass->height};
  /* Constant counts let the compiler specialise the per-field loop. */
  switch (count) {
    case 1: run_count(pass, &tc, 1, sources, destinations); break;
    case 2: run_count(pass, &tc, 2, sources, destinations); break;
    case 3: run_count(pass, &tc, 3, sources, destinations); break;
    case 4: run_count(pass, &tc, 4, sources, destinations); break;
    default: break;
  }
}
