/* Density sources and sinks of the fluid simulation: Gaussian emitters, painted strokes,
 * velocity impulses, relaxation toward the base fogmap and dissipation. Everything wraps
 * around the periodic domain. */
#include <float.h>
#include <stdbool.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sim/fluid_internal.h"

static int wrap(int i, int n) {
  i %= n;
  return i < 0 ? i + n : i;
}

static bool within_reach(float v) { return fabsf(v) <= FLUID_MAX_REACH; }

/* The cells [lo, lo + count) along one axis covering [centre - reach, centre + reach],
 * at most one period (so no cell is visited twice); returns whether that took the whole
 * period. Then the period is the one centred on the middle of the span, so each cell is
 * taken at its image nearest the centre (a source whose reach passes half the grid, on
 * one side from its centre, lost its other side to the far image). */
static bool cover(float centre_lo, float centre_hi, float reach, int n, int *lo, int *count) {
  /* in double: centres and reaches are within FLUID_MAX_REACH cells (fluid.h), so the span
   * fits an int, but its count did not for a reach near float's */
  const double a = floor((double)centre_lo - reach), b = ceil((double)centre_hi + reach);
  if (b - a + 1 <= n) {
    *lo = (int)a;
    *count = (int)(b - a) + 1;
    return false;
  }
  /* [mid - n/2, mid + n/2): every cell's image nearest the middle (from floor(mid) - n/2, a
   * centre at 32.99 on 64 cells took cell 0 at its far image: 0.0043 instead of 0.0082) */
  *lo = (int)ceil(0.5 * ((double)centre_lo + centre_hi) - 0.5 * n);
  *count = n;
  return true;
}

/* The cells of [centre_lo - reach, centre_hi + reach] inside [0, n): cover() caps the count
 * at n but keeps a negative start, which wrapping makes every cell once and clipping would
 * cut short (a stroke wider than the grid left its far cells unpainted). */
static void within(float centre_lo, float centre_hi, float reach, int n, int *lo, int *count) {
  /* clamped in float before the conversion: a reach far outside stays in int's range */
  const int first = (int)fminf(fmaxf(floorf(centre_lo - reach), 0.0f), (float)n);
  const int last = (int)fmaxf(fminf(ceilf(centre_hi + reach), (float)(n - 1)), -1.0f);
  *lo = first;
  *count = last >= first ? last - first + 1 : 0;
}

int fluid_emission_build(fluid_sim *sim, fog_error *err) {
  if (!sim->desc.emitter_count) return 0;
  const int w = sim->width, h = sim->height;
  const size_t n = (size_t)w * h;
  sim->emission = fftwf_malloc(n * sizeof(float));
  if (!sim->emission) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "fluid sim: out of memory for emitters");
    return 1;
  }
  fluid_emission_fill(sim);
  return 0;
}

void fluid_emission_fill(fluid_sim *sim) {
  if (!sim->emission) return;
  const int w = sim->width, h = sim->height;
  memset(sim->emission, 0, (size_t)w * h * sizeof(float));
  /* Precomputed: the emitters change only through fluid_sim_set_params, so each step adds
   * one table instead of evaluating exp() per cell (density added per step =
   * rate * dt * Gaussian). */
  for (int e = 0; e < sim->desc.emitter_count; e++) {
    const fluid_emitter *em = &sim->emitters[e];
    const float reach = 4.0f * em->radius; /* exp(-8) ≈ 3e-4 of the peak at the edge */
    int x0, nx, z0, nz;
    cover(em->x, em->x, reach, w, &x0, &nx);
    cover(em->z, em->z, reach, h, &z0, &nz);
    const double inv_two_s2 = 1.0 / (2.0 * (double)em->radius * em->radius);
    for (int dz = 0; dz < nz; dz++) {
      const double ez = (z0 + dz) - (double)em->z;
      float *row = sim->emission + (size_t)wrap(z0 + dz, h) * w;
      for (int dx = 0; dx < nx; dx++) {
        const double ex = (x0 + dx) - (double)em->x;
        /* at most what a cell may hold: a step's amount past FLT_MAX was inf, and
         * relaxation's 0 x (base - inf) made the emitter's centre NaN, then 0 */
        float *cell = &row[wrap(x0 + dx, w)];
        *cell = (float)fmin((double)*cell + (double)em->rate * sim->desc.dt *
                                                exp(-(ex * ex + ez * ez) * inv_two_s2),
                            (double)FOGMAP_MAX_DENSITY);
      }
    }
  }
}

/* After advection, per cell: + emission, relaxation toward the base (exact decay of
 * d rho/dt = r (base - rho) over dt), dissipation (exact decay of d rho/dt = -d rho), and
 * the clamp that keeps the density in [0, FOGMAP_MAX_DENSITY], turns NaN into 0 and flushes
 * would-be subnormals to 0. */
void fluid_density_sources(fluid_sim *sim, float *density) {
  const size_t n = (size_t)sim->width * sim->height;
  const float *restrict emission = sim->emission, *restrict base = sim->base;
  const float relax = sim->relax_gain, keep = sim->keep;
  float *restrict rho = density;
  if (!emission && relax == 0 && keep == 1) {
    for (size_t c = 0; c < n; c++) rho[c] = fluid_clean_density(rho[c]);
    return;
  }
  for (size_t c = 0; c < n; c++) {
    float v = rho[c];
    if (emission) v += emission[c];
    v += relax * ((base ? base[c] : 0.0f) - v);
    v *= keep;
    rho[c] = fluid_clean_density(v);
  }
}

