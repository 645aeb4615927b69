/* One headless frame of a scene config (render_frame.h). */
#include "app/render_frame.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/render_fog.h"
#include "render/render.h"
#include "sim/sim.h"

int render_frame_load_heightmap(const scene_config *cfg, float **heights, int *width,
                                int *height, render_frame_error *err) {
  *heights = NULL;
  *width = *height = 0;
  if (!cfg->terrain.heightmap[0]) return 0;
  fogmap map;
  sim_error serr;
  /* A 16-bit grey PNG reads as value / 65535: heights in [0, 1]. */
  if (fogmap_load(cfg->terrain.heightmap, &(fogmap_load_desc){0}, &map, &serr)) {
    snprintf(err->message, sizeof err->message, "%.200s:%d: [terrain] heightmap: %.280s", cfg->path,
             cfg->terrain.heightmap_line, serr.message);
    return 1;
  }
  *heights = map.density; /* ownership moves to the caller */
  *width = map.width;
  *height = map.height;
  return 0;
}

int render_frame(const scene_config *cfg, int width, int height, float *rgba,
                 float *transmittance, float *depth, render_frame_info *info,
                 render_frame_error *err) {
  render_error rerr = {0};
  *info = (render_frame_info){0};
  float *heights = NULL;
  int hw = 0, hh = 0;
  if (render_frame_load_heightmap(cfg, &heights, &hw, &hh, err)) return 1;

  int status = 1;
  gl_context *ctx = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &rerr);
  if (!ctx) {
    snprintf(err->message, sizeof err->message, "%s", rerr.message);
    free(heights);
    return 1;
  }
  snprintf(info->gl_description, sizeof info->gl_description, "%s, %s, %s",
           gl_context_platform(ctx), gl_context_version(ctx), gl_context_renderer(ctx));
  scene_desc desc;
  scene_config_scene_desc(cfg, heights, hw, hh, &desc);
  scene_geometry geo;
  scene_pass *pass = NULL;
  gl_target target = {0}, fog_target = {0};
  render_fog fog = {0};
  float *distance = NULL;
  if (scene_geometry_create(&geo, &desc, &rerr)) goto fail_early;
  pass = scene_pass_create(&geo, &rerr);
  if (!pass || scene_target_create(&target, width, height, &rerr)) goto fail;
  camera cam;
  scene_config_camera(cfg, &cam);
  scene_pass_run(pass, &cam, &target);
  size_t pixels = (size_t)width * height;
  distance = malloc(pixels * sizeof *distance);
  if (!distance) {
    snprintf(rerr.message, sizeof rerr.message, "out of memory");
    goto fail;
  }
  if (gl_target_read(&target, 1, 1, distance, &rerr)) goto fail;
  if (scene_config_has_fog(cfg)) {
    /* fogmap -> wavelet pyramid -> fog pass over the scene's colour and distance. */
    if (render_fog_create(&fog, cfg, &rerr)) goto fail;
    if (gl_target_create(&fog_target,
                         &(gl_target_desc){.width = width, .height = height,
                                           .color_formats = {GL_RGBA32F, GL_R32F}},
                         &rerr) ||
        render_fog_draw(&fog, &cam, &target, &fog_target, &rerr))
      goto fail;
    if (rgba && gl_target_read(&fog_target, 0, 4, rgba, &rerr)) goto fail;
    if (transmittance && gl_target_read(&fog_target, 1, 1, transmittance, &rerr)) goto fail;
    info->has_fog = true;
  } else {
    if (rgba && gl_target_read(&target, 0, 4, rgba, &rerr)) goto fail;
    if (transmittance)
      for (size_t k = 0; k < pixels; k++) transmittance[k] = 1.0f;
  }
  if (gl_util_check("render", &rerr)) goto fail;
  if (depth)
    for (size_t k = 0; k < pixels; k++)
      depth[k] = distance[k] >= SCENE_SKY_DISTANCE ? (float)cam.far_plane : distance[k];
  status = 0;
fail:
  if (status) snprintf(err->message, sizeof err->message, "%s", rerr.message);
  free(distance);
  render_fog_destroy(&fog);
  gl_target_destroy(&fog_target);
  gl_target_destroy(&target);
  scene_pass_destroy(pass);
  scene_geometry_destroy(&geo);
  gl_context_destroy(ctx);
  free(heights);
  return status;
fail_early:
  snprintf(err->message, sizeof err->message, "%s", rerr.message);
  gl_context_destroy(ctx);
  free(heights);
  return 1;
}
