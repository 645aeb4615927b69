/* Window output (gl_present.h). */
#include "render/gl_present.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

struct gl_presenter {
  GLuint program;
  GLint u_image, u_image_per_pixel, u_bilinear, u_exposure_scale, u_tone_map, u_dither, u_top_row;
};

gl_presenter *gl_presenter_create(fog_error *err) {
  gl_presenter *p = calloc(1, sizeof *p);
  if (!p) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the window presenter");
    return NULL;
  }
  p->program = gl_util_program("scene_sky_vs.glsl", "scene_present_fs.glsl", err);
  if (!p->program) {
    free(p);
    return NULL;
  }
  p->u_image = glGetUniformLocation(p->program, "image");
  p->u_image_per_pixel = glGetUniformLocation(p->program, "image_per_pixel");
  p->u_bilinear = glGetUniformLocation(p->program, "bilinear");
  p->u_exposure_scale = glGetUniformLocation(p->program, "exposure_scale");
  p->u_tone_map = glGetUniformLocation(p->program, "tone_map");
  p->u_dither = glGetUniformLocation(p->program, "dither");
  p->u_top_row = glGetUniformLocation(p->program, "top_row");
  return p;
}

void gl_presenter_destroy(gl_presenter *p) {
  if (!p) return;
  if (p->program) glDeleteProgram(p->program);
  free(p);
}

void gl_presenter_draw(gl_presenter *p, const gl_target *source, int width, int height,
                       gl_present_scaling scaling, const display_transform *display) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(p->program);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, source->color[0]);
  glUniform1i(p->u_image, 0);
  glUniform2f(p->u_image_per_pixel, (float)source->width / width, (float)source->height / height);
  glUniform1i(p->u_bilinear, scaling == GL_PRESENT_BILINEAR);
  glUniform1f(p->u_exposure_scale, (float)exp2(display->exposure)); /* as display_map */
  glUniform1i(p->u_tone_map, (int)display->tone_map);
  glUniform1i(p->u_dither, display->dither);
  glUniform1i(p->u_top_row, height - 1);
  glBindVertexArray(gl_util_empty_vao());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
}

int gl_read_window(int width, int height, float *rgb, fog_error *err) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return gl_util_read_pixels(GL_BACK, width, height, 3, rgb, err);
}

float gl_target_read_texel(const gl_target *target, int attachment, int x, int y) {
  float value = NAN;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, target->framebuffer);
  glReadBuffer(GL_COLOR_ATTACHMENT0 + (GLenum)attachment);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, target->height - 1 - y, 1, 1, GL_RED, GL_FLOAT, &value); /* GL: bottom-up */
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return glGetError() == GL_NO_ERROR ? value : NAN;
}

void gl_finish(void) { glFinish(); }
