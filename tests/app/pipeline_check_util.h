/* What every pipeline check starts with: a scene config loaded, the headless GL context
 * made current (pipeline_create needs one), the config's camera; and a frame read back. */
#ifndef FOGPIPE_TEST_PIPELINE_CHECK_UTIL_H
#define FOGPIPE_TEST_PIPELINE_CHECK_UTIL_H

#include <stdio.h>

#include "app/config.h"
#include "app/pipeline.h"
#include "render/gl_context.h"

/* One frame drawn (waiting for the step) and read back into out; non-zero (printed) on
 * failure. */
static inline int pipeline_check_frame(pipeline *p, const camera *cam, const frame_pixels *out) {
  fog_error err = {0};
  if (pipeline_frame(p, cam, true, &err) || pipeline_read_frame(p, out, &err)) {
    fprintf(stderr, "frame: %s\n", err.message);
    return 1;
  }
  return 0;
}

/* A synchronous pipeline (each frame waits for its step) of width x height at 24 frames a
 * second; NULL (the reason printed) when it cannot be made. */
static inline pipeline *pipeline_check_make(const scene_config *cfg, int width, int height) {
  fog_error err = {0};
  pipeline *p = pipeline_create(&(pipeline_desc){.config = cfg, .width = width,
                                                 .height = height, .frame_seconds = 1.0 / 24.0,
                                                 .synchronous = true},
                                &err);
  if (!p) fprintf(stderr, "pipeline_create: %s\n", err.message);
  return p;
}

/* NULL (the reason printed) when the config or the context fails. */
static inline gl_context *pipeline_check_begin(const char *config_path, scene_config *cfg,
                                               camera *cam) {
  fog_error cerr = {0};
  if (scene_config_load(config_path, cfg, &cerr)) {
    fprintf(stderr, "%s\n", cerr.message);
    return NULL;
  }
  fog_error rerr = {0};
  gl_context *gl = gl_context_create(&(gl_context_desc){0}, &rerr);
  if (!gl) fprintf(stderr, "%s\n", rerr.message);
  scene_config_camera(cfg, cam);
  return gl;
}

#endif
