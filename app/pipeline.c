/* pipeline: sim step → transform (worker thread) → upload → render (GL thread), double
 * buffered. See app/pipeline.h for the contract. */
#define _POSIX_C_SOURCE 200809L
#include "app/pipeline.h"

#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <string.h>
#include <time.h>

#include "app/clock.h"
#include "app/live_rung.h"
#include "app/pipeline_fog.h"
#include "app/render_frame.h"
#include "app/vdb_source.h"
#include "render/fog_pass.h"
#include "render/gl_present.h"
#include "render/gl_util.h"
#include "render/scene.h"
#include "sim/sim.h"
#include "transform/transform.h"

/* The fog pass holds A_0..A_J and D_1..D_J in FOG_PASS_MAX_GRIDS texture slots. */
#define MAX_STROKES 256

/* ---- timings: a ring of the last PIPELINE_TIMING_WINDOW frames, medians on demand ---- */

void pipeline_timings_to_array(const pipeline_timings *t, double v[PIPELINE_TIMING_FIELDS]) {
  const double fields[PIPELINE_TIMING_FIELDS] = {t->sim,   t->transform, t->upload,
                                                 t->render, t->frame,   t->scene,
                                                 t->sim_cpu, t->transform_cpu, t->sun_shadow,
                                                 t->sun_shadow_cpu};
  memcpy(v, fields, sizeof fields);
}

pipeline_timings pipeline_timings_from_array(const double v[PIPELINE_TIMING_FIELDS]) {
  return (pipeline_timings){.sim = v[0], .transform = v[1], .upload = v[2], .render = v[3],
                            .frame = v[4], .scene = v[5], .sim_cpu = v[6],
                            .transform_cpu = v[7], .sun_shadow = v[8],
                            .sun_shadow_cpu = v[9]};
}

typedef struct timing_ring {
  double values[PIPELINE_TIMING_FIELDS][PIPELINE_TIMING_WINDOW];
  int count, next;
} timing_ring;

static void timing_push(timing_ring *ring, const pipeline_timings *t) {
  double v[PIPELINE_TIMING_FIELDS];
  pipeline_timings_to_array(t, v);
  for (int s = 0; s < PIPELINE_TIMING_FIELDS; s++) ring->values[s][ring->next] = v[s];
  ring->next = (ring->next + 1) % PIPELINE_TIMING_WINDOW;
  if (ring->count < PIPELINE_TIMING_WINDOW) ring->count++;
}

static double median_of(const double *values, int n) {
  if (n == 0) return 0.0;
  double sorted[PIPELINE_TIMING_WINDOW];
  memcpy(sorted, values, (size_t)n * sizeof *values);
  return app_median(sorted, n);
}

static double now_ms(void) { return 1e3 * app_clock_seconds(); }

/* CPU time of the calling thread: what a stage costs, whether or not the thread was
 * waiting for a core (in the worker it shares 2 cores with llvmpipe's render threads). */
static double thread_cpu_ms(void) { return 1e3 * app_thread_cpu_seconds(); }
/* ---- slots: the CPU stages' output for one simulation step ---- */

typedef enum slot_state { SLOT_FREE = 0, SLOT_FILLING, SLOT_READY } slot_state;

typedef struct pipeline_slot {
  slot_state state;
  fog_pyramid pyramid; /* grids of this step (shapes follow the plan that filled it) */
  long step;           /* simulation step shown */
  double sim_ms, transform_ms;          /* wall clock */
  double sim_cpu_ms, transform_cpu_ms;  /* thread CPU time */
  /* The fog's shadow at this step (docs/light.md): how T_s is found, and the sun's
   * optical-depth volume where that is _VOLUME, computed for the sun of `applied`. */
  fog_sun_shadow_kind self_shadow;
  fog_sun_shadow sun_shadow;
  bool shadow_fresh; /* computed at this step (else the one on screen stays) */
  float shadow_shape[4]; /* shadow_shape_of the params it was computed with (when fresh) */
  double sun_shadow_ms, sun_shadow_cpu_ms; /* 0 CPU when not fresh */
} pipeline_slot;

/* Live (pipeline_desc.live), the worker refreshes the sun's volume every
 * LIVE_SHADOW_INTERVAL-th step (and at once when the sun or the shadow setting changes):
 * the fog drifts a few cells a second, and a volume per step took a core's 33 ms a frame
 * from llvmpipe (live fps 18 -> 9 on the default scene). Recordings compute it every step. */
#define LIVE_SHADOW_INTERVAL 4

/* What the worker owns: the simulation, the transform plan and its scratch arrays. */
typedef struct cpu_stages {
  /* the last sun volume computed: its step, sun, fog shape and kind (LIVE_SHADOW_INTERVAL) */
  long shadow_step;
  double shadow_sun[3];
  float shadow_shape[4];
  bool shadow_on;
  fog_sun_shadow_kind shadow_kind;
  fluid_sim *sim;
  fogmap base;  /* initial density and relaxation target */
  fluid_emitter emitters[4];
  int emitter_count;
  transform_plan *plan;
  int degree, levels; /* of the plan */
  float *coefficients;
  float *approx[FOG_MAX_LEVELS + 1];
  float *detail[FOG_MAX_LEVELS + 1];
  long steps; /* simulation steps taken */
  /* [fog] vdb: the sequence is played instead of simulated (sim stays NULL); frame n
   * shows the fogmap at time (n - 1)·frame_seconds (app/vdb_source.h). */
  bool has_vdb;
  vdb_source vdb;
  fogmap vdb_map;
  /* [fog] sequence (a bake): frame n shows the sequence's file n, nothing is simulated;
   * past the last file (sequence_count, counted at creation) the last one stays, as a VDB
   * sequence holds its last frame (and the worker may run a frame ahead). */
  bool has_sequence;
  long sequence_count;
  /* sim cells per fogmap cell: 1, or k (1/k) for a map simulated k times finer (coarser) */
  double finer;
  fogmap sequence_map;
} cpu_stages;

/* What the GL thread asked for since the last step, copied under the lock by the
 * thread that runs the CPU stages. */
typedef struct worker_requests {
  pipeline_params params;
  bool params_changed, reset;
  fluid_stroke strokes[MAX_STROKES];
  int stroke_count;
} worker_requests;

struct pipeline {
  scene_config config;
  int width, height;
  double frame_seconds;
  int steps_per_frame;
  bool synchronous;
  bool time_passes;
  bool live;

  /* Shared between the threads, under lock. */
  pthread_mutex_t lock;
  pthread_cond_t changed;
  pthread_t worker;
  bool worker_running, quit;
  pipeline_slot slots[2];
  int fill_index, take_index;
  pipeline_params params;   /* the newest, as set by the GL thread */
  unsigned params_version;  /* bumped on every set */
  fluid_stroke strokes[MAX_STROKES];
  int stroke_count;
  bool reset_requested;
  int step_requests;
  fog_error worker_error; /* the worker's failure: code FOG_SUCCESS while it has none */

  bool stepped_once;        /* the CPU stages produced a step (the first frame needs one) */

  /* Owned by the thread running the CPU stages. */
  cpu_stages cpu;
  worker_requests requests;
  unsigned applied_version;
  pipeline_params applied;

  /* GL thread. */
  scene_geometry geometry;
  bool geometry_made;
  scene_pass *scene;
  gl_target scene_target;
  /* The scene target holds the scene (colour, distance) seen from scene_camera: the
   * terrain and objects do not move, so the scene pass re-runs only when the camera or
   * the size changes; the fog, which changes every frame, is drawn over it each frame. */
  camera scene_camera;
  bool scene_current;
  pipeline_fog *fog;
  long shown_step;
  /* Lamps that move or flicker (scene_config_lamps_animated): set for the shown step's time
   * (shown_lamps_time; NAN before the first frame), on the surfaces and in the fog. Else the
   * params' lamps (the demo places them), shown_lamps what the surfaces have now. */
  bool lamps_animated;
  /* Live: the last frame's fog was drawn without the lamps' light, which the renderer's
   * loop cap refused (docs/platform.md); recordings fail instead. */
  bool lamps_dropped;
  fog_lamps shown_lamps;
  double shown_lamps_time;
  timing_ring timings;
  pipeline_timings last;
  double last_frame_start;
  bool have_frame;
  camera last_camera;
  /* The fog's shadow on screen: its kind, and a copy of the approximations it was computed
   * from (A_0 .. A_J: the volume walks the coarsest fine enough, fog_sun_shadow_compute), so
   * that a sun moved while the worker has no new step (paused) re-lights the fog here
   * (shadow_volume, shadow_grids) as the worker would. */
  fog_sun_shadow_kind shown_self_shadow;
  int levels_most; /* the most levels the fogmap's size allows (and FOG_MAX_LEVELS) */
  double shown_shadow_sun[3];
  float shown_shadow_shape[4]; /* shadow_shape_of the params the volume shown was made with */
  transform_grid shadow_grids[FOG_MAX_LEVELS + 1];
  int shadow_levels; /* J of shadow_grids: shadow_grids[shadow_levels] is the finest */
  fog_sun_shadow shadow_volume;
  /* The demo's live rung (params.live_rung, app/live_rung.h): fitted to the finest grid of
   * the shown step (shadow_grids[shadow_levels]) when the kind changes and at every step (the bounded
   * rungs every LIVE_RUNG_REFIT steps: show_live_rung), measured every
   * LIVE_RUNG_INTERVAL frames on the view's surface distances (rung_depth). */
  live_rung rung;
  long rung_step;
  float rung_shape[4]; /* shadow_shape_of the params the rung was fitted with */
  int rung_frames;
  float *rung_depth;
  /* A bounded rung's own sun-shadow volume (LIVE_RUNG_GAUSSIANS, _ELLIPSOIDS), for the sun
   * rung_shadow_sun; rung_shadow_shown while the fog pass holds it rather than the fogmap's. */
  fog_sun_shadow rung_shadow;
  double rung_shadow_sun[3];
  bool rung_shadow_valid; /* rung_shadow holds the fitted rung's volume for rung_shadow_sun */
  bool rung_shadow_shown;
};

