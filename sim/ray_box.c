/* Ray / axis-aligned box clipping (see ray_box.h). */
#include "sim/ray_box.h"

#include <math.h>

int ray_box_clip(const double o[3], const double d[3], const double lo[3], const double hi[3],
                 double *t0, double *t1) {
  double a = -INFINITY, b = INFINITY;
  for (int c = 0; c < 3; c++) {
    if (fabs(d[c]) < 1e-15) {
      if (o[c] < lo[c] || o[c] > hi[c]) return 0;
      continue;
    }
    /* The slab lo[c] <= o[c] + t d[c] <= hi[c]; the interval is the slabs' intersection. */
    double s0 = (lo[c] - o[c]) / d[c], s1 = (hi[c] - o[c]) / d[c];
    if (s0 > s1) {
      const double t = s0;
      s0 = s1;
      s1 = t;
    }
    a = fmax(a, s0);
    b = fmin(b, s1);
  }
  *t0 = a;
  *t1 = b;
  return b > a;
}
