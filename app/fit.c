/* `fogpipe fit`: rungs fitted, measured and timed (app/fit.h). */
#define _POSIX_C_SOURCE 200809L
#include "app/fit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/clock.h"
#include "app/fit_density.h"
#include "app/fit_fogmap.h"
#include "app/fit_rungs.h"
#include "app/fit_views.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "render/fog_sun_shadow.h"
#include "sim/sim.h"

/* Rungs whose times lie within this factor of the fastest one within the tolerance tie. */
#define FIT_TIE 1.25

/* A fog model and what it points into: the session that built it, and (model = volume,
 * which a session keeps on the GL only) the grid read from its file. Both the reference
 * and each rung at a frame are one. */
typedef struct held_model {
  fog_model model;
  render_session *session;
  vdb_frame frame;
  volume_grid_desc grid;
  bool has_frame;
  fog_quadric quadrics[FOG_MAX_QUADRICS]; /* the volume's quadrics beside, density scaled */
} held_model;

/* A volume read from its file with the config's quadric volumes beside it, as the renderer
 * draws them (render_fog_beside: each density times density_scale). Without them a plume
 * beside an opaque sphere was fitted, measured and written as the plume alone. */
static void held_volume(held_model *m, const scene_config *cfg) {
  m->model = (fog_model){.kind = FOG_MODEL_VOLUME, .grid3d = &m->grid};
  const int count = scene_config_fog_quadrics(cfg, m->quadrics);
  if (count == 0) return;
  m->model.quadrics = m->quadrics;
  m->model.quadric_count = count;
}

static void held_model_destroy(held_model *m) {
  render_session_destroy(m->session);
  if (m->has_frame) vdb_frame_destroy(&m->frame);
  *m = (held_model){0};
}


/* The richest fog the input has: the VDB frame as a volume wherever [fog] vdb is set
 * (model = fogmap projects it to 2.5D; the grid is the truth), else the input's model. */
static int reference_create(held_model *r, const scene_config *cfg, fog_error *err) {
  *r = (held_model){0};
  fog_error rerr = {0};
  if (cfg->fog.model == FOG_MODEL_VOLUME || cfg->fog.vdb[0]) {
    if (render_fog_load_volume(cfg, &r->frame, &r->grid, &rerr)) {
      vdb_frame_destroy(&r->frame);
      fog_error_pass(err, &rerr);
      return 1;
    }
    r->has_frame = true;
    held_volume(r, cfg);
    return 0;
  }
  if (!scene_config_has_fog(cfg)) {
    /* the caller names the file */
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "the scene has no fog to fit");
    return 1;
  }
  fog_error ferr;
  if (!(r->session = render_session_create(cfg, 8, 8, &ferr))) {
    fog_error_pass(err, &ferr);
    return 1;
  }
  r->model = render_fog_model(render_session_fog(r->session));
  return 0;
}

/* Whether a volume's grid is empty (every voxel 0: an empty VDB frame is one zero voxel
 * at index 0, whose box is no fog's). */
static bool empty_grid(const fog_model *m) {
  if (m->kind != FOG_MODEL_VOLUME || !m->grid3d) return false;
  const volume_grid_desc *g = m->grid3d;
  const size_t n = (size_t)g->dim[0] * g->dim[1] * g->dim[2];
  for (size_t i = 0; i < n; i++)
    if (g->values[i] != 0.0f) return false;
  return true;
}

/* Whether the model holds any fog: an empty grid with no quadric volumes beside it does
 * not; any other model is taken to (its samples and rays say whether it is zero). */
static bool holds_fog(const fog_model *m) {
  return !empty_grid(m) || (fog_model_quadrics_beside(m) && m->quadric_count > 0);
}

/* The fog's bounds; Gaussians over an RBF base: theirs (the base is the same in any box;
 * the terrain's footprint, 0 to 50 high, never sampled a tube of them at 300, nor did its
 * rays find one 60 across in 1000: fitted as the base alone); for other fog without an
 * end, the terrain's footprint between the box's floor and top; joined with the quadric
 * volumes beside it. */
