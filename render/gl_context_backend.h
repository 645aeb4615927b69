/* Private to render/gl_context*.c: the table each backend fills (GLFW's platform files
 * are the model), and the part of a context every backend shares. Not a public header. */
#ifndef FOGPIPE_RENDER_GL_CONTEXT_BACKEND_H
#define FOGPIPE_RENDER_GL_CONTEXT_BACKEND_H

#include <stdbool.h>

#include "render/gl_context.h"

typedef struct gl_context_backend {
  void (*destroy)(gl_context *ctx);
  void *(*window)(gl_context *ctx);
  bool (*should_close)(gl_context *ctx);
  void (*poll_events)(gl_context *ctx);
  void (*swap_buffers)(gl_context *ctx);
  void (*framebuffer_size)(gl_context *ctx, int *width, int *height);
} gl_context_backend;

/* Every backend's context struct starts with this. */
struct gl_context {
  const gl_context_backend *backend;
  const char *platform;  /* "egl-device", "egl-surfaceless", "egl-default", "glfw" */
  int major, minor;      /* the GL version obtained */
  char version[160];
  char renderer[160];
  char debug_log[4096];  /* KHR_debug messages (debug builds), newest appended */
};

/* The two backends (gl_context_egl.c, gl_context_glfw.c). */
gl_context *gl_context_egl_create(const gl_context_desc *desc, fog_error *err);
gl_context *gl_context_glfw_create(const gl_context_desc *desc, fog_error *err);

/* Shared by both once their context is current: reads version and renderer strings,
 * checks for a 4.x core context, and (debug builds) routes KHR_debug output into
 * ctx->debug_log. Returns non-zero with err filled if the context is unusable. */
int gl_context_finish_setup(gl_context *ctx, fog_error *err);

#endif
