/* pipeline_fog: the pipeline's view of the GL fog pass (render/fog_pass.h): upload one
 * step's pyramid of transform_grids, draw the fog over the scene pass's colour and
 * surface-distance textures into colour + transmittance, read back, present to a window.
 * Kept apart from pipeline.c so the pipeline's threading does not depend on the pass's
 * details. */
#ifndef FOGPIPE_APP_PIPELINE_FOG_H
#define FOGPIPE_APP_PIPELINE_FOG_H

#include <stdbool.h>

#include "render/camera.h"
#include "render/display.h"
#include "render/fog_field.h"
#include "render/fog_light.h"
#include "render/fog_pass.h"
#include "render/fog_sun_shadow.h"
#include "render/sun_shadow_map.h"
#include "render/gl_util.h"
#include "transform/fog_error.h"
#include "transform/transform.h"


typedef struct pipeline_fog_settings {
  const fog_volume *volume;
  float mu;
  int lod_method; /* fog_lod_method */
  float fog_colour[3];
  fog_sun sun;
  fog_lamps lamps;
  bool hardware_filtering;
  int resolution_divisor; /* fog_pass_params.resolution_divisor */
  /* fog_pass_params.self_shadow, shadow_steps and shadow_nodes; with a shadow the fog also dims the
   * surfaces' sun-lit share (the scene target's attachment 2). */
  fog_sun_shadow_kind self_shadow;
  int shadow_steps, shadow_nodes;
  bool shadow_pieces;
  int shaft_samples; /* fog_pass_params.shaft_samples */
  const sun_shadow_map *shafts; /* fog_pass_params.shafts: NULL none */
  const lamp_shadow_maps *lamp_shadows; /* fog_pass_params.lamp_shadows: NULL none */
  fog_walk_settings walk;       /* fog_pass_params.walk */
  /* A model drawn in the fogmap's place (the demo's live rung; NULL: the fogmap): its kind,
   * extinction, y0 and scale height, Gaussians or quadric volumes (drawn before those
   * beside). self_shadow is then that model's kind, and a volume the rung's own. */
  const fog_model *rung;
  /* fog_pass_params.model_quadrics: quadric volumes beside the fogmap (densities scaled) */
  const fog_quadric *quadrics;
  int quadric_count;
} pipeline_fog_settings;

typedef struct pipeline_fog pipeline_fog;

pipeline_fog *pipeline_fog_create(fog_error *err);
void pipeline_fog_destroy(pipeline_fog *fog);
int pipeline_fog_resize(pipeline_fog *fog, int width, int height, fog_error *err);
/* Copies the grids (render/fog_field.h) into textures (re-created when their sizes change). */
int pipeline_fog_upload(pipeline_fog *fog, const fog_pyramid *pyramid, fog_error *err);
/* Uploads the sun's optical-depth volume (settings.self_shadow = FOG_SUN_SHADOW_VOLUME). */
int pipeline_fog_upload_sun_shadow(pipeline_fog *fog, const fog_sun_shadow *shadow, fog_error *err);
/* Draws the fog over the scene target (colour 0, distance 1) into the fog target. */
int pipeline_fog_render(pipeline_fog *fog, const camera *cam, const gl_target *scene,
                        const pipeline_fog_settings *settings, fog_error *err);
/* Rows top first; any pointer may be NULL (inscatter: 3 floats a pixel). */
int pipeline_fog_read(pipeline_fog *fog, float *rgba, float *transmittance, float *inscatter,
                      fog_error *err);
/* Draws the fog target's colour to the default framebuffer at width x height through the
 * display transform. */
int pipeline_fog_present(pipeline_fog *fog, int width, int height,
                         const display_transform *display, fog_error *err);

#endif
