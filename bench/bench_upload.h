/* Upload of the coefficient textures, direct vs through a pixel-unpack buffer
 * (bench_upload.c); `fogpipe bench render` prints it. Needs a current GL context. */
#ifndef FOGPIPE_BENCH_UPLOAD_H
#define FOGPIPE_BENCH_UPLOAD_H

#include <stddef.h>

#include "bench/bench.h"
#include "render/gl_util.h"
#include "render/render.h"

typedef struct bench_upload_timing {
  double direct_ms, staged_ms; /* medians per pyramid upload */
  size_t bytes;                /* all textures of the pyramid */
  int textures;
} bench_upload_timing;

int bench_time_uploads(const fog_lod *lod, int rounds, bench_upload_timing *out, fog_error *err);

#endif
