/* RBF puffs carried by the simulation (app/rbf_carrier.h), against its documented meaning:
 * - no flow (no [sim] wind, no turbulence): the puffs are the wind's closed form
 *   (render/fog_rbf_emitter.h), centres to 1e-9, radii and densities bit for bit;
 * - a uniform drift D: the wind's closed form with wind + D (the flow holds its mean at the
 *   drift);
 * - a turbulent flow: between two step times (and to a time between them) a puff moves by
 *   the time times the velocity at its position, the velocity taken from a flow of our own
 *   (sim/fluid.h, the documented grid: square cells, the domain's longer side
 *   RBF_CARRIER_GRID of them, world speeds over the cell and viscosity over its square, the
 *   largest eddies a quarter of the shorter side, stepped as often) sampled bilinearly and
 *   periodically here, plus the emitter's wind: two emitters of different lifetimes whose
 *   puffs cross the domain's edges; the eddies move the puffs off the wind's lines; and a time
 *   gives the same puffs bit for bit whichever times were asked before it (forwards,
 *   backwards, or alone). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "app/rbf_carrier.h"
#include "sim/sim.h"
#include "test_util.h"

enum { CAP = 512 };

static const fog_rbf_emitter emitter = {.position = {30, 40, -50}, .rate = 20, .lifetime = 3,
                                        .radius = 2, .density = 0.1, .spread = 3,
                                        .diffusion = 0.5, .wind = {1.5, 0.8, -0.5}, .seed = 9};

static rbf_carrier_desc desc_with(double wind_x, double wind_z, double turbulence) {
  return (rbf_carrier_desc){.emitters = &emitter, .emitter_count = 1, .origin = {-200, -150},
                            .size = {400, 300}, .grid = RBF_CARRIER_GRID,
                            .step = RBF_CARRIER_STEP, .wind = {wind_x, wind_z},
                            .turbulence = turbulence, .viscosity = 0.0, .seed = 5};
}

/* The carried puffs against the wind's closed form with the emitter's wind plus `drift`. */
static void check_closed_form(const char *label, double drift_x, double drift_z,
                              double tolerance) {
  fog_error err = {0};
  rbf_carrier_desc d = desc_with(drift_x, drift_z, 0.0);
  rbf_carrier *c = rbf_carrier_create(&d, &err);
  CHECK(c != NULL, "%s: %s", label, err.message);
  if (!c) return;
  fog_rbf_emitter moved = emitter;
  moved.wind[0] += drift_x, moved.wind[2] += drift_z;
  static fog_rbf got[CAP], want[CAP];
  double worst = 0.0;
  bool shapes = true;
  for (int f = 0; f < 40; f++) {
    const double t = 0.123 * f;
    const int n = rbf_carrier_puffs(c, t, got, CAP, &err);
    CHECK(n == fog_rbf_emitter_puffs(&moved, t, want, CAP) && n == 60, "%s: %d puffs at %g",
          label, n, t);
    for (int i = 0; i < n && i < 60; i++) {
      for (int a = 0; a < 3; a++) worst = fmax(worst, fabs(got[i].centre[a] - want[i].centre[a]));
      shapes = shapes && got[i].radius == want[i].radius && got[i].density == want[i].density;
    }
  }
  printf("%s: centres within %.2e of the wind's closed form\n", label, worst);
  CHECK(worst <= tolerance, "%s: centres off by %.3e", label, worst);
  CHECK(shapes, "%s: radii or densities differ from the closed form's", label);
  rbf_carrier_destroy(c);
}

/* Our own flow: the documented grid and units, sampled bilinearly and periodically. */
typedef struct reference_flow {
  fluid_sim *sim;
  double cell;
  int w, h;
} reference_flow;

static void reference_velocity(const reference_flow *r, const rbf_carrier_desc *d, double x,
                               double z, double v[2]) {
  double u = (x - d->origin[0]) / r->cell, s = (z - d->origin[1]) / r->cell;
  int i = (int)floor(u), j = (int)floor(s);
  double fx = u - i, fz = s - j;
  i = ((i % r->w) + r->w) % r->w, j = ((j % r->h) + r->h) % r->h;
  const int i1 = (i + 1) % r->w, j1 = (j + 1) % r->h;
  const float *g[2] = {fluid_sim_velocity_x(r->sim), fluid_sim_velocity_z(r->sim)};
  for (int a = 0; a < 2; a++)
    v[a] = r->cell * ((1 - fz) * ((1 - fx) * g[a][j * r->w + i] + fx * g[a][j * r->w + i1]) +
                      fz * ((1 - fx) * g[a][j1 * r->w + i] + fx * g[a][j1 * r->w + i1]));
}

