/* frustum_culls_box never culls a box that has a visible point: for random cameras and
 * boxes, every box it culls is checked point by point (a 9^3 lattice) against the
 * projection's own view volume, written here from camera_basis (depth along forward in
 * [near, far], |ndc| <= 1). It must also cull what it can: every box wholly behind the
 * camera, and a good share of the boxes outside the view. */
#include <math.h>
#include <stdlib.h>

#include "render/frustum.h"
#include "render/vec3.h"
#include "test_util.h"

static double uniform(unsigned *state, double lo, double hi) {
  *state = *state * 1664525u + 1013904223u;
  return lo + (hi - lo) * ((*state >> 8) / 16777216.0);
}

/* Whether camera-relative point p is inside the view volume (no slack). */
static bool visible(const camera *cam, int w, int h, const double p[3]) {
  double right[3], up[3], forward[3], near, far;
  camera_basis(cam, w, h, right, up, forward);
  camera_depth_range(cam, &near, &far);
  double depth = vec3_dot(p, forward);
  if (depth < near || depth > far) return false;
  /* p = depth (forward + x right + y up) with right, up orthogonal to forward */
  double x = vec3_dot(p, right) / (depth * vec3_dot(right, right));
  double y = vec3_dot(p, up) / (depth * vec3_dot(up, up));
  return fabs(x) <= 1.0 && fabs(y) <= 1.0;
}

int main(void) {
  unsigned state = 2024;
  int culled = 0, outside = 0, outside_culled = 0, behind = 0, behind_culled = 0;
  int wrongly_culled = 0, boxes = 4000;
  for (int b = 0; b < boxes; b++) {
    camera cam = {.yaw = uniform(&state, -3.2, 3.2), .pitch = uniform(&state, -1.5, 1.5),
                  .fov_y = uniform(&state, 0.2, 2.0),
                  .near_plane = b % 2 ? 0.0 : uniform(&state, 0.01, 5.0),
                  .far_plane = b % 3 ? 0.0 : uniform(&state, 50.0, 500.0)};
    int w = 64 + b % 200, h = 64 + (b * 7) % 150;
    double lo[3], hi[3];
    for (int c = 0; c < 3; c++) {
      double centre = uniform(&state, -300, 300), half = uniform(&state, 0.01, 60);
      lo[c] = centre - half, hi[c] = centre + half;
    }
    frustum f;
    frustum_from_camera(&f, &cam, w, h);
    bool cull = frustum_culls_box(&f, lo, hi);
    int seen = 0;
    for (int i = 0; i <= 8; i++)
      for (int j = 0; j <= 8; j++)
        for (int k = 0; k <= 8; k++) {
          double p[3] = {lo[0] + (hi[0] - lo[0]) * i / 8, lo[1] + (hi[1] - lo[1]) * j / 8,
                         lo[2] + (hi[2] - lo[2]) * k / 8};
          seen += visible(&cam, w, h, p);
        }
    double right[3], up[3], forward[3], far_corner[3];
    camera_basis(&cam, w, h, right, up, forward);
    for (int c = 0; c < 3; c++) far_corner[c] = forward[c] >= 0 ? hi[c] : lo[c];
    bool wholly_behind = vec3_dot(far_corner, forward) < 0;
    culled += cull;
    if (cull && seen) {
      if (wrongly_culled++ < 3)
        fprintf(stderr, "box %d culled with %d of 729 lattice points visible\n", b, seen);
    }
    if (!seen) outside++, outside_culled += cull;
    if (wholly_behind) behind++, behind_culled += cull;
  }
  printf("%d boxes: %d culled; %d with no visible lattice point, %d of them culled; "
         "%d wholly behind the camera, %d culled\n",
         boxes, culled, outside, outside_culled, behind, behind_culled);
  CHECK(wrongly_culled == 0, "%d boxes culled that have visible points", wrongly_culled);
  CHECK(behind > 100 && behind_culled == behind, "%d of %d boxes behind the camera culled",
        behind_culled, behind);
  CHECK(outside > boxes / 4 && outside_culled > outside * 3 / 4,
        "only %d of %d boxes outside the view culled", outside_culled, outside);
  return test_finish("test_frustum");
}
