/* The simulated density of a scene's frame n, as `fogpipe record` would show it (the
 * pipeline's own simulation set-up and steps per frame, drawing nothing, as `fogpipe bake`
 * runs it): a benchmark's "fog the product ships". */
#include <stdio.h>
#include <string.h>

#include "app/config.h"
#include "app/pipeline.h"
#include "bench/bench.h"
#include "render/render.h"
#include "sim/sim.h"

int bench_simulated_density(const char *config_path, int frame, double fps, fogmap *out,
                            char *error, size_t cap) {
  scene_config cfg;
  fog_error cerr = {0};
  if (scene_config_load(config_path, &cfg, &cerr)) {
    snprintf(error, cap, "%s", cerr.message);
    return 1;
  }
  fog_error gerr = {0};
  gl_context *gl = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &gerr);
  if (!gl) {
    snprintf(error, cap, "%s", gerr.message);
    return 1;
  }
  fog_error perr = {0};
  pipeline *p = pipeline_create(&(pipeline_desc){.config = &cfg, .width = 16, .height = 16,
                                                 .frame_seconds = 1.0 / fps,
                                                 .synchronous = true},
                                &perr);
  int status = !p || !pipeline_simulates(p) || pipeline_skip(p, frame, &perr);
  if (status) {
    snprintf(error, cap, "%s: %s", config_path,
             !p || perr.message[0] ? perr.message : "it simulates nothing");
  } else {
    const fogmap *density = pipeline_sim_density(p);
    fog_error serr = {0};
    status = fogmap_create(out, density->width, density->height, &serr);
    if (status)
      snprintf(error, cap, "%s", serr.message);
    else
      memcpy(out->density, density->density,
             sizeof(float) * (size_t)density->width * density->height);
  }
  if (p) pipeline_destroy(p);
  gl_context_destroy(gl);
  return status;
}
