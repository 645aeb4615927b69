/* Headless backend: an EGL context with no surface, rendering into FBOs only.
 * (docs/platform.md "Headless OpenGL".) Display paths, in order:
 *   1. EGL_EXT_device_enumeration, hardware devices (what NVIDIA machines offer);
 *   2. EGL_MESA_platform_surfaceless (Mesa: llvmpipe on machines without a GPU);
 *   3. device enumeration, software devices (EGL_MESA_device_software);
 *   4. eglGetDisplay(EGL_DEFAULT_DISPLAY).
 * Hardware devices come first so a machine with both Mesa and a GPU driver installed
 * renders on the GPU. Each display asks for 4.5 core, then 4.3 (4.6 is refused by
 * Mesa 22 with EGL_BAD_MATCH). No environment variables needed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "render/gl_context_backend.h"

typedef struct egl_context {
  gl_context base;
  EGLDisplay display;
  EGLContext context;
  struct egl_context *next_live;  /* contexts alive, so a shared display is terminated last */
} egl_context;

static egl_context *live_contexts;

#if defined(FOGPIPE_SANITIZE)
/* Sanitizer builds only (make test-sanitize): LeakSanitizer can name the library behind a
 * leaked allocation only while it is loaded, and GLVND and Mesa dlclose their drivers at
 * exit, so Mesa's own never-freed allocations showed as "<unknown module>" and could not be
 * suppressed by name (tests/sanitizers/lsan.supp). Every module stays loaded instead: this
 * definition interposes libc's for the GL libraries. */
int dlclose(void *handle);
int dlclose(void *handle) {
  (void)handle;
  return 0;
}
#endif

static bool has_extension(const char *list, const char *name) {
  if (!list) return false;
  size_t n = strlen(name);
  for (const char *p = list; (p = strstr(p, name)); p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

static const char *egl_error_name(EGLint code) {
  switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    default: return "EGL error";
  }
}

/* Appends one attempt's outcome to the message shown if every path fails. */
static void note(char *log, size_t size, const char *fmt, const char *what, EGLint code) {
  size_t used = strlen(log);
  if (used + 2 >= size) return;
  if (used) log[used++] = ';', log[used++] = ' ', log[used] = '\0';
  snprintf(log + used, size - used, fmt, what, egl_error_name(code), code);
}

static bool display_in_use(EGLDisplay display) {
  for (egl_context *c = live_contexts; c; c = c->next_live)
    if (c->display == display) return true;
  return false;
}

/* Initialises display and makes a 4.5 (else 4.3) core context current on it with no
 * surface. Returns EGL_NO_CONTEXT (display terminated unless shared) on failure. */
static EGLContext try_display(EGLDisplay display, const char *path, char *log, size_t size) {
  if (display == EGL_NO_DISPLAY) {
    note(log, size, "%s: no display (%s 0x%x)", path, eglGetError());
    return EGL_NO_CONTEXT;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    note(log, size, "%s: eglInitialize failed (%s 0x%x)", path, eglGetError());
    return EGL_NO_CONTEXT;
  }
  const char *extensions = eglQueryString(display, EGL_EXTENSIONS);
  EGLContext context = EGL_NO_CONTEXT;
  if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
    note(log, size, "%s: no EGL_KHR_surfaceless_context (%s 0x%x)", path, EGL_SUCCESS);
    goto fail;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    note(log, size, "%s: eglBindAPI(EGL_OPENGL_API) failed (%s 0x%x)", path, eglGetError());
    goto fail;
  }
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!has_extension(extensions, "EGL_KHR_no_config_context") &&
      !has_extension(extensions, "EGL_MESA_configless_context")) {
    const EGLint want[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                           EGL_OPENGL_BIT, EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display, want, &config, 1, &count) || count < 1) {
      note(log, size, "%s: no config with EGL_OPENGL_BIT (%s 0x%x)", path, eglGetError());
      goto fail;
    }
  }
  static const EGLint versions[][2] = {{4, 5}, {4, 3}};
  for (size_t v = 0; v < sizeof versions / sizeof versions[0]; v++) {
    const EGLint attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION, versions[v][0],
        EGL_CONTEXT_MINOR_VERSION, versions[v][1],
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
#ifndef NDEBUG
        EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE,
#endif
        EGL_NONE};
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
    if (context != EGL_NO_CONTEXT) break;
    char what[96];
    snprintf(what, sizeof what, "%s: %d.%d core refused", path, versions[v][0], versions[v][1]);
    note(log, size, "%s (%s 0x%x)", what, eglGetError());
  }
  if (context == EGL_NO_CONTEXT) goto fail;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    note(log, size, "%s: eglMakeCurrent without surface failed (%s 0x%x)", path,
         eglGetError());
    eglDestroyContext(display, context);
    context = EGL_NO_CONTEXT;
    goto fail;
  }
  return context;
