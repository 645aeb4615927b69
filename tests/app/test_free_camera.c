/* The window commands' free camera (app/free_camera.h), one set of controls for `demo` and
 * `view`, checked against render/camera.h's own basis (the rays the renderer shoots):
 *   - W for half a second moves speed/2 along the view's forward, at any yaw and pitch;
 *     Shift 4x; S back;
 *   - D moves along the image's right (level: camera_basis's right direction), E straight up;
 *   - a drag turns by 0.004 rad a pixel from the second frame held (the first only takes
 *     hold), none after release; the arrow keys turn at 1.2 rad/s;
 *   - the pitch stops at +-pi/2 (straight up or down, where render's camera still draws). */
#include <math.h>
#include <stdio.h>

#include "app/free_camera.h"
#include "test_util.h"

static void unit(const double v[3], double out[3]) {
  const double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int i = 0; i < 3; i++) out[i] = v[i] / n;
}

/* Where one step of input `in` over dt takes a camera at yaw, pitch, minus where it was. */
static void moved(double yaw, double pitch, free_camera_input in, double dt, double out[3]) {
  free_camera fc = {.cam = {.position = {10, 20, 30}, .yaw = yaw, .pitch = pitch,
                            .fov_y = 1.0, .aspect = CAMERA_ASPECT_OF_IMAGE, .near_plane = 0.5, .far_plane = 1000},
                    .speed = 80.0};
  free_camera_step(&fc, &(free_camera_input){.forward = in.forward, .right = in.right,
                                             .up = in.up, .fast = in.fast},
                   dt);
  out[0] = fc.cam.position[0] - 10, out[1] = fc.cam.position[1] - 20;
  out[2] = fc.cam.position[2] - 30;
}

static double distance(const double a[3], const double b[3]) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

int main(void) {
  const double yaws[3] = {0.0, 0.7, -2.5}, pitches[3] = {0.0, 0.4, -1.1};
  double worst = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      camera cam = {.yaw = yaws[i], .pitch = pitches[j], .fov_y = 1.0, .aspect = CAMERA_ASPECT_OF_IMAGE, .near_plane = 0.5,
                    .far_plane = 1000};
      double right[3], up[3], forward[3], level[3], want[3], got[3];
      camera_basis(&cam, 64, 64, right, up, forward);
      unit(right, level);
      for (int k = 0; k < 3; k++) want[k] = 40 * forward[k];
      moved(yaws[i], pitches[j], (free_camera_input){.forward = 1}, 0.5, got);
      worst = fmax(worst, distance(got, want));
      for (int k = 0; k < 3; k++) want[k] = -160 * forward[k];
      moved(yaws[i], pitches[j], (free_camera_input){.forward = -1, .fast = true}, 0.5, got);
      worst = fmax(worst, distance(got, want));
      for (int k = 0; k < 3; k++) want[k] = 40 * level[k];
      moved(yaws[i], pitches[j], (free_camera_input){.right = 1}, 0.5, got);
      worst = fmax(worst, distance(got, want));
      CHECK(fabs(level[1]) < 1e-12, "the image's right tilts (%g)", level[1]);
      moved(yaws[i], pitches[j], (free_camera_input){.up = 1}, 0.5, got);
      worst = fmax(worst, distance(got, (const double[3]){0, 40, 0}));
    }
  printf("moves against camera_basis: max distance %.2e world units\n", worst);
  CHECK(worst < 1e-12, "a move strays %.3e from camera_basis's axes", worst);

  /* a drag: hold, then turn by the cursor's motion, then let go */
  free_camera fc = {.cam = {.fov_y = 1.0, .aspect = CAMERA_ASPECT_OF_IMAGE, .near_plane = 0.5, .far_plane = 1000}, .speed = 1};
  free_camera_step(&fc, &(free_camera_input){.cursor_x = 100, .cursor_y = 50, .look = true}, 0.1);
  CHECK(fc.cam.yaw == 0 && fc.cam.pitch == 0, "the first frame held turned (%g, %g)",
        fc.cam.yaw, fc.cam.pitch);
  free_camera_step(&fc, &(free_camera_input){.cursor_x = 150, .cursor_y = 30, .look = true}, 0.1);
  CHECK(fabs(fc.cam.yaw - 0.2) < 1e-15 && fabs(fc.cam.pitch - 0.08) < 1e-15,
        "a drag of (50, -20) px turned to yaw %g pitch %g, expected 0.2 and 0.08", fc.cam.yaw,
        fc.cam.pitch);
  free_camera_step(&fc, &(free_camera_input){.cursor_x = 400, .cursor_y = 30}, 0.1);
  free_camera_step(&fc, &(free_camera_input){.cursor_x = 600, .cursor_y = 30, .look = true}, 0.1);
  CHECK(fabs(fc.cam.yaw - 0.2) < 1e-15, "released, then held again: turned to %g", fc.cam.yaw);
  /* arrows, and the pitch's stop */
  free_camera_step(&fc, &(free_camera_input){.cursor_x = 600, .cursor_y = 30, .turn_right = -1},
                   0.5);
  CHECK(fabs(fc.cam.yaw - (0.2 - 0.6)) < 1e-15, "Left for 0.5 s: yaw %g", fc.cam.yaw);
  for (int k = 0; k < 10; k++)
    free_camera_step(&fc, &(free_camera_input){.cursor_x = 600, .cursor_y = 30, .turn_up = 1},
                     0.5);
  CHECK(fc.cam.pitch == FREE_CAMERA_PITCH_LIMIT, "Up held: pitch %g", fc.cam.pitch);
  return test_finish("test_free_camera");
}