/* Two emitters near the domain's edges, their puffs crossing them (the flow is periodic:
 * x past 200 and z below -150 wrap), the second living shorter than the first (the flow starts
 * at minus the longer lifetime). */
static const fog_rbf_emitter edge_emitters[2] = {
    {.position = {185, 40, 20}, .rate = 20, .lifetime = 3, .radius = 2, .density = 0.1,
     .spread = 3, .diffusion = 0.5, .wind = {6, 0.8, -0.5}, .seed = 9},
    {.position = {-20, 10, -140}, .rate = 10, .lifetime = 2, .radius = 1, .density = 0.2,
     .spread = 2, .diffusion = 0.0, .wind = {-1, 0.2, -8}, .seed = 4}};
enum { EDGE_PUFFS = 60 + 20 };

/* A puff's move over `span` seconds from p by the reference flow plus its emitter's wind. */
static double move_error(const reference_flow *r, const rbf_carrier_desc *d,
                         const fog_rbf_emitter *e, const fog_rbf *p, const fog_rbf *q,
                         double span, double *speed) {
  double v[2], worst = 0.0;
  reference_velocity(r, d, p->centre[0], p->centre[2], v);
  const double want[3] = {p->centre[0] + span * (v[0] + e->wind[0]),
                          p->centre[1] + span * e->wind[1],
                          p->centre[2] + span * (v[1] + e->wind[2])};
  for (int a = 0; a < 3; a++) worst = fmax(worst, fabs(q->centre[a] - want[a]));
  *speed = fmax(*speed, hypot(v[0] - 4.0, v[1] + 2.0));
  return worst;
}

