/* gl_context: the dispatch over the two backends (gl_context_egl.c headless,
 * gl_context_glfw.c window) and the setup both share once a context is current. */
#include <stdio.h>
#include <string.h>

#include <GL/glcorearb.h>

#include "render/gl_context_backend.h"

gl_context *gl_context_create(const gl_context_desc *desc, fog_error *err) {
  gl_context_desc d = desc ? *desc : (gl_context_desc){0};
  if (d.kind == GL_CONTEXT_WINDOW) return gl_context_glfw_create(&d, err);
  return gl_context_egl_create(&d, err);
}

void gl_context_destroy(gl_context *ctx) {
  if (ctx) ctx->backend->destroy(ctx);
}

const char *gl_context_version(const gl_context *ctx) { return ctx->version; }
const char *gl_context_renderer(const gl_context *ctx) { return ctx->renderer; }

bool gl_context_is_software(const gl_context *ctx) {
  const char *r = ctx->renderer;
  return strstr(r, "llvmpipe") || strstr(r, "softpipe") || strstr(r, "Software");
}
const char *gl_context_platform(const gl_context *ctx) { return ctx->platform; }
const char *gl_context_debug_log(const gl_context *ctx) { return ctx->debug_log; }
void gl_context_clear_debug_log(gl_context *ctx) { ctx->debug_log[0] = '\0'; }

void gl_context_gl_version(const gl_context *ctx, int *major, int *minor) {
  if (major) *major = ctx->major;
  if (minor) *minor = ctx->minor;
}

void *gl_context_glfw_window(gl_context *ctx) {
  return ctx->backend->window ? ctx->backend->window(ctx) : NULL;
}
bool gl_context_should_close(gl_context *ctx) {
  return ctx->backend->should_close ? ctx->backend->should_close(ctx) : false;
}
void gl_context_poll_events(gl_context *ctx) {
  if (ctx->backend->poll_events) ctx->backend->poll_events(ctx);
}
void gl_context_swap_buffers(gl_context *ctx) {
  if (ctx->backend->swap_buffers) ctx->backend->swap_buffers(ctx);
}
void gl_context_framebuffer_size(gl_context *ctx, int *width, int *height) {
  if (ctx->backend->framebuffer_size) {
    ctx->backend->framebuffer_size(ctx, width, height);
  } else {
    if (width) *width = 0;
    if (height) *height = 0;
  }
}

#ifndef NDEBUG
/* KHR_debug (core in 4.3): keep errors, warnings and performance notes, drop the
 * notifications that drivers send for every buffer upload. */
static void APIENTRY debug_message(GLenum source, GLenum type, GLuint id, GLenum severity,
                                     GLsizei length, const GLchar *message,
                                     const void *user) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  gl_context *ctx = (gl_context *)user;
  size_t used = strlen(ctx->debug_log);
  size_t room = sizeof ctx->debug_log - used;
  if (room > 1) snprintf(ctx->debug_log + used, room, "GL: %s\n", message);
}
#endif

int gl_context_finish_setup(gl_context *ctx, fog_error *err) {
  const char *version = (const char *)glGetString(GL_VERSION);
  const char *renderer = (const char *)glGetString(GL_RENDERER);
  if (!version) {
    fog_fail(err, FOG_ERR_GRAPHICS,
             "the %s context is current but glGetString(GL_VERSION) returned NULL "
             "(GL entry points not reaching the driver?)",
             ctx->platform);
    return 1;
  }
  snprintf(ctx->version, sizeof ctx->version, "%s", version);
  snprintf(ctx->renderer, sizeof ctx->renderer, "%s", renderer ? renderer : "?");
  glGetIntegerv(GL_MAJOR_VERSION, &ctx->major);
  glGetIntegerv(GL_MINOR_VERSION, &ctx->minor);
  if (ctx->major < 4 || (ctx->major == 4 && ctx->minor < 3)) {
    fog_fail(err, FOG_ERR_GRAPHICS, "OpenGL %d.%d from %s (%s): fogpipe needs 4.3 core or newer",
             ctx->major, ctx->minor, ctx->platform, ctx->renderer);
    return 1;
  }
#ifndef NDEBUG
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(debug_message, ctx);
#endif
  return 0;
}
