/* A size too small for J levels is refused with a message naming the largest J that
 * fits (symmetric: every split needs >= 2 samples; periodic: also an even length). */
#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "transform/transform.h"

static void refused(int w, int h, int J, transform_boundary mode, int largest) {
  transform_plan *plan = (transform_plan *)1;
  fog_error err = {0};
  int rc = !(plan = transform_plan_create(&(transform_desc){.width = w, .height = h,
      .levels = J, .boundary = mode}, &err));
  char want[64];
  snprintf(want, sizeof want, "largest J that fits is %d", largest);
  CHECK(rc != 0 && plan == NULL, "%dx%d J=%d accepted", w, h, J);
  CHECK(strstr(err.message, want) != NULL, "%dx%d J=%d: message \"%s\" lacks \"%s\"", w, h, J,
        err.message, want);
  CHECK(err.code == FOG_ERR_INVALID_ARGUMENT, "%dx%d J=%d: code %s", w, h, J,
        fog_result_text(err.code));
  CHECK(transform_max_levels(w, h, mode) == largest, "max levels of %dx%d: %d, want %d", w, h,
        transform_max_levels(w, h, mode), largest);
  /* and the largest J itself is accepted */
  rc = !(plan = transform_plan_create(&(transform_desc){.width = w, .height = h,
      .levels = largest, .boundary = mode}, &err));
  CHECK(rc == 0, "%dx%d J=%d refused: %s", w, h, largest, err.message);
  if (!rc) transform_plan_destroy(plan);
}

int main(void) {
  refused(16, 16, 5, TRANSFORM_SYMMETRIC, 4);
  refused(17, 16, 9, TRANSFORM_SYMMETRIC, 4);  /* 17 allows 5, 16 allows 4 */
  refused(1024, 3, 3, TRANSFORM_SYMMETRIC, 2);
  refused(1, 64, 1, TRANSFORM_SYMMETRIC, 0);
  refused(48, 40, 4, TRANSFORM_PERIODIC, 3);   /* 40 = 8 * 5 */
  refused(17, 16, 1, TRANSFORM_PERIODIC, 0);   /* odd width */
  /* the largest int: halving it as (n + 1) / 2 overflowed and never reached 1 */
  CHECK(transform_max_levels(INT_MAX, INT_MAX, TRANSFORM_SYMMETRIC) == 31,
        "INT_MAX: %d levels, expected 31", transform_max_levels(INT_MAX, INT_MAX,
                                                                TRANSFORM_SYMMETRIC));
  transform_plan *plan;
  fog_error err;
  CHECK((plan = transform_plan_create(&(transform_desc){.width = 0, .height = 4}, &err)) == NULL,
        "0x4 accepted");
  CHECK((plan = transform_plan_create(&(transform_desc){.width = 4, .height = 4, .levels = -1},
        &err)) == NULL, "negative levels accepted");
  /* a grid export of a level the plan does not have is refused before any size is read
   * (transform_grid_size read past the plan's level arrays first) */
  if ((plan = transform_plan_create(&(transform_desc){.width = 16, .height = 16, .levels = 2},
                                    &err))) {
    float coefficients[64 * 64];
    transform_grid grid = {.width = 64, .height = 64, .coefficients = coefficients};
    for (int level = -1; level <= 3; level += 4) {
      err = (fog_error){0};
      CHECK(transform_grid_export(plan, level, coefficients, &grid, &err) != 0 &&
                strstr(err.message, "expected 0..2"),
            "grid export of level %d: %s", level, err.message);
    }
    transform_plan_destroy(plan);
  }
  return test_finish("test_bad_size");
}
