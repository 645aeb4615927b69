/* `fogpipe fit`: rungs fitted, measured and timed (app/fit.h). */
#include "app/fit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/clock.h"
#include "app/fit_density.h"
#include "app/fit_views.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "render/fog_sun_shadow.h"
#include "sim/sim.h"

/* Gaussians per bank: 1 to 64 (a config holds SCENE_CONFIG_MAX_RBFS). */
static const int rbf_sizes[] = {1, 2, 4, 8, 16, 32, 64};
_Static_assert(SCENE_CONFIG_MAX_RBFS >= 64, "a config holds the largest bank");
/* The fogmap's rungs: each basis at three LOD factors (levels 3, switching). */
static const char *const basis_names[] = {"haar", "linear", "quadratic"};
static const double fogmap_mus[] = {1.0, 0.5, 0.25};
/* Rungs whose times lie within this factor of the fastest one within the tolerance tie. */
#define FIT_TIE 1.25

/* The reference fog: the model, and what it points into. */
typedef struct reference {
  fog_model model;
  render_session *session; /* the input's own model, as the renderer builds it */
  vdb_frame frame;         /* model = volume: the grid */
  volume_grid_desc grid;
  bool has_frame;
} reference;

static void reference_destroy(reference *r) {
  render_session_destroy(r->session);
  if (r->has_frame) vdb_frame_destroy(&r->frame);
  *r = (reference){0};
}

/* The richest fog the input has: the VDB frame as a volume wherever [fog] vdb is set
 * (model = fogmap projects it to 2.5D; the grid is the truth), else the input's model. */
static int reference_create(reference *r, const scene_config *cfg, fit_error *err) {
  *r = (reference){0};
  render_error rerr = {{0}};
  if (cfg->fog.model == FOG_MODEL_VOLUME || cfg->fog.vdb[0]) {
    if (render_fog_load_volume(cfg, &r->frame, &r->grid, &rerr)) {
      vdb_frame_destroy(&r->frame);
      snprintf(err->message, sizeof err->message, "%s", rerr.message);
      return 1;
    }
    r->has_frame = true;
    r->model = (fog_model){.kind = FOG_MODEL_VOLUME, .grid3d = &r->grid};
    return 0;
  }
  if (!scene_config_has_fog(cfg)) {
    snprintf(err->message, sizeof err->message, "%.400s: the scene has no fog to fit",
             cfg->path);
    return 1;
  }
  render_frame_error ferr;
  if (!(r->session = render_session_create(cfg, 8, 8, &ferr))) {
    snprintf(err->message, sizeof err->message, "%s", ferr.message);
    return 1;
  }
  r->model = render_fog_model(render_session_fog(r->session));
  return 0;
}

/* The fog's bounds; for fog without an end, the terrain's footprint between the box's
 * floor and top. */
static bool fit_domain(const fog_model *m, const scene_config *cfg, double lo[3], double hi[3]) {
  if (!fog_model_bounds(m, lo, hi)) {
    const scene_terrain_config *t = &cfg->terrain;
    lo[0] = t->origin[0], hi[0] = t->origin[0] + t->size[0];
    lo[2] = t->origin[2], hi[2] = t->origin[2] + t->size[1];
    lo[1] = cfg->box.floor, hi[1] = cfg->box.top;
  }
  for (int a = 0; a < 3; a++)
    if (!(lo[a] < hi[a]) || !isfinite(lo[a]) || !isfinite(hi[a])) return false;
  return true;
}

/* The input scene with its fog model's own lines cleared, for an analytic rung. */
static scene_config *analytic_config(const scene_config *input, fog_model_kind kind) {
  scene_config *c = malloc(sizeof *c);
  if (!c) return NULL;
  *c = *input;
  scene_fog_config *f = &c->fog;
  f->model = kind;
  f->fogmap[0] = f->vdb[0] = f->sequence[0] = '\0';
  f->rbf_count = f->rbf_emitter_count = f->quadric_count = 0;
  f->rbf_base = 0.0;
  f->density_scale = 1.0;
  f->volume_step = 0.0;
  f->profile_set = false;
  return c;
}

