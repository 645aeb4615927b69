/* The CPU scene geometry sees a box as the GL draws it, on flat ground at y = 0 (a box of
 * 20 x 10 x 20 at the origin, written here, not read from the code):
 *  - from above, the roof at its height, normal up;
 *  - from inside looking up, the roof's underside, normal down (the side the ray sees, as
 *    the shader turns it towards the camera; it was the outer normal);
 *  - from inside looking along +x, the wall's inside, normal -x;
 *  - from inside looking down, no bottom face (the GL draws none): the ground, normal up
 *    (it was the bottom face seen from above, normal down);
 *  - from under the ground looking up, the terrain's underside, normal down. */
#include <math.h>

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

int main(void) {
  static float heights[9 * 9];
  scene_desc desc = {.terrain = {.origin = {-100, 0, -100}, .size = {200, 200}, .height = 1,
                                 .heights = heights, .heights_width = 9, .heights_height = 9},
                     .boxes = {{.center = {0, 0}, .size = {20, 10, 20}}},
                     .box_count = 1,
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
  scene_geometry_destroy(&geo);
  return test_finish("test_scene_box_sides");
}