/* Squared distance from (px, pz) to the segment a-b. */
static float segment_distance2(float px, float pz, float ax, float az, float bx, float bz) {
  const float dx = bx - ax, dz = bz - az;
  const float len2 = dx * dx + dz * dz;
  float t = len2 > 0 ? ((px - ax) * dx + (pz - az) * dz) / len2 : 0.0f;
  t = fminf(fmaxf(t, 0.0f), 1.0f);
  const float ex = px - (ax + t * dx), ez = pz - (az + t * dz);
  return ex * ex + ez * ez;
}

int fluid_sim_paint(fluid_sim *sim, const fluid_stroke *s, fog_error *err) {
  if (!within_reach(s->x0) || !within_reach(s->z0) || !within_reach(s->x1) ||
      !within_reach(s->z1) || !isfinite(s->amount) || !(s->radius > 0) ||
      !within_reach(s->radius)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fluid sim: stroke needs end points and a radius > 0 within %g cells and a finite "
             "amount", FLUID_MAX_REACH);
    return 1;
  }
  const int w = sim->width, h = sim->height;
  int x0, nx, z0, nz;
  bool wrap_x = false, wrap_z = false;
  if (s->within_grid) { /* the grid's own cells of the reach, not n cells from its start */
    within(fminf(s->x0, s->x1), fmaxf(s->x0, s->x1), s->radius, w, &x0, &nx);
    within(fminf(s->z0, s->z1), fmaxf(s->z0, s->z1), s->radius, h, &z0, &nz);
  } else {
    /* an axis the reach wraps around: each cell at whichever image is nearest the segment */
    wrap_x = cover(fminf(s->x0, s->x1), fmaxf(s->x0, s->x1), s->radius, w, &x0, &nx);
    wrap_z = cover(fminf(s->z0, s->z1), fmaxf(s->z0, s->z1), s->radius, h, &z0, &nz);
  }
  const float inv_r2 = 1.0f / (s->radius * s->radius);
  float *rho = sim->density[sim->current];
  for (int dz = 0; dz < nz; dz++) {
    const float pz = (float)(z0 + dz);
    if (s->within_grid && (z0 + dz < 0 || z0 + dz >= h)) continue;
    float *row = rho + (size_t)wrap(z0 + dz, h) * w;
    for (int dx = 0; dx < nx; dx++) {
      if (s->within_grid && (x0 + dx < 0 || x0 + dx >= w)) continue;
      float d2 = INFINITY;
      for (int ix = wrap_x ? -1 : 0; ix <= (wrap_x ? 1 : 0); ix++)
        for (int iz = wrap_z ? -1 : 0; iz <= (wrap_z ? 1 : 0); iz++)
          d2 = fminf(d2, segment_distance2((float)(x0 + dx + ix * w), pz + (float)(iz * h),
                                           s->x0, s->z0, s->x1, s->z1));
      const float q = d2 * inv_r2;
      if (q >= 1.0f) continue;
      /* A smooth compact brush: (1 - q)^2 is C1 at the rim, peak 1 on the centre line. */
      const float weight = (1.0f - q) * (1.0f - q);
      float *cell = &row[wrap(x0 + dx, w)];
      *cell = fluid_clean_density(*cell + s->amount * weight);
    }
  }
  return 0;
}

int fluid_sim_add_impulse(fluid_sim *sim, float x, float z, float radius, float du, float dv,
                          fog_error *err) {
  /* |du|, |dv| up to FLUID_MAX_IMPULSE: two of 3e38 made the velocity infinite, then NaN */
  if (!within_reach(x) || !within_reach(z) || !(fabsf(du) <= FLUID_MAX_IMPULSE) ||
      !(fabsf(dv) <= FLUID_MAX_IMPULSE) || !(radius > 0) || !within_reach(radius)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fluid sim: impulse needs a position and a radius > 0 within %g cells and a "
             "velocity of at most %g cells/s", FLUID_MAX_REACH, FLUID_MAX_IMPULSE);
    return 1;
  }
  const int w = sim->width, h = sim->height;
  int x0, nx, z0, nz;
  cover(x, x, 4.0f * radius, w, &x0, &nx);
  cover(z, z, 4.0f * radius, h, &z0, &nz);
  /* in double: 1/(2 r^2) of a radius near float's least overflows float (0 x inf at the
   * centre cell is a NaN) */
  const double inv_two_s2 = 1.0 / (2.0 * (double)radius * radius);
  for (int dz = 0; dz < nz; dz++) {
    const double ez = (double)(z0 + dz) - z;
    const size_t row = (size_t)wrap(z0 + dz, h) * w;
    for (int dx = 0; dx < nx; dx++) {
      const double ex = (double)(x0 + dx) - x;
      const float g = (float)exp(-(ex * ex + ez * ez) * inv_two_s2);
      const size_t c = row + wrap(x0 + dx, w);
      sim->velocity[c] += du * g;
      sim->velocity[sim->stride + c] += dv * g;
    }
  }
  return 0;
}
