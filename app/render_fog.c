/* The static fog of a scene config (render_fog.h). */
#include "app/render_fog.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/vdb_source.h"
#include "app/volume_blend.h"
#include "sim/sim.h"

void render_fog_destroy(render_fog *fog) {
  fog_pyramid_destroy(&fog->pyramid);
  free(fog->rbfs);
  rbf_carrier_destroy(fog->carrier);
  if (fog->pass) fog_pass_destroy(fog->pass);
  for (int k = 0; k < 2; k++) vdb_frame_destroy(&fog->played[k]);
  fog_sun_shadow_destroy(&fog->sun_shadow);
  fog_perlin_destroy(&fog->perlin);
  *fog = (render_fog){0};
}

/* Where a VDB error comes from: "CONFIG:LINE: [fog] vdb: " for a config's line, or nothing
 * for a VDB given on the command line (fit's INPUT: its path is the config's, line 0), whose
 * own message names the file: "x.vdb:0: [fog] vdb:" pointed at a line nobody wrote. */
static void vdb_error_wrap(fog_error *err, const fog_error *serr, const scene_config *cfg,
                           const char *detail) {
  if (cfg->fog.vdb_line > 0)
    fog_error_wrap(err, serr, "%.200s:%d: [fog] vdb: %s", cfg->path, cfg->fog.vdb_line, detail);
  else
    fog_error_wrap(err, serr, "%s", detail);
}

/* "no frame N" of a sequence: at the config's vdb_frame or vdb line, or (a VDB on the
 * command line: no line) at the sequence's pattern. */
static void vdb_no_frame(fog_error *err, const scene_config *cfg, int first, int last) {
  const scene_fog_config *f = &cfg->fog;
  const int line = f->vdb_frame_line ? f->vdb_frame_line : f->vdb_line;
  if (line > 0)
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "%.200s:%d: [fog] %s: no frame %d in the sequence (frames %d..%d)", cfg->path, line,
             f->vdb_frame_line ? "vdb_frame" : "vdb", f->vdb_frame, first, last);
  else
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%.400s: no frame %d in the sequence (frames %d..%d)",
             f->vdb, f->vdb_frame, first, last);
}

/* The fog of a `[fog] vdb` config: frame cfg->fog.vdb_frame of the sequence (the last by
 * default), placed and profiled by the sequence (vdb_source_apply_config). */
static int render_vdb_fog(render_fog *fog, const scene_config *cfg, fog_error *err) {
  vdb_source source;
  fog_error cerr;
  if (vdb_source_open_config(&source, cfg, &cerr)) {
    fog_error_pass(err, &cerr);
    return 1;
  }
  int status = 1;
  fogmap map = {0};
  scene_config *placed = malloc(sizeof *placed);
  int index = vdb_source_index_of(&source, cfg->fog.vdb_frame);
  if (!placed) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    goto done;
  }
  if (index < 0) {
    vdb_no_frame(err, cfg, source.frame_numbers[0], source.frame_numbers[source.count - 1]);
    goto done;
  }
  *placed = *cfg;
  if (vdb_source_apply_config(&source, placed, err)) goto done;
  fog_error serr;
  if (vdb_source_fogmap_at(&source, index / source.fps, &map, &serr)) {
    vdb_error_wrap(err, &serr, cfg, "");
    goto done;
  }
  status = render_fog_create_map(fog, placed, &map, err);
done:
  fogmap_destroy(&map);
  free(placed);
  vdb_source_destroy(&source);
  return status;
}

