/* The headless EGL context: it is created without a display, is OpenGL 4.3+ core, and a
 * shader's output written to an RGBA32F FBO comes back exactly, unclamped and with rows
 * top first (gl_target_read flips GL's bottom-up rows). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "test_util.h"

static const char *vertex_source =
    "#version 430 core\n"
    "void main() {\n"
    "  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
    "  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
    "}\n";
/* Values chosen to be exact in float and outside [0,1]: clamping or 8-bit storage fails. */
static const char *fragment_source =
    "#version 430 core\n"
    "layout(location = 0) out vec4 colour;\n"
    "layout(location = 1) out float single;\n"
    "void main() {\n"
    "  colour = vec4(gl_FragCoord.x, gl_FragCoord.y, -2.5, 1.0e6);\n"
    "  single = gl_FragCoord.x * 1000.0 + gl_FragCoord.y;\n"
    "}\n";

int main(void) {
  fog_error err = {0};
  gl_context *ctx = gl_context_create(&(gl_context_desc){0}, &err);
  CHECK(ctx != NULL, "headless context: %s", err.message);
  if (!ctx) return test_finish("test_context_headless");
  int major = 0, minor = 0;
  gl_context_gl_version(ctx, &major, &minor);
  printf("%s | %s | %s\n", gl_context_platform(ctx), gl_context_version(ctx),
         gl_context_renderer(ctx));
  CHECK(major == 4 && minor >= 3, "GL %d.%d, expected 4.3+", major, minor);
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  CHECK(profile & GL_CONTEXT_CORE_PROFILE_BIT, "profile mask 0x%x is not core", profile);
  CHECK(strstr(gl_context_version(ctx), "Core Profile") || major >= 4,
        "version string %s", gl_context_version(ctx));
  CHECK(gl_context_glfw_window(ctx) == NULL, "headless context has a window");

  enum { W = 37, H = 23 }; /* odd sizes: pack alignment and row flipping */
  gl_target target;
  int status = gl_target_create(
      &target, &(gl_target_desc){.width = W, .height = H, .color_formats = {GL_RGBA32F, GL_R32F}, .depth = true},
      &err);
  CHECK(status == 0, "render target: %s", err.message);
  GLuint program = gl_util_program_from_source("test", vertex_source, fragment_source, &err);
  CHECK(program != 0, "program: %s", err.message);

  /* A broken shader gives the info log in the message. */
  fog_error bad = {0};
  GLuint broken = gl_util_program_from_source("broken.glsl", vertex_source,
                                              "#version 430 core\nvoid main() { x = 1; }\n", &bad);
  CHECK(broken == 0 && strstr(bad.message, "broken.glsl: fragment shader") != NULL,
        "broken shader message: %s", bad.message);
#ifndef NDEBUG
  /* Debug builds route KHR_debug output into the context's log. */
  CHECK(strstr(gl_context_debug_log(ctx), "error") != NULL, "KHR_debug log: '%s'",
        gl_context_debug_log(ctx));
#endif
  gl_context_clear_debug_log(ctx);

  if (status == 0 && program) {
    gl_target_bind(&target);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(program);
    glBindVertexArray(gl_util_empty_vao());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    float *rgba = malloc(sizeof(float) * W * H * 4);
    float *single = malloc(sizeof(float) * W * H);
    CHECK(gl_target_read(&target, 0, 4, rgba, &err) == 0, "read rgba: %s", err.message);
    CHECK(gl_target_read(&target, 1, 1, single, &err) == 0, "read r32f: %s", err.message);
    int bad_pixels = 0;
    for (int row = 0; row < H; row++)
      for (int x = 0; x < W; x++) {
        int gl_y = H - 1 - row; /* row 0 of the read-back is the top of the image */
        const float *p = rgba + ((size_t)row * W + x) * 4;
        float want_single = (x + 0.5f) * 1000.0f + (gl_y + 0.5f);
        if (p[0] != x + 0.5f || p[1] != gl_y + 0.5f || p[2] != -2.5f || p[3] != 1.0e6f ||
            single[(size_t)row * W + x] != want_single) {
          if (bad_pixels++ < 3)
            fprintf(stderr, "pixel (%d,%d): %g %g %g %g / %g, expected %g %g -2.5 1e6 / %g\n",
                    x, row, p[0], p[1], p[2], p[3], single[(size_t)row * W + x], x + 0.5,
                    gl_y + 0.5, want_single);
        }
      }
    CHECK(bad_pixels == 0, "%d of %d pixels differ from the shader's exact values", bad_pixels,
          W * H);
    free(rgba);
    free(single);
    glDeleteProgram(program);
  }
  gl_target_destroy(&target);
  CHECK(gl_util_check("end of test", &err) == 0, "%s", err.message);
  CHECK(gl_context_debug_log(ctx)[0] == '\0' || strstr(gl_context_debug_log(ctx), "error") == NULL,
        "KHR_debug: %s", gl_context_debug_log(ctx));
  gl_context_destroy(ctx);

  /* A second context after the first is gone (the display is re-initialised). */
  ctx = gl_context_create(NULL, &err);
  CHECK(ctx != NULL, "second headless context: %s", err.message);
  gl_context_destroy(ctx);
  return test_finish("test_context_headless");
}
