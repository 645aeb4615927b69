/* Semi-Lagrangian advection: bilinear, clamped cubic and MacCormack (see advect.h for
 * the references). One thread, no allocation; the departure point of a
 * cell is traced once and shared by every field advected in the same pass. The one-cell
 * kernels are in advect_cell.h; on CPUs with AVX2 the passes run 8 cells at a time
 * (advect_avx2.c), with the same bits. */
#include "sim/advect_cell.h"

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

ADVECT_INLINE void semi_lagrangian(const advect_pass *p, const trace_ctx *tc, int count,
                                   int cubic, const float *const *src, float *const *dst,
                                   float *departures) {
  for (int z = 0; z < p->height; z++)
    for (int x = 0; x < p->width; x++)
      semi_lagrangian_cell(p, tc, count, cubic, src, dst, departures, x, z);
}

ADVECT_INLINE void maccormack_correct(const advect_pass *p, const trace_ctx *tc, int count,
                                      int cubic, const float *const *src,
                                      const float *const *forward, float *const *dst,
                                      const float *departures) {
  for (int z = 0; z < p->height; z++)
    for (int x = 0; x < p->width; x++)
      maccormack_cell(p, tc, count, cubic, src, forward, dst, departures, x, z);
}

/* One forward pass (departures recorded when not NULL) and one MacCormack correction:
 * 8 cells at a time where the CPU has AVX2 and the caller did not ask for the portable
 * loop, else the scalar loop, compiled once per interpolator (a constant `cubic`). */
static void forward_pass(const advect_pass *p, const trace_ctx *tc, int count, int cubic,
                         const float *const *src, float *const *dst, float *departures) {
#ifdef ADVECT_AVX2
  if (!p->portable && __builtin_cpu_supports("avx2")) {
    advect_avx2_semi_lagrangian(p, tc, count, cubic, src, dst, departures);
    return;
  }
#endif
  if (cubic)
    semi_lagrangian(p, tc, count, 1, src, dst, departures);
  else
    semi_lagrangian(p, tc, count, 0, src, dst, departures);
}

static void correction_pass(const advect_pass *p, const trace_ctx *tc, int count, int cubic,
                            const float *const *src, const float *const *forward,
                            float *const *dst, const float *departures) {
#ifdef ADVECT_AVX2
  if (!p->portable && __builtin_cpu_supports("avx2")) {
    advect_avx2_maccormack_correct(p, tc, count, cubic, src, forward, dst, departures);
    return;
  }
#endif
  if (cubic)
    maccormack_correct(p, tc, count, 1, src, forward, dst, departures);
  else
    maccormack_correct(p, tc, count, 0, src, forward, dst, departures);
}

static void run_count(const advect_pass *p, const trace_ctx *tc, int count,
                      const float *const *src, float *const *dst) {
  switch (p->scheme) {
    case ADVECT_MONOTONE_CUBIC:
      forward_pass(p, tc, count, 1, src, dst, 0);
      return;
    case ADVECT_MACCORMACK:
    case ADVECT_MACCORMACK_BILINEAR: {
      const long n = (long)p->width * p->height;
      float *forward[4];
      const long stride = n + ADVECT_ARRAY_PAD;
      for (int f = 0; f < count; f++) forward[f] = p->scratch + f * stride;
      float *departures = p->scratch + count * stride;
      const int cubic = p->scheme == ADVECT_MACCORMACK;
      forward_pass(p, tc, count, cubic, src, forward, departures);
      correction_pass(p, tc, count, cubic, src, (const float *const *)forward, dst, departures);
      return;
    }
    case ADVECT_BILINEAR:
    default:
      forward_pass(p, tc, count, 0, src, dst, 0);
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