int render_fog_volume_sequence(const scene_config *cfg, vdb_sequence *seq, fog_error *err) {
  fog_error serr = {0};
  const char *input = cfg->fog.vdb;
  if (vdb_sequence_find(&input, 1, -1, -1, seq, &serr)) {
    vdb_error_wrap(err, &serr, cfg, "");
    return 1;
  }
  /* every frame placed one way and no hole in the numbers, as the fogmap's vdb_source
   * refuses (the player steps through the files in order: frames 3, 40 drew as neighbours) */
  if (vdb_sequence_check_placement(seq, &serr) ||
      vdb_sequence_check_gaps(seq, cfg->fog.vdb, &serr)) {
    vdb_error_wrap(err, &serr, cfg, "");
    vdb_sequence_destroy(seq);
    return 1;
  }
  /* every frame sound before any is drawn (the volume reads its frames as they play; the
   * fogmap's source reads them all at once): a damaged frame 47 stopped a recording after
   * 46 frames, and `fit` in the middle of its rungs (vdb_precheck_file: ~1 ms a file) */
  for (int i = 0; i < seq->count; i++)
    if (vdb_precheck_file(seq->paths[i], &serr)) {
      char detail[32];
      snprintf(detail, sizeof detail, "frame %d: ", seq->frames[i]);
      vdb_error_wrap(err, &serr, cfg, detail);
      vdb_sequence_destroy(seq);
      return 1;
    }
  return 0;
}

/* One file of the sequence as the volume's grid (render_fog_load_volume). An empty grid
 * in a sequence of more than one frame (before the smoke, or after it) is a frame without
 * fog, as the fogmap's source plays it: one voxel of 0. */
static int load_volume_file(const scene_config *cfg, const vdb_sequence *seq, int index,
                            vdb_frame *frame, volume_grid_desc *grid, fog_error *err) {
  const scene_fog_config *f = &cfg->fog;
  fog_error serr = {0};
  if (vdb_frame_load(seq->paths[index],
                     &(vdb_frame_desc){.grid = f->vdb_grid,
                                       .up = f->vdb_up == 1 ? VDB_UP_Y : VDB_UP_Z,
                                       .keep_grid = 1, .grid_only = 1,
                                       .empty_ok = seq->count > 1},
                     frame, &serr)) {
    vdb_error_wrap(err, &serr, cfg, "");
    return 1;
  }
  vdb_dense_grid *g = &frame->grid;
  const vdb_world_map *w = &frame->world;
  size_t n = (size_t)g->dim[0] * g->dim[1] * g->dim[2], fog = 0;
  while (fog < n && !(g->values[fog] > 0.0f)) fog++;
  if (fog == n && seq->count == 1) {
    /* one file alone with nothing to draw: what a wrong [fog] vdb_grid looks like (as a
     * fogmap, and to import, it is refused the same way; a sequence plays such a frame) */
    fog_fail(err, FOG_ERR_BAD_FILE, "%.300s:%d: [fog] vdb: %.300s: grid '%s' holds no fog "
             "(its %lld active voxels are all 0%s)", cfg->path, f->vdb_line,
             seq->paths[index], f->vdb_grid[0] ? f->vdb_grid : "density", g->active_voxels,
             g->negative_voxels > 0 ? " once its negative ones are clamped: a signed grid, "
                                      "not a density?" : "");
    vdb_frame_destroy(frame);
    return 1;
  }
  for (size_t i = 0; i < n; i++) g->values[i] = (float)(f->density_scale * g->values[i]);
  /* u_c = (p_a - base_a) / step_a - index_min_c for the world axis a fed by index axis c. */
  *grid = (volume_grid_desc){.dim = {g->dim[0], g->dim[1], g->dim[2]}, .values = g->values};
  for (int a = 0; a < 3; a++) {
    const int c = w->index_axis[a];
    grid->index_from_world[c][a] = 1.0 / w->step[a];
    grid->index_offset[c] = -w->base[a] / w->step[a] - g->index_min[c];
  }
  return 0;
}

int render_fog_load_volume(const scene_config *cfg, vdb_frame *frame, volume_grid_desc *grid,
                           fog_error *err) {
  const scene_fog_config *f = &cfg->fog;
  *frame = (vdb_frame){0};
  vdb_sequence seq;
  if (render_fog_volume_sequence(cfg, &seq, err)) return 1;
  int index = vdb_frame_index(seq.frames, seq.count, f->vdb_frame);
  int status = 1;
  if (index < 0)
    vdb_no_frame(err, cfg, seq.frames[0], seq.frames[seq.count - 1]);
  else
    status = load_volume_file(cfg, &seq, index, frame, grid, err);
  vdb_sequence_destroy(&seq);
  return status;
}

