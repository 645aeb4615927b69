/* ray_box_clip against the definition of the interval: for random lines (including ones
 * parallel to a face, inside and outside its slab) the point origin + t dir lies in the
 * box exactly for t in [t0, t1] (checked at the ends, just inside and just outside them,
 * and on a fine sweep of t), and a reported miss has no point of the line in the box. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "sim/sim.h"
#include "test_util.h"

static uint64_t rng = 0x243F6A8885A308D3ull;
static double uniform(double a, double b) { /* xorshift64* */
  rng ^= rng >> 12;
  rng ^= rng << 25;
  rng ^= rng >> 27;
  return a + (b - a) * (double)((rng * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

static int inside(const double p[3], const double lo[3], const double hi[3], double slack) {
  for (int a = 0; a < 3; a++)
    if (p[a] < lo[a] - slack || p[a] > hi[a] + slack) return 0;
  return 1;
}

static void at(const double o[3], const double d[3], double t, double p[3]) {
  for (int a = 0; a < 3; a++) p[a] = o[a] + t * d[a];
}

int main(void) {
  const double lo[3] = {-2.0, 0.5, 10.0}, hi[3] = {3.0, 4.0, 12.5};
  int hits = 0, misses = 0, bad_hit = 0, bad_miss = 0;
  for (int r = 0; r < 20000; r++) {
    double o[3], d[3], p[3], t0 = 0, t1 = 0;
    for (int a = 0; a < 3; a++) {
      o[a] = uniform(lo[a] - 6.0, hi[a] + 6.0);
      d[a] = uniform(-1.0, 1.0);
    }
    if (r % 4 == 0) d[r / 4 % 3] = 0.0; /* parallel to a pair of faces */
    if (!ray_box_clip(o, d, lo, hi, &t0, &t1)) {
      misses++;
      /* No point of the line within the box (sweep far enough to pass it). */
      for (int s = -4000; s <= 4000 && !bad_miss; s++) {
        at(o, d, s * 0.01, p);
        if (inside(p, lo, hi, -1e-9)) bad_miss = 1 + r;
      }
      continue;
    }
    hits++;
    const double eps = 1e-7 * (1.0 + fabs(t0) + fabs(t1));
    double p0[3], p1[3], q0[3], q1[3];
    at(o, d, t0, p0);
    at(o, d, t1, p1);
    at(o, d, t0 - 1e-3, q0);
    at(o, d, t1 + 1e-3, q1);
    int ok = t1 > t0 && inside(p0, lo, hi, 1e-9) && inside(p1, lo, hi, 1e-9) &&
             !inside(q0, lo, hi, 0.0) && !inside(q1, lo, hi, 0.0);
    for (int s = 1; s < 64 && ok; s++) {
      at(o, d, t0 + (t1 - t0) * s / 64.0, p);
      ok = inside(p, lo, hi, eps);
    }
    if (!ok && !bad_hit) bad_hit = 1 + r;
  }
  printf("%d lines meet the box, %d miss it\n", hits, misses);
  CHECK(hits > 1000 && misses > 1000, "too few hits (%d) or misses (%d) to test", hits, misses);
  CHECK(!bad_hit, "line %d: [t0, t1] is not the part of the line inside the box", bad_hit - 1);
  CHECK(!bad_miss, "line %d: reported a miss but passes through the box", bad_miss - 1);
  return test_finish("test_ray_box_clip");
}
