/* RBF puffs carried by the simulation (app/rbf_carrier.h). */
#include "app/rbf_carrier.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim/sim.h"

/* One live puff's state: its index k, its birth position (kept: the emitter's hash and
 * rejection sampling once a puff, not twice a step) and its displacement from there at the
 * flow's time. */
typedef struct carried_puff {
  long k; /* NO_PUFF: none */
  double start[3], offset[3];
} carried_puff;

#define NO_PUFF LONG_MIN

typedef struct carried_emitter {
  fog_rbf_emitter emitter;
  int count;           /* fog_rbf_emitter_count: the ring's slots (slot_of) */
  carried_puff *ring;
} carried_emitter;

struct rbf_carrier {
  rbf_carrier_desc desc;
  carried_emitter *emitters;
  int emitter_count, puff_count;
  fluid_sim *flow;
  double cell;         /* world units per flow cell */
  int width, height;   /* flow cells */
  double start;        /* t of step 0: minus the longest lifetime */
  long steps;          /* steps taken since the start */
};

double rbf_carrier_time(const rbf_carrier *c) { return c->start + (double)c->steps * c->desc.step; }

bool rbf_carrier_serves(const rbf_carrier *c, const rbf_carrier_desc *d) {
  const rbf_carrier_desc *m = &c->desc;
  if (m->emitter_count != d->emitter_count || m->grid != d->grid || m->step != d->step ||
      m->turbulence != d->turbulence || m->viscosity != d->viscosity || m->seed != d->seed)
    return false;
  for (int a = 0; a < 2; a++)
    if (m->origin[a] != d->origin[a] || m->size[a] != d->size[a] || m->wind[a] != d->wind[a])
      return false;
  /* doubles and a uint64_t: no padding bytes to compare */
  for (int e = 0; e < c->emitter_count; e++)
    if (memcmp(&c->emitters[e].emitter, &d->emitters[e], sizeof d->emitters[e]) != 0) return false;
  return true;
}

/* The flow's velocity at world (x, z): bilinear between the cells' points (cell (i, j) at
 * the integer point, sim/fluid.h), periodic, in world units per second. */
static void flow_velocity(const rbf_carrier *c, double x, double z, double velocity[2]) {
  const double u = (x - c->desc.origin[0]) / c->cell, v = (z - c->desc.origin[1]) / c->cell;
  const double fu = floor(u), fv = floor(v), su = u - fu, sv = v - fv;
  const long w = c->width, h = c->height;
  const long i0 = (((long)fu % w) + w) % w, j0 = (((long)fv % h) + h) % h;
  const long i1 = (i0 + 1) % w, j1 = (j0 + 1) % h;
  const float *grids[2] = {fluid_sim_velocity_x(c->flow), fluid_sim_velocity_z(c->flow)};
  for (int a = 0; a < 2; a++) {
    const float *g = grids[a];
    /* in double: a float difference of the corners would round at 6e-8 of itself */
    const double g00 = g[j0 * w + i0], g10 = g[j0 * w + i1], g01 = g[j1 * w + i0];
    const double g11 = g[j1 * w + i1];
    const double top = g00 + su * (g10 - g00), bottom = g01 + su * (g11 - g01);
    velocity[a] = (top + sv * (bottom - top)) * c->cell;
  }
}

/* A puff's velocity at world point p: the flow's in x and z, plus its emitter's wind. */
static void puff_velocity(const rbf_carrier *c, const fog_rbf_emitter *e, const double p[3],
                          double velocity[3]) {
  double flow[2];
  flow_velocity(c, p[0], p[2], flow);
  velocity[0] = flow[0] + e->wind[0];
  velocity[1] = e->wind[1];
  velocity[2] = flow[1] + e->wind[2];
}

/* Puff k's slot: k % count, k may be negative (puffs born before the flow's start). */
static carried_puff *slot_of(const carried_emitter *ce, long k) {
  return &ce->ring[((k % ce->count) + ce->count) % ce->count];
}

/* The centre of puff k (born at `born`) at time t, the flow at time `now` (<= t): its
 * displacement at now plus its velocity times the time since now (or since its birth, for a
 * puff born after now: then it has no displacement yet). */
