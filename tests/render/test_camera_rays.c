/* The camera's two faces agree: the ray camera_ray() gives for pixel (px, py) (row 0 at
 * the top), pushed through camera_view_matrix and camera_projection_matrix, lands on that
 * pixel's centre (so rasterised surfaces and per-pixel fog rays see the same point);
 * camera_view_matrix_world = view matrix of (world - position); camera_look_at aims the
 * centre of the image at the target; row 0 looks up, column 0 looks left. */
#include <math.h>
#include <stdio.h>

#include "render/camera.h"
#include "fog_test_scene.h"
#include "test_util.h"

static void mat_vec(const float m[16], const double v[4], double out[4]) {
  for (int r = 0; r < 4; r++) {
    out[r] = 0.0;
    for (int c = 0; c < 4; c++) out[r] += (double)m[c * 4 + r] * v[c];
  }
}

int main(void) {
  double worst_pixel = 0.0;
  for (int k = 0; k < 200; k++) {
    camera cam = {.position = {fog_test_range(-500, 500), fog_test_range(-50, 200),
                               fog_test_range(-500, 500)},
                  .yaw = fog_test_range(-3.1, 3.1), .pitch = fog_test_range(-1.4, 1.4),
                  .fov_y = fog_test_range(0.2, 2.0), .aspect = (k % 2) ? 0.0 : 1.7,
                      .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    int width = 64 + k % 7 * 33, height = 36 + k % 5 * 21;
    float view[16], view_world[16], proj[16];
    camera_view_matrix(&cam, view);
    camera_view_matrix_world(&cam, view_world);
    camera_projection_matrix(&cam, width, height, proj);
    for (int s = 0; s < 20; s++) {
      double px = floor(fog_test_range(0, width)), py = floor(fog_test_range(0, height));
      double o[3], d[3];
      camera_ray(&cam, px, py, width, height, o, d);
      CHECK(fabs(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - 1.0) < 1e-14, "ray not unit length");
      double dist = fog_test_range(1.0, 100.0);
      double rel[4] = {d[0] * dist, d[1] * dist, d[2] * dist, 1.0}, eye[4], clip[4];
      mat_vec(view, rel, eye);
      mat_vec(proj, eye, clip);
      double ndc_x = clip[0] / clip[3], ndc_y = clip[1] / clip[3];
      double back_px = (ndc_x + 1.0) * 0.5 * width - 0.5;
      double back_py = (1.0 - ndc_y) * 0.5 * height - 0.5; /* row 0 at the top */
      double e = fmax(fabs(back_px - px), fabs(back_py - py));
      if (e > worst_pixel) worst_pixel = e;
      CHECK(e < 1e-3, "pixel (%g, %g) comes back at (%g, %g)", px, py, back_px, back_py);
      CHECK(eye[2] < 0.0, "a visible point must have eye z < 0 (OpenGL looks down -Z)");
      /* The world matrix on the world point gives the same eye-space point. */
      double world[4] = {o[0] + rel[0], o[1] + rel[1], o[2] + rel[2], 1.0}, eye_w[4];
      mat_vec(view_world, world, eye_w);
      for (int i = 0; i < 3; i++)
        CHECK(fabs(eye_w[i] - eye[i]) < 1e-4 * (1.0 + fabs(cam.position[0]) + fabs(cam.position[2])),
              "view_matrix_world differs from view_matrix on (world - position)");
    }
  }
  printf("worst pixel round trip %.2e\n", worst_pixel);
  /* look_at: with an even image the centre lies between the four middle pixels. */
  camera cam = {.position = {3, 4, 5},
                .fov_y = CAMERA_DEFAULT_FOV_Y, .near_plane = CAMERA_DEFAULT_NEAR,
                .far_plane = CAMERA_DEFAULT_FAR};
  double target[3] = {-20, 1, 30}, o[3], d[3], want[3];
  camera_look_at(&cam, target);
  camera_ray(&cam, 49.5, 29.5, 100, 60, o, d); /* fractional pixel: the exact centre */
  double n = 0.0;
  for (int i = 0; i < 3; i++) {
    want[i] = target[i] - o[i];
    n += want[i] * want[i];
  }
  for (int i = 0; i < 3; i++) CHECK(fabs(d[i] - want[i] / sqrt(n)) < 1e-12, "look_at centre ray");
  /* look_at straight down or up: the view a pitch of -90 or 90 draws (yaw 0: +X to the
   * right, -Z at the top looking down); atan2(0, -0) made the yaw pi, the image turned
   * half round */
  for (int up = 0; up < 2; up++) {
    camera vertical = cam;
    const double below[3] = {3, up ? 100 : -100, 5};
    camera_look_at(&vertical, below);
    CHECK(vertical.yaw == 0.0 && fabs(vertical.pitch - (up ? 1 : -1) * 1.5707963267948966) < 1e-15,
          "look_at straight %s: yaw %g pitch %g, expected 0 and %s90 degrees", up ? "up" : "down",
          vertical.yaw, vertical.pitch, up ? "" : "-");
    camera_ray(&vertical, 99, 29.5, 100, 60, o, d); /* the right edge: towards +X */
    CHECK(d[0] > 0.3, "look_at straight %s: the right edge looks along x %g", up ? "up" : "down",
          d[0]);
  }
  /* Orientation: yaw = pitch = 0 looks along -Z; row 0 looks up, column 0 to -X. */
  camera flat = {.position = {0, 0, 0},
                .fov_y = CAMERA_DEFAULT_FOV_Y, .near_plane = CAMERA_DEFAULT_NEAR,
                .far_plane = CAMERA_DEFAULT_FAR};
  camera_ray(&flat, 50, 0, 101, 61, o, d);
  CHECK(d[1] > 0.0 && d[2] < 0.0, "top row looks up and forward (-Z)");
  camera_ray(&flat, 0, 30, 101, 61, o, d);
  CHECK(d[0] < 0.0 && fabs(d[1]) < 1e-15, "left column looks to -X");
  return test_finish("test_camera_rays");
}
