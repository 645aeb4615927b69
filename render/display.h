/* The display transform: scene-linear colour to the [0, 1] a screen or an 8-bit image
 * shows, before the sRGB transfer function. Exposure scales by 2^stops; the tone map then
 * either clips (today's images, bit for bit at 0 stops) or rolls highlights off so that
 * fog brighter than white keeps its shading. PNGs, the window, screenshots and the
 * recording's preview video go through it; EXR frames stay scene-linear (a compositor
 * applies its own view transform). gl_presenter_draw applies the same in GLSL
 * (scene_present_fs.glsl). */
#ifndef FOGPIPE_RENDER_DISPLAY_H
#define FOGPIPE_RENDER_DISPLAY_H

#include <stdbool.h>
#include <stddef.h>

typedef enum display_tone_map {
  DISPLAY_CLAMP = 0, /* min(x, 1): highlights clip to white */
  DISPLAY_ACES,      /* Narkowicz's fit of the ACES filmic curve (2015): a toe, a shoulder */
  DISPLAY_REINHARD,  /* x / (1 + x) (Reinhard et al. 2002, eq. 3): never reaches white */
} display_tone_map;

typedef struct display_transform {
  double exposure; /* stops: the colour is scaled by 2^exposure before the tone map */
  display_tone_map tone_map;
  /* 8-bit output (PNG, window, preview video) dithered with the 8 x 8 Bayer matrix
   * (sim/image.h: srgb8_encode_dithered) rather than rounded: no bands in dark gradients */
  bool dither;
} display_transform;

/* 0 stops, clamp, dithered: the linear colour as it is, clipped to [0, 1]. */
display_transform display_transform_default(void);

/* One channel's display value in [0, 1] (negative and NaN input give 0). */
float display_map(const display_transform *t, float linear);
/* n values (RGB triples or any channels alike) from linear into out (may be linear). */
void display_map_values(const display_transform *t, const float *linear, float *out, size_t n);

#endif