#define LIVE_RUNG_INTERVAL 8

/* ---- the CPU stages (run by the worker, or inline when synchronous) ---- */

/* The smallest side the simulation takes a fogmap at: even, and large enough for the
 * solver's default turbulence scale (a quarter of the shorter side, > 4 cells). */
#define MIN_SIM_SIDE 32
/* The largest: the FFT solver's grids beyond it are too slow to be live. */
#define MAX_SIM_SIDE 2048

/* The map bilinear between its cells' centres (clamped at its edges) at (u, v) in cells. */
static double bilinear_at(const fogmap *m, double u, double v) {
  u = fmin(fmax(u, 0.0), m->width - 1.0), v = fmin(fmax(v, 0.0), m->height - 1.0);
  const int x0 = (int)u, z0 = (int)v;
  const int x1 = x0 + 1 < m->width ? x0 + 1 : x0, z1 = z0 + 1 < m->height ? z0 + 1 : z0;
  const double fu = u - x0, fv = v - z0;
  const float *d = m->density;
  const size_t w = (size_t)m->width;
  return (1 - fv) * ((1 - fu) * d[z0 * w + x0] + fu * d[z0 * w + x1]) +
         fv * ((1 - fu) * d[z1 * w + x0] + fu * d[z1 * w + x1]);
}

/* A fogmap the solver cannot take at its own size, on a grid it can, covering the same
 * world: k times finer (odd sides or sides under MIN_SIM_SIDE; the map bilinear at the
 * finer cells' centres, close to what its B-spline draws), as it is with an odd side padded
 * by a row or column of no fog (where k times finer would pass MAX_SIM_SIDE), or k times
 * coarser (the mean of k x k cells, past MAX_SIM_SIDE, padded likewise). cell_size is
 * divided or multiplied by k and *finer receives the sim cells per map cell (k, 1, 1/k).
 * A map that no such grid holds (4100 x 40: 14 cells across once coarse) is refused.
 * (Resampled to a fixed 256^2 at the same cell size, a 9 x 9 map drew 28x too large.) */
static int fit_to_solver(const fogmap *loaded, double *cell_size, double *finer, fogmap *base,
                         fog_error *err) {
  const int w = loaded->width, h = loaded->height, larger = w > h ? w : h;
  int up = 1, down = 1;
  if (larger > MAX_SIM_SIDE) {
    down = (larger + MAX_SIM_SIDE - 1) / MAX_SIM_SIDE;
  } else {
    while ((w * up) % 2 || (h * up) % 2 || w * up < MIN_SIM_SIDE || h * up < MIN_SIM_SIDE) up++;
    if (larger * up > MAX_SIM_SIDE) up = 1; /* padded instead */
  }
  int nw = up * ((w + down - 1) / down), nh = up * ((h + down - 1) / down);
  nw += nw % 2, nh += nh % 2;
  if (nw < MIN_SIM_SIDE || nh < MIN_SIM_SIDE || nw > MAX_SIM_SIDE || nh > MAX_SIM_SIDE)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "a %dx%d map cannot be simulated: no grid of %d to %d square cells a side "
                    "covers it (render and view draw it as it is)", w, h, MIN_SIM_SIDE,
                    MAX_SIM_SIDE);
  fog_error serr = {0};
  if (fogmap_create(base, nw, nh, &serr)) return fog_error_pass(err, &serr);
  for (int z = 0; z < nh; z++)
    for (int x = 0; x < nw; x++) {
      if (up > 1) {
        base->density[(size_t)z * nw + x] =
            (float)bilinear_at(loaded, (x + 0.5) / up - 0.5, (z + 0.5) / up - 0.5);
        continue;
      }
      double sum = 0.0; /* down x down cells, those past the map's edge no fog */
      for (int dz = 0; dz < down; dz++)
        for (int dx = 0; dx < down; dx++) {
          const int sx = x * down + dx, sz = z * down + dz;
          if (sx < w && sz < h) sum += loaded->density[(size_t)sz * w + sx];
        }
      base->density[(size_t)z * nw + x] = (float)(sum / ((double)down * down));
    }
  *cell_size = *cell_size / up * down;
  *finer = (double)up / down;
  return 0;
}

/* The base density the simulation starts from and relaxes toward: the config's fogmap
 * when it has one (its own size when the FFT solver accepts it; otherwise fit_to_solver,
 * which also sets the pipeline's cell size), else clear air on a 256 x 256 grid: a config
 * without fog has none, as `render` draws it, until emitters or the brush make some. */
static int make_base(scene_config *cfg, fogmap *base, double *finer, fog_error *err) {
  *finer = 1.0;
  fog_error serr = {0};
  if (cfg->fog.fogmap[0]) {
    fogmap loaded = {0};
    fogmap_load_desc desc = {.channel = cfg->fog.channel[0] ? cfg->fog.channel : NULL,
                             .channel_setting = "[fog] channel"};
    if (fogmap_load(cfg->fog.fogmap, &desc, &loaded, &serr))
      return fog_error_wrap(err, &serr, "%.200s:%d: [fog] fogmap: ", cfg->path,
                            cfg->fog.fogmap_line);
    bool usable = loaded.width % 2 == 0 && loaded.height % 2 == 0 &&
                  loaded.width >= MIN_SIM_SIDE && loaded.height >= MIN_SIM_SIDE &&
                  loaded.width <= MAX_SIM_SIDE && loaded.height <= MAX_SIM_SIDE;
    if (usable) {
      *base = loaded;
      return 0;
    }
    int status = fit_to_solver(&loaded, &cfg->box.cell_size, finer, base, &serr);
    fogmap_destroy(&loaded);
    return status ? fog_error_wrap(err, &serr, "%.200s:%d: [fog] fogmap: ", cfg->path,
                                   cfg->fog.fogmap_line)
                  : 0;
  }
  const int n = SCENE_CLEAR_AIR_CELLS;
  if (fogmap_create(base, n, n, &serr)) return fog_error_pass(err, &serr); /* zeros */
  return 0;
}

/* The solver's desc for the live parameters (base: the density it starts from and relaxes
 * toward, NULL when only changing parameters). */
static fluid_sim_desc sim_desc(pipeline *p, const pipeline_params *params, const fogmap *start) {
  cpu_stages *c = &p->cpu;
  const double cell = p->config.box.cell_size > 0 ? p->config.box.cell_size : 1.0;
  for (int e = 0; e < c->emitter_count; e++) c->emitters[e].rate = params->emitter_rate;
  /* The turbulence's shape (largest eddies, slope, coupling) is the solver's default. */
  fluid_sim_desc d = fluid_sim_desc_default(c->base.width, c->base.height);
  d.dt = (float)(p->frame_seconds / p->steps_per_frame);
  /* the config's viscosity is in map cells^2 a second; a map simulated k times finer has
   * k^2 times as many sim cells^2 */
  d.viscosity = (float)(params->viscosity * c->finer * c->finer);
  /* The config's wind is in world units per second; the sim's in cells per second. */
  d.wind_drift_x = (float)(params->wind[0] / cell);
  d.wind_drift_z = (float)(params->wind[1] / cell);
  d.turbulence = (float)(params->turbulence / cell);
  d.seed = scene_config_sim_seed(&p->config);
  d.emitters = c->emitters;
  d.emitter_count = c->emitter_count;
  d.relaxation = 0.05f;
  d.dissipation = 0.02f;
  d.base = start;
  return d;
}

static int sim_create(pipeline *p, const pipeline_params *params, const fogmap *start,
                      fog_error *err) {
  cpu_stages *c = &p->cpu;
  if (c->has_vdb || c->has_sequence) return 0; /* a sequence is played, not simulated */
  fluid_sim_desc desc = sim_desc(p, params, start);
  fog_error serr = {0};
  fluid_sim *sim = fluid_sim_create(&desc, &serr);
  if (!sim) return fog_error_wrap(err, &serr, "simulation: ");
  if (c->sim) fluid_sim_destroy(c->sim);
  c->sim = sim;
  return 0;
}

static void plan_destroy(cpu_stages *c) {
  transform_plan_destroy(c->plan);
  c->plan = NULL;
  free(c->coefficients);
  c->coefficients = NULL;
  for (int l = 0; l <= FOG_MAX_LEVELS; l++) {
    free(c->approx[l]);
    free(c->detail[l]);
    c->approx[l] = c->detail[l] = NULL;
  }
}