/* Sequence index `index` from the two-frame cache (a slot is loaded when it holds a grid),
 * read into the slot that does not hold `keep` (the other frame of the pair being shown)
 * when it is not there. */
static int played_frame(render_fog *fog, const scene_config *cfg, const vdb_sequence *seq,
                        int index, int keep, int *slot, fog_error *err) {
  for (int k = 0; k < 2; k++)
    if (fog->played[k].grid.values && fog->played_index[k] == index) {
      *slot = k;
      return 0;
    }
  int k = fog->played[0].grid.values && fog->played_index[0] == keep ? 1 : 0;
  vdb_frame_destroy(&fog->played[k]);
  if (load_volume_file(cfg, seq, index, &fog->played[k], &fog->played_grid[k], err))
    return 1;
  fog->played_index[k] = index;
  *slot = k;
  return 0;
}

void render_fog_set_shafts(render_fog *fog, const scene_config *cfg, const sun_shadow_map *map) {
  fog->shafts = cfg->fog.albedo > 0 && cfg->shadow.shafts ? map : NULL;
}

void render_fog_set_lamp_shadows(render_fog *fog, const lamp_shadow_maps *maps) {
  fog->lamp_shadows = maps;
}

fog_model render_fog_model(render_fog *fog) {
  const fog_pass_params *p = &fog->params;
  /* fog_lod's details start at D_1 (fog_pyramid_lod): this one passed the pyramid's unused
   * slot 0 as D_1, an empty grid, and the sum of details walked it to NaN on the CPU */
  fog->lod = fog_pyramid_lod(&fog->pyramid, p->mu);
  return (fog_model){.kind = p->model, .volume = &fog->volume, .lod = &fog->lod,
                     .lod_method = p->lod_method, .extinction = p->model_extinction,
                     .y0 = p->model_y0, .scale_height = p->model_scale_height,
                     .rbfs = fog->rbfs, .rbf_count = p->model_rbf_count,
                     .grid3d = fog->grid3d, .quadrics = fog->quadrics,
                     .quadric_count = p->model_quadric_count, .fog_start = p->model_fog_start,
                     .fog_end = p->model_fog_end, .perlin = p->model_perlin,
                     .time = p->model_time, .perlin_integral = p->model_perlin_integral};
}

/* The fog's shadows for the model (docs/light.md): how T_s is found, and the sun's
 * optical-depth volume computed and uploaded where the model needs one. Only with
 * [fog] albedo > 0: albedo 0 is eq. 4, the image as it was. */
static int render_fog_shadow(render_fog *fog, const scene_config *cfg, const fog_model *model,
                             fog_error *err) {
  fog_pass_params *p = &fog->params;
  bool on = cfg->fog.albedo > 0 && cfg->shadow.fog_self_shadow;
  p->self_shadow = on ? fog_sun_shadow_kind_of(model, p->sun.direction) : FOG_SUN_SHADOW_NONE;
  p->shadow_steps = cfg->shadow.steps;
  p->shadow_nodes = cfg->shadow.nodes;
  p->shadow_pieces = scene_config_light_rule(cfg).pieces;
  p->shaft_samples = cfg->shadow.shaft_samples;
  fog->ground_shadow = p->self_shadow != FOG_SUN_SHADOW_NONE;
  if (p->self_shadow != FOG_SUN_SHADOW_VOLUME) return 0;
  const int n = cfg->shadow.resolution;
  if (!fog->sun_shadow.optical_depth &&
      fog_sun_shadow_create(&fog->sun_shadow, &(fog_sun_shadow_desc){.across = n, .along = n},
                            err))
    return 1;
  if (fog_sun_shadow_compute(&fog->sun_shadow, model, p->sun.direction, 2, err)) return 1;
  return fog_pass_upload_sun_shadow(fog->pass, &fog->sun_shadow, err);
}

