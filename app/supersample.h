/* Supersampling of the headless frames ([render] supersample = k): the frame is drawn at k
 * times the width and height, and each k x k block becomes one pixel. Colour, alpha,
 * transmittance and in-scatter are block means (what a box filter of the pixel's area
 * sees: silhouettes and shadow edges anti-aliased); depth is the block's nearest surface
 * (a compositor's Z must name one surface, and the nearest keeps a fogged object's
 * outline in front of what lies behind it), the sky only where no sample has a surface. */
#ifndef FOGPIPE_APP_SUPERSAMPLE_H
#define FOGPIPE_APP_SUPERSAMPLE_H

#include "app/frame_pixels.h"
#include "transform/fog_error.h"

/* The k x k-finer frame's buffers for out's non-NULL outputs, for width x height output
 * pixels (k * width x k * height each); NULL pointers where out has none. 1 on failure
 * (out of memory), with nothing left allocated. */
int supersample_buffers(const frame_pixels *out, int width, int height, int k,
                        frame_pixels *fine, fog_error *err);
void supersample_free(frame_pixels *fine);
/* out (width x height) from fine (k * width x k * height), every output out names; sky:
 * the depth the frames hold where a ray meets no surface (the camera's far plane). */
void supersample_reduce(const frame_pixels *fine, int width, int height, int k, float sky,
                        const frame_pixels *out);

#endif