static bool fit_domain(const fog_model *m, const scene_config *cfg, double lo[3], double hi[3]) {
  fog_model gaussians = *m;
  gaussians.extinction = 0.0; /* the Gaussians' own bounds, without the base */
  double qlo[3], qhi[3];
  if (empty_grid(m)) /* the quadric volumes beside it alone */
    return fog_model_quadrics_beside(m) &&
           fog_quadric_bounds(m->quadrics, m->quadric_count, lo, hi);
  if (!fog_model_bounds(m, lo, hi) &&
      !(m->kind == FOG_MODEL_RBF && fog_model_bounds(&gaussians, lo, hi))) {
    const scene_terrain_config *t = &cfg->terrain;
    lo[0] = t->origin[0], hi[0] = t->origin[0] + t->size[0];
    lo[2] = t->origin[2], hi[2] = t->origin[2] + t->size[1];
    lo[1] = cfg->box.floor, hi[1] = cfg->box.top;
  }
  /* and the quadric volumes beside the model */
  if (fog_model_quadrics_beside(m) && fog_quadric_bounds(m->quadrics, m->quadric_count, qlo, qhi))
    for (int a = 0; a < 3; a++) lo[a] = fmin(lo[a], qlo[a]), hi[a] = fmax(hi[a], qhi[a]);
  for (int a = 0; a < 3; a++)
    if (!(lo[a] < hi[a]) || !isfinite(lo[a]) || !isfinite(hi[a])) return false;
  return true;
}

/* The volume from its file (and a session only when it is to be timed); any other model
 * from a session. */
static int rung_model_create(held_model *m, const scene_config *cfg, const fit_desc *d, bool timed,
                             fog_error *err) {
  *m = (held_model){0};
  const bool volume = cfg->fog.model == FOG_MODEL_VOLUME;
  fog_error ferr;
  if ((timed || !volume) &&
      !(m->session = render_session_create(cfg, d->width, d->height, &ferr))) {
    fog_error_pass(err, &ferr);
    return 1;
  }
  if (!volume) {
    m->model = render_fog_model(render_session_fog(m->session));
    return 0;
  }
  fog_error rerr = {0};
  m->has_frame = true;
  if (render_fog_load_volume(cfg, &m->frame, &m->grid, &rerr)) {
    fog_error_pass(err, &rerr);
    held_model_destroy(m);
    return 1;
  }
  held_volume(m, cfg);
  return 0;
}

/* The session's GL milliseconds per frame: the median of d->timed_frames after one. */
static int time_session(render_session *s, const fit_desc *d, float *pixels, double *ms,
                        fog_error *err) {
  const frame_pixels out = {.transmittance = pixels};
  double times[64];
  const int n = d->timed_frames < 64 ? d->timed_frames : 64;
  fog_error ferr;
  for (int i = -1; i < n; i++) {
    double t0 = app_clock_seconds();
    if (render_session_frame(s, &out, &ferr)) {
      fog_error_pass(err, &ferr);
      return 1;
    }
    if (i >= 0) times[i] = 1e3 * (app_clock_seconds() - t0);
  }
  *ms = app_median(times, n);
  return 0;
}

/* The rung's error on every frame's views (the worst ray of all; the worst frame's mean)
 * and its GL time at the last frame (a headless session from view 0). A rung that plays
 * the input's VDB (its fogmap, its volume) is rebuilt at each frame; the others are one
 * fog for all. */