static transform_boundary boundary_of(const pipeline *p) {
  return p->config.fog.boundary == SCENE_BOUNDARY_PERIODIC ? TRANSFORM_PERIODIC
                                                           : TRANSFORM_SYMMETRIC;
}

/* The levels the fogmap's size allows (and the renderer's cap), for `levels` asked. */
static int levels_allowed(const pipeline *p, int levels) {
  const int most = transform_max_levels(p->cpu.base.width, p->cpu.base.height, boundary_of(p));
  if (levels > most) levels = most;
  if (levels > FOG_MAX_LEVELS) levels = FOG_MAX_LEVELS;
  return levels < 0 ? 0 : levels;
}

static int plan_create(pipeline *p, int degree, int levels, fog_error *err) {
  cpu_stages *c = &p->cpu;
  plan_destroy(c);
  const int w = c->base.width, h = c->base.height;
  const transform_boundary boundary = boundary_of(p);
  levels = levels_allowed(p, levels);
  fog_error terr = {0};
  transform_desc desc = {.width = w, .height = h, .levels = levels,
                         .basis = transform_basis_of_degree(degree), .boundary = boundary};
  if (!(c->plan = transform_plan_create(&desc, &terr)))
    return fog_error_wrap(err, &terr, "transform: ");
  c->coefficients = transform_alloc_floats((size_t)w * h);
  bool ok = c->coefficients != NULL;
  for (int l = 0; l <= levels && ok; l++) {
    int w = 0, h = 0;
    transform_level_size(c->plan, l, &w, &h);
    c->approx[l] = transform_alloc_floats((size_t)w * h);
    c->detail[l] = transform_alloc_floats((size_t)w * h);
    ok = c->approx[l] && c->detail[l];
  }
  if (!ok) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the transform");
  c->degree = degree;
  c->levels = levels;
  return 0;
}

/* Makes the slot's grids match the plan (allocates only when the plan changed). */
static int slot_shape(pipeline *p, pipeline_slot *slot, fog_error *err) {
  cpu_stages *c = &p->cpu;
  fog_pyramid *py = &slot->pyramid;
  bool same = py->levels == c->levels && py->degree == c->degree && py->approx[0].coefficients;
  if (same) return 0;
  fog_pyramid_destroy(py);
  py->levels = c->levels;
  py->degree = c->degree;
  fog_error terr = {0};
  for (int l = 0; l <= c->levels; l++) {
    int w = 0, h = 0;
    transform_grid_size(c->plan, l, &w, &h);
    if (transform_grid_create(&py->approx[l], w, h, &terr) ||
        transform_grid_create(&py->detail[l], w, h, &terr))
      return fog_error_wrap(err, &terr, "transform: ");
  }
  return 0;
}

static void take_requests(pipeline *p, worker_requests *r) {
  r->params = p->params;
  r->params_changed = p->params_version != p->applied_version;
  p->applied_version = p->params_version;
  r->reset = p->reset_requested;
  p->reset_requested = false;
  r->stroke_count = p->stroke_count;
  memcpy(r->strokes, p->strokes, (size_t)p->stroke_count * sizeof *r->strokes);
  p->stroke_count = 0;
}

static bool sim_params_differ(const pipeline_params *a, const pipeline_params *b) {
  return a->wind[0] != b->wind[0] || a->wind[1] != b->wind[1] ||
         a->turbulence != b->turbulence || a->viscosity != b->viscosity ||
         a->emitter_rate != b->emitter_rate;
}

/* One simulation step (several sim sub-steps when the frame is longer than the sim's
 * dt) and the transform of its density into the slot's grids. */
/* Frame n of the config's [fog] sequence into *map (replacing what it held); it must have
 * the size of frame 1. */
static int load_sequence_frame(pipeline *p, long n, fogmap *map, fog_error *err) {
  const scene_config *cfg = &p->config;
  char path[SCENE_CONFIG_PATH_MAX + 32];
  if (!scene_config_sequence_path(cfg->fog.sequence, n, path, sizeof path))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s:%d: [fog] sequence: no path for frame %ld",
                    cfg->path, cfg->fog.sequence_line, n);
  fogmap loaded = {0};
  fog_error serr = {0};
  /* the config's channel, as render reads the sequence's first frame */
  const fogmap_load_desc desc = {.channel = cfg->fog.channel[0] ? cfg->fog.channel : NULL,
                                 .channel_setting = "[fog] channel"};
  if (fogmap_load(path, &desc, &loaded, &serr))
    return fog_error_wrap(err, &serr, "%s:%d: [fog] sequence: frame %ld: ", cfg->path,
                          cfg->fog.sequence_line, n);
  const fogmap *first = &p->cpu.base;
  if (first->density && (loaded.width != first->width || loaded.height != first->height)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "%s:%d: [fog] sequence: frame %ld (%s) is %dx%d, frame 1 %dx%d: expected every "
             "frame the size of frame 1", cfg->path, cfg->fog.sequence_line, n, path,
             loaded.width, loaded.height, first->width, first->height);
    fogmap_destroy(&loaded); /* after the message, which names its size */
    return 1;
  }
  fogmap_destroy(map);
  *map = loaded;
  return 0;
}

static fog_volume volume_of(const pipeline *p, const pipeline_params *params);

/* The unit direction towards the sun of params' angles (the panel may have moved them). */
static void sun_direction_of(const pipeline *p, const pipeline_params *params, double dir[3]) {
  scene_light light = p->config.light;
  light.sun_azimuth = params->sun_azimuth;
  light.sun_elevation = params->sun_elevation;
  scene_light_sun_direction(&light, dir);
}

/* What the fog's sun-shadow volume depends on besides the sun and the fog's grid: the
 * density and the vertical profile (volume_of). A volume is remade when any of them
 * changed, not only the sun: a density typed in while paused kept the old volume, and the
 * fog lost its self-shadow. */
static void shadow_shape_of(const pipeline_params *params, float shape[4]) {
  shape[0] = params->density, shape[1] = (float)params->profile_kind;
  shape[2] = params->fog_height, shape[3] = params->scale_height;
}

/* The fog's shadow of a step (docs/light.md) for the unit direction sun (of params'
 * angles): only with albedo > 0 and [light] fog_self_shadow on; the volume is computed from
 * the step's approximations approx[0 .. levels], walking the coarsest fine enough for its
 * columns as `render` does (threads: the worker's one, or both cores when the GL thread
 * waits). */
static int compute_shadow(const pipeline *p, const pipeline_params *params,
                          const transform_grid *approx, int levels, const double sun[3],
                          int threads, fog_sun_shadow_kind *kind, fog_sun_shadow *volume,
                          fog_error *err) {
  *kind = FOG_SUN_SHADOW_NONE;
  if (!(params->sun.albedo > 0) || !params->fog_self_shadow) return 0;
  fog_volume v = volume_of(p, params);
  fog_lod lod = {.levels = levels, .approx = approx, .mu = 1.0};
  fog_model m = {.kind = FOG_MODEL_FOGMAP, .volume = &v, .lod = &lod};
  *kind = fog_sun_shadow_kind_of(&m, sun);
  if (*kind != FOG_SUN_SHADOW_VOLUME) return 0;
  fog_error rerr = {0};
  const int n = p->config.shadow.resolution;
  if (!volume->optical_depth &&
      fog_sun_shadow_create(volume, &(fog_sun_shadow_desc){.across = n, .along = n}, &rerr))
    return fog_error_wrap(err, &rerr, "sun shadow: ");
  if (fog_sun_shadow_compute(volume, &m, sun, threads, &rerr))
    return fog_error_wrap(err, &rerr, "sun shadow: ");
  return 0;
}

