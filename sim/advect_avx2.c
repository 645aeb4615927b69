/* The advection passes 8 cells at a time with AVX2 gathers (sim/advect_cell.h declares
 * them; sim/advect.c calls them on CPUs that have AVX2). Every lane does the scalar code's
 * operations in the same order (C11: no contraction), so the bits are those of
 * semi_lagrangian_cell and maccormack_cell, which also take any group of 8 whose stencils
 * wrap around the periodic edge (or whose positions are far outside, which locate()
 * wraps). tests/sim/test_advect_simd_matches_scalar.c compares the two, every scheme. */
#include "sim/advect_cell.h"

#ifdef ADVECT_AVX2
#include <immintrin.h>

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
  w[0] = _mm256_mul_ps(
      half, _mm256_sub_ps(_mm256_add_ps(m3, _mm256_mul_ps(_mm256_set1_ps(2.0f), t2)), t));
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
#define PAIRS_0213 _MM_SHUFFLE(3, 1, 2, 0) /* 64-bit pairs in the order 0, 2, 1, 3 */
      __m256 px = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(ev), PAIRS_0213));
      __m256 pz = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(od), PAIRS_0213));
#undef PAIRS_0213
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

__attribute__((target("avx2"))) void advect_avx2_semi_lagrangian(
    const advect_pass *p, const trace_ctx *tc, int count, int cubic, const float *const *src,
    float *const *dst, float *departures) {
  /* one call per interpolator, a constant in each */
  if (cubic)
    semi_lagrangian_avx2(p, tc, count, 1, src, dst, departures);
  else
    semi_lagrangian_avx2(p, tc, count, 0, src, dst, departures);
}

__attribute__((target("avx2"))) void advect_avx2_maccormack_correct(
    const advect_pass *p, const trace_ctx *tc, int count, int cubic, const float *const *src,
    const float *const *forward, float *const *dst, const float *departures) {
  if (cubic)
    maccormack_correct_avx2(p, tc, count, 1, src, forward, dst, departures);
  else
    maccormack_correct_avx2(p, tc, count, 0, src, forward, dst, departures);
}
#undef AVX2
#endif
