/* A VDB sequence played as fog (vdb_source.h). */
#include "app/vdb_source.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void vdb_source_destroy(vdb_source *source) {
  if (source->columns)
    for (int i = 0; i < source->count; i++) vdb_columns_destroy(&source->columns[i]);
  free(source->columns);
  free(source->frame_numbers);
  free(source->mass);
  fogmap_destroy(&source->cache[0]);
  fogmap_destroy(&source->cache[1]);
  *source = (vdb_source){0};
}

int vdb_source_open(vdb_source *source, const vdb_source_desc *desc, fog_error *err) {
  *source = (vdb_source){.cached = {-1, -1}};
  if (!(desc->fps > 0 && desc->fps < INFINITY))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: playback at %g frames per second: "
                    "expected a positive rate", desc->path, desc->fps);
  source->fps = desc->fps;
  source->loop = desc->loop;
  vdb_sequence seq;
  const char *input = desc->path;
  if (vdb_sequence_find(&input, 1, -1, -1, &seq, err)) return 1;
  int status = 1;
  const vdb_columns **cols = NULL;
  if (vdb_sequence_check_gaps(&seq, desc->path, err)) goto done;
  source->count = seq.count;
  source->columns = calloc((size_t)seq.count, sizeof *source->columns);
  source->frame_numbers = malloc((size_t)seq.count * sizeof *source->frame_numbers);
  source->mass = malloc((size_t)seq.count * sizeof *source->mass);
  cols = malloc((size_t)seq.count * sizeof *cols);
  if (!source->columns || !source->frame_numbers || !source->mass || !cols) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%.300s: out of memory for %d frames", desc->path,
             seq.count);
    goto done;
  }
  /* Pass 1 (as `fogpipe import`): read, place and project every frame; keep its columns. */
  /* a sequence's empty frame (before or after the smoke) is a frame without fog */
  vdb_frame_desc frame_desc = {.grid = desc->grid, .up = desc->up, .empty_ok = seq.count > 1};
  int with_fog = 0; /* the frames whose grid is not empty */
  /* placed two ways (a domain's corner apart), the frames would jump, as `import` refuses */
  fog_error perr = {0};
  if (vdb_sequence_check_placement(&seq, &perr)) {
    fog_error_wrap(err, &perr, "%.300s: ", desc->path);
    goto done;
  }
  for (int i = 0; i < seq.count; i++) {
    vdb_frame frame;
    if (vdb_frame_load(seq.paths[i], &frame_desc, &frame, err)) goto done;
    source->columns[i] = frame.columns;
    frame.columns = (vdb_columns){0};
    vdb_frame_destroy(&frame);
    const vdb_columns *c = &source->columns[i];
    source->frame_numbers[i] = seq.frames[i];
    source->mass[i] = c->mass;
    cols[i] = c;
    with_fog += c->width > 0;
  }
  if (!with_fog) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%.300s: every frame's grid '%s' is empty (no active "
             "voxels)", desc->path, desc->grid ? desc->grid : "density");
    goto done;
  }
  /* One fogmap grid (the union of the footprints) and one g for the whole sequence, so
   * that frames can be blended cell by cell and f·g stays comparable between frames. */
  fog_error inner = {0};
  if (vdb_fogmap_place_fit_columns(cols, seq.count, desc->resolution, 0.0, &source->place,
                                   &inner) ||
      vdb_profile_fit_columns(cols, seq.count, &(vdb_profile_desc){0}, &source->profile,
                              &inner) ||
      fogmap_create(&source->cache[0], source->place.width, source->place.height, &inner) ||
      fogmap_create(&source->cache[1], source->place.width, source->place.height, &inner)) {
    fog_error_wrap(err, &inner, "%.300s: ", desc->path);
    goto done;
  }
  status = 0;
done:
  free(cols);
  vdb_sequence_destroy(&seq);
  if (status) vdb_source_destroy(source);
  return status;
}

/* The cached fogmap of frame index, resampling it into the slot not holding `keep`. */
static const fogmap *frame_map(vdb_source *s, int index, int keep, fog_error *err) {
  for (int k = 0; k < 2; k++)
    if (s->cached[k] == index) return &s->cache[k];
  int slot = s->cached[0] == keep ? 1 : 0;
  s->cached[slot] = -1;
  if (vdb_columns_resample(&s->columns[index], &s->place, s->profile.thickness,
                           &s->cache[slot], err))
    return NULL;
  s->cached[slot] = index;
  return &s->cache[slot];
}

void vdb_sequence_position(double p, int count, int loop, int *a, int *b, double *weight) {
  const int n = count;
  /* index / fps · fps may miss the integer by an ulp: snap, so a frame's own time gives
   * that frame exactly. */
  if (fabs(p - nearbyint(p)) < 1e-9 * fmax(1.0, fabs(p))) p = nearbyint(p);
  if (loop) {
    p = fmod(p, (double)n);
    if (p < 0) p += n;
    *a = (int)floor(p);
    if (*a >= n) *a = n - 1; /* p just below n rounded up by the addition */
    *weight = p - *a;
    *b = (*a + 1) % n;
  } else {
    if (p <= 0) p = 0;
    if (p >= n - 1) p = n - 1;
    *a = (int)floor(p);
    *weight = p - *a;
    *b = *a + 1 < n ? *a + 1 : *a;
  }
}

