/* The GL context behind one small interface with two backends, so the renderer never
 * knows which one it runs in (GLFW's platform files are the model):
 *   - headless: EGL surfaceless (Mesa llvmpipe here; EGL_EXT_device_enumeration on NVIDIA),
 *     rendering into FBOs only;
 *   - window: a GLFW window (needs a display).
 * Both ask for OpenGL 4.5 core and fall back to 4.3 (docs/platform.md: 4.6 is refused).
 * GL entry points come from <GL/glcorearb.h> with GL_GLEXT_PROTOTYPES via libOpenGL. */
#ifndef FOGPIPE_RENDER_GL_CONTEXT_H
#define FOGPIPE_RENDER_GL_CONTEXT_H

#include <stdbool.h>

#include "transform/fog_error.h"

typedef enum gl_context_kind {
  GL_CONTEXT_HEADLESS = 0, /* default */
  GL_CONTEXT_WINDOW,
} gl_context_kind;

typedef struct gl_context_desc {
  gl_context_kind kind;
  int width, height;  /* window size (0: 1280x720); ignored headless */
  const char *title;  /* window title (NULL: "fogpipe") */
  bool vsync;
} gl_context_desc;

typedef struct gl_context gl_context;

/* Creates the context and makes it current on the calling thread. Returns NULL and fills
 * err when no context can be made (e.g. no display for a window). */
gl_context *gl_context_create(const gl_context_desc *desc, fog_error *err);
void gl_context_destroy(gl_context *ctx);

/* "4.5 (Core Profile) Mesa 22.3.6" and the renderer string, for logs and benchmarks. */
const char *gl_context_version(const gl_context *ctx);
const char *gl_context_renderer(const gl_context *ctx);
/* True for a CPU rasteriser (Mesa llvmpipe, softpipe, or any renderer calling itself
 * "Software"): per-pixel passes cost CPU time there, so live views lower resolution. */
bool gl_context_is_software(const gl_context *ctx);

/* Window backend only (no-ops headless): the GLFW window, events, buffer swap, close. */
void *gl_context_glfw_window(gl_context *ctx); /* GLFWwindow*, NULL headless */
bool gl_context_should_close(gl_context *ctx);
void gl_context_poll_events(gl_context *ctx);
void gl_context_swap_buffers(gl_context *ctx);
void gl_context_framebuffer_size(gl_context *ctx, int *width, int *height);

/* Added by the implementation (render/gl_context.c): */
/* The GL version obtained as numbers (e.g. 4 and 5). */
void gl_context_gl_version(const gl_context *ctx, int *major, int *minor);
/* How the context was made: "egl-device" (EGL_EXT_device_enumeration, what NVIDIA uses),
 * "egl-surfaceless" (Mesa), "egl-default" or "glfw". */
const char *gl_context_platform(const gl_context *ctx);
/* KHR_debug messages (errors and warnings) collected since creation or the last clear;
 * debug builds only (NDEBUG builds do not enable the debug output: "" always). */
const char *gl_context_debug_log(const gl_context *ctx);
void gl_context_clear_debug_log(gl_context *ctx);

#endif