int render_fog_set_volume_time(render_fog *fog, const scene_config *cfg, const vdb_sequence *seq,
                               int a, int b, double w, fog_error *err) {
  int sa, sb;
  if (played_frame(fog, cfg, seq, a, b, &sa, err)) return 1;
  const volume_grid_desc *shown = &fog->played_grid[sa];
  volume_grid_desc blended = {.values = NULL};
  if (w > 0.0 && b != a) {
    if (played_frame(fog, cfg, seq, b, a, &sb, err)) return 1;
    if (volume_blend_placed_alike(&fog->played[sa], &fog->played[sb])) {
      if (volume_blend(&fog->played[sa], &fog->played_grid[sa], &fog->played[sb],
                      &fog->played_grid[sb], w, &blended, err))
        return 1;
      shown = &blended;
    } else if (w >= 0.5) {
      shown = &fog->played_grid[sb]; /* placed differently: the nearer frame, unblended */
    }
  }
  fog->grid3d = shown;
  fog_model model = render_fog_model(fog);
  int status = fog_pass_upload_grid3d(fog->pass, shown, err) ||
               render_fog_shadow(fog, cfg, &model, err);
  fog->grid3d = NULL;
  free((float *)blended.values);
  return status;
}

/* model = volume: the grid of render_fog_load_volume, integrated exactly, or marched at
 * volume_step when that is set. */
static int render_volume_fog(render_fog *fog, const scene_config *cfg, fog_error *err) {
  const scene_fog_config *f = &cfg->fog;
  vdb_frame frame;
  volume_grid_desc grid;
  if (render_fog_load_volume(cfg, &frame, &grid, err)) return 1;
  fog->params = (fog_pass_params){
      .model = FOG_MODEL_VOLUME,
      .integrator = f->volume_step > 0 ? FOG_INTEGRATOR_MARCH : FOG_INTEGRATOR_EXACT,
      .fetch = f->filtering == SCENE_FILTERING_HARDWARE ? FOG_FETCH_HARDWARE : FOG_FETCH_MANUAL,
      .model_grid3d_step = f->volume_step,
      .fog_colour = {f->colour[0], f->colour[1], f->colour[2]},
      .sun = scene_config_fog_sun(cfg),
      .lamps = scene_config_fog_lamps(cfg),
      .walk = scene_config_walk(cfg),
  };
  fog->grid3d = &grid;
  fog_model model = render_fog_model(fog);
  int status = !(fog->pass = fog_pass_create(err)) || fog_pass_upload_grid3d(fog->pass, &grid, err) ||
               render_fog_shadow(fog, cfg, &model, err);
  fog->grid3d = NULL;
  vdb_frame_destroy(&frame); /* the GL holds the grid now */
  return status;
}

/* [fog] rbf_carrier = sim: the emitters' puffs at `time` carried by the [sim] flow over the
 * terrain (app/rbf_carrier.h), after the rbf lines in fog->rbfs (room made); the flow made
 * again when the config's emitters or [sim] keys changed. Returns their count, -1 on error. */
static int carried_puffs(render_fog *fog, const scene_config *cfg, double time, fog_error *err) {
  const rbf_carrier_desc desc = {
      .emitters = cfg->fog.rbf_emitters, .emitter_count = cfg->fog.rbf_emitter_count,
      .origin = {cfg->terrain.origin[0], cfg->terrain.origin[2]},
      .size = {cfg->terrain.size[0], cfg->terrain.size[1]}, .grid = RBF_CARRIER_GRID,
      .step = RBF_CARRIER_STEP, .wind = {cfg->sim.wind[0], cfg->sim.wind[1]},
      .turbulence = cfg->sim.turbulence, .viscosity = cfg->sim.viscosity,
      .seed = scene_config_sim_seed(cfg)};
  if (fog->carrier && !rbf_carrier_serves(fog->carrier, &desc)) {
    rbf_carrier_destroy(fog->carrier);
    fog->carrier = NULL;
  }
  if (!fog->carrier && !(fog->carrier = rbf_carrier_create(&desc, err))) {
    fog_error_wrap(err, err, "%.200s:%d: [fog] rbf_carrier: ", cfg->path,
                   cfg->fog.rbf_carrier_line);
    return -1;
  }
  const int count = rbf_carrier_puffs(fog->carrier, time, fog->rbfs + fog->rbf_count,
                                      fog->rbf_capacity - fog->rbf_count, err);
  if (count < 0)
    fog_error_wrap(err, err, "%.200s:%d: [fog] rbf_carrier: ", cfg->path,
                   cfg->fog.rbf_carrier_line);
  return count;
}

