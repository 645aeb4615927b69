/* FFT planning modes. The reproducible default (FFTW_ESTIMATE, wisdom forgotten) gives
 * the same frames whether or not measured wisdom was loaded earlier in the process; the
 * measured mode writes wisdom to $XDG_CACHE_HOME/fogpipe/fftw3f.wisdom and, once it is
 * there, repeats its frames exactly; an unusable cache folder is not an error. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sim/sim.h"
#include "test_util.h"

enum { N = 64, STEPS = 30 };

static float *run(fluid_fft_planning planning) {
  fog_error err;
  fluid_sim_desc desc = fluid_sim_desc_default(N, N);
  desc.turbulence = 10, desc.seed = 9, desc.fft_planning = planning;
  desc.emitters = &(fluid_emitter){20, 20, 3, 2}, desc.emitter_count = 1;
  fluid_sim *sim = fluid_sim_create(&desc, &err);
  CHECK(sim != NULL, "create: %s", err.message);
  if (!sim) return NULL;
  for (int s = 0; s < STEPS; s++) fluid_sim_step(sim, &err);
  float *copy = malloc(sizeof(float) * N * N);
  memcpy(copy, fluid_sim_density(sim)->density, sizeof(float) * N * N);
  fluid_sim_destroy(sim);
  return copy;
}

int main(void) {
  char dir[] = "/tmp/fogpipe_wisdom_XXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  setenv("XDG_CACHE_HOME", dir, 1);

  float *before = run(FLUID_FFT_REPRODUCIBLE);
  float *measured = run(FLUID_FFT_MEASURED_WISDOM);
  char path[512];
  snprintf(path, sizeof path, "%s/fogpipe/fftw3f.wisdom", dir);
  struct stat st;
  CHECK(stat(path, &st) == 0 && st.st_size > 0, "wisdom file %s written", path);
  float *again = run(FLUID_FFT_MEASURED_WISDOM);
  float *after = run(FLUID_FFT_REPRODUCIBLE);
  const size_t bytes = sizeof(float) * N * N;
  CHECK(before && after && !memcmp(before, after, bytes),
        "reproducible mode changed after wisdom was loaded");
  CHECK(measured && again && !memcmp(measured, again, bytes),
        "measured mode with its wisdom cached should repeat its frames");

  /* A cache path that cannot be a folder: planning still works. */
  setenv("XDG_CACHE_HOME", "/dev/null/not-a-folder", 1);
  float *no_cache = run(FLUID_FFT_MEASURED_WISDOM);
  CHECK(no_cache != NULL, "an unusable cache folder must not fail creation");

  remove(path);
  char sub[512];
  snprintf(sub, sizeof sub, "%s/fogpipe", dir);
  rmdir(sub);
  rmdir(dir);
  free(before), free(measured), free(again), free(after), free(no_cache);
  return test_finish("test_fluid_fft_wisdom");
}
