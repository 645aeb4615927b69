/* The rungs of a fit (app/fit_rungs.h). */
#define _POSIX_C_SOURCE 200809L
#include "app/fit_rungs.h"

#include <errno.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/fit_fogmap.h"

/* Gaussians per bank: 1 to 64 (a config holds SCENE_CONFIG_MAX_RBFS). */
static const int rbf_sizes[] = {1, 2, 4, 8, 16, 32, 64};
_Static_assert(SCENE_CONFIG_MAX_RBFS >= 64, "a config holds the largest bank");
/* The fogmap's rungs: each basis at three LOD factors (levels 3, switching). */
static const char *const basis_names[] = {"haar", "linear", "quadratic"};
static const double fogmap_mus[] = {1.0, 0.5, 0.25};

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

static fit_rung *add_rung(fit_result *r, scene_config *cfg, const char *family, fog_error *err) {
  if (!cfg) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the rungs");
    return NULL;
  }
  if (r->count == FIT_MAX_RUNGS) { /* a bug: the list below holds at most this many */
    free(cfg);
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "more than %d rungs", FIT_MAX_RUNGS);
    return NULL;
  }
  fit_rung *rung = &r->rungs[r->count++];
  *rung = (fit_rung){.config = cfg};
  snprintf(rung->family, sizeof rung->family, "%s", family);
  snprintf(rung->name, sizeof rung->name, "%s", family);
  return rung;
}

/* The worst |delta tau| of a bank over the views of every frame. */
static double bank_error(const fit_views *views, int view_sets, const fog_rbf *g, int n) {
  const fog_model m = {.kind = FOG_MODEL_RBF, .rbfs = g, .rbf_count = n};
  double worst = 0.0;
  for (int f = 0; f < view_sets; f++) {
    double max_error, mean_error;
    fit_views_measure(&views[f], &m, &max_error, &mean_error);
    /* NaN sticks: fmax drops it, and a bank measured NaN on a frame read as fine */
    if (!isnan(worst) && !(max_error <= worst)) worst = max_error;
  }
  return worst;
}

/* The moments' amplitudes, or those re-fitted on the views' optical depths
 * (fit_views_rbf_amplitudes), whichever misses the views by less: the least squares lowers
 * the mean error but not always the worst (docs/fit.md). */
static int refine_amplitudes(const fit_views *views, int view_sets, fog_rbf *g, int n) {
  fog_rbf *refit = malloc((size_t)n * sizeof *refit);
  if (!refit) return 1;
  memcpy(refit, g, (size_t)n * sizeof *refit);
  if (fit_views_rbf_amplitudes(views, view_sets, refit, n)) {
    free(refit);
    return 1;
  }
  if (bank_error(views, view_sets, refit, n) < bank_error(views, view_sets, g, n))
    memcpy(g, refit, (size_t)n * sizeof *refit);
  free(refit);
  return 0;
}

/* Homogeneous, the classic factors of distance, and height fog. */
static int add_analytic_rungs(fit_result *r, const scene_config *input, const fit_samples *s,
                              const fit_views *views, int view_sets, fog_error *err) {
  fit_rung *rung;
  double k = fit_homogeneous(s);
  if (!(rung = add_rung(r, analytic_config(input, FOG_MODEL_HOMOGENEOUS), "homogeneous", err)))
    return 1;
  rung->config->fog.density_scale = k;
  snprintf(rung->params, sizeof rung->params, "K=%.6g", k);

  /* the classic factors: a fog of the camera's distance, fitted on the views */
  double start, end;
  fit_views_linear(views, view_sets, &start, &end);
  if (!(rung = add_rung(r, analytic_config(input, FOG_MODEL_LINEAR), "linear", err))) return 1;
  rung->config->fog.fog_start = start, rung->config->fog.fog_end = end;
  snprintf(rung->params, sizeof rung->params, "start=%.6g end=%.6g (from the camera)", start, end);
  double a = fit_views_exp2(views, view_sets);
  if (a > 0.0) {
    if (!(rung = add_rung(r, analytic_config(input, FOG_MODEL_EXP2), "exp2", err))) return 1;
    rung->config->fog.density_scale = a;
    snprintf(rung->params, sizeof rung->params, "density=%.6g (from the camera)", a);
  }

  double y0, scale_height;
  if (fit_height(s, &k, &y0, &scale_height)) {
    scene_config *c = analytic_config(input, FOG_MODEL_HEIGHT);
    if (c) c->fog.density_scale = k, c->fog.fog_height = y0;
    const double least = c ? scene_config_min_scale_height(c) : 0.0;
    /* a scene that holds no H of the key's range (K past what float holds below y0): no
     * height rung */
    if (!(least <= SCENE_MAX_SCALE_HEIGHT)) {
      free(c);
      return 0;
    }
    if (!(rung = add_rung(r, c, "height", err))) return 1;
    scene_fog_config *f = &rung->config->fog;
    f->density_scale = k, f->fog_height = y0, f->scale_height = scale_height;
    /* The scene draws the fog down to the lowest point its view reaches (the camera, the
     * terrain's base), which the fog's domain need not: below y0 it grows as e^{(y0-y)/H},
     * and a scene whose fog passes float there does not load (scene_config_min_scale_height:
     * a fog floating 1000 above the terrain fitted H = 6.9 where 32.5 was the least). The rung
     * takes the least H the scene draws, and its error is measured as drawn. */
    if (scale_height < least) f->scale_height = 1.001 * least;
    f->scale_height = fmin(f->scale_height, SCENE_MAX_SCALE_HEIGHT); /* the key's range */
    snprintf(rung->params, sizeof rung->params, "K=%.6g y0=%.6g H=%.6g", k, y0, f->scale_height);
    if (f->scale_height != scale_height)
      snprintf(rung->params + strlen(rung->params), sizeof rung->params - strlen(rung->params),
               " (fitted %.4g: %s)", scale_height,
               scale_height < least ? "the least the scene holds" : "the key's largest");
  }
  return 0;
}

