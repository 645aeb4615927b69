/* OpenGL helpers: shaders from embedded files, render targets, read-back (gl_util.h). */
#include "render/gl_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/fog_shader_text.h"

/* ---- shader text with #include ---- */

typedef struct text_buffer {
  char *data;
  size_t length, capacity;
} text_buffer;

static int append(text_buffer *b, const char *s, size_t n) {
  if (b->length + n + 1 > b->capacity) {
    size_t capacity = b->capacity ? b->capacity : 4096;
    while (b->length + n + 1 > capacity) capacity *= 2;
    char *data = realloc(b->data, capacity);
    if (!data) return 1;
    b->data = data;
    b->capacity = capacity;
  }
  memcpy(b->data + b->length, s, n);
  b->length += n;
  b->data[b->length] = '\0';
  return 0;
}

static int expand(text_buffer *out, const char *name, int depth, fog_error *err) {
  char generated[FOG_SHADER_GENERATED_MAX];
  int generated_length = fog_shader_generated(name, generated, sizeof generated);
  if (generated_length == -2) {
    fog_fail(err, FOG_ERR_GRAPHICS,
             "generated shader header %s is longer than FOG_SHADER_GENERATED_MAX", name);
    return 1;
  }
  const char *text = generated_length >= 0 ? generated : render_shader_source(name);
  if (!text) {
    fog_fail(err, FOG_ERR_GRAPHICS,
             "shader file render/shaders/%s is not embedded (missing, or the build ran "
             "before it existed: re-run cmake)",
             name);
    return 1;
  }
  if (depth > 8) {
    fog_fail(err, FOG_ERR_GRAPHICS, "%s: #include nested deeper than 8", name);
    return 1;
  }
  for (const char *line = text; *line;) {
    const char *end = strchr(line, '\n');
    size_t n = end ? (size_t)(end - line) + 1 : strlen(line);
    const char *p = line;
    while (*p == ' ' || *p == '\t') p++;
    if (!strncmp(p, "#include", 8)) {
      const char *open = strchr(p, '"');
      const char *close = open ? strchr(open + 1, '"') : NULL;
      if (!close || close > line + n) {
        fog_fail(err, FOG_ERR_GRAPHICS, "%s: malformed #include line", name);
        return 1;
      }
      char included[128];
      snprintf(included, sizeof included, "%.*s", (int)(close - open - 1), open + 1);
      if (expand(out, included, depth + 1, err)) return 1;
      if (append(out, "\n", 1)) goto oom;
    } else if (append(out, line, n)) {
      goto oom;
    }
    line += n;
  }
  return 0;
oom:
  fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory expanding %s", name);
  return 1;
}

char *gl_util_shader_text(const char *name, fog_error *err) {
  text_buffer b = {0};
  if (expand(&b, name, 0, err)) {
    free(b.data);
    return NULL;
  }
  return b.data;
}

/* ---- compile and link ---- */

static const char *stage_name(GLenum stage) {
  switch (stage) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_COMPUTE_SHADER: return "compute";
    default: return "?";
  }
}

static GLuint compile(GLenum stage, const char *label, const char *source, fog_error *err) {
  GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, NULL);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[400] = "";
    glGetShaderInfoLog(shader, sizeof log, NULL, log);
    fog_fail(err, FOG_ERR_GRAPHICS, "%s: %s shader does not compile: %s", label, stage_name(stage),
             log);
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

static GLuint link(const char *label, GLuint *shaders, int count, fog_error *err) {
  GLuint program = glCreateProgram();
  for (int i = 0; i < count; i++) glAttachShader(program, shaders[i]);
  glLinkProgram(program);
  for (int i = 0; i < count; i++) glDeleteShader(shaders[i]);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[400] = "";
    glGetProgramInfoLog(program, sizeof log, NULL, log);
    fog_fail(err, FOG_ERR_GRAPHICS, "%s: program does not link: %s", label, log);
    glDeleteProgram(program);
    return 0;
  }
  return program;
}

GLuint gl_util_program_from_source(const char *label, const char *vertex_source,
                                   const char *fragment_source, fog_error *err) {
  GLuint shaders[2];
  shaders[0] = compile(GL_VERTEX_SHADER, label, vertex_source, err);
  if (!shaders[0]) return 0;
  shaders[1] = compile(GL_FRAGMENT_SHADER, label, fragment_source, err);
  if (!shaders[1]) {
    glDeleteShader(shaders[0]);
    return 0;
  }
  return link(label, shaders, 2, err);
}

