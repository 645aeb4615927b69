/* Every advection scheme runs 8 cells at a time with AVX2 gathers where the CPU has them
 * (sim/advect.c), and must give the bits of the portable scalar loop: random fields and
 * velocities, 1 to 4 fields, widths with and without a remainder past the last group of
 * 8, slow velocities (nearly every group vectorised) and fast ones (many groups whose
 * stencils wrap around the periodic edge, which the scalar cells take), and fields of
 * both signs. On a CPU without AVX2 (or a build without the gather loops) both runs
 * would be the scalar loop, so the test says so and is skipped (exit 77). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/sim.h"
#include "test_util.h"

static unsigned state = 2463534242u;
static float uniform(float lo, float hi) { /* xorshift32 */
  state ^= state << 13, state ^= state >> 17, state ^= state << 5;
  return lo + (hi - lo) * (float)(state >> 8) / 16777216.0f;
}

static void check(advect_scheme scheme, int w, int h, int count, float speed, float dt) {
  size_t n = (size_t)w * h;
  float *vx = malloc(n * sizeof *vx), *vz = malloc(n * sizeof *vz);
  float *src[4], *simd[4], *scalar[4];
  for (int f = 0; f < count; f++) {
    src[f] = malloc(n * sizeof(float));
    simd[f] = malloc(n * sizeof(float));
    scalar[f] = malloc(n * sizeof(float));
    for (size_t i = 0; i < n; i++) src[f][i] = uniform(f == 0 ? 0.0f : -1.0f, 1.0f);
  }
  for (size_t i = 0; i < n; i++) vx[i] = uniform(-speed, speed), vz[i] = uniform(-speed, speed);
  float *scratch = malloc(sizeof(float) * (size_t)advect_scratch_floats(w, h, count));
  advect_pass pass = {.width = w, .height = h, .velocity_x = vx, .velocity_z = vz, .dt = dt,
                      .scheme = scheme, .scratch = scratch};
  advect_fields(&pass, count, (const float *const *)src, simd);
  pass.portable = 1;
  advect_fields(&pass, count, (const float *const *)src, scalar);
  int differing = 0;
  for (int f = 0; f < count; f++)
    for (size_t i = 0; i < n; i++)
      differing += memcmp(&simd[f][i], &scalar[f][i], sizeof(float)) != 0;
  static const char *names[] = {"", "bilinear", "cubic", "maccormack", "maccormack-bilinear"};
  CHECK(differing == 0, "%s %dx%d, %d fields, speed %g: %d values differ from the scalar loop",
        names[scheme], w, h, count, (double)speed, differing);
  for (int f = 0; f < count; f++) free(src[f]), free(simd[f]), free(scalar[f]);
  free(vx), free(vz), free(scratch);
}

int main(void) {
#if defined(__GNUC__) && defined(__x86_64__) /* where sim/advect_avx2.c is built */
  if (!__builtin_cpu_supports("avx2")) {
    printf("skipped: this CPU has no AVX2, so the pass has only the scalar loop\n");
    return 77;
  }
#else
  printf("skipped: this build has no AVX2 gather loops (GCC/Clang on x86-64 only)\n");
  return 77;
#endif
  const int sizes[][2] = {{256, 256}, {64, 40}, {37, 29}, {8, 8}, {23, 64}};
  const advect_scheme schemes[] = {ADVECT_MONOTONE_CUBIC, ADVECT_BILINEAR, ADVECT_MACCORMACK,
                                   ADVECT_MACCORMACK_BILINEAR};
  for (int k = 0; k < 4; k++)
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++)
      for (int count = 1; count <= 4; count++) {
        check(schemes[k], sizes[s][0], sizes[s][1], count, 2.0f, 0.5f);  /* ~a cell a step */
        check(schemes[k], sizes[s][0], sizes[s][1], count, 40.0f, 0.5f); /* up to 20: wraps */
      }
  return test_finish("test_advect_simd_matches_scalar");
}
