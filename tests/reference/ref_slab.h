/* The slab test the test references share (Kay & Kajiya): narrows [*t0, *t1] to the part of
 * the line o + t d inside the closed box [lo, hi] (zero direction components allowed);
 * 0 when less than a point is left. Written apart from the renderer's slab tests. */
#ifndef FOGPIPE_TESTS_REFERENCE_REF_SLAB_H
#define FOGPIPE_TESTS_REFERENCE_REF_SLAB_H

static inline int ref_slab_clip(const double lo[3], const double hi[3], const double o[3],
                                const double d[3], double *t0, double *t1) {
  for (int k = 0; k < 3; k++) {
    if (d[k] == 0.0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return 0;
      continue;
    }
    double ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
    if (ta > tb) {
      double s = ta;
      ta = tb;
      tb = s;
    }
    if (ta > *t0) *t0 = ta;
    if (tb < *t1) *t1 = tb;
  }
  return *t0 < *t1;
}

#endif
