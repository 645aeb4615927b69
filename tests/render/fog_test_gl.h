/* Shared GL set-up for the fog pass tests: a headless context, the fog pass, a W x H
 * target (colour RGBA32F + transmittance R32F, what fog_pass_draw writes) and the input
 * textures the pass reads (gl.surface_tex, gl.dist_tex: surface colour and distance, rows
 * uploaded top first).
 *
 *   fog_test_gl gl;
 *   if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_x");
 *   ... fog_pass_draw(gl.pass, ...), gl_target_read(&gl.target, ...) ...
 *   fog_test_gl_teardown(&gl);
 *
 * Header-only (static inline) like fog_test_scene.h: tests/CMakeLists.txt builds each
 * test_*.c on its own. */
#ifndef FOGPIPE_TESTS_RENDER_FOG_TEST_GL_H
#define FOGPIPE_TESTS_RENDER_FOG_TEST_GL_H

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "render/render.h"
#include "test_util.h"

typedef struct fog_test_gl {
  gl_context *ctx;
  fog_pass *pass;
  gl_target target;
  bool has_target;
  int width, height;
  /* the pass's inputs, width x height: the surface colour (RGBA32F, all zero until a test
   * uploads its own) and the surface distance (R32F, undefined until uploaded) */
  GLuint surface_tex, dist_tex;
  float *dist; /* width x height, rows top first: the distances fog_test_gl_set_ground sent */
} fog_test_gl;

/* A width x height texture with NEAREST filtering: no mipmaps, so without it the texture
 * would be incomplete and texelFetch would read 0. data may be NULL (contents undefined). */
static inline GLuint fog_test_gl_texture(const fog_test_gl *gl, GLenum internal, GLenum format,
                                         const float *data) {
  GLuint t;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);
  glTexImage2D(GL_TEXTURE_2D, 0, internal, gl->width, gl->height, 0, format, GL_FLOAT, data);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

static inline void fog_test_gl_teardown(fog_test_gl *gl) {
  free(gl->dist);
  if (gl->surface_tex) glDeleteTextures(1, &gl->surface_tex);
  if (gl->dist_tex) glDeleteTextures(1, &gl->dist_tex);
  if (gl->has_target) gl_target_destroy(&gl->target);
  if (gl->pass) fog_pass_destroy(gl->pass);
  if (gl->ctx) gl_context_destroy(gl->ctx);
  *gl = (fog_test_gl){0};
}

/* CHECKs each step (context, pass, target) and returns true when all three exist (and
 * the two input textures are made). On
 * false it has released what it made and the test should return test_finish(...) at
 * once (the failures are recorded). */
static inline bool fog_test_gl_setup(fog_test_gl *gl, int width, int height, fog_error *err) {
  *gl = (fog_test_gl){.width = width, .height = height};
  gl->ctx = gl_context_create(&(gl_context_desc){0}, err);
  CHECK(gl->ctx != NULL, "headless context: %s", err->message);
  if (gl->ctx) CHECK((gl->pass = fog_pass_create(err)) != NULL, "fog_pass_create: %s", err->message);
  if (gl->pass) {
    gl->has_target =
        gl_target_create(&gl->target,
                         &(gl_target_desc){.width = width, .height = height,
                                           .color_formats = {GL_RGBA32F, GL_R32F}},
                         err) == 0;
    CHECK(gl->has_target, "target: %s", err->message);
  }
  if (!gl->has_target) {
    fog_test_gl_teardown(gl);
    return false;
  }
  float *zeros = calloc((size_t)width * height * 4, sizeof(float));
  gl->dist = calloc((size_t)width * height, sizeof(float));
  CHECK(zeros && gl->dist, "out of memory");
  if (!zeros || !gl->dist) {
    free(zeros);
    fog_test_gl_teardown(gl);
    return false;
  }
  gl->surface_tex = fog_test_gl_texture(gl, GL_RGBA32F, GL_RGBA, zeros);
  gl->dist_tex = fog_test_gl_texture(gl, GL_R32F, GL_RED, NULL);
  free(zeros);
  return true;
}

/* Uploads an image stored rows top first (as camera_ray's pixel rows and the CPU
 * references) into a texture of the target's size: GL rows are bottom-up, so flipped. */
static inline void fog_test_gl_upload_flipped(const fog_test_gl *gl, GLuint tex, GLenum format,
                                              int channels, const float *top_first) {
  const int w = gl->width, h = gl->height;
  float *flipped = malloc(sizeof(float) * w * h * channels);
  for (int y = 0; y < h; y++)
    for (int i = 0; i < w * channels; i++)
      flipped[(size_t)(h - 1 - y) * w * channels + i] = top_first[(size_t)y * w * channels + i];
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, format, GL_FLOAT, flipped);
  free(flipped);
}

/* The distance along the target's pixel rays (rows top first) to the plane y = ground_y,
 * 1e30 for sky: the surface distance texture the scene pass would write. */
static inline void fog_test_gl_ground_distance(const fog_test_gl *gl, const camera *cam,
                                               double ground_y, float *dist) {
  for (int py = 0; py < gl->height; py++)
    for (int px = 0; px < gl->width; px++) {
      double o[3], d[3];
      camera_ray(cam, px, py, gl->width, gl->height, o, d);
      double t = (d[1] < 0.0) ? (ground_y - o[1]) / d[1] : -1.0;
      dist[py * gl->width + px] = (t > 0.0) ? (float)t : 1e30f;
    }
}

/* The ground plane y = ground_y under cam as the pass's surface: its distances into gl->dist
 * and uploaded to gl->dist_tex. */
static inline void fog_test_gl_set_ground(fog_test_gl *gl, const camera *cam, double ground_y) {
  fog_test_gl_ground_distance(gl, cam, ground_y, gl->dist);
  fog_test_gl_upload_flipped(gl, gl->dist_tex, GL_RED, 1, gl->dist);
}

/* Pixel (px, py)'s ray (rows top first) and its surface distance from gl->dist: HUGE_VAL for
 * the sky. */
static inline double fog_test_gl_pixel_ray(const fog_test_gl *gl, const camera *cam, int px,
                                           int py, double o[3], double d[3]) {
  camera_ray(cam, px, py, gl->width, gl->height, o, d);
  float t = gl->dist[py * gl->width + px];
  return t >= 1e29f ? HUGE_VAL : (double)t;
}

/* Draws the fog pass (over gl's surface_tex and dist_tex) into the target and reads its
 * transmittance (attachment 1, rows top first) into tau. The target is first cleared to -1,
 * which no transmittance or colour can be, so a pixel the pass leaves unwritten fails any
 * comparison instead of showing the previous draw. Returns 0 on success (err says what
 * failed): the caller CHECKs it, so a failure names the test's own line and case. */
static inline int fog_test_gl_draw_tau(fog_test_gl *gl, const camera *cam,
                                       const fog_pass_params *params, float *tau,
                                       fog_error *err) {
  gl_target_bind(&gl->target);
  static const float unwritten[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
  glClearBufferfv(GL_COLOR, 0, unwritten);
  glClearBufferfv(GL_COLOR, 1, unwritten);
  if (fog_pass_draw(gl->pass, cam, params, gl->surface_tex, gl->dist_tex, gl->width,
                    gl->height, err))
    return 1;
  return gl_target_read(&gl->target, 1, 1, tau, err);
}

#endif