/* Banks of quadric volumes, one per cluster of the density (app/fit_density.h), of one
 * shape, and how a config line writes each (app/config.c's shapes). */
typedef enum bank_shape { BANK_ELLIPSOIDS, BANK_CYLINDERS, BANK_ORIENTED } bank_shape;
static const struct {
  const char *one, *many;
  int (*fit)(const fit_samples *, int, fog_quadric *);
} bank_shapes[] = {[BANK_ELLIPSOIDS] = {"ellipsoid", "ellipsoids", fit_ellipsoids},
                   [BANK_CYLINDERS] = {"cylinder", "cylinders", fit_cylinders},
                   [BANK_ORIENTED] = {"oriented ellipsoid", "oriented ellipsoids",
                                      fit_oriented_ellipsoids}};

/* The config line of a fitted volume, from its box: ellipsoid X Y Z RX RY RZ DENSITY,
 * cylinder X Y Z R HEIGHT DENSITY (standing on its base), or general A..J XMIN YMIN ZMIN
 * XMAX YMAX ZMAX DENSITY. */
static struct scene_quadric_line bank_line(bank_shape shape, const fog_quadric *v) {
  if (shape == BANK_ORIENTED) {
    struct scene_quadric_line line = {.shape = 4, .count = 17};
    memcpy(line.numbers, v->q, sizeof v->q);
    memcpy(line.numbers + 10, v->lo, sizeof v->lo);
    memcpy(line.numbers + 13, v->hi, sizeof v->hi);
    line.numbers[16] = v->density;
    return line;
  }
  double c[3], half[3];
  for (int a = 0; a < 3; a++) c[a] = 0.5 * (v->lo[a] + v->hi[a]), half[a] = 0.5 * (v->hi[a] - v->lo[a]);
  if (shape == BANK_CYLINDERS)
    return (struct scene_quadric_line){
        .shape = 2, .count = 6, .numbers = {c[0], v->lo[1], c[2], half[0], 2 * half[1], v->density}};
  return (struct scene_quadric_line){
      .shape = 1, .count = 7, .numbers = {c[0], c[1], c[2], half[0], half[1], half[2], v->density}};
}

/* Banks of `from`, 2 from, ... up to FOG_MAX_QUADRICS volumes (the most a scene holds), one
 * rung each while the fog holds more clusters. */