static fit_rung *add_rung(fit_result *r, scene_config *cfg, const char *family,
                          fit_error *err) {
  if (!cfg) {
    snprintf(err->message, sizeof err->message, "out of memory for the rungs");
    return NULL;
  }
  if (r->count == FIT_MAX_RUNGS) { /* a bug: the list below holds at most this many */
    free(cfg);
    snprintf(err->message, sizeof err->message, "more than %d rungs", FIT_MAX_RUNGS);
    return NULL;
  }
  fit_rung *rung = &r->rungs[r->count++];
  *rung = (fit_rung){.config = cfg};
  snprintf(rung->family, sizeof rung->family, "%s", family);
  snprintf(rung->name, sizeof rung->name, "%s", family);
  return rung;
}

/* The ladder's rungs for this input, in order, their parameters fitted to the samples. */
static int make_rungs(fit_result *r, const scene_config *input, const fog_model *reference,
                      const fit_samples *s, fit_error *err) {
  fit_rung *rung;
  double k = fit_homogeneous(s);
  if (!(rung = add_rung(r, analytic_config(input, FOG_MODEL_HOMOGENEOUS), "homogeneous", err)))
    return 1;
  rung->config->fog.density_scale = k;
  snprintf(rung->params, sizeof rung->params, "K=%.6g", k);

  double y0, scale_height;
  if (fit_height(s, &k, &y0, &scale_height)) {
    if (!(rung = add_rung(r, analytic_config(input, FOG_MODEL_HEIGHT), "height", err))) return 1;
    scene_fog_config *f = &rung->config->fog;
    f->density_scale = k, f->fog_height = y0, f->scale_height = scale_height;
    snprintf(rung->params, sizeof rung->params, "K=%.6g y0=%.6g H=%.6g", k, y0, scale_height);
  }

  double centre[3], radii[3], density;
  if (fit_ellipsoid(s, centre, radii, &density)) {
    if (!(rung = add_rung(r, analytic_config(input, FOG_MODEL_QUADRIC), "quadric", err)))
      return 1;
    snprintf(rung->name, sizeof rung->name, "ellipsoid");
    scene_fog_config *f = &rung->config->fog;
    f->quadric_count = 1;
    f->quadrics[0] = fog_quadric_ellipsoid(centre, radii, density, 0.0);
    f->quadric_lines[0] = (struct scene_quadric_line){
        .shape = 1, /* ellipsoid X Y Z RX RY RZ DENSITY (app/config.c) */
        .count = 7,
        .numbers = {centre[0], centre[1], centre[2], radii[0], radii[1], radii[2], density}};
    snprintf(rung->params, sizeof rung->params, "centre %.4g %.4g %.4g radii %.4g %.4g %.4g K=%.4g",
             centre[0], centre[1], centre[2], radii[0], radii[1], radii[2], density);
  }

  int previous = 0;
  for (size_t i = 0; i < sizeof rbf_sizes / sizeof rbf_sizes[0]; i++) {
    scene_config *c = analytic_config(input, FOG_MODEL_RBF);
    int made = c ? fit_rbfs(s, rbf_sizes[i], c->fog.rbfs) : -1;
    if (made < 0) {
      free(c);
      snprintf(err->message, sizeof err->message, "out of memory fitting Gaussians");
      return 1;
    }
    if (made <= previous) { /* the fog holds no more clusters */
      free(c);
      continue;
    }
    previous = made;
    if (!(rung = add_rung(r, c, "rbf", err))) return 1;
    c->fog.rbf_count = made;
    snprintf(rung->name, sizeof rung->name, "rbf %d", made);
    const fog_rbf *g = &c->fog.rbfs[0];
    snprintf(rung->params, sizeof rung->params, "%d Gaussian%s (first: %.4g %.4g %.4g r=%.4g c=%.4g)",
             made, made == 1 ? "" : "s", g->centre[0], g->centre[1], g->centre[2], g->radius,
             g->density);
  }

  /* The fogmap: the input's own, or its VDB projected (model = volume's vdb). */
  const scene_fog_config *in = &input->fog;
  bool has_map = (in->model == FOG_MODEL_FOGMAP && (in->fogmap[0] || in->vdb[0])) ||
                 (in->model == FOG_MODEL_VOLUME && in->vdb[0]);
  for (int degree = 0; has_map && degree < 3; degree++)
    for (size_t m = 0; m < sizeof fogmap_mus / sizeof fogmap_mus[0]; m++) {
      scene_config *c = malloc(sizeof *c);
      if (c) *c = *input;
      if (!(rung = add_rung(r, c, "fogmap", err))) return 1;
      scene_fog_config *f = &c->fog;
      f->model = FOG_MODEL_FOGMAP, f->degree = degree, f->levels = 3,
      f->mu = fogmap_mus[m], f->lod = SCENE_LOD_SWITCH;
      f->volume_step = 0.0;
      snprintf(rung->name, sizeof rung->name, "fogmap %s mu %g", basis_names[degree], f->mu);
      snprintf(rung->params, sizeof rung->params, "basis %s, levels 3, mu %g, %s",
               basis_names[degree], f->mu, f->vdb[0] ? "the VDB frame projected" : "the fogmap");
    }

  if (reference->kind == FOG_MODEL_VOLUME) {
    scene_config *c = malloc(sizeof *c);
    if (c) *c = *input, c->fog.model = FOG_MODEL_VOLUME, c->fog.volume_step = 0.0;
    if (!(rung = add_rung(r, c, "volume", err))) return 1;
    snprintf(rung->params, sizeof rung->params, "the 3D grid, exact");
  } else if (in->model != FOG_MODEL_FOGMAP) {
    scene_config *c = malloc(sizeof *c);
    if (c) *c = *input;
    if (!(rung = add_rung(r, c, fog_model_table[in->model].name, err))) return 1;
    snprintf(rung->name, sizeof rung->name, "%s as given", fog_model_table[in->model].name);
    snprintf(rung->params, sizeof rung->params, "the input's own model");
  }
  return 0;
}

