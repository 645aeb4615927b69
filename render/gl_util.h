/* Small OpenGL helpers shared by the passes: shaders built from the embedded GLSL files
 * with readable errors (file name, stage and the GLSL info log), render targets (FBO +
 * textures), float read-back with rows top first, and glGetError checks.
 * Every function needs a current context (render/gl_context.h). */
#ifndef FOGPIPE_RENDER_GL_UTIL_H
#define FOGPIPE_RENDER_GL_UTIL_H

#include <limits.h>
#include <stdbool.h>

#include <GL/glcorearb.h>

#include "transform/fog_error.h"

/* The text of render/shaders/<name> embedded at build time (render/embed_shaders.cmake);
 * NULL if there is no such file. */
const char *render_shader_source(const char *name);

/* The embedded file with every line `#include "other.glsl"` replaced by that file's text
 * (recursively, depth 8), so CPU-mirrored formulas live in one .glsl file. Returns a
 * malloc'd string (caller frees) or NULL with err naming the missing file. */
char *gl_util_shader_text(const char *name, fog_error *err);

/* Compiles and links a program from embedded files: a vertex + fragment pair, or a
 * compute shader. On failure returns 0 and err holds "<file>: <stage> shader: <info log>"
 * (or the link log). */
GLuint gl_util_program(const char *vertex_name, const char *fragment_name, fog_error *err);
GLuint gl_util_compute_program(const char *compute_name, fog_error *err);
/* The same from source strings; label names them in errors. */
GLuint gl_util_program_from_source(const char *label, const char *vertex_source,
                                   const char *fragment_source, fog_error *err);

/* Returns non-zero and fills err ("<what>: GL_INVALID_OPERATION") if glGetError reports
 * anything; clears every pending error. */
int gl_util_check(const char *what, fog_error *err);

/* A framebuffer with up to 4 colour textures (any sized internal format: GL_RGBA16F,
 * GL_RGBA32F, GL_R32F, GL_RGBA8, ...) and an optional depth texture (GL_DEPTH_COMPONENT32F).
 * Colour textures are GL_NEAREST (colour 0 GL_LINEAR with linear_color0: a target the window
 * shows scaled), clamp to edge; draw buffers 0..n-1 are enabled. */
#define GL_TARGET_MAX_COLOR 4
typedef struct gl_target_desc {
  int width, height;
  GLenum color_formats[GL_TARGET_MAX_COLOR]; /* 0 ends the list */
  bool depth;
  bool linear_color0;
} gl_target_desc;

typedef struct gl_target {
  int width, height, color_count;
  GLuint framebuffer;
  GLuint color[GL_TARGET_MAX_COLOR];
  GLuint depth;  /* 0 when none */
} gl_target;

int gl_target_create(gl_target *target, const gl_target_desc *desc, fog_error *err);
void gl_target_destroy(gl_target *target);
/* Binds the framebuffer for drawing and sets the viewport to its size. */
void gl_target_bind(const gl_target *target);

/* Reads colour attachment `attachment` of target as `channels` floats per pixel (1: GL_RED,
 * 2: GL_RG, 3: GL_RGB, 4: GL_RGBA) into out (width*height*channels), rows TOP FIRST (GL
 * reads bottom-up; this flips). Returns non-zero on a GL error. */
int gl_target_read(const gl_target *target, int attachment, int channels, float *out,
                   fog_error *err);
/* Reads the bound read framebuffer's buffer `read_buffer` (e.g. GL_BACK for a window) as
 * RGB floats, rows top first. */
int gl_util_read_pixels(GLenum read_buffer, int width, int height, int channels, float *out,
                        fog_error *err);

/* A VAO to bind for gl_VertexID full-screen triangles (core profile needs one bound).
 * Created on first use (and again when a new context no longer knows it). */
GLuint gl_util_empty_vao(void);

/* How the texture bound to a target is sampled, every field given. */
typedef struct gl_sampling {
  GLint filter;     /* GL_LINEAR or GL_NEAREST, minifying and magnifying (no mipmaps) */
  GLint wrap[3];    /* S, T, R; R is set on 3D textures only */
  float border[4];  /* what GL_CLAMP_TO_BORDER reads outside */
  bool compare;     /* depth comparison for sampler*Shadow: passes when ref <= stored */
} gl_sampling;
void gl_util_set_sampling(GLenum target, const gl_sampling *sampling);

/* The common case of gl_util_set_sampling, for the texture bound to `target` (2D, 2D
 * array or 3D): GL_LINEAR filtering with a zero border (values outside the texture read
 * as 0, as coefficients and densities beyond a grid are), or GL_NEAREST for
 * texelFetch-only textures. */
void gl_util_texture_sampling(GLenum target, bool linear_zero_border);

/* The most loop iterations one shader invocation runs before the renderer ends its loops
 * early, measured by a probe shader (render/gl_loop_cap.c): 65535 on Mesa's llvmpipe, where
 * every loop of a shader that was not unrolled counts against one budget and a shader past
 * it draws wrong values without any error. GL_UTIL_NO_LOOP_CAP where the probe's 2^22
 * iterations all ran. Restores the bindings it changes. */
#define GL_UTIL_NO_LOOP_CAP LONG_MAX
int gl_util_loop_cap(long *cap, fog_error *err);

#endif
