/* The EXR's Z channel (app/frame_exr.h): the camera-space depth of each pixel's surface,
 * its distance along the pixel's ray times the cosine to the view axis, checked against
 * the surface point's own projection on the axis; the sky is the far plane. Two cases the
 * first rule missed: a far plane that is no float (1000.1: the sky's stored depth is its
 * float, below the double, and took a per-pixel Z), and a surface at the frame's edge
 * further along its ray than the far plane (a z-plane), whose Z is still less than it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app/frame_exr.h"
#include "test_util.h"

enum { W = 5, H = 3 };

int main(void) {
  camera cam = {.position = {3, 40, -7}, .yaw = 0.4, .pitch = -0.3, .fov_y = 1.6,
                .near_plane = 0.1, .far_plane = 1000.1};
  static float rgba[4 * W * H], one[W * H], depth[W * H], inscatter[3 * W * H];
  static float scratch[FRAME_EXR_PLANES * W * H];
  const float sky = (float)cam.far_plane;
  for (int k = 0; k < W * H; k++) {
    one[k] = 1.0f;
    depth[k] = k % 4 == 0 ? sky : 120.0f + 90.0f * (float)k; /* 1300 at the last: past far */
  }
  image_channel channels[FRAME_EXR_CHANNELS];
  frame_exr_channels(rgba, one, depth, inscatter, &cam, W, H, false, scratch, channels);
  const float *z = NULL;
  for (int c = 0; c < FRAME_EXR_CHANNELS; c++)
    if (!strcmp(channels[c].name, "Z")) z = channels[c].pixels;
  CHECK(z != NULL, "no Z channel");
  if (!z) return test_finish("test_frame_exr_z");
  double right[3], up[3], forward[3], worst = 0.0;
  camera_basis(&cam, W, H, right, up, forward);
  const double f_len = sqrt(forward[0] * forward[0] + forward[1] * forward[1] +
                            forward[2] * forward[2]);
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      const int k = py * W + px;
      if (depth[k] == sky) {
        CHECK(z[k] == sky, "pixel (%d, %d): the sky's Z %.9g, expected the far plane %.9g", px,
              py, (double)z[k], (double)sky);
        continue;
      }
      double o[3], dir[3], along = 0.0;
      camera_ray(&cam, px, py, W, H, o, dir);
      for (int a = 0; a < 3; a++) along += depth[k] * dir[a] * forward[a] / f_len;
      worst = fmax(worst, fabs(z[k] - along) / along);
      CHECK(z[k] < cam.far_plane || depth[k] < cam.far_plane,
            "pixel (%d, %d): depth %g past the far plane kept Z %g", px, py, (double)depth[k],
            (double)z[k]);
    }
  CHECK(worst < 1e-6, "Z against the surface point's depth along the axis: %.3e", worst);
  CHECK(depth[W * H - 1] > cam.far_plane && z[W * H - 1] < cam.far_plane,
        "the edge surface past the far plane along its ray: Z %g", (double)z[W * H - 1]);
  return test_finish("test_frame_exr_z");
}
