/* app_median (app/clock.h), the one median of the pipeline's timings, fit's --timed N and
 * the benchmarks: the middle value of an odd count and the mean of the middle two of an
 * even one, whatever the order given. fit took times[n / 2] alone: for --timed 2 the
 * slower of the two frames, which can move a rung out of the 25 % tie with another. */
#include <stdio.h>

#include "app/clock.h"
#include "test_util.h"

int main(void) {
  double one[] = {7.0};
  CHECK(app_median(one, 1) == 7.0, "median of {7}: %g", app_median(one, 1));
  double two[] = {9.0, 3.0};
  const double m2 = app_median(two, 2);
  CHECK(m2 == 6.0, "median of {9, 3}: %g, expected 6", m2);
  double three[] = {5.0, -1.0, 2.0};
  CHECK(app_median(three, 3) == 2.0, "median of {5, -1, 2}: %g", app_median(three, 3));
  double four[] = {4.0, 1.0, 10.0, 2.0};
  const double m4 = app_median(four, 4);
  CHECK(m4 == 3.0, "median of {4, 1, 10, 2}: %g, expected 3", m4);
  CHECK(four[0] == 1.0 && four[1] == 2.0 && four[2] == 4.0 && four[3] == 10.0,
        "the values are not sorted in place");
  double ties[] = {2.0, 2.0, 1.0, 2.0, 3.0, 2.0};
  CHECK(app_median(ties, 6) == 2.0, "median of ties: %g", app_median(ties, 6));
  return test_finish("test_app_median");
}
