/* The EXR layout of a frame (app/frame_exr.h). */
#include "app/frame_exr.h"

#include <math.h>
#include <stddef.h>

bool frame_exr_channels(const float *rgba, const float *transmittance, const float *depth,
                        const float *inscatter, const camera *cam, int width, int height,
                        bool bottom_up, float *scratch,
                        image_channel channels[FRAME_EXR_CHANNELS]) {
  const size_t n = (size_t)width * (size_t)height;
  float *plane[FRAME_EXR_PLANES];
  for (int c = 0; c < FRAME_EXR_PLANES; c++) plane[c] = scratch + (size_t)c * n;
  double right[3], up[3], forward[3];
  camera_basis(cam, width, height, right, up, forward);
  for (int y = 0; y < height; y++) {
    const size_t src = (size_t)(bottom_up ? height - 1 - y : y) * width, dst = (size_t)y * width;
    for (int x = 0; x < width; x++) {
      for (int c = 0; c < 4; c++) plane[c][dst + x] = rgba[4 * (src + x) + c];
      plane[4][dst + x] = transmittance[src + x];
      plane[5][dst + x] = depth[src + x];
      /* the ray of camera_ray through the pixel's centre (row 0 at the top) is
       * forward + nx right + ny up before its length is divided out: cos = 1 / length */
      const double nx = 2.0 * (x + 0.5) / width - 1.0, ny = 1.0 - 2.0 * (y + 0.5) / height;
      double len2 = 0.0;
      for (int a = 0; a < 3; a++) {
        const double v = forward[a] + nx * right[a] + ny * up[a];
        len2 += v * v;
      }
      /* the sky is the far plane exactly as the frame holds it (a float): a surface at the
       * frame's edge may lie further along its ray than the far plane, which is a z-plane */
      const float d = depth[src + x], sky = (float)cam->far_plane;
      plane[6][dst + x] = d == sky ? sky : (float)(d / sqrt(len2));
      for (int c = 0; c < 3; c++) plane[7 + c][dst + x] = inscatter[3 * (src + x) + c];
    }
  }
  /* a non-finite value stays half: the writer refuses it, naming the pixel */
  bool beyond_half = false;
  for (size_t k = 0; k < 4 * n && !beyond_half; k++)
    beyond_half = isfinite(rgba[k]) && fabsf(rgba[k]) > FRAME_EXR_HALF_MAX;
  const int half = !beyond_half;
  const image_channel layout[FRAME_EXR_CHANNELS] = {
      {.name = "R", .pixels = plane[0], .as_half = half},
      {.name = "G", .pixels = plane[1], .as_half = half},
      {.name = "B", .pixels = plane[2], .as_half = half},
      {.name = "A", .pixels = plane[3], .as_half = half},
      {.name = "transmittance", .pixels = plane[4], .as_half = 0},
      {.name = "depth", .pixels = plane[5], .as_half = 0},
      {.name = "Z", .pixels = plane[6], .as_half = 0},
      {.name = "inscatter.R", .pixels = plane[7], .as_half = 0},
      {.name = "inscatter.G", .pixels = plane[8], .as_half = 0},
      {.name = "inscatter.B", .pixels = plane[9], .as_half = 0},
  };
  for (int c = 0; c < FRAME_EXR_CHANNELS; c++) channels[c] = layout[c];
  return beyond_half;
}