static int measure_rung(fit_rung *rung, const fit_desc *d, const fit_views *views, int frame_count,
                        const fit_light *light, const scene_camera_config *camera, float *pixels,
                        fog_error *err) {
  scene_config *shot = malloc(sizeof *shot);
  if (!shot) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    return 1;
  }
  const bool follows = d->frames && rung->config->fog.vdb[0];
  held_model m = {0};
  double worst = 0.0, worst_mean = 0.0, worst_light = light ? 0.0 : NAN;
  int status = 1;
  /* A rung this renderer refuses with the scene's lamps (llvmpipe's loop cap: the
   * ellipsoids under night_lamps' 9 lamps) is measured without them, as lamps are no part
   * of the error, and not timed: its time is NaN, so it is never chosen (a scene that
   * does not draw), and the other rungs stand (the whole fit failed). */
  bool refused = false;
  for (int f = 0; f < frame_count; f++) {
    const bool last = f == frame_count - 1;
    if (f == 0 || follows) {
      held_model_destroy(&m);
      *shot = *rung->config;
      shot->camera = *camera;
      if (follows) shot->fog.vdb_frame = d->frames[f];
      if (refused) shot->lamp_count = 0;
      if (rung_model_create(&m, shot, d, last || !follows, err)) {
        if (refused || shot->lamp_count == 0 || err->code != FOG_ERR_UNSUPPORTED) goto done;
        refused = true;
        shot->lamp_count = 0;
        if (rung_model_create(&m, shot, d, last || !follows, err)) goto done;
      }
    }
    double max_error, mean_error;
    fit_views_measure(&views[f], &m.model, &max_error, &mean_error);
    /* the worst frame's; a NaN sticks (a later finite frame would have dropped it) */
    if (!isnan(worst) && !(max_error <= worst)) worst = max_error;
    if (!isnan(worst_mean) && !(mean_error <= worst_mean)) worst_mean = mean_error;
    if (light) {
      double light_error;
      fog_error rerr = {0};
      if (fit_views_measure_light(&views[f], &m.model, light, &light_error, &rerr)) {
        fog_error_wrap(err, &rerr, "the light: ");
        goto done;
      }
      if (!isnan(worst_light) && !(light_error <= worst_light)) worst_light = light_error;
    }
    if (last && !refused && time_session(m.session, d, pixels, &rung->ms, err)) {
      if (shot->lamp_count == 0 || err->code != FOG_ERR_UNSUPPORTED) goto done;
      refused = true;
    }
  }
  if (refused) {
    rung->ms = NAN;
    const size_t used = strlen(rung->params);
    snprintf(rung->params + used, sizeof rung->params - used, "%s(refused by this renderer "
             "with the scene's lamps: not timed, not chosen)", used ? " " : "");
  }
  rung->max_error = worst;
  rung->mean_error = worst_mean;
  rung->light_error = worst_light;
  status = 0;
done:
  if (status) {
    fog_error_wrap(err, err, "rung %s: ", rung->name);
  }
  held_model_destroy(&m);
  free(shot);
  return status;
}

bool fit_within(const fit_rung *rung, double tolerance, bool by_mean) {
  return (by_mean ? rung->mean_error : rung->max_error) <= tolerance;
}

int fit_choose(const fit_result *r, double tolerance, bool by_mean) {
  double fastest = HUGE_VAL;
  for (int i = 0; i < r->count; i++)
    if (fit_within(&r->rungs[i], tolerance, by_mean)) fastest = fmin(fastest, r->rungs[i].ms);
  for (int i = 0; i < r->count; i++) /* ladder order: the simplest of the ties */
    if (fit_within(&r->rungs[i], tolerance, by_mean) && r->rungs[i].ms <= FIT_TIE * fastest)
      return i;
  return -1;
}

int fit_scene_for_volume(scene_config *cfg, const int *frames, int frame_count,
                         fog_error *err) {
  /* around every frame that holds fog (the default frame, the last, was often an empty
   * one: the scene stood around its zero voxel at the origin) */
  double lo[3], hi[3], position[3], target[3];
  bool any = false;
  const int shown = cfg->fog.vdb_frame;
  for (int f = 0; f < (frames ? frame_count : 1); f++) {
    if (frames) cfg->fog.vdb_frame = frames[f];
    held_model ref;
    if (reference_create(&ref, cfg, err)) {
      cfg->fog.vdb_frame = shown;
      return 1;
    }
    double flo[3], fhi[3];
    if (holds_fog(&ref.model) && fit_domain(&ref.model, cfg, flo, fhi)) {
      for (int a = 0; a < 3; a++) {
        lo[a] = any ? fmin(lo[a], flo[a]) : flo[a];
        hi[a] = any ? fmax(hi[a], fhi[a]) : fhi[a];
      }
      any = true;
    }
    held_model_destroy(&ref);
  }
  cfg->fog.vdb_frame = shown;
  if (!any) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%.400s: %s", cfg->path,
             frames && frame_count > 1 ? "the fog has no extent to fit (every frame's grid is "
                                         "empty)"
                                       : "the grid holds no fog");
    return 1;
  }
  double reach = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
  scene_terrain_config *t = &cfg->terrain;
  t->height = 0.01 * reach;
  t->origin[0] = 0.5 * (lo[0] + hi[0]) - 15.0 * reach;
  t->origin[2] = 0.5 * (lo[2] + hi[2]) - 15.0 * reach;
  t->origin[1] = lo[1] - 0.02 * reach;
  t->size[0] = t->size[1] = 30.0 * reach;
  t->resolution = 129;
  t->heightmap[0] = '\0';
  cfg->object_count = 0;
  fit_view_pose(lo, hi, 0, position, target);
  scene_camera_config *c = &cfg->camera;
  memcpy(c->position, position, sizeof position);
  memcpy(c->look_at, target, sizeof target);
  c->look_at_set = true;
  c->fov = 60.0;
  c->near_plane = 1e-3 * reach;
  c->far_plane = 1e3 * reach;
  return 0;
}