static int cpu_stages_run(pipeline *p, const worker_requests *r, pipeline_slot *slot,
                          fog_error *err) {
  cpu_stages *c = &p->cpu;
  if (r->params_changed) {
    if (r->params.degree != c->degree || r->params.levels != c->levels) {
      if (plan_create(p, r->params.degree, r->params.levels, err)) return 1;
    }
    /* A changed wind, turbulence, viscosity or emitter rate is set in place: the density
     * and the flow carry on (no reallocation, no FFTW replanning). */
    if (c->sim && sim_params_differ(&r->params, &p->applied)) {
      fluid_sim_desc desc = sim_desc(p, &r->params, NULL);
      fog_error serr = {0};
      if (fluid_sim_set_params(c->sim, &desc, &serr))
        return fog_error_wrap(err, &serr, "simulation: ");
    }
    p->applied = r->params;
  }
  if (r->reset) {
    if (sim_create(p, &p->applied, &c->base, err)) return 1;
    c->steps = 0;
    c->shadow_step = 0; /* new fog: a new sun volume with the next step */
  }
  fog_error serr = {0};
  for (int s = 0; s < r->stroke_count && c->sim; s++)
    fluid_sim_paint(c->sim, &r->strokes[s], &serr); /* bad strokes are dropped */

  double t0 = now_ms(), c0 = thread_cpu_ms();
  /* Frame n shows the fog after n - 1 frames of simulation, at time (n - 1)/fps as the
   * lamps' and a VDB sequence's clocks: the first frame is the base itself. (It was one
   * frame in, ahead of moving lamps; docs/farm.md.) */
  for (int s = 0; c->steps > 0 && s < p->steps_per_frame && c->sim; s++)
    if (fluid_sim_step(c->sim, &serr)) return fog_error_wrap(err, &serr, "simulation: ");
  c->steps++;
  if (c->has_vdb &&
      vdb_source_fogmap_at(&c->vdb, (double)(c->steps - 1) * p->frame_seconds, &c->vdb_map,
                           &serr))
    return fog_error_wrap(err, &serr, "vdb: ");
  double t1 = now_ms(), c1 = thread_cpu_ms();
  if (slot_shape(p, slot, err)) return 1;
  if (c->has_sequence && (c->steps <= c->sequence_count || !c->sequence_map.density) &&
      load_sequence_frame(p, c->steps < c->sequence_count ? c->steps : c->sequence_count,
                          &c->sequence_map, err))
    return 1;
  const fogmap *density = c->has_vdb        ? &c->vdb_map
                          : c->has_sequence ? &c->sequence_map
                                            : fluid_sim_density(c->sim);
  transform_forward(c->plan, density->density, c->coefficients);
  /* non-negative levels, the density itself as A_J (transform_density_pyramid) */
  if (transform_density_pyramid(
          c->plan, density->density, c->coefficients, c->approx,
          p->applied.lod_method == FOG_LOD_SUM_OF_DETAILS ? c->detail : NULL, err))
    return 1;
  fog_error terr = {0};
  for (int l = 0; l <= c->levels; l++) {
    if (transform_grid_export(c->plan, l, c->approx[l], &slot->pyramid.approx[l], &terr))
      return fog_error_wrap(err, &terr, "transform: ");
    if (l > 0 && p->applied.lod_method == FOG_LOD_SUM_OF_DETAILS &&
        transform_grid_export(c->plan, l, c->detail[l], &slot->pyramid.detail[l], &terr))
      return fog_error_wrap(err, &terr, "transform: ");
  }
  slot->pyramid.has_details = p->applied.lod_method == FOG_LOD_SUM_OF_DETAILS;
  double t2 = now_ms(), c2 = thread_cpu_ms();
  double sun[3];
  sun_direction_of(p, &p->applied, sun);
  const bool on = p->applied.sun.albedo > 0 && p->applied.fog_self_shadow;
  float shape[4];
  shadow_shape_of(&p->applied, shape);
  slot->shadow_fresh = !p->live || c->shadow_step == 0 || on != c->shadow_on ||
                       memcmp(sun, c->shadow_sun, sizeof sun) ||
                       memcmp(shape, c->shadow_shape, sizeof shape) ||
                       c->steps - c->shadow_step >= LIVE_SHADOW_INTERVAL;
  if (slot->shadow_fresh) {
    if (compute_shadow(p, &p->applied, slot->pyramid.approx, slot->pyramid.levels, sun,
                       p->synchronous ? 2 : 1, &slot->self_shadow, &slot->sun_shadow, err))
      return 1;
    c->shadow_step = c->steps, c->shadow_on = on, c->shadow_kind = slot->self_shadow;
    memcpy(c->shadow_sun, sun, sizeof sun);
    memcpy(c->shadow_shape, shape, sizeof shape);
    memcpy(slot->shadow_shape, shape, sizeof shape);
  } else {
    slot->self_shadow = c->shadow_kind;
  }
  slot->sun_shadow_ms = now_ms() - t2;
  slot->sun_shadow_cpu_ms = slot->shadow_fresh ? thread_cpu_ms() - c2 : 0.0;
  slot->step = c->steps;
  slot->sim_ms = t1 - t0;
  slot->transform_ms = t2 - t1;
  slot->sim_cpu_ms = c1 - c0;
  slot->transform_cpu_ms = c2 - c1;
  return 0;
}

static void *worker_main(void *arg) {
  pipeline *p = arg;
  worker_requests *r = &p->requests;
  pthread_mutex_lock(&p->lock);
  while (!p->quit) {
    pipeline_slot *slot = &p->slots[p->fill_index];
    bool may_step = !p->params.paused || p->step_requests > 0 || p->reset_requested ||
                    !p->stepped_once;
    if (slot->state != SLOT_FREE || !may_step || p->worker_error.code) {
      pthread_cond_wait(&p->changed, &p->lock);
      continue;
    }
    if (p->params.paused && p->step_requests > 0) p->step_requests--;
    take_requests(p, r);
    slot->state = SLOT_FILLING;
    pthread_mutex_unlock(&p->lock);

    fog_error err = {0};
    int status = cpu_stages_run(p, r, slot, &err);

    pthread_mutex_lock(&p->lock);
    if (status) {
      p->worker_error = err;
      if (!p->worker_error.code) p->worker_error.code = FOG_ERR_INVALID_ARGUMENT;
      slot->state = SLOT_FREE;
    } else {
      slot->state = SLOT_READY;
      p->fill_index ^= 1;
      p->stepped_once = true;
    }
    pthread_cond_broadcast(&p->changed);
  }
  pthread_mutex_unlock(&p->lock);
  return NULL;
}

/* ---- create / destroy ---- */

static pipeline_params params_from_config(const scene_config *cfg) {
  const scene_light light = cfg->light;
  return (pipeline_params){
      .degree = cfg->fog.degree,
      .levels = cfg->fog.levels,
      .mu = (float)cfg->fog.mu,
      .lod_method = cfg->fog.lod == SCENE_LOD_SUM ? FOG_LOD_SUM_OF_DETAILS : FOG_LOD_SWITCH,
      .density = (float)cfg->fog.density_scale,
      .fog_colour = {cfg->fog.colour[0], cfg->fog.colour[1], cfg->fog.colour[2]},
      .sun = scene_config_fog_sun(cfg),
      .sun_azimuth = (float)light.sun_azimuth,
      .sun_elevation = (float)light.sun_elevation,
      .fog_self_shadow = cfg->shadow.fog_self_shadow != 0,
      .shafts = cfg->shadow.shafts != 0,
      .lamps = scene_config_fog_lamps(cfg),
      .profile_kind = (int)cfg->fog.profile, /* scene_profile numbers fog_profile_kind */
      .fog_height = (float)cfg->fog.fog_height,
      .scale_height = (float)cfg->fog.scale_height,
      .wind = {(float)cfg->sim.wind[0], (float)cfg->sim.wind[1]},
      .turbulence = (float)cfg->sim.turbulence,
      .viscosity = (float)cfg->sim.viscosity,
      .emitter_rate = (float)cfg->sim.emitter_rate,
  };
}

static int load_scene(pipeline *p, fog_error *err) {
  const scene_config *cfg = &p->config;
  if (render_scene_geometry_create(&p->geometry, cfg, err)) return 1;
  p->geometry_made = true;
  fog_error rerr = {0};
  p->scene = scene_pass_create(&p->geometry, &rerr);
  /* Terrain LOD in the live demo only: recordings draw the full mesh (their depth is the
   * exact first hit, as render's). */
  if (!p->scene ||
      scene_pass_set_terrain_lod(p->scene, p->live ? p->config.terrain.lod_error : 0.0, &rerr) ||
      scene_pass_set_lamp_shadows(p->scene, scene_config_lamp_shadow_size(&p->config), &rerr))
    return fog_error_wrap(err, &rerr, "scene pass: ");
  p->shown_lamps = scene_config_fog_lamps(&p->config);
  if (scene_pass_set_lamps(p->scene, &p->shown_lamps, &rerr))
    return fog_error_wrap(err, &rerr, "scene pass: ");
  p->lamps_animated = scene_config_lamps_animated(&p->config);
  p->shown_lamps_time = NAN;
  return 0;
}

