/* The one-cell kernels of sim/advect.c's passes, shared by its scalar loops and the AVX2
 * loops of sim/advect_avx2.c (which must give the same bits, and fall back to these cells
 * where their stencils wrap). Internal to the sim library: include sim/advect.h instead. */
#ifndef FOGPIPE_SIM_ADVECT_CELL_H
#define FOGPIPE_SIM_ADVECT_CELL_H

#include "sim/advect.h"

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

#if defined(__GNUC__) && defined(__x86_64__)
/* sim/advect_avx2.c: the passes 8 cells at a time, for CPUs with AVX2 (the caller checks;
 * the default build stays portable). Same arguments and bits as semi_lagrangian and
 * maccormack_correct in sim/advect.c. */
#define ADVECT_AVX2 1
void advect_avx2_semi_lagrangian(const advect_pass *p, const trace_ctx *tc, int count,
                                 int cubic, const float *const *src, float *const *dst,
                                 float *departures);
void advect_avx2_maccormack_correct(const advect_pass *p, const trace_ctx *tc, int count,
                                    int cubic, const float *const *src,
                                    const float *const *forward, float *const *dst,
                                    const float *departures);
#endif

#endif