void fit_result_destroy(fit_result *r) {
  for (int i = 0; i < r->count; i++) free(r->rungs[i].config);
  if (r->scratch[0]) {
    char path[sizeof r->scratch + 32];
    snprintf(path, sizeof path, "%s/%s", r->scratch, FIT_FOGMAP_FILE);
    remove(path);
    rmdir(r->scratch);
  }
  *r = (fit_result){.chosen = -1};
}

int fit_run(const fit_desc *d, fit_result *r, fog_error *err) {
  *r = (fit_result){.chosen = -1};
  if (!(d->tolerance > 0) || d->rays_per_side < 1 || d->sample_side < 2 || d->width < 1 ||
      d->height < 1 || d->timed_frames < 1 || (d->frames && d->frame_count < 1)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fit: expected tolerance > 0, rays, samples, size and frames >= 1");
    return 1;
  }
  if (d->frames && !d->input->fog.vdb[0]) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "%.400s: frames of a sequence need [fog] vdb (a VDB sequence)", d->input->path);
    return 1;
  }
  const int frame_count = d->frames ? d->frame_count : 1;
  r->frame_count = frame_count;
  held_model *refs = calloc((size_t)frame_count, sizeof *refs);
  fit_views *views = calloc((size_t)frame_count, sizeof *views);
  scene_config *framed = malloc(sizeof *framed);
  fit_samples samples = {0};
  float *pixels = malloc((size_t)d->width * d->height * sizeof *pixels);
  int status = 1;
  if (!refs || !views || !framed || !pixels) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    goto done;
  }
  /* The references, frame by frame, and the domain that holds them all: an empty frame
   * (a bake's first ones) holds nothing (its grid, one zero voxel at index 0, stretched
   * the domain 3.4 times a side to the origin) */
  bool any_fog = false;
  for (int f = 0; f < frame_count; f++) {
    *framed = *d->input;
    if (d->frames) framed->fog.vdb_frame = d->frames[f];
    if (reference_create(&refs[f], framed, err)) goto done;
    if (!holds_fog(&refs[f].model) && (f < frame_count - 1 || any_fog)) continue;
    double lo[3], hi[3];
    if (!holds_fog(&refs[f].model) || !fit_domain(&refs[f].model, d->input, lo, hi)) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
               "%.400s: the fog has no extent to fit (%s)", d->input->path,
               frame_count > 1 ? "every frame's grid is empty" : "an empty grid, or [box] floor >= top");
      goto done;
    }
    for (int a = 0; a < 3; a++) {
      r->lo[a] = any_fog ? fmin(r->lo[a], lo[a]) : lo[a];
      r->hi[a] = any_fog ? fmax(r->hi[a], hi[a]) : hi[a];
    }
    any_fog = true;
  }
  /* The density the static rungs fit: the frames' mean. A classic factor's fog lies about
   * an eye: the scene's camera's (the views measure each from its own camera); it was the
   * world's origin, where no view stands. */
  camera input_camera;
  scene_config_camera(d->input, &input_camera);
  for (int f = 0; f < frame_count; f++) {
    fit_samples one;
    fog_model sampled = refs[f].model;
    if (fog_model_about_eye(&sampled))
      memcpy(sampled.eye, input_camera.position, sizeof sampled.eye);
    if (fit_samples_create(f ? &one : &samples, &sampled, r->lo, r->hi, d->sample_side,
                           err))
      goto done;
    if (fit_views_create(&views[f], &refs[f].model, r->lo, r->hi, d->rays_per_side, err)) {
      if (f) fit_samples_destroy(&one); /* frame 0's are samples, freed at done */
      goto done;
    }
    if (f) {
      size_t n = (size_t)one.n[0] * one.n[1] * one.n[2];
      for (size_t i = 0; i < n; i++) samples.k[i] += one.k[i];
      fit_samples_destroy(&one);
    }
  }
  for (size_t i = 0, n = (size_t)samples.n[0] * samples.n[1] * samples.n[2]; i < n; i++)
    samples.k[i] /= frame_count;
  /* No fog on any sample nor on any view ray: nothing to fit (every rung scored 0, and a
   * linear fog starting past the domain's far side, opaque beyond it, could be chosen) */
  bool seen = false;
  for (size_t i = 0, n = (size_t)samples.n[0] * samples.n[1] * samples.n[2]; i < n && !seen; i++)
    seen = samples.k[i] != 0.0;
  for (int f = 0; f < frame_count && !seen; f++)
    for (int k = 0; k < views[f].count && !seen; k++) seen = views[f].reference[k] < 1.0;
  if (!seen) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "%.400s: the fog is zero everywhere the fit looks (every sample, every view "
             "ray): nothing to fit", d->input->path);
    goto done;
  }
  r->rays = views[0].count;
  /* A lit input: the reference's in-scatter on every frame's rays. */
  const scene_fog_config *fog = &d->input->fog;
  const fit_light light = {.sun = scene_config_fog_sun(d->input),
                           .ambient = {fog->colour[0], fog->colour[1], fog->colour[2]},
                           .self_shadow = d->input->shadow.fog_self_shadow,
                           .resolution = d->input->shadow.resolution,
                           .rule = scene_config_light_rule(d->input)};
  r->lit = fog->albedo > 0.0;
  for (int f = 0; r->lit && f < frame_count; f++) {
    fog_error rerr = {0};
    if (fit_views_light(&views[f], &refs[f].model, &light, &rerr)) {
      fog_error_wrap(err, &rerr, "the light: ");
      goto done;
    }
  }
  if (fit_rungs_make(r, d->input, &refs[0].model, &samples, views, frame_count, err))
    goto done;
  for (int f = 0; f < frame_count; f++) /* one GL context at a time: the rungs make theirs */
    held_model_destroy(&refs[f]);
  /* Every rung drawn from view 0, outside the fog looking at it. */
  double position[3], target[3];
  fit_view_pose(r->lo, r->hi, 0, position, target);
  double reach = 0.0;
  for (int a = 0; a < 3; a++) reach = fmax(reach, r->hi[a] - r->lo[a]);
  scene_camera_config camera = d->input->camera;
  memcpy(camera.position, position, sizeof position);
  memcpy(camera.look_at, target, sizeof target);
  camera.look_at_set = true;
  camera.fov = 60.0;
  camera.near_plane = 1e-3 * reach;
  camera.far_plane = 1e3 * reach;
  for (int i = 0; i < r->count; i++) {
    if (d->stop && *d->stop) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "stopped after %d of %d rungs", i, r->count);
      goto done;
    }
    if (measure_rung(&r->rungs[i], d, views, frame_count, r->lit ? &light : NULL, &camera,
                     pixels, err))
      goto done;
  }
  r->chosen = fit_choose(r, d->tolerance, d->by_mean);
  status = 0;
done:
  for (int f = 0; refs && f < frame_count; f++) held_model_destroy(&refs[f]);
  for (int f = 0; views && f < frame_count; f++) fit_views_destroy(&views[f]);
  free(refs), free(views), free(framed), free(pixels);
  fit_samples_destroy(&samples);
  if (status) fit_result_destroy(r);
  return status;
}