/* model = rbf: the rbf lines and the emitters' puffs at `time`, density_scale applied. */
static int rbfs_at(render_fog *fog, const scene_config *cfg, double time, fog_error *err) {
  const scene_fog_config *f = &cfg->fog;
  int n = f->rbf_count;
  for (int e = 0; e < f->rbf_emitter_count; e++) n += fog_rbf_emitter_count(&f->rbf_emitters[e]);
  if (!fog->rbfs || n > fog->rbf_capacity) {
    fog_rbf *grown = realloc(fog->rbfs, sizeof(fog_rbf) * (size_t)(n > 0 ? n : 1));
    if (!grown) {
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "rbf fog: out of memory (%d Gaussians)", n);
      return 1;
    }
    fog->rbfs = grown, fog->rbf_capacity = n > 0 ? n : 1;
  }
  fog->rbf_count = 0;
  for (int i = 0; i < f->rbf_count; i++) fog->rbfs[fog->rbf_count++] = f->rbfs[i];
  if (f->rbf_carrier == SCENE_RBF_CARRIER_SIM && f->rbf_emitter_count > 0) {
    int puffs = carried_puffs(fog, cfg, time, err);
    if (puffs < 0) return 1;
    fog->rbf_count += puffs;
  } else {
    for (int e = 0; e < f->rbf_emitter_count; e++)
      fog->rbf_count += fog_rbf_emitter_puffs(&f->rbf_emitters[e], time,
                                              fog->rbfs + fog->rbf_count, n - fog->rbf_count);
  }
  for (int i = 0; i < fog->rbf_count; i++) fog->rbfs[i].density *= f->density_scale;
  fog->params.model_rbfs = fog->rbfs;
  fog->params.model_rbf_count = fog->rbf_count;
  return 0;
}

int render_fog_set_rbfs(render_fog *fog, const scene_config *cfg, double time, fog_error *err) {
  if (cfg->fog.model != FOG_MODEL_RBF) return 0;
  if (rbfs_at(fog, cfg, time, err)) return 1;
  fog_model model = render_fog_model(fog);
  return render_fog_shadow(fog, cfg, &model, err);
}

/* The config's fog reads the Perlin octaves: model = perlin, or quadric volumes with noise. */
static bool uses_octaves(const scene_config *cfg) {
  return cfg->fog.model == FOG_MODEL_PERLIN ||
         (cfg->fog.model == FOG_MODEL_QUADRIC &&
          fog_quadric_noisy(cfg->fog.quadrics, cfg->fog.quadric_count));
}

bool render_fog_animated(const scene_config *cfg) {
  return (cfg->fog.model == FOG_MODEL_RBF && cfg->fog.rbf_emitter_count > 0) ||
         uses_octaves(cfg);
}

int render_fog_set_time(render_fog *fog, const scene_config *cfg, double time, fog_error *err) {
  if (!render_fog_animated(cfg)) return 0;
  if (uses_octaves(cfg))
    fog->params.model_time = time;
  else if (rbfs_at(fog, cfg, time, err))
    return 1;
  fog_model model = render_fog_model(fog);
  return render_fog_shadow(fog, cfg, &model, err);
}

