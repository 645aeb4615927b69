/* The renderer's loop cap, measured (gl_util.h, gl_util_loop_cap): Mesa's llvmpipe
 * (gallivm) keeps one counter per shader invocation, decremented at the end of every
 * iteration of every loop that was not unrolled, and ends all loops once it reaches 0
 * (LP_MAX_TGSI_LOOP_ITERATIONS, 65535). A shader past it draws a wrong value, silently. */
#include <limits.h>

#include "render/gl_util.h"

/* More than any cap the probe is meant to find, and exact in the float counter (2^24). */
#define LOOP_CAP_PROBE_ITERATIONS (1 << 22)

/* The state that could keep the probe's one pixel from being written. */
static const GLenum probe_off[] = {GL_SCISSOR_TEST, GL_RASTERIZER_DISCARD, GL_CULL_FACE,
                                   GL_DEPTH_TEST,   GL_STENCIL_TEST,       GL_BLEND};
enum { PROBE_OFF_COUNT = sizeof probe_off / sizeof probe_off[0] };

typedef struct saved_state {
  GLboolean enabled[PROBE_OFF_COUNT], mask[4];
  GLint draw_fb, read_fb, program, vao, viewport[4];
} saved_state;

static void save_and_clear(saved_state *s) {
  for (int i = 0; i < PROBE_OFF_COUNT; i++)
    s->enabled[i] = glIsEnabled(probe_off[i]), glDisable(probe_off[i]);
  glGetBooleani_v(GL_COLOR_WRITEMASK, 0, s->mask);
  glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fb);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fb);
  glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
  glGetIntegerv(GL_VIEWPORT, s->viewport);
}

static void restore(const saved_state *s) {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fb);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fb);
  /* a program or VAO deleted while bound was freed when the probe's replaced it */
  glUseProgram(glIsProgram((GLuint)s->program) ? (GLuint)s->program : 0);
  glBindVertexArray(glIsVertexArray((GLuint)s->vao) ? (GLuint)s->vao : 0);
  glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
  glColorMaski(0, s->mask[0], s->mask[1], s->mask[2], s->mask[3]);
  for (int i = 0; i < PROBE_OFF_COUNT; i++)
    if (s->enabled[i]) glEnable(probe_off[i]);
}

int gl_util_loop_cap(long *cap, fog_error *err) {
  saved_state saved;
  save_and_clear(&saved);
  GLuint prog = gl_util_program("fog_pass_vs.glsl", "loop_cap_fs.glsl", err);
  gl_target target = {0};
  int failed = !prog || gl_target_create(&target, &(gl_target_desc){.width = 1, .height = 1,
                                                                    .color_formats = {GL_R32F}},
                                         err);
  float count = -1.0f;
  if (!failed) {
    gl_target_bind(&target);
    static const float unwritten[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
    glClearBufferfv(GL_COLOR, 0, unwritten);
    glUseProgram(prog);
    glUniform1i(glGetUniformLocation(prog, "loop_cap_iterations"), LOOP_CAP_PROBE_ITERATIONS);
    glBindVertexArray(gl_util_empty_vao());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    failed = gl_target_read(&target, 0, 1, &count, err);
  }
  if (target.framebuffer) gl_target_destroy(&target);
  if (prog) glDeleteProgram(prog);
  restore(&saved);
  if (failed || gl_util_check("the loop-cap probe", err)) return 1;
  if (!(count >= 1)) /* the pixel was not written, or no loop ran at all */
    return fog_fail(err, FOG_ERR_GRAPHICS,
                    "the loop-cap probe read %g: expected >= 1 loop iterations "
                    "(render/gl_loop_cap.c)", count);
  *cap = count < LOOP_CAP_PROBE_ITERATIONS ? (long)count : GL_UTIL_NO_LOOP_CAP;
  return 0;
}
