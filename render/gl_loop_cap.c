/* The renderer's loop cap, measured (gl_util.h, gl_util_loop_cap): Mesa's llvmpipe
 * (gallivm) keeps one counter per shader invocation, decremented at the end of every
 * iteration of every loop that was not unrolled, and ends all loops once it reaches 0
 * (LP_MAX_TGSI_LOOP_ITERATIONS, 65535). A shader past it draws a wrong value, silently. */
#include <limits.h>

#include "render/gl_util.h"

/* More than any cap the probe is meant to find, and exact in the float counter (2^24). */
#define LOOP_CAP_PROBE_ITERATIONS (1 << 22)

int gl_util_loop_cap(long *cap, fog_error *err) {
  GLint draw_fb, read_fb, program, vao, viewport[4];
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fb);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fb);
  glGetIntegerv(GL_CURRENT_PROGRAM, &program);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
  glGetIntegerv(GL_VIEWPORT, viewport);
  GLuint prog = gl_util_program("fog_pass_vs.glsl", "loop_cap_fs.glsl", err);
  if (!prog) return 1;
  gl_target target = {0};
  if (gl_target_create(&target, &(gl_target_desc){.width = 1, .height = 1,
                                                  .color_formats = {GL_R32F}},
                       err)) {
    glDeleteProgram(prog);
    return 1;
  }
  gl_target_bind(&target);
  glUseProgram(prog);
  glUniform1i(glGetUniformLocation(prog, "loop_cap_iterations"), LOOP_CAP_PROBE_ITERATIONS);
  glBindVertexArray(gl_util_empty_vao());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  float count = 0;
  int failed = gl_target_read(&target, 0, 1, &count, err);
  gl_target_destroy(&target);
  glDeleteProgram(prog);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)draw_fb);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)read_fb);
  /* a program or VAO deleted while bound was freed when the probe's replaced it */
  glUseProgram(glIsProgram((GLuint)program) ? (GLuint)program : 0);
  glBindVertexArray(glIsVertexArray((GLuint)vao) ? (GLuint)vao : 0);
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  if (failed || gl_util_check("the loop-cap probe", err)) return 1;
  *cap = count < LOOP_CAP_PROBE_ITERATIONS ? (long)count : GL_UTIL_NO_LOOP_CAP;
  return 0;
}