/* model = perlin (or quadric volumes with noise): the octaves of the config, the Perlin
 * fog filling the terrain's footprint between [box] floor and top (checked by the config),
 * uploaded to the pass. */
static int perlin_fog(render_fog *fog, const scene_config *cfg, fog_error *err) {
  const scene_fog_config *f = &cfg->fog;
  fog_perlin_desc desc = fog_perlin_desc_default();
  desc.seed = f->perlin_seed;
  desc.octaves = f->perlin_octaves;
  desc.size = f->perlin_size;
  desc.feature_size = f->perlin_feature;
  for (int i = 0; i < desc.octaves; i++)
    for (int a = 0; a < 3; a++)
      desc.wind[i][a] = f->perlin_wind[(f->perlin_wind_count == 3 ? 0 : 3 * i) + a];
  const scene_terrain_config *t = &cfg->terrain;
  desc.lo[0] = t->origin[0], desc.lo[1] = cfg->box.floor, desc.lo[2] = t->origin[2];
  desc.hi[0] = t->origin[0] + t->size[0], desc.hi[1] = cfg->box.top,
  desc.hi[2] = t->origin[2] + t->size[1];
  if (f->model != FOG_MODEL_PERLIN) /* the volumes' turbulence reads no box: any valid one */
    for (int a = 0; a < 3; a++) desc.lo[a] = -1.0, desc.hi[a] = 1.0;
  if (fog_perlin_create(&fog->perlin, &desc, err)) {
    fog_error_wrap(err, err, "%.200s:%d: [fog] model = %s: ", cfg->path, f->model_line,
                   fog_model_table[f->model].name);
    return 1;
  }
  fog->params.model_perlin = &fog->perlin;
  fog->params.model_perlin_integral = (fog_perlin_integral)f->perlin_integral;
  return fog_pass_upload_perlin(fog->pass, &fog->perlin, err);
}

/* An analytic model of the ladder (docs/architecture.md, the model table): no fogmap and no
 * transform, the pass's parameters alone (render/fog_models.def lists the keys each reads;
 * docs/config.md what they mean). */
static int render_analytic_fog(render_fog *fog, const scene_config *cfg, fog_error *err) {
  const scene_fog_config *f = &cfg->fog;
  bool rbf = f->model == FOG_MODEL_RBF;
  bool quadric = f->model == FOG_MODEL_QUADRIC;
  const int quadric_count = quadric ? scene_config_fog_quadrics(cfg, fog->quadrics) : 0;
  fog->params = (fog_pass_params){
      .model = f->model,
      .model_extinction = rbf ? f->rbf_base : f->density_scale,
      .model_y0 = f->fog_height,
      .model_scale_height = f->scale_height,
      .model_fog_start = f->fog_start,
      .model_fog_end = f->fog_end,
      .model_quadrics = fog->quadrics,
      .model_quadric_count = quadric_count,
      .fog_colour = {f->colour[0], f->colour[1], f->colour[2]},
      .sun = scene_config_fog_sun(cfg),
      .lamps = scene_config_fog_lamps(cfg),
      .walk = scene_config_walk(cfg),
  };
  /* a carrier kept from the fog this one replaces (render_fog_remake) goes on from its own
   * time, not from 0: asking 0 would replay its flow from the start */
  const double time = fog->carrier ? fmax(0.0, rbf_carrier_time(fog->carrier)) : 0.0;
  if (rbf && rbfs_at(fog, cfg, time, err)) return 1;
  if (!(fog->pass = fog_pass_create(err)) ||
      (uses_octaves(cfg) && perlin_fog(fog, cfg, err)))
    return 1;
  fog_model model = render_fog_model(fog);
  return render_fog_shadow(fog, cfg, &model, err);
}

/* Quadric volumes beside another model's fog ([fog] quadric lines with any model): their
 * densities times density_scale, as model = quadric takes them; the pass adds their depth,
 * extinction and shadow (fog_model_quadrics_beside). */
