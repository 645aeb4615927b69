/* The EXR layout of a rendered frame, one definition for `fogpipe render` and `record`:
 * R, G, B, A as half (as float where half cannot hold them); transmittance, depth (the
 * distance along each pixel's ray), Z (the camera-space depth compositors read: along the
 * view axis, RenderMan's z) and inscatter.R/G/B as 32-bit float (rgb = transmittance x
 * surface + inscatter). The channels are written sorted by name, whatever their order
 * here. */
#ifndef FOGPIPE_APP_FRAME_EXR_H
#define FOGPIPE_APP_FRAME_EXR_H

#include <stdbool.h>

#include "render/camera.h"
#include "sim/sim.h"

#define FRAME_EXR_PLANES 10  /* R G B A, transmittance, depth, Z, inscatter R G B */
#define FRAME_EXR_CHANNELS 10

/* The largest value a half-float channel holds. */
#define FRAME_EXR_HALF_MAX 65504.0f

/* De-interleaves a frame read back (rgba: 4 floats a pixel, inscatter: 3; rows bottom up
 * as GL reads them, or top first) into FRAME_EXR_PLANES planes of scratch, top row first,
 * and lists the channels pointing at them. Z is depth times the cosine of each pixel
 * centre's ray to cam's view axis; the sky (depth equal to cam's far plane as a float, as
 * the frames hold it) is the far plane in both. Returns true when R, G, B, A go as 32-bit float
 * instead: some finite value of theirs lies beyond FRAME_EXR_HALF_MAX (a lamp's core at
 * 1e9), which half would lose; the caller says so. */
bool frame_exr_channels(const float *rgba, const float *transmittance, const float *depth,
                        const float *inscatter, const camera *cam, int width, int height,
                        bool bottom_up, float *scratch,
                        image_channel channels[FRAME_EXR_CHANNELS]);

#endif
