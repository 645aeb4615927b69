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

#if defined(__GNUC__) && defined(__x86_64__)
/* The clamped cubic and bilinear passes 8 cells at a time with AVX2 gathers (chosen at run
 * time; the default build stays portable). Every lane does the scalar code's operations in the same
 * order (C11: no contraction), so the bits are those of semi_lagrangian_cell, which also
 * takes any group of 8 whose stencils wrap around the periodic edge (or whose positions
 * are far outside, which locate() wraps). */
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

/* The bilinear sample of f at cells (i, k) (row offset r = k w) with fractions tx, tz. */
AVX2 __m256 bilinear8(const float *f, __m256i at, int w, __m256 tx, __m256 tz) {
  __m256i one = _mm256_set1_epi32(1), down = _mm256_set1_epi32(w);
  __m256i at_c = _mm256_add_epi32(at, down);
  __m256 a = _mm256_i32gather_ps(f, at, 4), b = _mm256_i32gather_ps(f, _mm256_add_epi32(at, one), 4);
  __m256 c = _mm256_i32gather_ps(f, at_c, 4), d = _mm256_i32gather_ps(f, _mm256_add_epi32(at_c, one), 4);
  return lerp8(lerp8(a, b, tx), lerp8(c, d, tx), tz);
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

/* One pass, 8 cells at a time: the clamped cubic (`cubic`) or the clamped bilinear. */
__attribute__((target("avx2"), always_inline)) static inline void semi_lagrangian_avx2(
    const advect_pass *p, const trace_ctx *tc, int count, int cubic, const float *const *src,
    float *const *dst) {
  const int w = p->width, h = p->height;
  const float sdt = p->dt, half_sdt = 0.5f * p->dt;
  const __m256 lane = _mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i wv = _mm256_set1_epi32(w);
  for (int z = 0; z < h; z++) {
    const __m256 zf = _mm256_set1_ps((float)z);
    int x = 0;
    for (; x + 8 <= w; x += 8) {
      long idx = (long)z * w + x;
      __m256 xf = _mm256_add_ps(_mm256_set1_ps((float)x), lane);
      /* trace: the midpoint, the velocity there, the departure point */
      __m256 vx = _mm256_loadu_ps(tc->vx + idx), vz = _mm256_loadu_ps(tc->vz + idx);
      __m256 mx = _mm256_sub_ps(xf, _mm256_mul_ps(_mm256_set1_ps(half_sdt), vx));
      __m256 mz = _mm256_sub_ps(zf, _mm256_mul_ps(_mm256_set1_ps(half_sdt), vz));
      __m256i ix, iz, jx, jz;
      __m256 tx, tz, sx, sz;
      if (!locate8(mx, 0, w - 2, &ix, &tx) || !locate8(mz, 0, h - 2, &iz, &tz)) goto scalar;
      __m256i at = _mm256_add_epi32(_mm256_mullo_epi32(iz, wv), ix);
      __m256 ux = bilinear8(tc->vx, at, w, tx, tz), uz = bilinear8(tc->vz, at, w, tx, tz);
      __m256 dx = _mm256_sub_ps(xf, _mm256_mul_ps(_mm256_set1_ps(sdt), ux));
      __m256 dz = _mm256_sub_ps(zf, _mm256_mul_ps(_mm256_set1_ps(sdt), uz));
      if (!cubic) { /* the 2x2 cell without wrap: cells 0 .. n-2 */
        if (!locate8(dx, 0, w - 2, &jx, &sx) || !locate8(dz, 0, h - 2, &jz, &sz)) goto scalar;
        __m256i cell = _mm256_add_epi32(_mm256_mullo_epi32(jz, wv), jx);
        __m256i one = _mm256_set1_epi32(1), below = _mm256_add_epi32(cell, wv);
        for (int f = 0; f < count; f++) {
          __m256 a = _mm256_i32gather_ps(src[f], cell, 4);
          __m256 b = _mm256_i32gather_ps(src[f], _mm256_add_epi32(cell, one), 4);
          __m256 c = _mm256_i32gather_ps(src[f], below, 4);
          __m256 d = _mm256_i32gather_ps(src[f], _mm256_add_epi32(below, one), 4);
          __m256 v = lerp8(lerp8(a, b, sx), lerp8(c, d, sx), sz);
          __m256 lo = _mm256_min_ps(_mm256_min_ps(a, b), _mm256_min_ps(c, d));
          __m256 hi = _mm256_max_ps(_mm256_max_ps(a, b), _mm256_max_ps(c, d));
          _mm256_storeu_ps(dst[f] + idx, _mm256_min_ps(_mm256_max_ps(v, lo), hi));
        }
        continue;
      }
      /* the 4x4 stencil without wrap: cells 1 .. n-3 */
      if (!locate8(dx, 1, w - 3, &jx, &sx) || !locate8(dz, 1, h - 3, &jz, &sz)) goto scalar;
      __m256 wx[4], wz[4];
      catmull_rom8(sx, wx);
      catmull_rom8(sz, wz);
      /* stencil tap (row k, column j) at corner + k w + j, corner = (jz - 1) w + jx - 1 */
      __m256i corner = _mm256_sub_epi32(_mm256_add_epi32(_mm256_mullo_epi32(jz, wv), jx),
                                        _mm256_add_epi32(wv, _mm256_set1_epi32(1)));
      for (int f = 0; f < count; f++) {
        __m256 v = _mm256_setzero_ps(), inner[4];
        for (int k = 0; k < 4; k++) {
          __m256i row = _mm256_add_epi32(corner, _mm256_set1_epi32(k * w));
          __m256 g[4];
          for (int j = 0; j < 4; j++)
            g[j] = _mm256_i32gather_ps(src[f], _mm256_add_epi32(row, _mm256_set1_epi32(j)), 4);
          __m256 r = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(wx[0], g[0]),
                                                               _mm256_mul_ps(wx[1], g[1])),
                                                 _mm256_mul_ps(wx[2], g[2])),
                                   _mm256_mul_ps(wx[3], g[3]));
          v = _mm256_add_ps(v, _mm256_mul_ps(wz[k], r));
          if (k == 1) inner[0] = g[1], inner[1] = g[2];
          if (k == 2) inner[2] = g[1], inner[3] = g[2];
        }
        /* clamp_to_cell: min_f/max_f are minps/maxps with the same operand order */
        __m256 lo = _mm256_min_ps(_mm256_min_ps(inner[0], inner[1]), _mm256_min_ps(inner[2], inner[3]));
        __m256 hi = _mm256_max_ps(_mm256_max_ps(inner[0], inner[1]), _mm256_max_ps(inner[2], inner[3]));
        _mm256_storeu_ps(dst[f] + idx, _mm256_min_ps(_mm256_max_ps(v, lo), hi));
      }
      continue;
    scalar:
      for (int c = 0; c < 8; c++)
        semi_lagrangian_cell(p, tc, count, cubic, src, dst, 0, x + c, z);
    }
    for (; x < w; x++) semi_lagrangian_cell(p, tc, count, cubic, src, dst, 0, x, z);
  }
}