static void render_fog_beside(render_fog *fog, const scene_config *cfg) {
  if (cfg->fog.model == FOG_MODEL_QUADRIC || cfg->fog.quadric_count == 0) return;
  fog->params.model_quadrics = fog->quadrics;
  fog->params.model_quadric_count = scene_config_fog_quadrics(cfg, fog->quadrics);
}

static int render_fog_create_model(render_fog *fog, const scene_config *cfg, rbf_carrier *kept,
                                   fog_error *err);
static int render_file_fog(render_fog *fog, const scene_config *cfg, fog_error *err);

int render_fog_create(render_fog *fog, const scene_config *cfg, fog_error *err) {
  int status = render_fog_create_model(fog, cfg, NULL, err);
  if (!status) render_fog_beside(fog, cfg);
  return status;
}

int render_fog_remake(render_fog *fog, const scene_config *cfg, fog_error *err) {
  rbf_carrier *kept = fog->carrier;
  fog->carrier = NULL;
  render_fog_destroy(fog);
  int status = render_fog_create_model(fog, cfg, kept, err);
  if (!status) render_fog_beside(fog, cfg);
  return status;
}

/* kept: a carrier of RBF puffs the fog takes over (NULL: none). */
static int render_fog_create_model(render_fog *fog, const scene_config *cfg, rbf_carrier *kept,
                                   fog_error *err) {
  *fog = (render_fog){.carrier = kept};
  const scene_fog_config *f = &cfg->fog;
  if (f->model == FOG_MODEL_VOLUME) {
    int status = render_volume_fog(fog, cfg, err);
    if (status) render_fog_destroy(fog); /* keeps err */
    return status;
  }
  if (f->model != FOG_MODEL_FOGMAP) return render_analytic_fog(fog, cfg, err);
  /* The fogmap's paths begin from a zeroed fog (render_fog_create_map): the carrier goes
   * back in after them, for the fog after this one (a window's rung, then its config). */
  fog->carrier = NULL;
  int status = f->vdb[0] ? render_vdb_fog(fog, cfg, err) : render_file_fog(fog, cfg, err);
  if (status) rbf_carrier_destroy(kept);
  else fog->carrier = kept;
  return status;
}

/* The fogmap of cfg's file ([fog] fogmap, or a bake's frame 1). */
static int render_file_fog(render_fog *fog, const scene_config *cfg, fog_error *err) {
  const scene_fog_config *f = &cfg->fog;
  /* A bake ([fog] sequence) shows its frame 1 as a still (record plays it). */
  char first[SCENE_CONFIG_PATH_MAX + 32];
  const bool baked = f->sequence[0] && scene_config_sequence_path(f->sequence, 1, first,
                                                                  sizeof first);
  const char *path = baked ? first : f->fogmap;
  const char *key = baked ? "sequence" : "fogmap";
  const int line = baked ? f->sequence_line : f->fogmap_line;
  fogmap map = {0};
  fog_error serr;
  fogmap_load_desc load = {.channel = f->channel[0] ? f->channel : NULL,
                           .channel_setting = "[fog] channel"};
  if (!path[0]) {
    /* no fogmap, quadric volumes beside: the clear air the pipeline's simulation starts
     * from */
    if (fogmap_create(&map, SCENE_CLEAR_AIR_CELLS, SCENE_CLEAR_AIR_CELLS, &serr))
      return fog_error_pass(err, &serr);
    const int status = render_fog_create_map(fog, cfg, &map, err);
    fogmap_destroy(&map);
    return status;
  }
  if (fogmap_load(path, &load, &map, &serr)) {
    fog_error_wrap(err, &serr, "%.200s:%d: [fog] %s: ", cfg->path, line, key);
    return 1;
  }
  int status = render_fog_create_map(fog, cfg, &map, err);
  fogmap_destroy(&map);
  if (status) { /* name the file: the GL's limits, the transform's sizes are about it */
    fog_error_wrap(err, err, "%.120s:%d: [fog] %s: %.120s: ", cfg->path, line, key, path);
  }
  return status;
}