int vdb_source_fogmap_at(vdb_source *source, double t, fogmap *out, fog_error *err) {
  const int w = source->place.width, h = source->place.height, n = source->count;
  if (!out->density && fogmap_create(out, w, h, err)) return 1;
  if (out->width != w || out->height != h) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "vdb source: fogmap is %dx%d, the sequence's grid is %dx%d", out->width, out->height,
             w, h);
    return 1;
  }
  if (!isfinite(t)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "vdb source: time %g is not finite", t);
    return 1;
  }
  int a, b;
  double weight;
  vdb_sequence_position(t * source->fps, n, source->loop, &a, &b, &weight);
  const fogmap *fa = frame_map(source, a, weight > 0 ? b : -1, err);
  if (!fa) return 1;
  size_t cells = (size_t)w * h;
  if (weight == 0) {
    memcpy(out->density, fa->density, cells * sizeof(float));
    return 0;
  }
  const fogmap *fb = frame_map(source, b, a, err);
  if (!fb) return 1;
  /* Linear in time between two frames: f is linear in the column optical depth, so the
   * mass (Σ f·cell²·T) is interpolated linearly too. */
  const float wa = (float)(1.0 - weight), wb = (float)weight;
  for (size_t k = 0; k < cells; k++) out->density[k] = wa * fa->density[k] + wb * fb->density[k];
  return 0;
}

int vdb_frame_index(const int *numbers, int count, int number) {
  if (number < 0) return count - 1;
  for (int i = 0; i < count; i++)
    if (numbers[i] == number) return i;
  return -1;
}

int vdb_source_index_of(const vdb_source *source, int number) {
  return vdb_frame_index(source->frame_numbers, source->count, number);
}

double vdb_source_duration(const vdb_source *source) { return source->count / source->fps; }

int vdb_source_open_config(vdb_source *source, const scene_config *cfg, fog_error *err) {
  const scene_fog_config *f = &cfg->fog;
  fog_error serr = {0};
  vdb_source_desc desc = {.path = f->vdb,
                          .grid = f->vdb_grid[0] ? f->vdb_grid : NULL,
                          .up = f->vdb_up == 1 ? VDB_UP_Y : VDB_UP_Z,
                          .fps = f->vdb_fps,
                          .resolution = f->vdb_resolution,
                          .loop = f->vdb_loop};
  if (vdb_source_open(source, &desc, &serr)) {
    if (f->vdb_line > 0)
      fog_error_wrap(err, &serr, "%.200s:%d: [fog] vdb: ", cfg->path, f->vdb_line);
    else /* a VDB on the command line (fit's INPUT): its own message names the file */
      fog_error_pass(err, &serr);
    return 1;
  }
  return 0;
}

int vdb_source_apply_config(const vdb_source *source, scene_config *cfg, fog_error *err) {
  const vdb_profile *g = &source->profile;
  scene_fog_config *f = &cfg->fog;
  scene_box_config *box = &cfg->box;
  if (!box->origin_set) {
    box->origin[0] = source->place.origin_x;
    box->origin[1] = source->place.origin_z;
  }
  if (!box->cell_size_set) box->cell_size = source->place.cell_size;
  /* g's support: B-spline knots reach (degree+1)/2 spacings beyond the first/last knot
   * (sim/vdb_import.h, vdb_profile). */
  double bottom = g->y_bottom, top = g->y_top;
  if (g->kind == VDB_PROFILE_BSPLINE) {
    double half = 0.5 * (g->degree + 1) * g->spacing;
    bottom = g->origin - half;
    top = g->origin + (g->count - 1) * g->spacing + half;
  }
  if (!box->floor_set) box->floor = bottom;
  if (!box->top_set) box->top = top;
  if (box->top <= box->floor) { /* the file set one of them (the loader checks a pair) */
    const int line = box->top_set ? box->top_line : box->floor_line; /* 0: set in code */
    char at[16] = "";
    if (line > 0) snprintf(at, sizeof at, ":%d", line);
    return fog_fail(err, FOG_ERR_BAD_CONFIG,
                    "%.300s%s: [box] %s = %g lies %s the VDB's fog, whose %s is %g: an empty "
                    "box (set %s too, or move it)", cfg->path, at,
                    box->top_set ? "top" : "floor", box->top_set ? box->top : box->floor,
                    box->top_set ? "below" : "above", box->top_set ? "floor" : "top",
                    box->top_set ? box->floor : box->top, box->top_set ? "floor" : "top");
  }
  if (f->profile_set) return 0;
  if (g->kind == VDB_PROFILE_BSPLINE) {
    f->profile = SCENE_PROFILE_BSPLINE;
    f->profile_degree = g->degree;
    f->profile_origin = g->origin;
    f->profile_spacing = g->spacing;
    f->profile_count = g->count < SCENE_CONFIG_MAX_PROFILE ? g->count : SCENE_CONFIG_MAX_PROFILE;
    memcpy(f->profile_coefficients, g->values, (size_t)f->profile_count * sizeof(double));
  } else if (g->scale_height > 0) {
    f->profile = SCENE_PROFILE_EXPONENTIAL;
    f->fog_height = g->y_bottom;
    f->scale_height = g->scale_height;
  } else {
    f->profile = SCENE_PROFILE_SLAB;
  }
  return 0;
}
