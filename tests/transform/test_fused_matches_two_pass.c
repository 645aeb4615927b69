/* The single-pass forward level (symmetric, non-standard) and the two-pass
 * rows-then-column-strips version (periodic mode, small levels, desc.two_pass) compute
 * the same coefficients (to float rounding: the ends sum in another order); likewise
 * the single-pass inverse level (Haar, CDF 5/3) and the two-pass inverse. With two
 * threads the single-pass levels split their rows, each thread re-lifting the rows
 * before its range: the result must have the same bits as with one thread. */
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "transform_test_util.h"

int main(void) {
  /* the last ones are big enough for two threads to split their levels */
  const int sizes[][2] = {{8, 8},     {9, 8},     {16, 17},   {33, 67},
                          {64, 64},   {130, 99},  {300, 257}, {256, 257},
                          {1024, 24}, {157, 300}, {512, 65}};
  for (int b = 0; b < 3; b++)
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
      int w = sizes[s][0], h = sizes[s][1];
      int J = transform_max_levels(w, h, TRANSFORM_SYMMETRIC);
      transform_desc desc = {.width = w, .height = h, .levels = J, .basis = test_bases[b]};
      transform_plan *one, *two, *split;
      fog_error err;
      test_plan_pair(desc, &one, &two);
      desc.threads = 2;
      CHECK((split = transform_plan_create(&desc, &err)) != NULL, "%s", err.message);
      size_t n = (size_t)w * h;
      float *f = malloc(n * sizeof *f), *c1 = malloc(n * sizeof *f), *c2 = malloc(n * sizeof *f);
      test_fill_fogmap(f, w, h);
      transform_forward(one, f, c1);
      transform_forward(two, f, c2);
      double diff = 0.0;
      for (size_t i = 0; i < n; i++) diff = fmax(diff, fabs((double)c1[i] - c2[i]));
      CHECK(diff <= 1e-6 * test_max_abs(c2, n), "%s %dx%d J=%d: fused and two-pass differ by %.3g",
            test_basis_names[b], w, h, J, diff);
      transform_forward(split, f, c2);
      CHECK(!memcmp(c1, c2, n * sizeof *c1), "%s %dx%d J=%d: the fused level split between "
            "two threads changes bits", test_basis_names[b], w, h, J);
      transform_inverse(one, c1, c2);
      transform_inverse(split, c1, f);
      CHECK(!memcmp(f, c2, n * sizeof *f), "%s %dx%d J=%d: the fused inverse split between "
            "two threads changes bits", test_basis_names[b], w, h, J);
      test_fill_fogmap(f, w, h);
      transform_forward(two, f, c2);
      /* the inverse too (streaming for Haar and CDF 5/3 with one thread) */
      transform_inverse(one, c2, c1);
      transform_inverse(two, c2, f);
      diff = 0.0;
      for (size_t i = 0; i < n; i++) diff = fmax(diff, fabs((double)c1[i] - f[i]));
      CHECK(diff <= 1e-6 * test_max_abs(f, n), "%s %dx%d J=%d: inverses differ by %.3g",
            test_basis_names[b], w, h, J, diff);
      free(f), free(c1), free(c2);
      transform_plan_destroy(one);
      transform_plan_destroy(two);
      transform_plan_destroy(split);
    }
  return test_finish("test_fused_matches_two_pass");
}
