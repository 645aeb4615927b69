/* The display transform (render/display.h). */
#include "render/display.h"

#include <math.h>

display_transform display_transform_default(void) {
  return (display_transform){.exposure = 0.0, .tone_map = DISPLAY_CLAMP, .dither = true};
}

/* x already scaled by 2^exposure. */
static float tone_map(display_tone_map curve, float x) {
  if (!(x > 0.0f)) return 0.0f; /* negative, zero, NaN */
  float y;
  switch (curve) {
    case DISPLAY_ACES:
      /* K. Narkowicz, "ACES Filmic Tone Mapping Curve" (2015): x(ax + b) / (x(cx + d) + e) */
      y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
      break;
    case DISPLAY_REINHARD:
      y = x / (1.0f + x);
      break;
    default:
      y = x;
      break;
  }
  return y < 1.0f ? y : 1.0f; /* inf in: 1 */
}

float display_map(const display_transform *t, float linear) {
  /* exp2(0) is 1 exactly: at 0 stops the clamp gives today's images bit for bit */
  return tone_map(t->tone_map, linear * (float)exp2(t->exposure));
}

void display_map_values(const display_transform *t, const float *linear, float *out, size_t n) {
  const float scale = (float)exp2(t->exposure); /* once, not per value */
  for (size_t i = 0; i < n; i++) out[i] = tone_map(t->tone_map, linear[i] * scale);
}