fail:
  if (!display_in_use(display)) eglTerminate(display);
  return EGL_NO_CONTEXT;
}

static void egl_destroy(gl_context *base) {
  egl_context *ctx = (egl_context *)base;
  eglMakeCurrent(ctx->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(ctx->display, ctx->context);
  for (egl_context **p = &live_contexts; *p; p = &(*p)->next_live)
    if (*p == ctx) {
      *p = ctx->next_live;
      break;
    }
  /* EGL displays are per-platform singletons: terminate only when nobody else uses it. */
  if (!display_in_use(ctx->display)) eglTerminate(ctx->display);
  eglReleaseThread();
  free(ctx);
}

static const gl_context_backend egl_backend = {.destroy = egl_destroy};

gl_context *gl_context_egl_create(const gl_context_desc *desc, fog_error *err) {
  egl_context *ctx = calloc(1, sizeof *ctx);
  if (!ctx) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the EGL context");
    return NULL;
  }
  ctx->base.backend = &egl_backend;
  char log[400] = "";
  const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);

  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
      (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  PFNEGLQUERYDEVICESEXTPROC query_devices =
      (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string =
      (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");

  EGLDeviceEXT devices[16];
  EGLint device_count = 0;
  bool can_enumerate = get_platform_display && query_devices &&
                       has_extension(client, "EGL_EXT_platform_device") &&
                       (has_extension(client, "EGL_EXT_device_enumeration") ||
                        has_extension(client, "EGL_EXT_device_base"));
  if (can_enumerate && !query_devices(16, devices, &device_count)) device_count = 0;

  /* Pass 0: hardware devices; pass 2: software devices; pass 1: Mesa surfaceless. */
  for (int pass = 0; pass < 3 && ctx->context == EGL_NO_CONTEXT; pass++) {
    if (pass == 1) {
      if (get_platform_display && has_extension(client, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d =
            get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
        ctx->context = try_display(d, "surfaceless", log, sizeof log);
        if (ctx->context != EGL_NO_CONTEXT) ctx->display = d, ctx->base.platform = "egl-surfaceless";
      }
      continue;
    }
    for (EGLint i = 0; i < device_count && ctx->context == EGL_NO_CONTEXT; i++) {
      const char *dev_ext = query_device_string ? query_device_string(devices[i], EGL_EXTENSIONS) : NULL;
      bool software = has_extension(dev_ext, "EGL_MESA_device_software");
      if (software != (pass == 2)) continue;
      EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
      char path[32];
      snprintf(path, sizeof path, "device %d", (int)i);
      ctx->context = try_display(d, path, log, sizeof log);
      if (ctx->context != EGL_NO_CONTEXT) ctx->display = d, ctx->base.platform = "egl-device";
    }
  }
  if (ctx->context == EGL_NO_CONTEXT) {
    EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    ctx->context = try_display(d, "default display", log, sizeof log);
    if (ctx->context != EGL_NO_CONTEXT) ctx->display = d, ctx->base.platform = "egl-default";
  }
  if (ctx->context == EGL_NO_CONTEXT) {
    fog_fail(err, FOG_ERR_GRAPHICS,
             "no headless OpenGL 4.3+ core context from EGL (%d devices enumerated): %s",
             (int)device_count, log[0] ? log : "no EGL platform available");
    free(ctx);
    return NULL;
  }
  ctx->next_live = live_contexts;
  live_contexts = ctx;
  if (gl_context_finish_setup(&ctx->base, err)) {
    egl_destroy(&ctx->base);
    return NULL;
  }
  return &ctx->base;
}