static void puff_centre(const rbf_carrier *c, const carried_emitter *ce, long k, double born,
                        double now, double t, double centre[3]) {
  const carried_puff *p = slot_of(ce, k);
  const bool carried = p->k == k;
  double start[3], velocity[3];
  if (carried)
    for (int a = 0; a < 3; a++) start[a] = p->start[a];
  else
    fog_rbf_emitter_start(&ce->emitter, k, start);
  for (int a = 0; a < 3; a++) centre[a] = start[a] + (carried ? p->offset[a] : 0.0);
  puff_velocity(c, &ce->emitter, centre, velocity);
  const double since = t - (carried ? now : fmax(born, now));
  for (int a = 0; a < 3; a++) centre[a] += velocity[a] * since;
}

/* Back to the start: the flow's first state, no puff carried yet. */
static void restart(rbf_carrier *c) {
  fluid_sim_reset(c->flow);
  c->steps = 0;
  for (int e = 0; e < c->emitter_count; e++)
    for (int i = 0; i < c->emitters[e].count; i++) c->emitters[e].ring[i].k = NO_PUFF;
}

/* One step of the puffs (by the flow as it is now) and then of the flow. */
static int step(rbf_carrier *c, fog_error *err) {
  /* both as rbf_carrier_time computes a step's time, the one way every path takes */
  const double now = rbf_carrier_time(c);
  const double next = c->start + (double)(c->steps + 1) * c->desc.step;
  for (int e = 0; e < c->emitter_count; e++) {
    carried_emitter *ce = &c->emitters[e];
    const long newest = fog_rbf_emitter_newest(&ce->emitter, next);
    for (long k = newest - ce->count + 1; k <= newest; k++) {
      double centre[3];
      const double born = fog_rbf_emitter_birth(&ce->emitter, k);
      puff_centre(c, ce, k, born, now, next, centre);
      carried_puff *p = slot_of(ce, k);
      if (p->k != k) fog_rbf_emitter_start(&ce->emitter, k, p->start); /* its first step */
      p->k = k;
      for (int a = 0; a < 3; a++) p->offset[a] = centre[a] - p->start[a];
    }
  }
  fog_error serr = {0};
  if (fluid_sim_step(c->flow, &serr)) {
    restart(c); /* the puffs moved but the flow did not: start again rather than drift */
    return fog_error_wrap(err, &serr, "rbf carrier: ");
  }
  c->steps++;
  return 0;
}

