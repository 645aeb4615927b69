/* Density sources and sinks against their closed forms, with the fluid at rest (no
 * drift, no turbulence: advection is then the identity): a Gaussian emitter adds
 * rate·dt·exp(-r²/2σ²) per step; relaxation toward the base decays the difference as
 * exp(-rate·t); dissipation as exp(-rate·t); a stroke paints amount·(1-(d/r)²)² along
 * its segment (wrapping around the domain) and a negative one erases, clamped at 0;
 * NaN, negative and infinite base values are sanitised; bad input is refused with a
 * message. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sim/sim.h"
#include "test_util.h"

enum { N = 64 };

int main(void) {
  fog_error err;
  const float dt = 0.05f;
  /* Emitter near a corner: its Gaussian wraps onto the opposite sides. */
  const fluid_emitter em = {2.0f, 61.0f, 3.0f, 4.0f};
  fluid_sim_desc desc = fluid_sim_desc_default(N, N);
  desc.dt = dt, desc.emitters = &em, desc.emitter_count = 1;
  desc.advection = FLUID_ADVECT_BILINEAR;
  fluid_sim *sim = fluid_sim_create(&desc, &err);
  CHECK(sim != NULL, "create: %s", err.message);
  for (int s = 0; s < 10; s++) fluid_sim_step(sim, &err);
  double worst = 0;
  for (int z = 0; z < N; z++)
    for (int x = 0; x < N; x++) {
      double dx = fabs(x - 2.0), dz = fabs(z - 61.0);
      dx = fmin(dx, N - dx), dz = fmin(dz, N - dz);
      double exact = 10 * 4.0 * dt * exp(-(dx * dx + dz * dz) / 18.0);
      if (exact < 4.0 * dt * 10 * exp(-8.0)) exact = 0; /* beyond the 4-sigma cut */
      worst = fmax(worst, fabs(fluid_sim_density(sim)->density[z * N + x] - exact));
    }
  printf("emitter after 10 steps: max error %.3g (peak %.3g)\n", worst, 10 * 4.0 * dt);
  CHECK(worst <= 2e-3 * 10 * 4.0 * dt, "emitter max error %g", worst);

  /* An emitter whose step's amount passes FLT_MAX (rate 3e38, dt 2: the public API allows
   * it): its centre holds the most a cell may (1e12), not 0 (inf, then relaxation's
   * 0 x -inf made it NaN, cleaned to 0: a hole where the most fog is) */
  {
    const fluid_emitter huge = {16.0f, 16.0f, 2.0f, 3e38f};
    fluid_sim_desc hd = fluid_sim_desc_default(32, 32);
    hd.dt = 2.0f, hd.emitters = &huge, hd.emitter_count = 1;
    fluid_sim *hs = fluid_sim_create(&hd, &err);
    CHECK(hs != NULL, "create: %s", err.message);
    if (hs) {
      fluid_sim_step(hs, &err);
      const float *hr = fluid_sim_density(hs)->density;
      CHECK(hr[16 * 32 + 16] == FOGMAP_MAX_DENSITY && hr[16 * 32 + 17] == FOGMAP_MAX_DENSITY,
            "a huge emitter's centre %g and neighbour %g, expected %g", hr[16 * 32 + 16],
            hr[16 * 32 + 17], FOGMAP_MAX_DENSITY);
      fluid_sim_destroy(hs);
    }
  }

  /* Strokes: paint across the x seam, then erase more than is there. */
  CHECK(!fluid_sim_paint(sim, &(fluid_stroke){58, 20, 70, 20, 4, 1.5f, false}, &err), "%s",
        err.message);
  const float *rho = fluid_sim_density(sim)->density;
  CHECK(fabsf(rho[20 * N + 62] - 1.5f) < 1e-6f, "stroke centre line %g", rho[20 * N + 62]);
  CHECK(fabsf(rho[20 * N + 4] - 1.5f) < 1e-6f, "stroke wrapped past the seam %g",
        rho[20 * N + 4]);
  CHECK(fabsf(rho[22 * N + 62] - 1.5f * 0.75f * 0.75f) < 1e-6f, "stroke falloff %g",
        rho[22 * N + 62]);
  CHECK(rho[25 * N + 62] == 0.0f, "outside the radius %g", rho[25 * N + 62]);
  /* within_grid: the part past the seam is left out, not wrapped (the demo's brush at the
   * fog box's edge) */
  CHECK(!fluid_sim_paint(sim, &(fluid_stroke){58, 40, 70, 40, 4, 1.5f, true}, &err), "%s",
        err.message);
  CHECK(fabsf(rho[40 * N + 62] - 1.5f) < 1e-6f && rho[40 * N + 4] == 0.0f &&
            rho[40 * N + 0] == 0.0f,
        "a stroke within the grid: centre %g, past the seam %g, %g", rho[40 * N + 62],
        rho[40 * N + 4], rho[40 * N + 0]);
  /* one wider than the grid (a drag across the box in one frame): every cell on its line */
  CHECK(!fluid_sim_paint(sim, &(fluid_stroke){-8.5f, 30, 71.5f, 30, 3, 1.0f, true}, &err), "%s",
        err.message);
  float thinnest = INFINITY;
  for (int x = 0; x < N; x++) thinnest = fminf(thinnest, rho[30 * N + x]);
  CHECK(thinnest >= 1.0f - 1e-6f, "a stroke across the whole grid left a cell at %g", thinnest);
  CHECK(!fluid_sim_paint(sim, &(fluid_stroke){50, 20, 75, 20, 6, -10.0f, false}, &err), "%s",
        err.message);
  float lowest = INFINITY;
  for (int i = 0; i < N * N; i++) lowest = fminf(lowest, rho[i]);
  CHECK(lowest == 0.0f && rho[20 * N + 62] == 0.0f, "erase clamps at 0: %g", lowest);
  CHECK(fluid_sim_paint(sim, &(fluid_stroke){NAN, 0, 1, 1, 2, 1, false}, &err) != 0,
        "NaN stroke refused");
  CHECK(fluid_sim_paint(sim, &(fluid_stroke){0, 0, 1, 1, 0, 1, false}, &err) != 0,
        "zero radius refused");
  fluid_sim_destroy(sim);

  /* Relaxation and dissipation: closed-form exponentials. The base carries NaN,
   * negative and infinite values, which must be read as 0, 0 and FOGMAP_MAX_DENSITY (the
   * most a fogmap may hold when loaded: a baked frame loads back). */
  fogmap base;
  fogmap_create(&base, N, N, &err);
  for (int i = 0; i < N * N; i++) base.density[i] = 2.0f;
  base.density[5] = NAN;
  base.density[6] = -3.0f;
  base.density[7] = INFINITY;
  desc = fluid_sim_desc_default(N, N);
  desc.dt = dt, desc.base = &base, desc.relaxation = 1.5f;
  sim = fluid_sim_create(&desc, &err);
  CHECK(sim != NULL, "create: %s", err.message);
  rho = fluid_sim_density(sim)->density;
  CHECK(rho[5] == 0.0f && rho[6] == 0.0f && rho[7] == FOGMAP_MAX_DENSITY, "sanitised base %g %g %g",
        rho[5], rho[6], rho[7]);
  CHECK(!fluid_sim_paint(sim, &(fluid_stroke){30, 30, 30, 30, 3, 4.0f, false}, &err), "paint");
  for (int s = 0; s < 20; s++) fluid_sim_step(sim, &err);
  rho = fluid_sim_density(sim)->density;
  /* rho(t) = base + (rho0 - base) exp(-r t) at the stroke's centre (rho0 = 6). */
  double exact = 2.0 + 4.0 * exp(-1.5 * 20 * dt);
  CHECK(fabs(rho[30 * N + 30] - exact) < 1e-5 * exact, "relaxation %g vs %g",
        rho[30 * N + 30], exact);
  fluid_sim_destroy(sim);

  desc.relaxation = 0, desc.dissipation = 0.7f;
  sim = fluid_sim_create(&desc, &err);
  for (int s = 0; s < 30; s++) fluid_sim_step(sim, &err);
  exact = 2.0 * exp(-0.7 * 30 * dt);
  rho = fluid_sim_density(sim)->density;
  CHECK(fabs(rho[100] - exact) < 1e-5 * exact, "dissipation %g vs %g", rho[100], exact);
  fluid_sim_destroy(sim);

  /* Sources whose reach passes half the grid: each cell at its image nearest the source.
   * An emitter of radius 10 (reach 40) at the middle of 64 cells: the closed form with the
   * minimum-image distance on both sides (its far side came from the far image: 0.0015
   * where 0.0198 is right); a stroke of reach past the period: its own end painted (its
   * cells near the end were taken at the image before the start: +0.31 for +1); an impulse
   * of a radius near float's least: finite velocity. */
  {
    const fluid_emitter wide = {32.0f, 32.0f, 10.0f, 4.0f};
    fluid_sim_desc d = fluid_sim_desc_default(N, N);
    d.dt = dt, d.emitters = &wide, d.emitter_count = 1, d.relaxation = 0, d.dissipation = 0;
    d.advection = FLUID_ADVECT_BILINEAR;
    fluid_sim *wsim = fluid_sim_create(&d, &err);
    CHECK(wsim != NULL, "create: %s", err.message);
    if (wsim) {
      fluid_sim_step(wsim, &err);
      const float *wr = fluid_sim_density(wsim)->density;
      double werst = 0;
      for (int x = 0; x < N; x++) {
        double ex = fabs(x - 32.0);
        ex = fmin(ex, N - ex);
        const double want = 4.0 * dt * exp(-ex * ex / 200.0);
        werst = fmax(werst, fabs(wr[32 * N + x] - want) / want);
      }
      CHECK(werst <= 1e-3, "an emitter reaching past half the grid: %.3g off", werst);
      const float end_before = wr[10 * N + 60], past_before = wr[10 * N + 62];
      CHECK(!fluid_sim_paint(wsim, &(fluid_stroke){0, 10, 60, 10, 6, 1.0f, false}, &err), "%s",
            err.message);
      const double past = (1 - 4.0 / 36) * (1 - 4.0 / 36); /* 2 cells past its end */
      CHECK(fabs(wr[10 * N + 60] - end_before - 1.0) < 1e-5 &&
                fabs(wr[10 * N + 62] - past_before - past) < 1e-5,
            "a stroke of reach past the period: its end +%g (1), 2 cells past it +%g (%g)",
            wr[10 * N + 60] - end_before, wr[10 * N + 62] - past_before, past);
      CHECK(!fluid_sim_add_impulse(wsim, 20.0f, 20.0f, 1e-20f, 1.0f, 0.0f, &err), "%s",
            err.message);
      fluid_sim_step(wsim, &err);
      const float *u = fluid_sim_velocity_x(wsim), *v = fluid_sim_velocity_z(wsim);
      int bad = 0;
      for (int c = 0; c < N * N; c++) bad += !isfinite(u[c]) || !isfinite(v[c]);
      CHECK(bad == 0, "an impulse of radius 1e-20: %d cells of velocity not finite", bad);
      fluid_sim_destroy(wsim);
    }
  }

  /* A Gaussian wider than half the grid, at a centre between cells: each cell takes its
   * image nearest the centre (the period started at floor(centre) - N/2, so cell 0 of an
   * emitter at 32.99 took its far image: 0.0043 of 0.0082). One step, one image a cell. */
  const float centres[2] = {32.99f, 31.3f};
  for (int k = 0; k < 2; k++) {
    const fluid_emitter wide = {centres[k], 32.0f, 10.0f, 1.0f};
    fluid_sim_desc wd = fluid_sim_desc_default(N, N);
    wd.dt = 1.0f, wd.emitters = &wide, wd.emitter_count = 1;
    fluid_sim *wsim = fluid_sim_create(&wd, &err);
    CHECK(wsim != NULL, "a wide emitter: %s", err.message);
    if (!wsim) continue;
    fluid_sim_step(wsim, &err);
    const float *d = fluid_sim_density(wsim)->density;
    double worst = 0;
    for (int x = 0; x < N; x++) {
      double dx = fabs(x - (double)centres[k]);
      dx = fmin(dx, N - dx);
      const double exact = exp(-dx * dx / 200.0);
      worst = fmax(worst, fabs(d[32 * N + x] - exact) / exact);
    }
    CHECK(worst < 1e-5, "an emitter of sigma 10 at x = %g: worst relative error %.3g (a cell "
          "at its far image)", (double)centres[k], worst);
    fluid_sim_destroy(wsim);
  }
  /* Sources past FLUID_MAX_REACH are refused (a radius of 3.75e8 overflowed the cell count
   * and covered no cell; an impulse of 3e38 made the velocity infinite) */
  {
    const fluid_emitter huge = {32.0f, 32.0f, 3.75e8f, 1.0f};
    fluid_sim_desc hd = fluid_sim_desc_default(N, N);
    hd.emitters = &huge, hd.emitter_count = 1;
    CHECK(!fluid_sim_create(&hd, &err) && strstr(err.message, "emitter 0"),
          "an emitter of radius 3.75e8: %s", err.message);
    fluid_sim_desc id = fluid_sim_desc_default(N, N);
    fluid_sim *isim = fluid_sim_create(&id, &err);
    CHECK(isim && fluid_sim_add_impulse(isim, 32, 32, 3.75e8f, 1, 0, &err) &&
              fluid_sim_add_impulse(isim, 32, 32, 3, 3e38f, 0, &err) &&
              fluid_sim_paint(isim, &(fluid_stroke){0, 0, 1e9f, 0, 2, 1, false}, &err),
          "an impulse of radius 3.75e8 or of 3e38 cells/s, or a stroke to 1e9, was taken");
    fluid_sim_destroy(isim);
    fluid_sim_desc sd = fluid_sim_desc_default(N, N);
    sd.turbulence = 1.0, sd.turbulence_slope = -64.0;
    CHECK(!fluid_sim_create(&sd, &err) && strstr(err.message, "slope"),
          "a turbulence slope of -64 (every velocity NaN): %s", err.message);
  }

  /* Bad descs are refused with a message naming the problem. */
  desc = fluid_sim_desc_default(63, N);
  CHECK(!fluid_sim_create(&desc, &err) && strstr(err.message, "even"), "odd width: %s",
        err.message);
  fogmap small;
  fogmap_create(&small, 32, 32, &err);
  desc = fluid_sim_desc_default(N, N);
  desc.base = &small;
  CHECK(!fluid_sim_create(&desc, &err) &&
            strstr(err.message, "base"),
        "mismatched base: %s", err.message);
  desc = fluid_sim_desc_default(N, N);
  desc.dt = -1;
  CHECK(!fluid_sim_create(&desc, &err) && strstr(err.message, "dt"), "negative dt: %s",
        err.message);
  /* A zero-filled desc is refused, not read as "the defaults" (sim/fluid.h). */
  CHECK(!fluid_sim_create(&(fluid_sim_desc){0}, &err), "a zero desc was taken");
  fogmap_destroy(&small);
  fogmap_destroy(&base);
  return test_finish("test_fluid_sources");
}
