/* pipeline_fog: adapter from the pipeline to the GL fog pass; see app/pipeline_fog.h. */
#include "app/pipeline_fog.h"

#include "render/fog_pass.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct pipeline_fog {
  int width, height;
  fog_pass *pass;
  gl_target target;     /* colour 0: composited RGBA32F; colour 1: transmittance R32F */
  int levels;           /* J of the uploaded pyramid */
  int degree;
  bool has_details;
  bool uploaded;
  GLuint present_program;
};

/* Window presentation: linear colour → sRGB (IEC 61966-2-1), clamped; a full-screen
 * triangle from gl_VertexID. */
static const char present_vs[] =
    "#version 430 core\n"
    "out vec2 uv;\n"
    "void main() {\n"
    "  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
    "  uv = p;\n"
    "  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);\n"
    "}\n";
static const char present_fs[] =
    "#version 430 core\n"
    "in vec2 uv;\n"
    "out vec4 colour;\n"
    "uniform sampler2D image;\n"
    "vec3 srgb(vec3 c) {\n"
    "  c = clamp(c, 0.0, 1.0);\n"
    "  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));\n"
    "}\n"
    "void main() { colour = vec4(srgb(texture(image, uv).rgb), 1.0); }\n";

pipeline_fog *pipeline_fog_create(render_error *err) {
  pipeline_fog *fog = calloc(1, sizeof *fog);
  if (!fog) {
    snprintf(err->message, sizeof err->message, "out of memory");
    return NULL;
  }
  if (fog_pass_create(&fog->pass, err)) {
    free(fog);
    return NULL;
  }
  return fog;
}

void pipeline_fog_destroy(pipeline_fog *fog) {
  if (!fog) return;
  if (fog->present_program) glDeleteProgram(fog->present_program);
  gl_target_destroy(&fog->target);
  fog_pass_destroy(fog->pass);
  free(fog);
}

int pipeline_fog_resize(pipeline_fog *fog, int width, int height, render_error *err) {
  gl_target_destroy(&fog->target);
  fog->width = fog->height = 0;
  gl_target_desc desc = {.width = width, .height = height,
                         .color_formats = {GL_RGBA32F, GL_R32F}};
  if (gl_target_create(&fog->target, &desc, err)) return 1;
  fog->width = width;
  fog->height = height;
  /* Presenting scales the colour to the window: filter it (read-back uses glReadPixels,
   * and the fog pass never samples this texture, so this changes no recorded pixel). */
  glBindTexture(GL_TEXTURE_2D, fog->target.color[0]);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glBindTexture(GL_TEXTURE_2D, 0);
  return 0;
}

int pipeline_fog_upload(pipeline_fog *fog, const fog_pyramid *pyramid, render_error *err) {
  if (fog_pass_upload_pyramid(fog->pass, pyramid, err)) return 1;
  fog->levels = pyramid->levels;
  fog->degree = pyramid->degree;
  fog->has_details = pyramid->has_details;
  fog->uploaded = true;
  return 0;
}

int pipeline_fog_render(pipeline_fog *fog, const camera *cam, const gl_target *scene,
                        const pipeline_fog_settings *settings, render_error *err) {
  if (!fog->uploaded) {
    snprintf(err->message, sizeof err->message, "no fog grids uploaded yet");
    return 1;
  }
  /* The sum of details needs D_1..D_J; a step computed before the method changed has only
   * the approximations, so that one frame uses switching (the same image for mu = 1). */
  fog_lod_method method = (fog_lod_method)settings->lod_method;
  if (method == FOG_LOD_SUM_OF_DETAILS && !fog->has_details) method = FOG_LOD_SWITCH;
  fog_pass_params params = {
      .volume = settings->volume,
      .levels = fog->levels,
      .lod_method = method,
      .mu = settings->mu,
      .fog_colour = {settings->fog_colour[0], settings->fog_colour[1], settings->fog_colour[2]},
      .fetch = settings->hardware_filtering && fog->degree > 0 ? FOG_FETCH_HARDWARE
                                                               : FOG_FETCH_MANUAL,
      .resolution_divisor = settings->resolution_divisor,
  };
  gl_target_bind(&fog->target);
  return fog_pass_draw(fog->pass, cam, &params, scene->color[0], scene->color[1], fog->width,
                       fog->height, err);
}

int pipeline_fog_read(pipeline_fog *fog, float *rgba, float *transmittance, render_error *err) {
  if (rgba && gl_target_read(&fog->target, 0, 4, rgba, err)) return 1;
  if (transmittance && gl_target_read(&fog->target, 1, 1, transmittance, err)) return 1;
  return 0;
}

void pipeline_fog_present(pipeline_fog *fog, int width, int height) {
  if (!fog->target.framebuffer) return;
  if (!fog->present_program) {
    render_error err = {{0}};
    fog->present_program = gl_util_program_from_source("present", present_vs, present_fs, &err);
    if (!fog->present_program) {
      fprintf(stderr, "fogpipe: %s\n", err.message);
      return;
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(fog->present_program);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, fog->target.color[0]);
  glUniform1i(glGetUniformLocation(fog->present_program, "image"), 0);
  glBindVertexArray(gl_util_empty_vao());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
}