__attribute__((target("avx2"))) static void semi_lagrangian_cubic_avx2(
    const advect_pass *p, const trace_ctx *tc, int count, const float *const *src,
    float *const *dst) {
  semi_lagrangian_avx2(p, tc, count, 1, src, dst);
}

__attribute__((target("avx2"))) static void semi_lagrangian_bilinear_avx2(
    const advect_pass *p, const trace_ctx *tc, int count, const float *const *src,
    float *const *dst) {
  semi_lagrangian_avx2(p, tc, count, 0, src, dst);
}
#undef AVX2
#endif

/* MacCormack (Selle et al. 2008 eq. 5-7): phi_hat = A(phi) (the forward pass, done by
 * semi_lagrangian with departures recorded), phi_bar = A^R(phi_hat) (the same trace with
 * time reversed), phi_new = phi_hat + (phi - phi_bar)/2, clamped to the extrema of phi
 * around the departure point (their §4). */
ADVECT_INLINE void maccormack_correct(const advect_pass *p, const trace_ctx *tc, int count,
                                      int cubic, const float *const *src,
                                      const float *const *forward, float *const *dst,
                                      const float *departures) {
  const int w = p->width, h = p->height;
  for (int z = 0; z < h; z++) {
    for (int x = 0; x < w; x++) {
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
  }
}

static void run_count(const advect_pass *p, const trace_ctx *tc, int count,
                      const float *const *src, float *const *dst) {
  switch (p->scheme) {
    case ADVECT_MONOTONE_CUBIC:
#ifdef ADVECT_AVX2
      if (!p->portable && __builtin_cpu_supports("avx2")) {
        semi_lagrangian_cubic_avx2(p, tc, count, src, dst);
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
      if (p->scheme == ADVECT_MACCORMACK) {
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
      if (!p->portable && __builtin_cpu_supports("avx2")) {
        semi_lagrangian_bilinear_avx2(p, tc, count, src, dst);
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