GLuint gl_util_program(const char *vertex_name, const char *fragment_name, fog_error *err) {
  char *vs = gl_util_shader_text(vertex_name, err);
  if (!vs) return 0;
  char *fs = gl_util_shader_text(fragment_name, err);
  if (!fs) {
    free(vs);
    return 0;
  }
  GLuint shaders[2] = {compile(GL_VERTEX_SHADER, vertex_name, vs, err), 0};
  if (shaders[0]) shaders[1] = compile(GL_FRAGMENT_SHADER, fragment_name, fs, err);
  free(vs);
  free(fs);
  if (!shaders[1]) {
    if (shaders[0]) glDeleteShader(shaders[0]);
    return 0;
  }
  char label[256];
  snprintf(label, sizeof label, "%s + %s", vertex_name, fragment_name);
  return link(label, shaders, 2, err);
}

GLuint gl_util_compute_program(const char *compute_name, fog_error *err) {
  char *cs = gl_util_shader_text(compute_name, err);
  if (!cs) return 0;
  GLuint shader = compile(GL_COMPUTE_SHADER, compute_name, cs, err);
  free(cs);
  if (!shader) return 0;
  return link(compute_name, &shader, 1, err);
}

/* ---- errors ---- */

static const char *gl_error_name(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "GL error";
  }
}

int gl_util_check(const char *what, fog_error *err) {
  GLenum first = glGetError();
  if (first == GL_NO_ERROR) return 0;
  while (glGetError() != GL_NO_ERROR) {
  }
  fog_fail(err, FOG_ERR_GRAPHICS, "%s: %s (0x%x)", what, gl_error_name(first), first);
  return 1;
}

/* ---- render targets ---- */

int gl_target_create(gl_target *target, const gl_target_desc *desc, fog_error *err) {
  *target = (gl_target){.width = desc->width, .height = desc->height};
  if (desc->width <= 0 || desc->height <= 0) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "render target size %dx%d: expected > 0", desc->width,
             desc->height);
    return 1;
  }
  while (glGetError() != GL_NO_ERROR) {
  } /* every flag an earlier call left: the errors read below are this target's */
  /* The textures are made on the active unit: its binding is put back afterwards, so
   * making a target never unbinds a texture a pass has bound there. */
  GLint caller_texture = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &caller_texture);
  glGenFramebuffers(1, &target->framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, target->framebuffer);
  GLenum buffers[GL_TARGET_MAX_COLOR];
  for (int i = 0; i < GL_TARGET_MAX_COLOR && desc->color_formats[i]; i++) {
    glGenTextures(1, &target->color[i]);
    glBindTexture(GL_TEXTURE_2D, target->color[i]);
    glTexStorage2D(GL_TEXTURE_2D, 1, desc->color_formats[i], desc->width, desc->height);
    const GLint filter = i == 0 && desc->linear_color0 ? GL_LINEAR : GL_NEAREST;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D,
                           target->color[i], 0);
    buffers[i] = GL_COLOR_ATTACHMENT0 + i;
    target->color_count = i + 1;
  }
  if (desc->depth) {
    glGenTextures(1, &target->depth);
    glBindTexture(GL_TEXTURE_2D, target->depth);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, desc->width, desc->height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, target->depth,
                           0);
  }
  glBindTexture(GL_TEXTURE_2D, (GLuint)caller_texture);
  /* before the completeness check, which a texture without storage fails cryptically; every
   * queued error read, the first other one reported below */
  GLenum first_error = GL_NO_ERROR;
  bool out_of_memory = false;
  for (GLenum e; (e = glGetError()) != GL_NO_ERROR;) {
    out_of_memory |= e == GL_OUT_OF_MEMORY;
    if (first_error == GL_NO_ERROR && e != GL_OUT_OF_MEMORY) first_error = e;
  }
  if (out_of_memory) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY,
             "out of GPU memory for a %dx%d render target (%d colour textures%s): try a "
             "smaller size", desc->width, desc->height, target->color_count,
             desc->depth ? " and depth" : "");
    gl_target_destroy(target);
    return 1;
  }
  if (first_error != GL_NO_ERROR) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    fog_fail(err, FOG_ERR_GRAPHICS, "creating a %dx%d render target: %s (0x%x)", desc->width,
             desc->height, gl_error_name(first_error), first_error);
    gl_target_destroy(target);
    return 1;
  }
  if (target->color_count) glDrawBuffers(target->color_count, buffers);
  GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    fog_fail(err, FOG_ERR_GRAPHICS,
             "render target %dx%d with %d colour textures is incomplete (status 0x%x)", desc->width,
             desc->height, target->color_count, status);
    gl_target_destroy(target);
    return 1;
  }
  if (gl_util_check("creating a render target", err)) {
    gl_target_destroy(target);
    return 1;
  }
  return 0;
}