int render_fog_create_map(render_fog *fog, const scene_config *cfg, const fogmap *given,
                          fog_error *err) {
  *fog = (render_fog){0};
  const scene_fog_config *f = &cfg->fog;
  const fogmap map = *given;
  transform_boundary boundary =
      f->boundary == SCENE_BOUNDARY_PERIODIC ? TRANSFORM_PERIODIC : TRANSFORM_SYMMETRIC;
  int levels = f->levels;
  int max_levels = transform_max_levels(map.width, map.height, boundary);
  if (levels > max_levels) levels = max_levels;
  if (levels > FOG_MAX_LEVELS) levels = FOG_MAX_LEVELS;
  int status = 1;
  bool sum = f->lod == SCENE_LOD_SUM;
  fog_error perr = {0};
  if (fog_pyramid_create(&fog->pyramid, map.density, map.width, map.height, f->degree, levels,
                         boundary, &perr)) {
    fog_error_wrap(err, &perr, "%.200s: [fog] transform: ", cfg->path);
    goto done;
  }
  fog->map_width = map.width;
  fog->map_height = map.height;
  const scene_fog_shape shape = scene_config_fog_shape(cfg);
  fog->volume = scene_config_fog_volume(cfg, map.width, map.height, &shape);
  if (fog->volume.profile.kind == FOG_PROFILE_BSPLINE) {
    /* a copy: cfg may be a temporary (the VDB path) */
    memcpy(fog->profile_coefficients, f->profile_coefficients,
           (size_t)f->profile_count * sizeof(double));
    fog->volume.profile.coefficients = fog->profile_coefficients;
  }
  /* The LOD variants need the whole pyramid; with mu = 1 the switch method shows A_J only,
   * which is the fogmap itself. */
  fog->params = (fog_pass_params){
      .volume = &fog->volume,
      .levels = levels,
      .lod_method = sum ? FOG_LOD_SUM_OF_DETAILS : FOG_LOD_SWITCH,
      .mu = f->mu,
      .fog_colour = {f->colour[0], f->colour[1], f->colour[2]},
      .sun = scene_config_fog_sun(cfg),
      .lamps = scene_config_fog_lamps(cfg),
      .walk = scene_config_walk(cfg),
      .fetch = f->filtering == SCENE_FILTERING_HARDWARE ? FOG_FETCH_HARDWARE : FOG_FETCH_MANUAL,
  };
  if (!(fog->pass = fog_pass_create(err))) goto done;
  if (fog_pass_upload_pyramid(fog->pass, &fog->pyramid, err)) goto done;
  fog_model model = render_fog_model(fog);
  if (render_fog_shadow(fog, cfg, &model, err)) goto done;
  render_fog_beside(fog, cfg);
  status = 0;
done:
  if (status) {
    /* keep the message: render_fog_destroy clears the struct only */
    render_fog_destroy(fog);
  }
  return status;
}

int render_fog_draw(render_fog *fog, const camera *cam, const gl_target *scene,
                    const gl_target *out, fog_error *err) {
  gl_target_bind(out);
  fog->params.volume = &fog->volume; /* the struct may have been copied */
  fog->params.model_rbfs = fog->rbfs;
  fog->params.model_quadrics = fog->quadrics;
  if (fog->params.model_perlin) fog->params.model_perlin = &fog->perlin;
  fog->volume.profile.coefficients = fog->profile_coefficients;
  fog->params.surface_sun = fog->ground_shadow ? scene->color[2] : 0; /* 0: no attachment 2 */
  fog->params.surface_lamps = scene->color[3]; /* the lamps' share (0: none) */
  /* no shafts of a sun below the horizon (its light is 0 there; the look-ups cost) */
  fog->params.shafts = fog_sun_above_horizon(fog->params.sun.direction) > 0 ? fog->shafts : NULL;
  fog->params.lamp_shadows = fog->lamp_shadows;
  return fog_pass_draw(fog->pass, cam, &fog->params, scene->color[0], scene->color[1],
                       scene->width, scene->height, err);
}
