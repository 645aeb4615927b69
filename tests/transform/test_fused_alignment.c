/* The single-pass forward level places its ring of rows to match the output's offset
 * within a 64-byte line and starts its column vectors at the first aligned output
 * (transform_fused_linear.h): where the caller's buffers sit must not change a bit of
 * the result. Every input and output offset within a line (0..15 floats) gives the
 * coefficients of offset 0 exactly, and those match the two-pass transform (rows, then
 * strips of columns) to float rounding. */
#define _ISOC11_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"
#include "transform_test_util.h"

int main(void) {
  const int sizes[][2] = {{16, 16}, {33, 20}, {64, 64}, {130, 37}, {257, 18}, {1024, 24}};
  for (int b = 0; b < 3; b++)
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++)
      for (int all_levels = 0; all_levels < 2; all_levels++) {
        int w = sizes[s][0], h = sizes[s][1];
        int J = all_levels ? transform_max_levels(w, h, TRANSFORM_SYMMETRIC) : 1;
        transform_plan *one, *two;
        test_plan_pair((transform_desc){.width = w, .height = h, .levels = J, .basis = test_bases[b]},
                       &one, &two);
        size_t n = (size_t)w * h, bytes = (n + 16) * sizeof(float);
        bytes = (bytes + 63) / 64 * 64;
        float *in = aligned_alloc(64, bytes), *out = aligned_alloc(64, bytes);
        float *ref = malloc(n * sizeof *ref), *two_pass = malloc(n * sizeof *ref);
        float *f = malloc(n * sizeof *f);
        test_fill_fogmap(f, w, h);
        memcpy(in, f, n * sizeof *f);
        transform_forward(one, in, ref);
        transform_forward(two, f, two_pass);
        double diff = 0.0;
        for (size_t i = 0; i < n; i++) diff = fmax(diff, fabs((double)ref[i] - two_pass[i]));
        CHECK(diff <= 1e-6 * test_max_abs(two_pass, n), "%s %dx%d J=%d: fused and two-pass "
              "differ by %.3g", test_basis_names[b], w, h, J, diff);
        int mismatched = 0, first_in = -1, first_out = -1;
        for (int in_off = 0; in_off < 16; in_off++)
          for (int out_off = 0; out_off < 16; out_off++) {
            memcpy(in + in_off, f, n * sizeof *f);
            transform_forward(one, in + in_off, out + out_off);
            if (memcmp(out + out_off, ref, n * sizeof *ref)) {
              if (!mismatched++) first_in = in_off, first_out = out_off;
            }
          }
        CHECK(!mismatched, "%s %dx%d J=%d: %d of 256 buffer offsets change the result "
              "(first: input +%d, output +%d floats)", test_basis_names[b], w, h, J,
              mismatched, first_in, first_out);
        free(in), free(out), free(ref), free(two_pass), free(f);
        transform_plan_destroy(one);
        transform_plan_destroy(two);
      }
  return test_finish("test_fused_alignment");
}
