/* Supersampled frames (app/supersample.h). */
#include "app/supersample.h"

#include <math.h>
#include <stdlib.h>

#include "sim/sim.h"

void supersample_free(frame_pixels *fine) {
  free(fine->rgba), free(fine->transmittance), free(fine->depth), free(fine->inscatter);
  *fine = (frame_pixels){0};
}

int supersample_buffers(const frame_pixels *out, int width, int height, int k,
                        frame_pixels *fine, fog_error *err) {
  const size_t n = (size_t)width * k * (size_t)height * k;
  *fine = (frame_pixels){
      .rgba = out->rgba ? malloc(4 * n * sizeof(float)) : NULL,
      .transmittance = out->transmittance ? malloc(n * sizeof(float)) : NULL,
      .depth = out->depth ? malloc(n * sizeof(float)) : NULL,
      .inscatter = out->inscatter ? malloc(3 * n * sizeof(float)) : NULL};
  if ((out->rgba && !fine->rgba) || (out->transmittance && !fine->transmittance) ||
      (out->depth && !fine->depth) || (out->inscatter && !fine->inscatter)) {
    supersample_free(fine);
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY,
                    "out of memory for a %dx%d frame supersampled %d x %d", width, height, k, k);
  }
  return 0;
}

/* Each output pixel's channels values: the mean of its k x k block in fine (channels
 * floats a pixel), summed in double. */
static void block_mean(const float *fine, int width, int height, int k, int channels,
                       float *out) {
  const size_t fine_width = (size_t)width * k;
  for (int y = 0; y < height; y++)
    for (int x = 0; x < width; x++)
      for (int c = 0; c < channels; c++) {
        double sum = 0.0;
        for (int j = 0; j < k; j++) {
          const float *row = fine + ((size_t)(y * k + j) * fine_width + (size_t)x * k) * channels;
          for (int i = 0; i < k; i++) sum += row[i * channels + c];
        }
        out[((size_t)y * width + x) * channels + c] = (float)(sum / (k * k));
      }
}

/* The block's nearest surface; sky (the value the frame holds for no surface) only when
 * every sample is sky: the sky is the far plane, and a surface at the frame's edge can lie
 * further along its ray than that z-plane, so a plain minimum took the sky over it. */
static void block_nearest(const float *fine, int width, int height, int k, float sky,
                          float *out) {
  const size_t fine_width = (size_t)width * k;
  for (int y = 0; y < height; y++)
    for (int x = 0; x < width; x++) {
      float nearest = INFINITY;
      for (int j = 0; j < k; j++)
        for (int i = 0; i < k; i++) {
          const float d = fine[(size_t)(y * k + j) * fine_width + (size_t)x * k + i];
          if (d != sky && d < nearest) nearest = d;
        }
      out[(size_t)y * width + x] = nearest == INFINITY ? sky : nearest;
    }
}

void supersample_reduce(const frame_pixels *fine, int width, int height, int k, float sky,
                        const frame_pixels *out) {
  if (out->rgba) block_mean(fine->rgba, width, height, k, 4, out->rgba);
  if (out->transmittance) block_mean(fine->transmittance, width, height, k, 1, out->transmittance);
  if (out->inscatter) block_mean(fine->inscatter, width, height, k, 3, out->inscatter);
  if (out->depth) block_nearest(fine->depth, width, height, k, sky, out->depth);
}
