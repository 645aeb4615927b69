/* The GL ray march of a dense 3D grid (see volume_march.h). */
#include "render/volume_march.h"

#include <stdio.h>
#include <stdlib.h>

#include "render/gl_util.h"

struct volume_march {
  GLuint texture, program;
  int dim[3];
  float index_from_world[9]; /* column-major for glUniformMatrix3fv */
  float index_offset[3];
  gl_target target;
};

void volume_grid_index_of(const volume_grid_desc *grid, const double p[3], double u[3]) {
  for (int c = 0; c < 3; c++) {
    u[c] = grid->index_offset[c];
    for (int a = 0; a < 3; a++) u[c] += grid->index_from_world[c][a] * p[a];
  }
}

void volume_grid_gl_matrix(const volume_grid_desc *grid, float m[9]) {
  for (int c = 0; c < 3; c++)
    for (int a = 0; a < 3; a++) m[3 * a + c] = (float)grid->index_from_world[c][a];
}

volume_march *volume_march_create(const volume_grid_desc *grid, fog_error *err) {
  for (int c = 0; c < 3; c++)
    if (grid->dim[c] < 1) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
               "volume march: grid %dx%dx%d: every dimension must be positive", grid->dim[0],
               grid->dim[1], grid->dim[2]);
      return NULL;
    }
  volume_march *m = calloc(1, sizeof *m);
  if (!m) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "volume march: out of memory");
    return NULL;
  }
  for (int c = 0; c < 3; c++) {
    m->dim[c] = grid->dim[c];
    m->index_offset[c] = (float)grid->index_offset[c];
  }
  volume_grid_gl_matrix(grid, m->index_from_world);
  m->program = gl_util_program("fog_pass_vs.glsl", "volume_march_fs.glsl", err);
  if (!m->program) {
    free(m);
    return NULL;
  }
  glGenTextures(1, &m->texture);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_3D, m->texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, grid->dim[0], grid->dim[1], grid->dim[2], 0, GL_RED,
               GL_FLOAT, grid->values);
  gl_util_texture_sampling(GL_TEXTURE_3D, true); /* hardware trilinear, zero border */
  glBindTexture(GL_TEXTURE_3D, 0);
  if (gl_util_check("volume march: upload", err)) {
    volume_march_destroy(m);
    return NULL;
  }
  return m;
}

void volume_march_destroy(volume_march *m) {
  if (!m) return;
  if (m->texture) glDeleteTextures(1, &m->texture);
  if (m->program) glDeleteProgram(m->program);
  if (m->target.framebuffer) gl_target_destroy(&m->target);
  free(m);
}

int volume_march_view(volume_march *m, const volume_view_desc *v, float *optical_depth,
                      fog_error *err) {
  if (v->side < 1 || !(v->step > 0)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "volume march: %d rays per side, step %g: expected >= 1 and > 0", v->side, v->step);
    return 1;
  }
  if (m->target.framebuffer && m->target.width != v->side) gl_target_destroy(&m->target);
  if (!m->target.framebuffer &&
      gl_target_create(&m->target, &(gl_target_desc){.width = v->side, .height = v->side,
                                                     .color_formats = {GL_R32F}},
                       err))
    return 1;
  gl_target_bind(&m->target);
  GLuint p = m->program;
  glUseProgram(p);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_3D, m->texture);
  glUniform1i(glGetUniformLocation(p, "march_density"), 0);
  glUniformMatrix3fv(glGetUniformLocation(p, "march_index_from_world"), 1, GL_FALSE,
                     m->index_from_world);
  glUniform3fv(glGetUniformLocation(p, "march_index_offset"), 1, m->index_offset);
  glUniform3f(glGetUniformLocation(p, "march_dims"), (float)m->dim[0], (float)m->dim[1],
              (float)m->dim[2]);
  glUniform3f(glGetUniformLocation(p, "march_lo"), (float)v->lo[0], (float)v->lo[1],
              (float)v->lo[2]);
  glUniform3f(glGetUniformLocation(p, "march_hi"), (float)v->hi[0], (float)v->hi[1],
              (float)v->hi[2]);
  glUniform3f(glGetUniformLocation(p, "march_dir"), (float)v->dir[0], (float)v->dir[1],
              (float)v->dir[2]);
  glUniform1f(glGetUniformLocation(p, "march_y_mid"), (float)v->y_mid);
  glUniform1i(glGetUniformLocation(p, "march_side"), v->side);
  glUniform1f(glGetUniformLocation(p, "march_step"), (float)v->step);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindVertexArray(gl_util_empty_vao());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindTexture(GL_TEXTURE_3D, 0);
  if (gl_util_check("volume march: draw", err)) return 1;
  return gl_target_read(&m->target, 0, 1, optical_depth, err);
}