pipeline *pipeline_create(const pipeline_desc *desc, fog_error *err) {
  pipeline *p = calloc(1, sizeof *p);
  if (!p) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    return NULL;
  }
  p->config = *desc->config;
  if (p->config.fog.model != FOG_MODEL_FOGMAP) {
    /* The other models have nothing to simulate: render and view draw them, and record
     * through a render session (cmd_record.c), a volume stepping through its frames. */
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "%s:%d: [fog] model = %s: the live pipeline simulates or plays a fogmap; "
             "expected model = fogmap here (fogpipe record, render and view draw the other "
             "models)",
             p->config.path, p->config.fog.model_line, fog_model_table[p->config.fog.model].name);
    free(p);
    return NULL;
  }
  p->width = desc->width > 0 ? desc->width : p->config.width;
  p->height = desc->height > 0 ? desc->height : p->config.height;
  p->frame_seconds = desc->frame_seconds;
  if (!(p->frame_seconds > 0 && p->frame_seconds <= PIPELINE_MAX_FRAME_SECONDS)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "a frame of %g s of simulated time: expected more than 0 and at most %g s (240 "
             "steps of 1/24 s)", p->frame_seconds, PIPELINE_MAX_FRAME_SECONDS);
    free(p);
    return NULL;
  }
  /* Keep the sim's step at most 1/24 s so fast frame rates and slow ones see the same
   * physics per second (semi-Lagrangian advection is stable at any step, but accuracy
   * is not). */
  p->steps_per_frame = (int)ceil(p->frame_seconds * 24.0 - 1e-9);
  if (p->steps_per_frame < 1) p->steps_per_frame = 1;
  p->synchronous = desc->synchronous;
  p->time_passes = desc->time_passes;
  p->live = desc->live;
  p->params = params_from_config(&p->config);
  p->applied = p->params;
  pthread_mutex_init(&p->lock, NULL);
  pthread_cond_init(&p->changed, NULL);

  cpu_stages *c = &p->cpu;
  c->finer = 1.0; /* the config's cells, unless make_base simulates the map finer */
  if (p->config.fog.sequence[0]) {
    /* A bake: frame 1 gives the grid's size, the files are read as the frames come. */
    c->has_sequence = true;
    if (load_sequence_frame(p, 1, &c->base, err)) {
      pipeline_destroy(p);
      return NULL;
    }
    char path[SCENE_CONFIG_PATH_MAX + 32];
    struct stat st;
    while (scene_config_sequence_path(p->config.fog.sequence, c->sequence_count + 1, path,
                                      sizeof path) &&
           stat(path, &st) == 0)
      c->sequence_count++;
  } else if (p->config.fog.vdb[0]) {
    /* The sequence places the fog and gives its profile (vdb_source_apply_config) before
     * the params are taken from the config. */
    fog_error cerr;
    if (vdb_source_open_config(&c->vdb, &p->config, &cerr)) {
      fog_error_pass(err, &cerr);
      pipeline_destroy(p);
      return NULL;
    }
    c->has_vdb = true;
    if (vdb_source_apply_config(&c->vdb, &p->config, err)) {
      pipeline_destroy(p);
      return NULL;
    }
    p->params = params_from_config(&p->config);
    p->applied = p->params;
    fog_error serr = {0};
    if (vdb_source_fogmap_at(&c->vdb, 0.0, &c->base, &serr)) {
      fog_error_wrap(err, &serr, "vdb: ");
      pipeline_destroy(p);
      return NULL;
    }
  } else if (make_base(&p->config, &c->base, &c->finer, err)) {
    pipeline_destroy(p);
    return NULL;
  }
  /* Three emitters spread over the map, upwind of its centre: the fog has sources to
   * blow away from. Positions in cells, x across the width and z across the height (on a
   * 256 x 32 map they sat in its first 64 columns, placed by the shorter side); radii from
   * the map's mean side; rates from the config. */
  const float w = (float)c->base.width, h = (float)c->base.height, n = sqrtf(w * h);
  c->emitter_count = 3;
  c->emitters[0] = (fluid_emitter){.x = 0.30f * w, .z = 0.35f * h, .radius = 0.03f * n};
  c->emitters[1] = (fluid_emitter){.x = 0.55f * w, .z = 0.70f * h, .radius = 0.04f * n};
  c->emitters[2] = (fluid_emitter){.x = 0.75f * w, .z = 0.30f * h, .radius = 0.025f * n};
  if (sim_create(p, &p->params, &c->base, err) ||
      plan_create(p, p->params.degree, p->params.levels, err)) {
    pipeline_destroy(p);
    return NULL;
  }
  p->params.levels = c->levels; /* clamped to what the grid allows */
  p->levels_most = levels_allowed(p, FOG_MAX_LEVELS); /* set once: read under the lock */
  p->applied = p->params;
  fog_error rerr = {0};
  p->fog = pipeline_fog_create(&rerr);
  if (!p->fog) {
    fog_error_wrap(err, &rerr, "fog pass: ");
    pipeline_destroy(p);
    return NULL;
  }
  if (load_scene(p, err) || pipeline_resize(p, p->width, p->height, err)) {
    pipeline_destroy(p);
    return NULL;
  }
  return p;
}

void pipeline_destroy(pipeline *p) {
  if (!p) return;
  if (p->worker_running) {
    pthread_mutex_lock(&p->lock);
    p->quit = true;
    pthread_cond_broadcast(&p->changed);
    pthread_mutex_unlock(&p->lock);
    pthread_join(p->worker, NULL);
  }
  for (int s = 0; s < 2; s++) fog_pyramid_destroy(&p->slots[s].pyramid);
  for (int s = 0; s < 2; s++) fog_sun_shadow_destroy(&p->slots[s].sun_shadow);
  fog_sun_shadow_destroy(&p->shadow_volume);
  fog_sun_shadow_destroy(&p->rung_shadow);
  for (int l = 0; l <= FOG_MAX_LEVELS; l++) transform_grid_destroy(&p->shadow_grids[l]);
  free(p->rung_depth);
  plan_destroy(&p->cpu);
  if (p->cpu.sim) fluid_sim_destroy(p->cpu.sim);
  fogmap_destroy(&p->cpu.base);
  if (p->cpu.has_vdb) vdb_source_destroy(&p->cpu.vdb);
  fogmap_destroy(&p->cpu.vdb_map);
  fogmap_destroy(&p->cpu.sequence_map);
  pipeline_fog_destroy(p->fog);
  if (p->scene) scene_pass_destroy(p->scene);
  gl_target_destroy(&p->scene_target);
  if (p->geometry_made) scene_geometry_destroy(&p->geometry);
  pthread_cond_destroy(&p->changed);
  pthread_mutex_destroy(&p->lock);
  free(p);
}

int pipeline_resize(pipeline *p, int width, int height, fog_error *err) {
  if (width < 1 || height < 1)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "render size %dx%d is not positive", width,
                    height);
  fog_error rerr = {0};
  gl_target_destroy(&p->scene_target);
  p->scene_current = false;
  if (scene_target_create(&p->scene_target, width, height, &rerr))
    return fog_error_wrap(err, &rerr, "scene target: ");
  free(p->rung_depth); /* the live rung's view: its size follows */
  p->rung_depth = NULL;
  if (p->fog && pipeline_fog_resize(p->fog, width, height, &rerr))
    return fog_error_wrap(err, &rerr, "fog target: ");
  p->width = width;
  p->height = height;
  return 0;
}

void pipeline_size(const pipeline *p, int *width, int *height) {
  *width = p->width;
  *height = p->height;
}

long pipeline_step_index(const pipeline *p) { return p->shown_step; }

int pipeline_skip(pipeline *p, long steps, fog_error *err) {
  if (p->worker_running)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "pipeline_skip after the first frame");
  fog_error serr = {0};
  for (long s = 0; s < steps; s++) {
    for (int k = 0; p->cpu.steps > 0 && k < p->steps_per_frame && p->cpu.sim; k++)
      if (fluid_sim_step(p->cpu.sim, &serr)) return fog_error_wrap(err, &serr, "simulation: ");
    p->cpu.steps++;
  }
  p->shown_step = p->cpu.steps;
  return 0;
}

bool pipeline_lamps_dropped(const pipeline *p) { return p->lamps_dropped; }

/* From what was fixed at creation, not from cpu.sim: a reset replaces that pointer in the
 * worker while the panel asks every frame. */
bool pipeline_simulates(const pipeline *p) { return !p->cpu.has_vdb && !p->cpu.has_sequence; }

bool pipeline_has_bspline_profile(const pipeline *p) { return p->config.fog.profile_count > 0; }

const fogmap *pipeline_sim_density(const pipeline *p) {
  return p->cpu.sim ? fluid_sim_density(p->cpu.sim) : NULL;
}

/* ---- the frame (GL thread) ---- */

static fog_volume volume_of(const pipeline *p, const pipeline_params *params) {
  const scene_fog_shape shape = {
      .extinction = params->density, .profile = (fog_profile_kind)params->profile_kind,
      .y0 = params->fog_height,
      .scale_height = params->scale_height > 0 ? params->scale_height : 1.0};
  return scene_config_fog_volume(&p->config, p->cpu.base.width, p->cpu.base.height, &shape);
}

/* After a slot's grids went up: its shadow volume too, and a copy of its approximations
 * for re-lighting (GL thread; the slot is still held). */
static int show_slot_shadow(pipeline *p, const pipeline_slot *slot, fog_error *err) {
  fog_error rerr = {0};
  p->shown_self_shadow = slot->self_shadow;
  if (slot->shadow_fresh) p->last.sun_shadow = slot->sun_shadow_ms;
  for (int l = 0; l <= slot->pyramid.levels; l++) {
    const transform_grid *from = &slot->pyramid.approx[l];
    transform_grid *copy = &p->shadow_grids[l];
    if (copy->width != from->width || copy->height != from->height) {
      transform_grid_destroy(copy);
      fog_error terr = {0};
      if (transform_grid_create(copy, from->width, from->height, &terr))
        return fog_error_wrap(err, &terr, "sun shadow: ");
    }
    float *coefficients = copy->coefficients;
    *copy = *from;
    copy->coefficients = coefficients;
    memcpy(coefficients, from->coefficients,
           (size_t)from->width * from->height * sizeof *coefficients);
  }
  p->shadow_levels = slot->pyramid.levels;
  if (!slot->shadow_fresh || slot->self_shadow != FOG_SUN_SHADOW_VOLUME) return 0;
  memcpy(p->shown_shadow_sun, slot->sun_shadow.sun, sizeof p->shown_shadow_sun);
  memcpy(p->shown_shadow_shape, slot->shadow_shape, sizeof p->shown_shadow_shape);
  if (pipeline_fog_upload_sun_shadow(p->fog, &slot->sun_shadow, &rerr))
    return fog_error_wrap(err, &rerr, "upload: ");
  p->rung_shadow_shown = false;
  return 0;
}

