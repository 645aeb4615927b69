/* One frame as the GL passes read it back: what player_frame, render_session_frame and
 * pipeline_read_frame fill. Rows top first; any pointer may be NULL (not read back). */
#ifndef FOGPIPE_APP_FRAME_PIXELS_H
#define FOGPIPE_APP_FRAME_PIXELS_H

typedef struct frame_pixels {
  float *rgba;          /* 4 floats a pixel: linear colour and alpha */
  float *transmittance; /* tau, 1 where there is no fog */
  float *depth;         /* distance along the view ray to the first surface; the far plane
                           for the sky */
  float *inscatter;     /* 3 floats a pixel: the light the fog adds, rgb = tau surface +
                           inscatter (render/fog_light.h); 0 where there is no fog */
} frame_pixels;

#endif
