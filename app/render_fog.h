/* The static fog of a scene config for headless frames (`fogpipe render`) and the window's
 * fog as held (app/window_session.c, made again after each panel edit): the config's
 * fogmap, its wavelet pyramid (transform/), uploaded to the GL fog pass
 * (render/fog_pass.h). The live and recorded animation goes through app/pipeline.h
 * instead; this path renders the fogmap exactly as the file holds it, without a
 * simulation step. */
#ifndef FOGPIPE_APP_RENDER_FOG_H
#define FOGPIPE_APP_RENDER_FOG_H

#include "app/config.h"
#include "app/rbf_carrier.h"
#include "render/fog_field.h"
#include "sim/sim.h"
#include "render/fog_pass.h"
#include "render/gl_util.h"
#include "transform/transform.h"


typedef struct render_fog {
  int map_width, map_height;
  fog_pyramid pyramid; /* model = fogmap: the map's (details too, whatever the LOD method) */
  fog_volume volume;
  double profile_coefficients[SCENE_CONFIG_MAX_PROFILE]; /* volume.profile's own copy */
  /* model = rbf: params.model_rbfs, density_scale applied: the config's rbf lines, then its
   * emitters' puffs at the time shown (render_fog_set_time); rbf_count of them */
  fog_rbf *rbfs;
  int rbf_count, rbf_capacity;
  rbf_carrier *carrier; /* [fog] rbf_carrier = sim: the flow carrying the puffs (owned) */
  fog_quadric quadrics[FOG_MAX_QUADRICS]; /* params.model_quadrics, density_scale applied:
                                             model = quadric's, or those beside the model */
  fog_perlin perlin; /* model = perlin: params.model_perlin, its octaves uploaded */
  fog_pass_params params;
  fog_pass *pass;
  /* The fog's shadow (docs/light.md): the sun's optical-depth volume where the model needs
   * one (params.self_shadow), and whether the fog shadows the surfaces. */
  fog_sun_shadow sun_shadow;
  bool ground_shadow;
  /* Light shafts: the scene pass's sun shadow map (render_fog_set_shafts); NULL: none. */
  const sun_shadow_map *shafts;
  /* The lamps' shadow cubes (render_fog_set_lamp_shadows); NULL: none. */
  const lamp_shadow_maps *lamp_shadows;
  fog_lod lod;                     /* model = fogmap: the pyramid as render_fog_model's */
  const volume_grid_desc *grid3d;  /* model = volume: the grid shown, while it is at hand */
  /* model = volume played (render_fog_set_volume_time): the last two VDB frames read (a
   * slot holds one when its grid has values), by sequence index, so a time between the
   * same two frames reads no file. */
  vdb_frame played[2];
  volume_grid_desc played_grid[2];
  int played_index[2];
} render_fog;

/* Loads the fogmap (cfg->fog.fogmap or, for a VDB sequence, frame cfg->fog.vdb_frame of
 * cfg->fog.vdb placed and profiled by the sequence: app/vdb_source.h), transforms it, creates the fog pass and
 * uploads the grids; for an analytic model (cfg->fog.model) only the pass and its
 * parameters. Needs a current GL context. Errors name the config's file:line. */
int render_fog_create(render_fog *fog, const scene_config *cfg, fog_error *err);
/* The same for a fogmap in memory (a VDB frame: app/vdb_source.h); cfg gives the box,
 * profile and rendering settings, cfg->fog.fogmap is not read. map is not kept. */
int render_fog_create_map(render_fog *fog, const scene_config *cfg, const fogmap *map,
                          fog_error *err);
void render_fog_destroy(render_fog *fog);
/* The fog of cfg in place of fog's (destroyed), keeping the flow that carries RBF puffs
 * ([fog] rbf_carrier = sim), through fog of other models too: the new fog goes on from the
 * flow's time instead of replaying it from its start, as a window's edits and rungs need.
 * On failure, as after a failed render_fog_create, render_fog_destroy frees what is left. */
int render_fog_remake(render_fog *fog, const scene_config *cfg, fog_error *err);
/* model = volume: cfg->fog.vdb as a sequence (vdb_sequence_destroy when done). Errors
 * name [fog] vdb's file:line. */
int render_fog_volume_sequence(const scene_config *cfg, vdb_sequence *seq, fog_error *err);
/* model = volume's grid: frame cfg->fog.vdb_frame of cfg->fog.vdb (the last for -1) with
 * density_scale applied, placed where the bake put it (the VDB's transform, its up axis
 * turned into Y; [box] does not move it). grid->values live in *frame: vdb_frame_destroy
 * when done (also safe after a failure). Errors name the config's file:line. */
int render_fog_load_volume(const scene_config *cfg, vdb_frame *frame, volume_grid_desc *grid,
                           fog_error *err);
/* model = volume: shows (1 - w) F[a] + w F[b] of seq (cfg's sequence; a, b its indices, as
 * vdb_sequence_position gives them) from now on, the two grids laid over each other voxel
 * by voxel on the union of their boxes: the fog at a time between two frames, as the 2.5D
 * fogmaps blend (the exact integral is linear in the density, so its optical depth is the
 * blend of the frames'). Frames placed differently (another transform) are not blended:
 * the nearer one shows. For the fog made by render_fog_create from cfg. */
int render_fog_set_volume_time(render_fog *fog, const scene_config *cfg, const vdb_sequence *seq,
                               int a, int b, double w, fog_error *err);
/* Whether the fog changes with time by itself: model = rbf with emitters (puffs carried by
 * the wind or the simulation's flow), model = perlin (its octaves drift). */
bool render_fog_animated(const scene_config *cfg);
/* model = rbf with emitters: the puffs at `time` seconds from now on (carried by the flow,
 * [fog] rbf_carrier = sim: a time before the last asked replays the flow from its start,
 * app/rbf_carrier.h); model = perlin: its
 * octaves where they have drifted by then (and the sun's volume
 * of the fog's shadow, where the model has one). For the fog made by render_fog_create from
 * cfg; nothing to do for other fog. */
int render_fog_set_time(render_fog *fog, const scene_config *cfg, double time, fog_error *err);
/* model = rbf: the config's Gaussians read again (a brush changed them, and their count;
 * app/rbf_brush.h) with its emitters' puffs at `time`, and the sun's shadow volume of them.
 * For the fog made by render_fog_create from a config of the same model. */
int render_fog_set_rbfs(render_fog *fog, const scene_config *cfg, double time, fog_error *err);
/* The scene pass's sun shadow map for light shafts ([light] shafts, with albedo > 0); the
 * map must outlive the fog's draws. */
void render_fog_set_shafts(render_fog *fog, const scene_config *cfg, const sun_shadow_map *map);
/* The scene pass's lamp shadow cubes (scene_pass_lamp_shadows, for the same lamps as the
 * fog's), read at each draw. */
void render_fog_set_lamp_shadows(render_fog *fog, const lamp_shadow_maps *maps);
/* The fog as the model table sees it (fog_models.h), pointing into fog (the volume's grid
 * only while render_fog has it: during creation and set_volume_time). Its eye is the
 * origin: the classic factors (linear, exp2) count distances from the camera that draws
 * them, which the caller sets. */
fog_model render_fog_model(render_fog *fog);
/* Draws the fog over the scene target (colour 0, distance 1) into out (RGBA32F colour 0,
 * R32F transmittance 1), both width x height. */
int render_fog_draw(render_fog *fog, const camera *cam, const gl_target *scene,
                    const gl_target *out, fog_error *err);

#endif
