/* Helper of the PyWavelets cross-check (tests/transform/pywt.cmake): writes a fogmap and
 * its coefficients (periodic mode) as raw float32 to a file, for pywt_compare.py.
 * usage: transform_pywt_dump haar|linear|quadratic standard|nonstandard W H J OUT */
#include <stdio.h>
#include <string.h>

#include "transform_test_util.h"

int main(int argc, char **argv) {
  if (argc != 7) return 2;
  transform_basis basis = !strcmp(argv[1], "haar")     ? TRANSFORM_HAAR
                          : !strcmp(argv[1], "linear") ? TRANSFORM_LINEAR
                                                       : TRANSFORM_QUADRATIC;
  int w = atoi(argv[3]), h = atoi(argv[4]), J = atoi(argv[5]);
  transform_plan *plan;
  fog_error err;
  if (!(plan = transform_plan_create(&(transform_desc){.width = w, .height = h, .levels = J,
          .basis = basis, .boundary = TRANSFORM_PERIODIC,
          .decomposition = strcmp(argv[2], "standard") ? TRANSFORM_NONSTANDARD
                                                       : TRANSFORM_STANDARD}, &err))) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  size_t n = (size_t)w * h;
  float *f = malloc(n * sizeof *f), *c = malloc(n * sizeof *c);
  test_fill_fogmap(f, w, h);
  transform_forward(plan, f, c);
  FILE *out = fopen(argv[6], "wb");
  if (!out || fwrite(f, sizeof *f, n, out) != n || fwrite(c, sizeof *c, n, out) != n) return 1;
  fclose(out);
  free(f), free(c);
  transform_plan_destroy(plan);
  return 0;
}