/* The sun moved, or the fog's density or profile changed (shadow_shape_of), or the albedo
 * became > 0, or a live rung's volume took its place, since the volume on screen was
 * computed, and no step brought one for them: compute it here from the last step's finest
 * grid. */
static int relight(pipeline *p, const pipeline_params *params, fog_error *err) {
  if (!(params->sun.albedo > 0) || !params->fog_self_shadow) {
    p->shown_self_shadow = FOG_SUN_SHADOW_NONE; /* switched off: at once */
    return 0;
  }
  if (!p->shadow_grids[p->shadow_levels].coefficients) return 0;
  double sun[3];
  float shape[4];
  sun_direction_of(p, params, sun);
  shadow_shape_of(params, shape);
  /* (while a rung's volume is in the pass, the fogmap's must go back) */
  if (p->shown_self_shadow != FOG_SUN_SHADOW_NONE && !p->rung_shadow_shown &&
      !memcmp(sun, p->shown_shadow_sun, sizeof sun) &&
      !memcmp(shape, p->shown_shadow_shape, sizeof shape))
    return 0;
  double t0 = now_ms();
  fog_sun_shadow_kind kind;
  if (compute_shadow(p, params, p->shadow_grids, p->shadow_levels, sun, 2, &kind,
                     &p->shadow_volume, err))
    return 1;
  p->shown_self_shadow = kind;
  memcpy(p->shown_shadow_sun, sun, sizeof sun);
  memcpy(p->shown_shadow_shape, shape, sizeof shape);
  fog_error rerr = {0};
  if (kind == FOG_SUN_SHADOW_VOLUME &&
      pipeline_fog_upload_sun_shadow(p->fog, &p->shadow_volume, &rerr))
    return fog_error_wrap(err, &rerr, "upload: ");
  if (kind == FOG_SUN_SHADOW_VOLUME) p->rung_shadow_shown = false;
  p->last.sun_shadow = now_ms() - t0;
  return 0;
}

/* A bounded rung's own sun-shadow volume, computed from its CPU twin when it was refitted,
 * the sun moved, or the fog pass holds the fogmap's (GL thread, both cores). */
static int show_rung_shadow(pipeline *p, const fog_model *rung, const double sun[3],
                            bool refitted, fog_error *err) {
  fog_error rerr = {0};
  if (p->rung_shadow_valid && !refitted &&
      !memcmp(sun, p->rung_shadow_sun, sizeof p->rung_shadow_sun)) {
    /* the same volume: a step's upload of the fogmap's only covered it */
    if (!p->rung_shadow_shown && pipeline_fog_upload_sun_shadow(p->fog, &p->rung_shadow, &rerr))
      return fog_error_wrap(err, &rerr, "upload: ");
    p->rung_shadow_shown = true;
    return 0;
  }
  double t0 = now_ms();
  const int n = p->config.shadow.resolution;
  if (!p->rung_shadow.optical_depth &&
      fog_sun_shadow_create(&p->rung_shadow, &(fog_sun_shadow_desc){.across = n, .along = n},
                            &rerr))
    return fog_error_wrap(err, &rerr, "live rung's sun shadow: ");
  p->rung_shadow_valid = false;
  if (fog_sun_shadow_compute(&p->rung_shadow, rung, sun, 2, &rerr))
    return fog_error_wrap(err, &rerr, "live rung's sun shadow: ");
  p->rung_shadow_valid = true;
  if (pipeline_fog_upload_sun_shadow(p->fog, &p->rung_shadow, &rerr))
    return fog_error_wrap(err, &rerr, "upload: ");
  memcpy(p->rung_shadow_sun, sun, sizeof p->rung_shadow_sun);
  p->rung_shadow_shown = true;
  p->last.sun_shadow = now_ms() - t0;
  return 0;
}

/* Takes a ready slot (waiting for one if asked) and uploads it; returns 1 if uploaded. */
static int take_slot(pipeline *p, bool wait, double *upload_ms, fog_error *err) {
  *upload_ms = 0.0;
  if (p->synchronous) {
    pipeline_slot *slot = &p->slots[0];
    worker_requests *r = &p->requests;
    pthread_mutex_lock(&p->lock);
    bool may_step = !p->params.paused || p->step_requests > 0 || p->reset_requested ||
                    !p->have_frame;
    if (may_step) {
      if (p->params.paused && p->step_requests > 0) p->step_requests--;
      take_requests(p, r);
    }
    pthread_mutex_unlock(&p->lock);
    int status = may_step ? cpu_stages_run(p, r, slot, err) : 0;
    if (status) return -1;
    if (!may_step) return 0;
    p->last.sim = slot->sim_ms;
    p->last.transform = slot->transform_ms;
    p->last.sim_cpu = slot->sim_cpu_ms;
    p->last.transform_cpu = slot->transform_cpu_ms;
    p->last.sun_shadow_cpu = slot->sun_shadow_cpu_ms;
    double t0 = now_ms();
    fog_error rerr = {0};
    if (pipeline_fog_upload(p->fog, &slot->pyramid, &rerr))
      return fog_error_wrap(err, &rerr, "upload: "), -1;
    if (show_slot_shadow(p, slot, err)) return -1;
    *upload_ms = now_ms() - t0;
    p->shown_step = slot->step;
    return 1;
  }
  if (!p->worker_running) {
    if (pthread_create(&p->worker, NULL, worker_main, p) != 0)
      return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "cannot start the pipeline's worker thread"), -1;
    p->worker_running = true;
  }
  pthread_mutex_lock(&p->lock);
  pipeline_slot *slot = &p->slots[p->take_index];
  /* The first frame always waits: there is nothing to show before it. While paused the
   * worker steps only on request, so waiting then would block for ever. */
  bool must_wait = (wait && (!p->params.paused || p->step_requests > 0)) || !p->have_frame;
  while (must_wait && slot->state != SLOT_READY && !p->worker_error.code)
    pthread_cond_wait(&p->changed, &p->lock);
  /* the worker's error is a later frame's when this one is ready (it steps one ahead: a
   * damaged bake file after the last frame asked for failed the frame before it) */
  if (p->worker_error.code && slot->state != SLOT_READY) {
    fog_error_pass(err, &p->worker_error);
    pthread_mutex_unlock(&p->lock);
    return -1;
  }
  bool ready = slot->state == SLOT_READY;
  pthread_mutex_unlock(&p->lock);
  if (!ready) return 0;

  double t0 = now_ms();
  fog_error rerr = {0};
  int status = pipeline_fog_upload(p->fog, &slot->pyramid, &rerr);
  fog_error shadow_err = {0};
  bool shadow_failed = !status && show_slot_shadow(p, slot, &shadow_err);
  *upload_ms = now_ms() - t0;
  p->last.sim = slot->sim_ms;
  p->last.transform = slot->transform_ms;
  p->last.sim_cpu = slot->sim_cpu_ms;
  p->last.transform_cpu = slot->transform_cpu_ms;
  p->last.sun_shadow_cpu = slot->sun_shadow_cpu_ms;
  p->shown_step = slot->step;
  pthread_mutex_lock(&p->lock);
  slot->state = SLOT_FREE; /* the textures hold the copy now */
  p->take_index ^= 1;
  pthread_cond_broadcast(&p->changed);
  pthread_mutex_unlock(&p->lock);
  if (status) return fog_error_wrap(err, &rerr, "upload: "), -1;
  if (shadow_failed) return fog_error_pass(err, &shadow_err), -1;
  return 1;
}

/* Every LIVE_RUNG_INTERVAL frames the live rung's error against the fogmap it stands for,
 * over this frame's view (app/live_rung.h). */
static int measure_live_rung(pipeline *p, const fog_model *fogmap_model, const camera *cam,
                             fog_error *err) {
  fog_error rerr = {0};
  if (!p->rung_depth &&
      !(p->rung_depth = malloc((size_t)p->width * p->height * sizeof *p->rung_depth)))
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the live rung's view");
  if (gl_target_read(&p->scene_target, 1, 1, p->rung_depth, &rerr))
    return fog_error_wrap(err, &rerr, "live rung: ");
  live_rung_measure(fogmap_model, cam, p->width, p->height, p->rung_depth, &p->rung);
  p->rung_frames = 0;
  return 0;
}

/* The panel's sun and lamps (or the lamps' animation at the shown step) reach the
 * surfaces: what changed marks the scene pass stale. */
