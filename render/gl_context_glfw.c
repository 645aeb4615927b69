/* Window backend: a GLFW 3.3 window with an OpenGL 4.5 core context, falling back to 4.3
 * (4.6 hints fail with GLXBadFBConfig on Mesa 22: docs/platform.md). GLFW has no
 * headless mode: without a display glfwInit fails, and we say so in one line. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GLFW/glfw3.h>

#include "render/gl_context_backend.h"

typedef struct glfw_context {
  gl_context base;
  GLFWwindow *window;
} glfw_context;

/* GLFW reports errors through a callback; keep the last one for our messages. */
static char glfw_last_error[256];
static void glfw_error(int code, const char *description) {
  snprintf(glfw_last_error, sizeof glfw_last_error, "%s (0x%x)", description, code);
}

static void glfw_destroy(gl_context *base) {
  glfw_context *ctx = (glfw_context *)base;
  if (ctx->window) glfwDestroyWindow(ctx->window);
  glfwTerminate();
  free(ctx);
}
static void *glfw_window(gl_context *base) { return ((glfw_context *)base)->window; }
static bool glfw_should_close(gl_context *base) {
  return glfwWindowShouldClose(((glfw_context *)base)->window);
}
static void glfw_poll_events(gl_context *base) { glfwPollEvents(); }
static void glfw_swap_buffers(gl_context *base) { glfwSwapBuffers(((glfw_context *)base)->window); }
static void glfw_framebuffer_size(gl_context *base, int *width, int *height) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(((glfw_context *)base)->window, &w, &h);
  if (width) *width = w;
  if (height) *height = h;
}

static const gl_context_backend glfw_backend = {
    .destroy = glfw_destroy,
    .window = glfw_window,
    .should_close = glfw_should_close,
    .poll_events = glfw_poll_events,
    .swap_buffers = glfw_swap_buffers,
    .framebuffer_size = glfw_framebuffer_size,
};

gl_context *gl_context_glfw_create(const gl_context_desc *desc, fog_error *err) {
  glfwSetErrorCallback(glfw_error);
  glfw_last_error[0] = '\0';
  if (!glfwInit()) {
    const char *display = getenv("DISPLAY");
    const char *wayland = getenv("WAYLAND_DISPLAY");
    fog_fail(err, FOG_ERR_GRAPHICS,
             "cannot open a window: %s (GLFW: %s); for headless rendering use `fogpipe "
             "render`, or run under xvfb-run",
             (display && *display) || (wayland && *wayland) ? "the display refused GLFW"
                                                            : "no display (DISPLAY is not set)",
             glfw_last_error[0] ? glfw_last_error : "glfwInit failed");
    return NULL;
  }
  glfw_context *ctx = calloc(1, sizeof *ctx);
  if (!ctx) {
    glfwTerminate();
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the window context");
    return NULL;
  }
  ctx->base.backend = &glfw_backend;
  ctx->base.platform = "glfw";
  int width = desc->width > 0 ? desc->width : 1280;
  int height = desc->height > 0 ? desc->height : 720;
  static const int versions[][2] = {{4, 5}, {4, 3}};
  char log[256] = "";
  for (size_t v = 0; v < sizeof versions / sizeof versions[0] && !ctx->window; v++) {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, versions[v][0]);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, versions[v][1]);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
#ifndef NDEBUG
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
#endif
    glfw_last_error[0] = '\0';
    ctx->window = glfwCreateWindow(width, height, desc->title ? desc->title : "fogpipe",
                                   NULL, NULL);
    if (!ctx->window) {
      size_t used = strlen(log);
      snprintf(log + used, sizeof log - used, "%s%d.%d core: %s", used ? "; " : "",
               versions[v][0], versions[v][1], glfw_last_error);
    }
  }
  if (!ctx->window) {
    fog_fail(err, FOG_ERR_GRAPHICS, "cannot create an OpenGL 4.3+ core window: %s", log);
    glfw_destroy(&ctx->base);
    return NULL;
  }
  glfwMakeContextCurrent(ctx->window);
  glfwSwapInterval(desc->vsync ? 1 : 0);
  if (gl_context_finish_setup(&ctx->base, err)) {
    glfw_destroy(&ctx->base);
    return NULL;
  }
  return &ctx->base;
}
