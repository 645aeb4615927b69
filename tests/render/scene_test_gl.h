/* Shared set-up for the scene pass tests: a headless context, a scene's geometry from its
 * scene_desc, the scene pass over it and a W x H scene target.
 *
 *   scene_test_gl s;
 *   if (!scene_test_gl_open(&s, &desc, W, H, &err)) return test_finish("test_x");
 *   ... scene_pass_run(s.pass, &cam, &s.target), s.geo.terrain ...
 *   scene_test_gl_teardown(&s);
 *
 * scene_test_gl_setup makes the same without a context, in the one already current.
 *
 * Header-only (static inline) like fog_test_gl.h: tests/CMakeLists.txt builds each test_*.c
 * on its own. */
#ifndef FOGPIPE_TESTS_RENDER_SCENE_TEST_GL_H
#define FOGPIPE_TESTS_RENDER_SCENE_TEST_GL_H

#include <stdbool.h>

#include "render/render.h"
#include "test_util.h"

typedef struct scene_test_gl {
  gl_context *ctx; /* scene_test_gl_open's own; NULL after scene_test_gl_setup */
  scene_geometry geo;
  scene_pass *pass;
  gl_target target;
  bool has_geo, has_target;
} scene_test_gl;

static inline void scene_test_gl_teardown(scene_test_gl *s) {
  if (s->has_target) gl_target_destroy(&s->target);
  if (s->pass) scene_pass_destroy(s->pass);
  if (s->has_geo) scene_geometry_destroy(&s->geo);
  if (s->ctx) gl_context_destroy(s->ctx);
  *s = (scene_test_gl){0};
}

/* CHECKs each step (geometry, pass, target) and returns true when all three exist. On false
 * it has released what it made and the test should end (the failures are recorded). */
static inline bool scene_test_gl_setup(scene_test_gl *s, const scene_desc *desc, int width,
                                       int height, fog_error *err) {
  *s = (scene_test_gl){0};
  s->has_geo = scene_geometry_create(&s->geo, desc, err) == 0;
  CHECK(s->has_geo, "geometry: %s", err->message);
  if (s->has_geo)
    CHECK((s->pass = scene_pass_create(&s->geo, err)) != NULL, "scene pass: %s", err->message);
  if (s->pass) {
    s->has_target = scene_target_create(&s->target, width, height, err) == 0;
    CHECK(s->has_target, "scene target: %s", err->message);
  }
  if (!s->has_target) scene_test_gl_teardown(s);
  return s->has_target;
}

/* scene_test_gl_setup in a headless context of its own (destroyed by the teardown). */
static inline bool scene_test_gl_open(scene_test_gl *s, const scene_desc *desc, int width,
                                      int height, fog_error *err) {
  gl_context *ctx = gl_context_create(NULL, err);
  CHECK(ctx != NULL, "context: %s", err->message);
  if (!ctx) return false;
  if (!scene_test_gl_setup(s, desc, width, height, err)) {
    gl_context_destroy(ctx);
    return false;
  }
  s->ctx = ctx;
  return true;
}

/* The valley several scene tests look at: a 1000-unit procedural terrain (129^2 samples, up
 * to 160 high) and two grey boxes, a low one and a tall post, the default light. */
static inline scene_desc scene_test_valley(void) {
  return (scene_desc){
      .terrain = {.origin = {-500, -20, -500}, .size = {1000, 1000}, .height = 160,
                  .resolution = 129, .seed = 3, .octaves = 6, .frequency = 3,
                  .persistence = 0.5},
      .boxes = {{.center = {0, -120}, .size = {30, 40, 20}, .colour = SCENE_BOX_GREY},
                {.center = {60, -200}, .size = {15, 80, 15}, .colour = SCENE_BOX_GREY}},
      .box_count = 2,
      .light = scene_light_default(),
  };
}

#endif