static int sync_surface_light(pipeline *p, fog_error *err) {
  pthread_mutex_lock(&p->lock);
  const double sun_azimuth = p->params.sun_azimuth, sun_elevation = p->params.sun_elevation;
  float sun_colour[3]; /* the surfaces' sun_colour is the fog's irradiance over pi */
  for (int c = 0; c < 3; c++) sun_colour[c] = (float)(p->params.sun.radiance[c] / SCENE_SUN_IRRADIANCE_PER_COLOUR);
  pthread_mutex_unlock(&p->lock);
  scene_light *light = &p->geometry.light;
  if (memcmp(sun_colour, light->sun_colour, sizeof sun_colour)) {
    /* the panel changed the sun's colour: the terrain and sky are lit anew */
    memcpy(light->sun_colour, sun_colour, sizeof sun_colour);
    p->scene_current = false;
  }
  if (sun_azimuth != light->sun_azimuth || sun_elevation != light->sun_elevation) {
    /* the panel moved the sun: the terrain is lit anew (the fog takes it below) */
    light->sun_azimuth = sun_azimuth, light->sun_elevation = sun_elevation;
    scene_light_sun_direction(light, p->geometry.sun_direction);
    p->scene_current = false;
  }
  fog_error lamp_err = {0};
  if (!p->lamps_animated) {
    pthread_mutex_lock(&p->lock);
    const fog_lamps placed = p->params.lamps;
    pthread_mutex_unlock(&p->lock);
    if (!fog_lamps_equal(&placed, &p->shown_lamps)) {
      /* the panel placed, moved or removed a lamp: the surfaces are lit anew */
      p->shown_lamps = placed;
      if (scene_pass_set_lamps(p->scene, &p->shown_lamps, &lamp_err))
        return fog_error_wrap(err, &lamp_err, "lamps: ");
      p->scene_current = false;
    }
  } else {
    double time = (double)(p->shown_step > 0 ? p->shown_step - 1 : 0) * p->frame_seconds;
    if (!(time == p->shown_lamps_time)) {
      p->shown_lamps = scene_config_fog_lamps_at(&p->config, time);
      p->shown_lamps_time = time;
      if (scene_pass_set_lamps(p->scene, &p->shown_lamps, &lamp_err))
        return fog_error_wrap(err, &lamp_err, "lamps: ");
      p->scene_current = false;
    }
  }
  return 0;
}

/* The live rung's frame (app/live_rung.h): refitted when due (bounded rungs every
 * LIVE_RUNG_REFIT steps: their shadow volume is the cost), its self-shadow kind into
 * *self_shadow and its own volume shown; back on the fogmap, the fogmap's volume again. */
static int show_live_rung(pipeline *p, const pipeline_params *params, bool rung,
                          const fog_model *fogmap_model, const double sun[3],
                          const fog_quadric *beside, int quadric_count,
                          fog_sun_shadow_kind *self_shadow, fog_error *err) {
  if (!rung) {
    p->rung.kind = LIVE_RUNG_FOGMAP; /* a later rung is fitted anew (a reset between) */
    if (!p->rung_shadow_shown) return 0;
    if (relight(p, params, err)) return 1;
    *self_shadow = p->shown_self_shadow;
    p->rung_shadow_shown = false;
    return 0;
  }
  const long since = p->shown_step - p->rung_step;
  /* the panel's density or profile (the fog the rung is fitted to and measured against)
   * changed: refit now, also while paused, or its error measures how stale it is */
  float shape[4];
  shadow_shape_of(params, shape);
  const bool refit = (int)p->rung.kind != params->live_rung ||
                     memcmp(shape, p->rung_shape, sizeof shape) ||
                     (live_rung_bounded(params->live_rung) ? since < 0 || since >= LIVE_RUNG_REFIT
                                                           : since != 0);
  if (refit) {
    memcpy(p->rung_shape, shape, sizeof shape);
    live_rung_fit(fogmap_model, (live_rung_kind)params->live_rung, &p->rung);
    /* the volumes beside the fogmap keep their places in the pass's FOG_MAX_QUADRICS */
    if (p->rung.model.kind == FOG_MODEL_QUADRIC &&
        p->rung.model.quadric_count > FOG_MAX_QUADRICS - quadric_count)
      p->rung.model.quadric_count = FOG_MAX_QUADRICS - quadric_count;
    p->rung_step = p->shown_step;
    p->rung_frames = LIVE_RUNG_INTERVAL; /* measure this frame */
  }
  /* lit as drawn: an ellipsoids rung's sun volume holds the [fog] quadric volumes beside
   * the fogmap too (drawn as its own, with no exact sun depth through them, they neither
   * cast nor received the sun's shadow on this rung alone) */
  fog_quadric lit[FOG_MAX_QUADRICS];
  const fog_model fitted = live_rung_model(&p->rung);
  const fog_model model = live_rung_with_beside(&fitted, beside, quadric_count, lit);
  /* the rung's own kind, whatever the fogmap's volume on hand */
  *self_shadow = params->sun.albedo > 0 && params->fog_self_shadow
                     ? fog_sun_shadow_kind_of(&model, sun)
                     : FOG_SUN_SHADOW_NONE;
  if (*self_shadow == FOG_SUN_SHADOW_VOLUME && show_rung_shadow(p, &model, sun, refit, err))
    return 1;
  return 0;
}

int pipeline_frame(pipeline *p, const camera *cam, bool wait, fog_error *err) {
  double frame_start = now_ms();
  double upload_ms = 0.0;
  int taken = take_slot(p, wait, &upload_ms, err);
  if (taken < 0) return 1;
  /* Without a new step (live, worker still busy) sim and transform keep the values of the
   * step on screen, so the medians describe steps, not idle frames. */

  if (sync_surface_light(p, err)) return 1;
  double t0 = now_ms();
  if (!p->scene_current || !camera_equal(&p->scene_camera, cam)) {
    scene_pass_run(p->scene, cam, &p->scene_target);
    p->scene_camera = *cam;
    p->scene_current = true;
  }
  if (p->time_passes) {
    gl_finish();
    p->last.scene = now_ms() - t0;
  }
  pthread_mutex_lock(&p->lock);
  pipeline_params params = p->params;
  pthread_mutex_unlock(&p->lock);
  fog_volume volume = volume_of(p, &params);
  const bool rung = params.live_rung > LIVE_RUNG_FOGMAP && params.live_rung < LIVE_RUNG_COUNT &&
                    p->shadow_grids[p->shadow_levels].coefficients;
  /* a rung lights itself (a bounded one by its own volume, the others in closed form): the
   * fogmap's volume waits until the menu returns to it, when relight sees the sun or the
   * shape it was made for changed (recomputing it for a closed-form rung cost 20-70 ms of
   * the timed frame at every sun change, for nothing) */
  if (!rung && relight(p, &params, err)) return 1;
  fog_error rerr = {0};
  fog_sun sun = params.sun;
  memcpy(sun.direction, p->geometry.sun_direction, sizeof sun.direction);
  /* [fog] quadric lines beside the fogmap: their densities on the live density scale */
  fog_quadric quadrics[FOG_MAX_QUADRICS];
  const int quadric_count = p->config.fog.quadric_count;
  for (int i = 0; i < quadric_count; i++) {
    quadrics[i] = p->config.fog.quadrics[i];
    quadrics[i].density *= params.density;
  }
  /* The live rung: the fitted model drawn in the fogmap's place, lit as that model is. */
  fog_lod finest = {.levels = 0, .approx = &p->shadow_grids[p->shadow_levels]};
  const fog_model fogmap_model = {.kind = FOG_MODEL_FOGMAP, .volume = &volume, .lod = &finest,
                                  .lod_method = FOG_LOD_SWITCH};
  fog_sun_shadow_kind self_shadow = p->shown_self_shadow;
  if (show_live_rung(p, &params, rung, &fogmap_model, sun.direction, quadrics, quadric_count,
                     &self_shadow, err))
    return 1;
  const fog_model rung_model = live_rung_model(&p->rung);
  pipeline_fog_settings settings = {
      .volume = &volume,
      .rung = rung ? &rung_model : NULL,
      .quadrics = quadrics,
      .quadric_count = quadric_count,
      .mu = params.mu,
      .lod_method = params.lod_method,
      .fog_colour = {params.fog_colour[0], params.fog_colour[1], params.fog_colour[2]},
      .sun = sun,
      .lamps = p->lamps_animated ? p->shown_lamps : params.lamps,
      .hardware_filtering = p->config.fog.filtering == SCENE_FILTERING_HARDWARE,
      .resolution_divisor = params.fog_resolution_divisor,
      .self_shadow = self_shadow,
      .shadow_steps = p->config.shadow.steps,
      .shadow_nodes = p->config.shadow.nodes,
      .shadow_pieces = scene_config_light_rule(&p->config).pieces,
      .shaft_samples = p->config.shadow.shaft_samples,
      .shafts = params.sun.albedo > 0 && params.shafts && fog_sun_above_horizon(sun.direction) > 0
                    ? scene_pass_sun_shadow(p->scene)
                    : NULL,
      .lamp_shadows = scene_pass_lamp_shadows(p->scene),
      .walk = scene_config_walk(&p->config),
  };
  int refused = pipeline_fog_render(p->fog, cam, &p->scene_target, &settings, &rerr);
  p->lamps_dropped = false;
  if (refused && p->live && rerr.code == FOG_ERR_UNSUPPORTED && settings.lamps.count > 0) {
    /* the lamps' light over this fog (a live rung's Gaussians or volumes under many lamps)
     * passes the renderer's loop cap: the live view draws the fog without it */
    settings.lamps.count = 0;
    p->lamps_dropped = true;
    rerr = (fog_error){0};
    refused = pipeline_fog_render(p->fog, cam, &p->scene_target, &settings, &rerr);
  }
  if (refused) return fog_error_wrap(err, &rerr, "render: ");
  /* llvmpipe (and GPUs) run the commands asynchronously: finish so the render time is
   * the time of this frame's drawing, not of the next read-back. */
  gl_finish();
  double t1 = now_ms();
  if (rung && ++p->rung_frames >= LIVE_RUNG_INTERVAL &&
      measure_live_rung(p, &fogmap_model, cam, err))
    return 1;
  if (gl_util_check("pipeline frame", &rerr)) return fog_error_pass(err, &rerr);

  p->last.upload = upload_ms;
  p->last.render = t1 - t0;
  p->last.frame = t1 - frame_start;
  /* Frame time of a live loop includes everything between frames (events, panel, swap):
   * measure start to start when frames follow each other. */
  if (p->have_frame && !wait) {
    double between = frame_start - p->last_frame_start;
    if (between > p->last.frame && between < 1000.0) p->last.frame = between;
  }
  p->last_frame_start = frame_start;
  p->have_frame = true;
  p->last_camera = *cam;
  timing_push(&p->timings, &p->last);
  return 0;
}