static int add_quadric_banks(fit_result *r, const scene_config *input, const fit_samples *s,
                             bank_shape shape, int from, fog_error *err) {
  int previous = from - 1;
  for (int count = from; count <= FOG_MAX_QUADRICS; count *= 2) {
    scene_config *c = analytic_config(input, FOG_MODEL_QUADRIC);
    int made = c ? bank_shapes[shape].fit(s, count, c->fog.quadrics) : -1;
    if (made < 0) {
      free(c);
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory fitting %s", bank_shapes[shape].many);
      return 1;
    }
    if (made <= previous) { /* the fog holds no more clusters */
      free(c);
      continue;
    }
    previous = made;
    fit_rung *rung = add_rung(r, c, "quadric", err);
    if (!rung) return 1;
    c->fog.quadric_count = made;
    for (int q = 0; q < made; q++) c->fog.quadric_lines[q] = bank_line(shape, &c->fog.quadrics[q]);
    if (made == 1)
      snprintf(rung->name, sizeof rung->name, "%s", bank_shapes[shape].one);
    else
      snprintf(rung->name, sizeof rung->name, "%s %d", bank_shapes[shape].many, made);
    if (made == 1)
      snprintf(rung->params, sizeof rung->params, "one %s of the density's moments",
               bank_shapes[shape].one);
    else
      snprintf(rung->params, sizeof rung->params, "%d %s, one per cluster of the density", made,
               bank_shapes[shape].many);
  }
  return 0;
}

/* One ellipsoid of the density's moments, then banks of ellipsoids, of cylinders and of
 * oriented ellipsoids. */
static int add_quadric_rungs(fit_result *r, const scene_config *input, const fit_samples *s,
                             fog_error *err) {
  fit_rung *rung;
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

  return add_quadric_banks(r, input, s, BANK_ELLIPSOIDS, 2, err) ||
         add_quadric_banks(r, input, s, BANK_CYLINDERS, 1, err) ||
         add_quadric_banks(r, input, s, BANK_ORIENTED, 1, err);
}