static void check_turbulent_steps(void) {
  fog_error err = {0};
  rbf_carrier_desc d = desc_with(4.0, -2.0, 12.0);
  d.emitters = edge_emitters, d.emitter_count = 2;
  d.viscosity = 30.0; /* world units^2 a second: 30 / 6.25^2 in the flow's cells */
  rbf_carrier *c = rbf_carrier_create(&d, &err);
  CHECK(c != NULL, "turbulent: %s", err.message);
  if (!c) return;
  /* 400 x 300 at 64 cells on the longer side: cells of 6.25, 64 x 48 of them; the
   * turbulence's largest eddies 12 cells (a quarter of 48), Kolmogorov's slope, the
   * fluctuations pulled toward it at 2 a second (app/rbf_carrier.h) */
  reference_flow r = {.cell = 400.0 / RBF_CARRIER_GRID, .w = 64, .h = 48};
  fluid_sim_desc flow = {.width = r.w, .height = r.h, .dt = (float)RBF_CARRIER_STEP,
                         .viscosity = (float)(30.0 / (r.cell * r.cell)),
                         .wind_drift_x = (float)(4.0 / r.cell),
                         .wind_drift_z = (float)(-2.0 / r.cell),
                         .turbulence = (float)(12.0 / r.cell), .turbulence_scale = 12.0f,
                         .turbulence_slope = -5.0 / 3.0, .wind_coupling = 2.0f, .seed = 5,
                         .advection = FLUID_ADVECT_MONOTONE_CUBIC};
  r.sim = fluid_sim_create(&flow, &err);
  CHECK(r.sim != NULL, "reference flow: %s", err.message);
  if (!r.sim) {
    rbf_carrier_destroy(c);
    return;
  }
  static fog_rbf before[CAP], after[CAP], between[CAP], alone[CAP], wind_only[CAP];
  /* the flow starts at t = -3 (the longer lifetime); step s ends at -3 + s/30 */
  const double start = -3.0, dt = RBF_CARRIER_STEP;
  long reference_steps = 0;
  double worst_step = 0.0, worst_between = 0.0, worst_speed = 0.0, off_lines = 0.0;
  int wrapped = 0;
  for (int s = 100; s <= 160; s += 20) {
    const double t0 = start + s * dt, t1 = start + (s + 1) * dt, tm = t0 + 0.4 * dt;
    const int n0 = rbf_carrier_puffs(c, t0, before, CAP, &err);
    const int nm = rbf_carrier_puffs(c, tm, between, CAP, &err);
    const int n1 = rbf_carrier_puffs(c, t1, after, CAP, &err);
    CHECK(n0 == EDGE_PUFFS && nm == EDGE_PUFFS && n1 == EDGE_PUFFS, "turbulent: %d, %d, %d "
          "puffs", n0, nm, n1);
    while (reference_steps < s) fluid_sim_step(r.sim, &err), reference_steps++;
    /* the puffs alive at both times: emitter by emitter, oldest first, so puff i at the
     * later time is puff i + (puffs born between) at the earlier */
    for (int e = 0, first = 0; e < 2; first += fog_rbf_emitter_count(&edge_emitters[e]), e++) {
      const fog_rbf_emitter *em = &edge_emitters[e];
      const int count = fog_rbf_emitter_count(em);
      const int shift = fog_rbf_emitter_newest(em, t1) - fog_rbf_emitter_newest(em, t0);
      const int shift_m = fog_rbf_emitter_newest(em, tm) - fog_rbf_emitter_newest(em, t0);
      for (int i = 0; i + shift < count; i++)
        worst_step = fmax(worst_step, move_error(&r, &d, em, &before[first + i + shift],
                                                 &after[first + i], dt, &worst_speed));
      for (int i = 0; i + shift_m < count; i++)
        worst_between = fmax(worst_between, move_error(&r, &d, em, &before[first + i + shift_m],
                                                       &between[first + i], 0.4 * dt,
                                                       &worst_speed));
      for (int i = 0; i < count; i++)
        wrapped += after[first + i].centre[0] > 200.0 || after[first + i].centre[2] < -150.0;
    }
    /* the eddies carry puffs off the lines the drift and wind alone would give */
    fog_rbf_emitter drifting = edge_emitters[0];
    drifting.wind[0] += 4.0, drifting.wind[2] -= 2.0;
    fog_rbf_emitter_puffs(&drifting, t1, wind_only, CAP);
    for (int i = 0; i < 60; i++)
      off_lines = fmax(off_lines, hypot(after[i].centre[0] - wind_only[i].centre[0],
                                        after[i].centre[2] - wind_only[i].centre[2]));
  }
  printf("turbulent: a step moves a puff as the reference flow says to %.2e, part of a step "
         "to %.2e (%d puffs past the domain's edge); eddies up to %.2f units/s; puffs up to "
         "%.2f off the drift's lines\n",
         worst_step, worst_between, wrapped, worst_speed, off_lines);
  CHECK(worst_step <= 1e-12, "turbulent: a step's move is off by %.3e", worst_step);
  CHECK(worst_between <= 1e-12, "turbulent: a part step's move is off by %.3e", worst_between);
  CHECK(wrapped > 20, "turbulent: only %d puffs crossed the domain's edge", wrapped);
  CHECK(worst_speed > 1.0, "turbulent: the flow has no eddies (%.3f)", worst_speed);
  CHECK(off_lines > 0.5, "turbulent: the puffs follow the drift alone (%.3f)", off_lines);

  /* Each time as a carrier of its own gives it, asked after a later time (so from the start
   * again) and after an earlier one. */
  const double times[3] = {2.71, 1.0, 2.71};
  bool same = true;
  for (int i = 0; i < 3; i++) {
    rbf_carrier *fresh = rbf_carrier_create(&d, &err);
    const int n = rbf_carrier_puffs(c, times[i], after, CAP, &err);
    const int m = fresh ? rbf_carrier_puffs(fresh, times[i], alone, CAP, &err) : -1;
    CHECK(n == EDGE_PUFFS && m == EDGE_PUFFS, "turbulent: %d and %d puffs at %g", n, m,
          times[i]);
    same = same && memcmp(after, alone, sizeof(fog_rbf) * EDGE_PUFFS) == 0;
    rbf_carrier_destroy(fresh);
  }
  CHECK(same, "turbulent: the puffs at a time depend on the times asked before it");
  CHECK(rbf_carrier_puffs(c, 2.71, after, EDGE_PUFFS - 1, &err) == -1,
        "too little room is refused");
  CHECK(rbf_carrier_puffs(c, -0.5, after, CAP, &err) == -1 && strstr(err.message, "before 0"),
        "a time before 0 is refused saying so: '%s'", err.message);
  CHECK(rbf_carrier_puffs(c, RBF_CARRIER_MAX_TIME + 100, after, CAP, &err) == -1 &&
            strstr(err.message, "expected at most 3600 s"),
        "a time past the replay's bound is refused saying so: '%s'", err.message);
  rbf_carrier_destroy(c);
  /* a carrier stepping on (a window open for hours) goes past the bound; a jump of more
   * than the bound from where it is, or a time that needs a replay from the start past
   * it, is refused (coarse 10 s steps, so that an hour is 360) */
  rbf_carrier_desc coarse = d;
  coarse.step = 10.0;
  /* from the start, a time of exactly the bound: its emitters' lead-in is not counted
   * (a 20 s lifetime here; the first bound refused it) */
  fog_rbf_emitter long_lived = d.emitters[0];
  long_lived.lifetime = 20.0;
  rbf_carrier_desc lead_in = coarse;
  lead_in.emitters = &long_lived, lead_in.emitter_count = 1;
  rbf_carrier *fresh_at_bound = rbf_carrier_create(&lead_in, &err);
  CHECK(fresh_at_bound && rbf_carrier_puffs(fresh_at_bound, RBF_CARRIER_MAX_TIME, after, CAP,
                                            &err) >= 0,
        "a fresh carrier asked for %g s: '%s'", RBF_CARRIER_MAX_TIME, err.message);
  rbf_carrier_destroy(fresh_at_bound);
  rbf_carrier *on = rbf_carrier_create(&coarse, &err);
  CHECK(on != NULL, "coarse carrier: %s", err.message);
  if (on) {
    bool stepped = true;
    for (double t = 600.0; t <= RBF_CARRIER_MAX_TIME + 1200.0 && stepped; t += 600.0)
      stepped = rbf_carrier_puffs(on, t, after, CAP, &err) >= 0;
    CHECK(stepped, "a carrier stepping on past %g s: %s", RBF_CARRIER_MAX_TIME, err.message);
    CHECK(rbf_carrier_puffs(on, 3.0 * RBF_CARRIER_MAX_TIME, after, CAP, &err) == -1 &&
              strstr(err.message, "from the time reached"),
          "a jump past the bound from the time reached: '%s'", err.message);
    CHECK(rbf_carrier_puffs(on, RBF_CARRIER_MAX_TIME + 10.0, after, CAP, &err) == -1 &&
              strstr(err.message, "from its start"),
          "a time behind the one reached, past the bound from the start: '%s'", err.message);
    rbf_carrier_destroy(on);
  }
  fluid_sim_destroy(r.sim);
}