static int compare_doubles(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The rung's error on the views and its GL time (a headless session from view 0). */
static int measure_rung(fit_rung *rung, const fit_desc *d, const fit_views *views,
                        const scene_camera_config *camera, float *pixels, fit_error *err) {
  render_frame_error ferr;
  scene_config *shot = malloc(sizeof *shot);
  if (!shot) {
    snprintf(err->message, sizeof err->message, "out of memory");
    return 1;
  }
  *shot = *rung->config;
  shot->camera = *camera;
  render_session *s = render_session_create(shot, d->width, d->height, &ferr);
  free(shot);
  if (!s) {
    snprintf(err->message, sizeof err->message, "rung %s: %.500s", rung->name, ferr.message);
    return 1;
  }
  fog_model model = render_fog_model(render_session_fog(s));
  vdb_frame frame;
  volume_grid_desc grid;
  bool has_frame = false;
  int status = 1;
  if (model.kind == FOG_MODEL_VOLUME) { /* the session keeps its grid on the GL only */
    render_error rerr = {{0}};
    has_frame = true;
    if (render_fog_load_volume(rung->config, &frame, &grid, &rerr)) {
      snprintf(err->message, sizeof err->message, "rung %s: %.500s", rung->name, rerr.message);
      goto done;
    }
    model.grid3d = &grid;
  }
  fit_views_measure(views, &model, &rung->max_error, &rung->mean_error);
  const frame_pixels out = {.transmittance = pixels};
  double times[64];
  const int n = d->timed_frames < 64 ? d->timed_frames : 64;
  for (int i = -1; i < n; i++) {
    double t0 = app_clock_seconds();
    if (render_session_frame(s, &out, &ferr)) {
      snprintf(err->message, sizeof err->message, "rung %s: %.500s", rung->name, ferr.message);
      goto done;
    }
    if (i >= 0) times[i] = 1e3 * (app_clock_seconds() - t0);
  }
  qsort(times, (size_t)n, sizeof times[0], compare_doubles);
  rung->ms = times[n / 2];
  status = 0;
done:
  if (has_frame) vdb_frame_destroy(&frame);
  render_session_destroy(s);
  return status;
}

int fit_choose(const fit_result *r, double tolerance, bool by_mean) {
  double fastest = HUGE_VAL;
#define WITHIN(g) ((by_mean ? (g).mean_error : (g).max_error) <= tolerance)
  for (int i = 0; i < r->count; i++)
    if (WITHIN(r->rungs[i])) fastest = fmin(fastest, r->rungs[i].ms);
  for (int i = 0; i < r->count; i++) /* ladder order: the simplest of the ties */
    if (WITHIN(r->rungs[i]) && r->rungs[i].ms <= FIT_TIE * fastest) return i;
#undef WITHIN
  return -1;
}

int fit_scene_for_volume(scene_config *cfg, fit_error *err) {
  reference ref;
  if (reference_create(&ref, cfg, err)) return 1;
  double lo[3], hi[3], position[3], target[3];
  bool ok = fit_domain(&ref.model, cfg, lo, hi);
  reference_destroy(&ref);
  if (!ok) {
    snprintf(err->message, sizeof err->message, "%.400s: the grid holds no fog", cfg->path);
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
  *r = (fit_result){.chosen = -1};
}

int fit_run(const fit_desc *d, fit_result *r, fit_error *err) {
  *r = (fit_result){.chosen = -1};
  if (!(d->tolerance > 0) || d->rays_per_side < 1 || d->sample_side < 2 || d->width < 1 ||
      d->height < 1 || d->timed_frames < 1) {
    snprintf(err->message, sizeof err->message,
             "fit: expected tolerance > 0, rays, samples, size and frames >= 1");
    return 1;
  }
  reference ref;
  if (reference_create(&ref, d->input, err)) return 1;
  fit_samples samples = {0};
  fit_views views = {0};
  float *pixels = NULL;
  int status = 1;
  if (!fit_domain(&ref.model, d->input, r->lo, r->hi)) {
    snprintf(err->message, sizeof err->message,
             "%.400s: the fog has no extent to fit (an empty grid, or [box] floor >= top)",
             d->input->path);
    goto done;
  }
  if (fit_samples_create(&samples, &ref.model, r->lo, r->hi, d->sample_side) ||
      fit_views_create(&views, &ref.model, r->lo, r->hi, d->rays_per_side)) {
    snprintf(err->message, sizeof err->message, "out of memory for the fit's samples and rays");
    goto done;
  }
  r->rays = views.count;
  if (make_rungs(r, d->input, &ref.model, &samples, err)) goto done;
  reference_destroy(&ref); /* one GL context at a time: the rungs make their own */
  pixels = malloc((size_t)d->width * d->height * sizeof *pixels);
  if (!pixels) {
    snprintf(err->message, sizeof err->message, "out of memory");
    goto done;
  }
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
  for (int i = 0; i < r->count; i++)
    if (measure_rung(&r->rungs[i], d, &views, &camera, pixels, err)) goto done;
  r->chosen = fit_choose(r, d->tolerance, d->by_mean);
  status = 0;
done:
  reference_destroy(&ref);
  fit_samples_destroy(&samples);
  fit_views_destroy(&views);
  free(pixels);
  if (status) fit_result_destroy(r);
  return status;
}