/* Banks of Gaussians of growing size, their amplitudes refined on the views. */
static int add_rbf_rungs(fit_result *r, const scene_config *input, const fit_samples *s,
                         const fit_views *views, int view_sets, fog_error *err) {
  fit_rung *rung;
  int previous = 0;
  for (size_t i = 0; i < sizeof rbf_sizes / sizeof rbf_sizes[0]; i++) {
    scene_config *c = analytic_config(input, FOG_MODEL_RBF);
    int made = c ? fit_rbfs(s, rbf_sizes[i], c->fog.rbfs) : -1;
    if (made < 0) {
      free(c);
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory fitting Gaussians");
      return 1;
    }
    if (made <= previous) { /* the fog holds no more clusters */
      free(c);
      continue;
    }
    if (made > 1 && refine_amplitudes(views, view_sets, c->fog.rbfs, made)) {
      free(c);
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory fitting Gaussians");
      return 1;
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
  return 0;
}

/* The fogmap: the input's own, or its VDB projected (model = volume's vdb), or the
 * samples of an analytic input's density projected (app/fit_fogmap.h) into a file of the
 * result's scratch folder. The classic factors are fog of the camera's distance, which no
 * fogmap holds. */
static int add_fogmap_rungs(fit_result *r, const scene_config *input, const fog_model *reference,
                            const fit_samples *s, fog_error *err) {
  fit_rung *rung;
  const scene_fog_config *in = &input->fog;
  bool has_map = (in->model == FOG_MODEL_FOGMAP && (in->fogmap[0] || in->vdb[0])) ||
                 (in->model == FOG_MODEL_VOLUME && in->vdb[0]);
  bool projects = !has_map && reference->kind != FOG_MODEL_VOLUME &&
                  in->model != FOG_MODEL_LINEAR && in->model != FOG_MODEL_EXP2;
  char projected[sizeof r->scratch + 32] = "";
  fit_fogmap ff = {0};
  int projected_status = projects ? fit_fogmap_project(reference, s->lo, s->hi,
                                                      s->n[0] > s->n[2] ? s->n[0] : s->n[2],
                                                      &ff, err)
                                   : 0;
  if (projected_status > 0) return 1;
  if (projected_status < 0) projects = false; /* no fog to project: no fogmap rungs */
  if (projects) {
    const char *temporary = getenv("TMPDIR");
    if (!temporary || !*temporary) temporary = "/tmp";
    const int n = snprintf(r->scratch, sizeof r->scratch, "%s/fogpipe-fit-XXXXXX", temporary);
    fog_error serr = {0};
    if (n >= (int)sizeof r->scratch || !mkdtemp(r->scratch)) {
      fog_fail(err, FOG_ERR_FILE_ACCESS, "the fogmap rungs: no folder in %.400s (TMPDIR): %s",
               temporary, n >= (int)sizeof r->scratch ? "its path is too long" : strerror(errno));
      r->scratch[0] = '\0';
      fit_fogmap_destroy(&ff);
      return 1;
    }
    snprintf(projected, sizeof projected, "%s/%s", r->scratch, FIT_FOGMAP_FILE);
    if (fogmap_save_exr(projected, &ff.map, &serr)) {
      fog_error_wrap(err, &serr, "the fogmap rungs: ");
      fit_fogmap_destroy(&ff);
      return 1;
    }
  }
  for (int degree = 0; (has_map || projects) && degree < 3; degree++)
    for (size_t m = 0; m < sizeof fogmap_mus / sizeof fogmap_mus[0]; m++) {
      scene_config *c = malloc(sizeof *c);
      if (c) *c = *input;
      if (c && projects) fit_fogmap_apply(&ff, projected, c);
      if (!(rung = add_rung(r, c, "fogmap", err))) {
        fit_fogmap_destroy(&ff);
        return 1;
      }
      scene_fog_config *f = &c->fog;
      f->model = FOG_MODEL_FOGMAP, f->degree = degree, f->levels = 3,
      f->mu = fogmap_mus[m], f->lod = SCENE_LOD_SWITCH;
      f->volume_step = 0.0;
      snprintf(rung->name, sizeof rung->name, "fogmap %s mu %g", basis_names[degree], f->mu);
      snprintf(rung->params, sizeof rung->params, "basis %s, levels 3, mu %g, %s",
               basis_names[degree], f->mu,
               projects ? "the density projected (a 2D map and a profile)"
               : f->vdb[0] ? "the VDB frame projected" : "the fogmap");
    }
  fit_fogmap_destroy(&ff);
  return 0;
}

/* Whether the input is one of the fixed fogmap rungs (its own map at levels 3, switching,
 * a mu of the ladder's: the default scene), which then stands for it as given. */
static bool fixed_fogmap_rung(const scene_fog_config *in) {
  if (in->model != FOG_MODEL_FOGMAP || !in->fogmap[0] || in->levels != 3 ||
      in->lod != SCENE_LOD_SWITCH)
    return false;
  for (size_t m = 0; m < sizeof fogmap_mus / sizeof fogmap_mus[0]; m++)
    if (in->mu == fogmap_mus[m]) return true;
  return false;
}

/* The ladder's rungs for this input, in order, their parameters fitted to the samples; the
 * last rung is the richest: the 3D volume, or the input's own model (left out where a fixed
 * fogmap rung is the input). */
int fit_rungs_make(fit_result *r, const scene_config *input, const fog_model *reference,
                   const fit_samples *s, const fit_views *views, int view_sets, fog_error *err) {
  if (add_analytic_rungs(r, input, s, views, view_sets, err) ||
      add_quadric_rungs(r, input, s, err) ||
      add_rbf_rungs(r, input, s, views, view_sets, err) ||
      add_fogmap_rungs(r, input, reference, s, err))
    return 1;
  const scene_fog_config *in = &input->fog;
  fit_rung *rung;
  if (reference->kind == FOG_MODEL_VOLUME) {
    scene_config *c = malloc(sizeof *c);
    if (c) *c = *input, c->fog.model = FOG_MODEL_VOLUME, c->fog.volume_step = 0.0;
    if (!(rung = add_rung(r, c, "volume", err))) return 1;
    snprintf(rung->params, sizeof rung->params, "the 3D grid, exact");
  } else if (!fixed_fogmap_rung(in)) {
    /* the input as it is: a fogmap too (its own basis, levels, mu and LOD, or a baked
     * sequence), unless a fixed fogmap rung above is it: without it an exact input could
     * end with no rung within a tight tolerance */
    scene_config *c = malloc(sizeof *c);
    if (c) *c = *input;
    if (!(rung = add_rung(r, c, fog_model_table[in->model].name, err))) return 1;
    snprintf(rung->name, sizeof rung->name, "%s as given", fog_model_table[in->model].name);
    snprintf(rung->params, sizeof rung->params, "the input's own model");
  }
  /* Fogshop's lamp integral is for Gaussians alone: a rung of another model, or with quadric
   * volumes beside its Gaussians, lights its lamps with ours (an rbf input with
   * `lamp_integral = fogshop` made every other rung a scene the pass and the loader refuse) */
  for (int i = 0; i < r->count; i++) {
    scene_config *c = r->rungs[i].config;
    if (c->lamp_method.integral == FOG_LAMP_FOGSHOP &&
        (c->fog.model != FOG_MODEL_RBF || c->fog.quadric_count > 0))
      c->lamp_method.integral = FOG_LAMP_ANGLE;
  }
  return 0;
}