void gl_target_destroy(gl_target *target) {
  if (target->color_count) glDeleteTextures(target->color_count, target->color);
  if (target->depth) glDeleteTextures(1, &target->depth);
  if (target->framebuffer) glDeleteFramebuffers(1, &target->framebuffer);
  *target = (gl_target){0};
}

void gl_target_bind(const gl_target *target) {
  glBindFramebuffer(GL_FRAMEBUFFER, target->framebuffer);
  glViewport(0, 0, target->width, target->height);
}

static GLenum channel_format(int channels) {
  static const GLenum formats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  return channels >= 1 && channels <= 4 ? formats[channels - 1] : GL_RGBA;
}

/* Reads the bound read framebuffer; flips rows so the top row comes first. */
static int read_flipped(int width, int height, int channels, float *out, fog_error *err) {
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, channel_format(channels), GL_FLOAT, out);
  size_t row = (size_t)width * channels;
  float *swap = malloc(row * sizeof *swap);
  if (!swap) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory reading pixels");
    return 1;
  }
  for (int y = 0; y < height / 2; y++) {
    float *a = out + (size_t)y * row, *b = out + (size_t)(height - 1 - y) * row;
    memcpy(swap, a, row * sizeof *swap);
    memcpy(a, b, row * sizeof *swap);
    memcpy(b, swap, row * sizeof *swap);
  }
  free(swap);
  return gl_util_check("glReadPixels", err);
}

int gl_target_read(const gl_target *target, int attachment, int channels, float *out,
                   fog_error *err) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, target->framebuffer);
  glReadBuffer(GL_COLOR_ATTACHMENT0 + attachment);
  int status = read_flipped(target->width, target->height, channels, out, err);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return status;
}

int gl_util_read_pixels(GLenum read_buffer, int width, int height, int channels, float *out,
                        fog_error *err) {
  glReadBuffer(read_buffer);
  return read_flipped(width, height, channels, out, err);
}

GLuint gl_util_empty_vao(void) {
  /* One per process is enough for our single-context programs; a new context (different
   * object namespace) is detected by glIsVertexArray. */
  static GLuint vao;
  if (!vao || !glIsVertexArray(vao)) glGenVertexArrays(1, &vao);
  return vao;
}

void gl_util_set_sampling(GLenum target, const gl_sampling *s) {
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, s->filter);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, s->filter);
  glTexParameteri(target, GL_TEXTURE_WRAP_S, s->wrap[0]);
  glTexParameteri(target, GL_TEXTURE_WRAP_T, s->wrap[1]);
  if (target == GL_TEXTURE_3D) glTexParameteri(target, GL_TEXTURE_WRAP_R, s->wrap[2]);
  glTexParameterfv(target, GL_TEXTURE_BORDER_COLOR, s->border);
  glTexParameteri(target, GL_TEXTURE_COMPARE_MODE,
                  s->compare ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
  if (s->compare) glTexParameteri(target, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
}

void gl_util_texture_sampling(GLenum target, bool linear_zero_border) {
  /* texelFetch ignores wrapping and the border: only the filter matters there */
  const GLint filter = linear_zero_border ? GL_LINEAR : GL_NEAREST;
  gl_util_set_sampling(target,
                       &(gl_sampling){.filter = filter,
                                      .wrap = {GL_CLAMP_TO_BORDER, GL_CLAMP_TO_BORDER,
                                               GL_CLAMP_TO_BORDER},
                                      .border = {0, 0, 0, 0}});
}
