/* Blender 3.x Mantaflow config/config_####.uni reader: a gzip'd little-endian struct
 * written by MANTA::writeConfiguration (intern/mantaflow/intern/MANTA_main.cpp); the
 * layout is the one ../shared/data/vdb/read_config_uni.py decodes:
 *   "<i3iff3f3f3f3i3f16f3i3i3i3ff4s" = 204 bytes. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <zlib.h>

#include "sim/vdb_import.h"

enum { CONFIG_BYTES = 204 };

static int32_t read_i32(const unsigned char **p) {
  uint32_t v = (uint32_t)(*p)[0] | (uint32_t)(*p)[1] << 8 | (uint32_t)(*p)[2] << 16 |
               (uint32_t)(*p)[3] << 24;
  *p += 4;
  return (int32_t)v;
}

static float read_f32(const unsigned char **p) {
  int32_t bits = read_i32(p);
  float f;
  memcpy(&f, &bits, sizeof f);
  return f;
}

int mantaflow_config_read(const char *path, mantaflow_config *out, fog_error *err) {
  *out = (mantaflow_config){0};
  FILE *f = fopen(path, "rb");
  if (!f) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot open Mantaflow config", path);
    return 1;
  }
  unsigned char magic[2] = {0};
  size_t got = fread(magic, 1, 2, f);
  fclose(f);
  /* gzread passes non-gzip bytes through unchanged: check the gzip magic ourselves. */
  if (got < 2 || magic[0] != 0x1f || magic[1] != 0x8b) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: not a Mantaflow config (expected a gzip file)", path);
    return 1;
  }
  gzFile gz = gzopen(path, "rb");
  if (!gz) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot open Mantaflow config", path);
    return 1;
  }
  unsigned char bytes[CONFIG_BYTES + 1];
  int n = gzread(gz, bytes, sizeof bytes);
  int gz_status = gzclose(gz);
  if (n != CONFIG_BYTES || gz_status != Z_OK) {
    fog_fail(err, FOG_ERR_BAD_FILE,
             "%s: Mantaflow config has %d bytes after gunzip (or is truncated), expected %d "
             "(Blender 3.x layout)",
             path, n, CONFIG_BYTES);
    return 1;
  }
  const unsigned char *p = bytes;
  out->active_fields = read_i32(&p);
  for (int a = 0; a < 3; a++) out->res[a] = read_i32(&p);
  out->dx = read_f32(&p);
  out->dt = read_f32(&p);
  for (int a = 0; a < 3; a++) out->p0[a] = read_f32(&p);
  for (int a = 0; a < 3; a++) out->p1[a] = read_f32(&p);
  for (int a = 0; a < 3; a++) out->dp0[a] = read_f32(&p);
  for (int a = 0; a < 3; a++) out->shift[a] = read_i32(&p);
  for (int a = 0; a < 3; a++) out->obj_shift_f[a] = read_f32(&p);
  /* float[4][4] written column by column: element (row r, column c) is at c*4 + r. */
  for (int c = 0; c < 4; c++)
    for (int r = 0; r < 4; r++) out->obmat[r][c] = read_f32(&p);
  for (int a = 0; a < 3; a++) out->base_res[a] = read_i32(&p);
  for (int a = 0; a < 3; a++) out->res_min[a] = read_i32(&p);
  for (int a = 0; a < 3; a++) out->res_max[a] = read_i32(&p);
  for (int a = 0; a < 3; a++) out->active_color[a] = read_f32(&p);
  out->time_total = read_f32(&p);
  memcpy(out->cache_version, p, 4);
  out->cache_version[4] = 0;
  for (int a = 0; a < 3; a++)
    if (out->base_res[a] <= 0 || out->res[a] <= 0 || !(out->p1[a] > out->p0[a])) {
      fog_fail(err, FOG_ERR_BAD_FILE,
               "%s: Mantaflow config has a degenerate domain on axis %d (base_res %d, res "
               "%d, p0 %g, p1 %g)",
               path, a, out->base_res[a], out->res[a], out->p0[a], out->p1[a]);
      return 1;
    }
  return 0;
}
