/* The CPU scene geometry sees a box as the GL draws it, on flat ground at y = 0 (a box of
 * 20 x 10 x 20 at the origin, written here, not read from the code):
 *  - from above, the roof at its height, normal up;
 *  - from inside looking up, the roof's underside, normal down (the side the ray sees, as
 *    the shader turns it towards the camera; it was the outer normal);
 *  - from inside looking along +x, the wall's inside, normal -x;
 *  - from inside looking down, no bottom face (the GL draws none): the ground, normal up
 *    (it was the bottom face seen from above, normal down);
 *  - from under the ground looking up, the terrain's underside, normal down;
 * and a box on bumpy ground stands on its footprint's lowest point: terrain_lowest_in
 * against 401 x 401 samples of the surface over random rectangles (inside, across the
 * edge, off the terrain): never above a sample (a box that floats shows a slit under its
 * walls; the 5 x 5 samples it used missed up to 6 units), within the sampling's step of
 * the lowest. */
#include <math.h>
#include <stdint.h>

#include "render/render.h"
#include "test_util.h"

static void check_hit(const scene_geometry *geo, const double o[3], const double d[3],
                      double want_s, const double want_n[3], const char *what) {
  double s = 0, n[3] = {0, 0, 0};
  const bool hit = scene_geometry_intersect(geo, o, d, INFINITY, &s, n);
  CHECK(hit && fabs(s - want_s) <= 1e-9 && fabs(n[0] - want_n[0]) + fabs(n[1] - want_n[1]) +
                                                   fabs(n[2] - want_n[2]) <= 1e-9,
        "%s: hit %d at %.12g (want %g), normal (%g, %g, %g) (want (%g, %g, %g))", what, hit, s,
        want_s, n[0], n[1], n[2], want_n[0], want_n[1], want_n[2]);
}

static uint64_t state = 88172645463325252ull;
static double uniform(double lo, double hi) {
  state ^= state << 13, state ^= state >> 7, state ^= state << 17;
  return lo + (hi - lo) * (double)(state >> 11) / 9007199254740992.0;
}

static void check_lowest(void) {
  enum { N = 17, S = 401 };
  static float heights[N * N];
  for (int k = 0; k < N * N; k++) heights[k] = (float)uniform(0, 1);
  terrain t;
  fog_error err = {0};
  if (terrain_create(&t, &(terrain_desc){.origin = {-80, 5, -80}, .size = {160, 160},
                                          .height = 30, .heights = heights, .heights_width = N,
                                          .heights_height = N},
                     &err)) {
    CHECK(0, "%s", err.message);
    return;
  }
  double above = -INFINITY, gap = 0;
  for (int trial = 0; trial < 60; trial++) {
    const double x0 = uniform(-120, 90), z0 = uniform(-120, 90);
    const double x1 = x0 + uniform(0.5, 70), z1 = z0 + uniform(0.5, 70);
    const double lowest = terrain_lowest_in(&t, x0, x1, z0, z1);
    double sampled = INFINITY;
    for (int j = 0; j < S; j++)
      for (int i = 0; i < S; i++)
        sampled = fmin(sampled, terrain_height_at(&t, x0 + (x1 - x0) * i / (S - 1),
                                                  z0 + (z1 - z0) * j / (S - 1)));
    above = fmax(above, lowest - sampled);
    gap = fmax(gap, sampled - lowest);
  }
  /* a slope is at most 30 units over a 10-unit cell; a sample lies within 0.25 of a point */
  CHECK(above <= 1e-9 && gap <= 3.0 * 0.25, "lowest ground: %g above a sample, %g below all",
        above, gap);
  /* and a box on it stands there */
  scene_desc desc = {.terrain = {.origin = {-80, 5, -80}, .size = {160, 160}, .height = 30,
                                 .heights = heights, .heights_width = N, .heights_height = N},
                     .boxes = {{.center = {7, -13}, .size = {43, 8, 29}}},
                     .box_count = 1,
                     .light = scene_light_default()};
  scene_geometry geo;
  if (scene_geometry_create(&geo, &desc, &err)) {
    CHECK(0, "%s", err.message);
  } else {
    const double want = terrain_lowest_in(&t, 7 - 21.5, 7 + 21.5, -13 - 14.5, -13 + 14.5);
    CHECK(geo.boxes[0].min[1] == want, "a box on bumpy ground stands at %.9g, the lowest "
          "point under it is %.9g", geo.boxes[0].min[1], want);
    scene_geometry_destroy(&geo);
  }
  terrain_destroy(&t);
}

int main(void) {
  static float heights[9 * 9];
  scene_desc desc = {.terrain = {.origin = {-100, 0, -100}, .size = {200, 200}, .height = 1,
                                 .heights = heights, .heights_width = 9, .heights_height = 9},
                     .boxes = {{.center = {0, 0}, .size = {20, 10, 20}},
                               {.center = {150, 0}, .size = {20, 10, 20}}},
                     .box_count = 2,
                     .light = scene_light_default()};
  fog_error err = {0};
  scene_geometry geo;
  if (scene_geometry_create(&geo, &desc, &err)) {
    CHECK(0, "%s", err.message);
    return test_finish("test_scene_box_sides");
  }
  const double up[3] = {0, 1, 0}, down[3] = {0, -1, 0}, east[3] = {1, 0, 0}, west[3] = {-1, 0, 0};
  check_hit(&geo, (double[3]){2, 30, 3}, down, 20, up, "the roof from above");
  check_hit(&geo, (double[3]){2, 4, 3}, up, 6, down, "the roof from inside");
  check_hit(&geo, (double[3]){2, 4, 3}, east, 8, west, "a wall from inside");
  check_hit(&geo, (double[3]){2, 4, 3}, down, 4, up, "the ground from inside the box");
  check_hit(&geo, (double[3]){50, -5, 50}, up, 5, down, "the ground from below");
  /* a box past the terrain's edge (x 140..160; the terrain ends at 100): from below it, in
   * through the open bottom to the roof's underside */
  check_hit(&geo, (double[3]){150, -5, 0}, up, 15, down, "a box's roof through its open bottom");
  scene_geometry_destroy(&geo);
  check_lowest();
  return test_finish("test_scene_box_sides");
}