int main(void) {
  check_closed_form("no flow", 0.0, 0.0, 1e-9);
  check_closed_form("uniform drift", 3.0, -1.5, 1e-5);
  check_turbulent_steps();
  fog_error err = {0};
  /* a long narrow domain (1000 x 200: 64 x 14 cells at RBF_CARRIER_GRID) was refused, its
   * shorter side too small for the flow's default eddies; it is given 18 */
  rbf_carrier_desc narrow = desc_with(2, 0, 5);
  narrow.size[0] = 1000, narrow.size[1] = 200, narrow.origin[0] = -500;
  rbf_carrier *c = rbf_carrier_create(&narrow, &err);
  CHECK(c != NULL, "a 1000 x 200 domain: %s", err.message);
  if (c) {
    static fog_rbf puffs[CAP];
    const int n = rbf_carrier_puffs(c, 1.5, puffs, CAP, &err);
    CHECK(n == fog_rbf_emitter_count(&emitter), "narrow: %d puffs: %s", n, err.message);
    rbf_carrier_destroy(c);
  }
  rbf_carrier_desc bad = desc_with(0, 0, 0);
  bad.size[1] = 0.0;
  CHECK(rbf_carrier_create(&bad, &err) == NULL && strstr(err.message, "size"),
        "a domain of no extent is refused naming it: '%s'", err.message);
  return test_finish("test_rbf_carrier");
}