int pipeline_read_frame(pipeline *p, const frame_pixels *out, fog_error *err) {
  fog_error rerr = {0};
  if (pipeline_fog_read(p->fog, out->rgba, out->transmittance, out->inscatter, &rerr))
    return fog_error_wrap(err, &rerr, "read-back: ");
  float *depth = out->depth;
  if (depth) {
    if (gl_target_read(&p->scene_target, 1, 1, depth, &rerr))
      return fog_error_wrap(err, &rerr, "read-back: ");
    /* The sky's distance is SCENE_SKY_DISTANCE (1e30); EXR readers and compositors want
     * a finite far value: the camera's far plane. Only the sky: the far plane is a z-plane,
     * so a surface near the frame's edge may lie further along its ray (render_frame's rule). */
    double near, far;
    camera_depth_range(&p->last_camera, &near, &far);
    for (size_t i = 0, n = (size_t)p->width * p->height; i < n; i++)
      if (depth[i] >= SCENE_SKY_DISTANCE) depth[i] = (float)far;
  }
  return 0;
}

int pipeline_present(pipeline *p, int width, int height, fog_error *err) {
  fog_error rerr = {0};
  const display_transform display = scene_config_display(&p->config);
  if (pipeline_fog_present(p->fog, width, height, &display, &rerr))
    return fog_error_wrap(err, &rerr, "present: ");
  return 0;
}

bool pipeline_live_rung(const pipeline *p, live_rung *out) {
  pipeline_params params = pipeline_get_params(p);
  if (params.live_rung <= LIVE_RUNG_FOGMAP || (int)p->rung.kind != params.live_rung) return false;
  *out = p->rung;
  return true;
}

pipeline_params pipeline_get_params(const pipeline *p) {
  pthread_mutex_lock((pthread_mutex_t *)&p->lock);
  pipeline_params params = p->params;
  pthread_mutex_unlock((pthread_mutex_t *)&p->lock);
  return params;
}

void pipeline_set_params(pipeline *p, const pipeline_params *params) {
  pthread_mutex_lock(&p->lock);
  /* a step asked for while paused and not yet taken does not play after a later pause */
  if (!params->paused) p->step_requests = 0;
  p->params = *params;
  /* the levels the map allows: the panel shows them, and the worker does not remake its
   * plan on every later edit because the levels asked differ from the plan's */
  if (p->params.levels > p->levels_most) p->params.levels = p->levels_most;
  if (p->params.levels < 0) p->params.levels = 0;
  p->params_version++;
  pthread_cond_broadcast(&p->changed);
  pthread_mutex_unlock(&p->lock);
}

void pipeline_step_once(pipeline *p) {
  pthread_mutex_lock(&p->lock);
  /* running, the simulation steps anyway: N pressed then used to queue steps that played
   * after the next pause */
  if (p->params.paused) p->step_requests++;
  pthread_cond_broadcast(&p->changed);
  pthread_mutex_unlock(&p->lock);
}

void pipeline_reset(pipeline *p) {
  pthread_mutex_lock(&p->lock);
  p->reset_requested = true;
  pthread_cond_broadcast(&p->changed);
  pthread_mutex_unlock(&p->lock);
}

/* Clips the segment a-b to [lo, hi] on both axes (Liang-Barsky); false when it misses. */
static bool clip_segment(double a[2], double b[2], const double lo[2], const double hi[2]) {
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 2; k++) {
    const double d = b[k] - a[k];
    if (d == 0.0) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - a[k]) / d, tb = (hi[k] - a[k]) / d;
    if (ta > tb) { const double s = ta; ta = tb; tb = s; }
    t0 = fmax(t0, ta), t1 = fmin(t1, tb);
  }
  if (t0 > t1) return false;
  const double a0[2] = {a[0], a[1]};
  for (int k = 0; k < 2; k++) {
    const double d = b[k] - a0[k];
    a[k] = a0[k] + t0 * d, b[k] = a0[k] + t1 * d;
  }
  return true;
}

void pipeline_paint(pipeline *p, double x0, double z0, double x1, double z1, double radius,
                    double amount) {
  /* World to sim cells: cell (x, z) sits at world origin + (x + 1/2) cell_size. */
  const scene_box_config *b = &p->config.box;
  double cell = b->cell_size > 0 ? b->cell_size : 1.0;
  double a[2] = {(x0 - b->origin[0]) / cell - 0.5, (z0 - b->origin[1]) / cell - 0.5};
  double e[2] = {(x1 - b->origin[0]) / cell - 0.5, (z1 - b->origin[1]) / cell - 0.5};
  /* Only what falls in the fog's box: the periodic simulation wrapped a stroke beside the
   * box onto its far side (a cursor 80 units past the west edge painted fog 1000 units
   * east). The centre line is clipped to the box grown by the brush's radius (a cursor
   * just outside still paints the brush's inside part), and no cell past an edge wraps. */
  const double r = radius / cell;
  const double lo[2] = {-0.5 - r, -0.5 - r},
               hi[2] = {p->cpu.base.width - 0.5 + r, p->cpu.base.height - 0.5 + r};
  if (!clip_segment(a, e, lo, hi)) return;
  fluid_stroke stroke = {
      .x0 = (float)a[0], .z0 = (float)a[1], .x1 = (float)e[0], .z1 = (float)e[1],
      .radius = (float)r,
      .amount = (float)amount,
      .within_grid = true,
  };
  pthread_mutex_lock(&p->lock);
  /* A brush held still queues the same stroke every frame: those add up in one (painting is
   * linear in the amount), so a pause of any length keeps them; only MAX_STROKES different
   * strokes wait for a step. */
  fluid_stroke *last = p->stroke_count ? &p->strokes[p->stroke_count - 1] : NULL;
  if (last && last->x0 == stroke.x0 && last->z0 == stroke.z0 && last->x1 == stroke.x1 &&
      last->z1 == stroke.z1 && last->radius == stroke.radius &&
      (last->amount > 0) == (stroke.amount > 0))
    last->amount += stroke.amount;
  else if (p->stroke_count < MAX_STROKES)
    p->strokes[p->stroke_count++] = stroke;
  pthread_cond_broadcast(&p->changed);
  pthread_mutex_unlock(&p->lock);
  if (p->synchronous) return;
}

bool pipeline_pick_surface(pipeline *p, const camera *cam, int px, int py, double world[3]) {
  if (px < 0 || py < 0 || px >= p->width || py >= p->height) return false;
  /* One texel of the distance texture. */
  const float distance = gl_target_read_texel(&p->scene_target, 1, px, py);
  if (!(distance < 0.5f * SCENE_SKY_DISTANCE)) return false;
  /* along the ray of the camera the distances were drawn from (the window's camera has
   * moved since: 120 units off at 500 turning at 5 fps); cam until a scene is drawn */
  const camera *drawn = p->scene_camera.fov_y > 0 ? &p->scene_camera : cam;
  double origin[3], dir[3];
  camera_ray(drawn, px, py, p->width, p->height, origin, dir);
  for (int i = 0; i < 3; i++) world[i] = origin[i] + distance * dir[i];
  return true;
}

pipeline_timings pipeline_get_timings(const pipeline *p, pipeline_timings *last) {
  if (last) *last = p->last;
  const timing_ring *r = &p->timings;
  double medians[PIPELINE_TIMING_FIELDS];
  for (int s = 0; s < PIPELINE_TIMING_FIELDS; s++) medians[s] = median_of(r->values[s], r->count);
  return pipeline_timings_from_array(medians);
}

void pipeline_fog_extent(const pipeline *p, int *cells_x, int *cells_z, double *origin_x,
                         double *origin_z, double *cell_size) {
  *cells_x = p->cpu.base.width;
  *cells_z = p->cpu.base.height;
  *origin_x = p->config.box.origin[0];
  *origin_z = p->config.box.origin[1];
  *cell_size = p->config.box.cell_size;
}
