/* The renderer's upload question (issue 3: "plain glTexSubImage2D; a PBO path only if it
 * measures faster"): the LOD pyramid's textures, as fog_pass_upload_lod sends them (each
 * grid as R32F, its cell polynomials as RGBA32F), sent either straight from client memory
 * or staged through one streamed pixel-unpack buffer (orphaned with glBufferData, filled
 * through glMapBufferRange, then glTexSubImage2D from offsets). The cell polynomials are
 * built once beforehand, so only the transfer is timed. Rounds alternate the two ways;
 * glFinish before and after each. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench/bench_upload.h"
#include "render/fog_cell_poly.h"

enum { MAX_TEXTURES = 2 * 16 };

typedef struct upload_texture {
  GLuint name;
  GLenum format; /* GL_RED or GL_RGBA */
  int width, height;
  const float *data;
  size_t bytes, offset; /* offset: within the staging buffer */
} upload_texture;

static void upload_direct(const upload_texture *t, int count) {
  for (int i = 0; i < count; i++) {
    glBindTexture(GL_TEXTURE_2D, t[i].name);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, t[i].width, t[i].height, t[i].format, GL_FLOAT,
                    t[i].data);
  }
}

static int upload_staged(GLuint buffer, size_t total, const upload_texture *t, int count) {
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, buffer);
  glBufferData(GL_PIXEL_UNPACK_BUFFER, (GLsizeiptr)total, NULL, GL_STREAM_DRAW);
  char *map = glMapBufferRange(GL_PIXEL_UNPACK_BUFFER, 0, (GLsizeiptr)total,
                               GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
  if (!map) {
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    return 1;
  }
  for (int i = 0; i < count; i++) memcpy(map + t[i].offset, t[i].data, t[i].bytes);
  glUnmapBuffer(GL_PIXEL_UNPACK_BUFFER);
  for (int i = 0; i < count; i++) {
    glBindTexture(GL_TEXTURE_2D, t[i].name);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, t[i].width, t[i].height, t[i].format, GL_FLOAT,
                    (const void *)(uintptr_t)t[i].offset);
  }
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  return 0;
}

int bench_time_uploads(const fog_lod *lod, int rounds, bench_upload_timing *out, fog_error *err) {
  upload_texture t[MAX_TEXTURES] = {0};
  float *cells[MAX_TEXTURES / 2] = {0};
  double *direct = malloc(sizeof(double) * (size_t)rounds);
  double *staged = malloc(sizeof(double) * (size_t)rounds);
  GLuint buffer = 0;
  int count = 0, status = 1;
  size_t total = 0;
  if (!direct || !staged || 2 * (2 * lod->levels + 1) > MAX_TEXTURES) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "bench upload: out of memory or too many levels");
    goto done;
  }
  for (int g = 0; g < 2 * lod->levels + 1; g++) {
    const transform_grid *grid =
        g <= lod->levels ? &lod->approx[g] : &lod->detail[g - lod->levels - 1];
    int cw, ch;
    fog_cell_poly_size(grid->width, grid->height, grid->degree, &cw, &ch);
    cells[g] = malloc(sizeof(float) * 4 * (size_t)cw * (size_t)ch);
    if (!cells[g]) {
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "bench upload: out of memory");
      goto done;
    }
    fog_cell_poly_build(grid, cells[g]);
    t[count++] = (upload_texture){.format = GL_RED, .width = grid->width,
                                  .height = grid->height, .data = grid->coefficients};
    t[count++] = (upload_texture){.format = GL_RGBA, .width = cw, .height = ch,
                                  .data = cells[g]};
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glActiveTexture(GL_TEXTURE0);
  for (int i = 0; i < count; i++) {
    int channels = t[i].format == GL_RGBA ? 4 : 1;
    t[i].bytes = sizeof(float) * (size_t)channels * (size_t)t[i].width * (size_t)t[i].height;
    t[i].offset = total;
    total += (t[i].bytes + 63) & ~(size_t)63;
    glGenTextures(1, &t[i].name);
    glBindTexture(GL_TEXTURE_2D, t[i].name);
    glTexImage2D(GL_TEXTURE_2D, 0, channels == 4 ? GL_RGBA32F : GL_R32F, t[i].width,
                 t[i].height, 0, t[i].format, GL_FLOAT, NULL);
  }
  glGenBuffers(1, &buffer);
  for (int r = -1; r < rounds; r++) { /* round -1: warm-up of both ways */
    glFinish();
    double t0 = app_clock_seconds();
    upload_direct(t, count);
    glFinish();
    double t1 = app_clock_seconds();
    if (upload_staged(buffer, total, t, count)) {
      fog_fail(err, FOG_ERR_GRAPHICS, "bench upload: glMapBufferRange failed");
      goto done;
    }
    glFinish();
    double t2 = app_clock_seconds();
    if (r >= 0) direct[r] = t1 - t0, staged[r] = t2 - t1;
  }
  out->direct_ms = 1e3 * app_median(direct, rounds);
  out->staged_ms = 1e3 * app_median(staged, rounds);
  out->bytes = total;
  out->textures = count;
  status = gl_util_check("bench upload", err);
done:
  glBindTexture(GL_TEXTURE_2D, 0);
  for (int i = 0; i < count; i++)
    if (t[i].name) glDeleteTextures(1, &t[i].name);
  if (buffer) glDeleteBuffers(1, &buffer);
  for (int g = 0; g < MAX_TEXTURES / 2; g++) free(cells[g]);
  free(direct);
  free(staged);
  return status;
}
