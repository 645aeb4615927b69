/* The EXR layout of a rendered frame, one definition for `fogpipe render` and `record`:
 * R, G, B, A as half (as float where half cannot hold them); transmittance, depth and Z (the same plane: what compositors read)
 * and inscatter.R/G/B as 32-bit float (rgb = transmittance x surface + inscatter). The
 * channels are written sorted by name, whatever their order here. */
#ifndef FOGPIPE_APP_FRAME_EXR_H
#define FOGPIPE_APP_FRAME_EXR_H

#include <stdbool.h>

#include "sim/sim.h"

#define FRAME_EXR_PLANES 9   /* R G B A, transmittance, depth, inscatter R G B */
#define FRAME_EXR_CHANNELS 10

/* The largest value a half-float channel holds. */
#define FRAME_EXR_HALF_MAX 65504.0f

/* De-interleaves a frame read back (rgba: 4 floats a pixel, inscatter: 3; rows bottom up
 * as GL reads them, or top first) into FRAME_EXR_PLANES planes of scratch, top row first,
 * and lists the channels pointing at them. Returns true when R, G, B, A go as 32-bit float
 * instead: some finite value of theirs lies beyond FRAME_EXR_HALF_MAX (a lamp's core at
 * 1e9), which half would lose; the caller says so. */
bool frame_exr_channels(const float *rgba, const float *transmittance, const float *depth,
                        const float *inscatter, int width, int height, bool bottom_up,
                        float *scratch, image_channel channels[FRAME_EXR_CHANNELS]);

#endif
