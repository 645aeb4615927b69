/* pipeline_fog: adapter from the pipeline to the GL fog pass; see app/pipeline_fog.h. */
#include "app/pipeline_fog.h"
#include "app/live_rung.h"

#include "render/fog_pass.h"
#include "render/gl_present.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct pipeline_fog {
  int width, height;
  fog_pass *pass;
  gl_target target;     /* colour 0: composited RGBA32F; 1: transmittance R32F; 2: in-scatter */
  int levels;           /* J of the uploaded pyramid */
  int degree;
  bool has_details;
  bool uploaded;
  gl_presenter *presenter;
};

pipeline_fog *pipeline_fog_create(fog_error *err) {
  pipeline_fog *fog = calloc(1, sizeof *fog);
  if (!fog) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    return NULL;
  }
  if (!(fog->pass = fog_pass_create(err))) {
    free(fog);
    return NULL;
  }
  return fog;
}

void pipeline_fog_destroy(pipeline_fog *fog) {
  if (!fog) return;
  gl_presenter_destroy(fog->presenter);
  gl_target_destroy(&fog->target);
  fog_pass_destroy(fog->pass);
  free(fog);
}

int pipeline_fog_resize(pipeline_fog *fog, int width, int height, fog_error *err) {
  gl_target_destroy(&fog->target);
  fog->width = fog->height = 0;
  /* Presenting scales the colour to the window: filtered (read-back uses glReadPixels, and
   * the fog pass never samples this texture, so this changes no recorded pixel). */
  gl_target_desc desc = {.width = width, .height = height,
                         .color_formats = {GL_RGBA32F, GL_R32F, GL_RGBA32F},
                         .linear_color0 = true};
  if (gl_target_create(&fog->target, &desc, err)) return 1;
  fog->width = width;
  fog->height = height;
  return 0;
}

int pipeline_fog_upload(pipeline_fog *fog, const fog_pyramid *pyramid, fog_error *err) {
  if (fog_pass_upload_pyramid(fog->pass, pyramid, err)) return 1;
  fog->levels = pyramid->levels;
  fog->degree = pyramid->degree;
  fog->has_details = pyramid->has_details;
  fog->uploaded = true;
  return 0;
}

int pipeline_fog_upload_sun_shadow(pipeline_fog *fog, const fog_sun_shadow *shadow,
                                   fog_error *err) {
  return fog_pass_upload_sun_shadow(fog->pass, shadow, err);
}

int pipeline_fog_render(pipeline_fog *fog, const camera *cam, const gl_target *scene,
                        const pipeline_fog_settings *settings, fog_error *err) {
  if (!fog->uploaded) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "no fog grids uploaded yet");
    return 1;
  }
  /* The sum of details needs D_1..D_J; a step computed before the method changed has only
   * the approximations, so that one frame uses switching (the same image for mu = 1). */
  fog_lod_method method = (fog_lod_method)settings->lod_method;
  if (method == FOG_LOD_SUM_OF_DETAILS && !fog->has_details) method = FOG_LOD_SWITCH;
  fog_pass_params params = {
      .volume = settings->volume,
      .levels = fog->levels,
      .lod_method = method,
      .mu = settings->mu,
      .fog_colour = {settings->fog_colour[0], settings->fog_colour[1], settings->fog_colour[2]},
      .sun = settings->sun,
      .lamps = settings->lamps,
      .fetch = settings->hardware_filtering && fog->degree > 0 ? FOG_FETCH_HARDWARE
                                                               : FOG_FETCH_MANUAL,
      .resolution_divisor = settings->resolution_divisor,
      .self_shadow = settings->self_shadow,
      .shadow_steps = settings->shadow_steps,
      .shadow_nodes = settings->shadow_nodes,
      .shadow_pieces = settings->shadow_pieces,
      .shaft_samples = settings->shaft_samples,
      .shafts = settings->shafts,
      .lamp_shadows = settings->lamp_shadows,
      .walk = settings->walk,
      .surface_sun = settings->self_shadow != FOG_SUN_SHADOW_NONE ? scene->color[2] : 0,
      .surface_lamps = scene->color[3],
      .model_quadrics = settings->quadrics,
      .model_quadric_count = settings->quadric_count,
  };
  fog_quadric volumes[FOG_MAX_QUADRICS]; /* a quadric rung's, then those beside */
  if (settings->rung) {
    const fog_model *rung = settings->rung;
    params.model = rung->kind;
    params.model_extinction = rung->extinction;
    params.model_y0 = rung->y0;
    params.model_scale_height = rung->scale_height;
    params.model_rbfs = rung->rbfs;
    params.model_rbf_count = rung->kind == FOG_MODEL_RBF ? rung->rbf_count : 0;
    if (rung->kind == FOG_MODEL_QUADRIC) {
      const fog_model drawn =
          live_rung_with_beside(rung, settings->quadrics, settings->quadric_count, volumes);
      params.model_quadrics = drawn.quadrics;
      params.model_quadric_count = drawn.quadric_count;
    }
  }
  gl_target_bind(&fog->target);
  return fog_pass_draw(fog->pass, cam, &params, scene->color[0], scene->color[1], fog->width,
                       fog->height, err);
}

int pipeline_fog_read(pipeline_fog *fog, float *rgba, float *transmittance, float *inscatter,
                      fog_error *err) {
  if (rgba && gl_target_read(&fog->target, 0, 4, rgba, err)) return 1;
  if (transmittance && gl_target_read(&fog->target, 1, 1, transmittance, err)) return 1;
  if (inscatter && gl_target_read(&fog->target, 2, 3, inscatter, err)) return 1;
  return 0;
}

int pipeline_fog_present(pipeline_fog *fog, int width, int height,
                         const display_transform *display, fog_error *err) {
  /* made on the first present: headless recordings never show a window */
  if (!fog->presenter && !(fog->presenter = gl_presenter_create(err))) return 1;
  if (fog->target.framebuffer)
    gl_presenter_draw(fog->presenter, &fog->target, width, height, GL_PRESENT_BILINEAR,
                      display);
  return 0;
}