rbf_carrier *rbf_carrier_create(const rbf_carrier_desc *d, fog_error *err) {
  const char *bad = d->emitter_count < 1                  ? "emitter_count"
                    : !(d->size[0] > 0 && d->size[1] > 0) ? "size"
                    : d->grid < 8                         ? "grid"
                    : !(d->step > 0)                      ? "step"
                    : !(d->turbulence >= 0)               ? "turbulence"
                    : !(d->viscosity >= 0)                ? "viscosity"
                                                          : NULL;
  if (bad) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "rbf carrier: bad %s", bad);
    return NULL;
  }
  rbf_carrier *c = calloc(1, sizeof *c);
  if (c && !(c->emitters = calloc((size_t)d->emitter_count, sizeof *c->emitters))) {
    free(c);
    c = NULL;
  }
  if (!c) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "rbf carrier: out of memory");
    return NULL;
  }
  c->desc = *d;
  c->desc.emitters = NULL;
  /* square cells, the longer side `grid` of them; the sim wants even sides, and its
   * default turbulence (eddies a quarter of the shorter side) more than 4 cells: at least
   * 18 (a 1000 x 200 terrain's 64 x 14 was refused; the flow reaches past the terrain) */
  c->cell = fmax(d->size[0], d->size[1]) / d->grid;
  int sides[2];
  for (int a = 0; a < 2; a++) {
    sides[a] = (int)ceil(d->size[a] / c->cell - 1e-9);
    sides[a] = sides[a] < 18 ? 18 : sides[a] + sides[a] % 2;
  }
  c->width = sides[0], c->height = sides[1];
  double longest = 0.0;
  c->emitter_count = d->emitter_count;
  for (int e = 0; e < d->emitter_count; e++) {
    carried_emitter *ce = &c->emitters[e];
    ce->emitter = d->emitters[e];
    ce->count = fog_rbf_emitter_count(&ce->emitter);
    ce->ring = malloc(sizeof *ce->ring * (size_t)ce->count);
    if (!ce->ring) {
      rbf_carrier_destroy(c);
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "rbf carrier: out of memory");
      return NULL;
    }
    c->puff_count += ce->count;
    longest = fmax(longest, ce->emitter.lifetime);
  }
  c->start = -longest;
  /* The flow in cells: the world's speeds over the cell size, viscosity over its square. */
  fog_error serr = {0};
  /* The turbulence's shape is the solver's default (sim/fluid.h): its largest eddies a
   * quarter of the shorter side, Kolmogorov's -5/3 spectrum, and the fluid's fluctuations
   * pulled toward it at 2 per second. */
  fluid_sim_desc flow = fluid_sim_desc_default(c->width, c->height);
  flow.dt = (float)d->step;
  flow.viscosity = (float)(d->viscosity / (c->cell * c->cell));
  flow.wind_drift_x = (float)(d->wind[0] / c->cell);
  flow.wind_drift_z = (float)(d->wind[1] / c->cell);
  flow.turbulence = (float)(d->turbulence / c->cell);
  flow.seed = d->seed;
  c->flow = fluid_sim_create(&flow, &serr);
  if (!c->flow) {
    rbf_carrier_destroy(c);
    fog_error_wrap(err, &serr, "rbf carrier: ");
    return NULL;
  }
  restart(c);
  return c;
}

void rbf_carrier_destroy(rbf_carrier *c) {
  if (!c) return;
  for (int e = 0; e < c->emitter_count; e++) free(c->emitters[e].ring);
  free(c->emitters);
  if (c->flow) fluid_sim_destroy(c->flow);
  free(c);
}

int rbf_carrier_puffs(rbf_carrier *c, double time, fog_rbf *out, int capacity, fog_error *err) {
  if (c->puff_count > capacity || !(time >= 0.0)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "rbf carrier: %s (%d puffs, room for %d, time %g)",
             time >= 0.0 ? "too little room" : "a time before 0", c->puff_count, capacity,
             time);
    return -1;
  }
  /* the last step at or before `time`: one expression for every caller, so whichever way a
   * time is reached it is the same step. What is bounded is the flow replayed to reach it
   * (from the start, or on from the step reached): a window open for hours steps on a frame
   * at a time, but a time asked out of the blue (in ms, say) is refused, not run for hours */
  const double steps_to = (time - c->start) / c->desc.step + 1e-9;
  const bool on = steps_to >= (double)c->steps && c->steps > 0; /* on from the step reached */
  /* the flow beyond time 0 to replay: from the start its lifetime's lead-in is not counted
   * (a time of 3600 s is reached as before) */
  const double replay = on ? (steps_to - (double)c->steps) * c->desc.step : time;
  if (replay > RBF_CARRIER_MAX_TIME) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "time %g s needs %g s of the simulation's flow "
             "beyond time 0 replayed (from %s); expected at most %g s", time, replay,
             on ? "the time reached" : "its start", RBF_CARRIER_MAX_TIME);
    return -1;
  }
  const long target = (long)floor(steps_to);
  if (target < c->steps) restart(c);
  while (c->steps < target)
    if (step(c, err)) return -1;
  const double now = rbf_carrier_time(c);
  int n = 0;
  for (int e = 0; e < c->emitter_count; e++) {
    const carried_emitter *ce = &c->emitters[e];
    const long newest = fog_rbf_emitter_newest(&ce->emitter, time);
    for (long k = newest - ce->count + 1; k <= newest; k++, n++) {
      const double born = fog_rbf_emitter_birth(&ce->emitter, k);
      puff_centre(c, ce, k, born, now, time, out[n].centre);
      fog_rbf_emitter_shape(&ce->emitter, time - born, &out[n]);
    }
  }
  return n;
}
