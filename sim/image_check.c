/* The writers' last guard: no image we write holds a NaN or an infinity. Such a pixel is
 * always a defect upstream (a value that overflowed float), and a compositor shows it as
 * black or spreads it through every filter; refusing it makes the defect visible. */
#include <math.h>

#include "sim/image_io.h"

int image_check_finite(const char *path, const char *channel, const float *values, int width,
                       int height, int stride, float limit, fog_error *err) {
  size_t count = (size_t)width * (size_t)height;
  for (size_t i = 0; i < count; i++) {
    float v = values[i * (size_t)stride];
    if (fabsf(v) <= limit) continue; /* false for NaN too */
    int x = (int)(i % (size_t)width), y = (int)(i / (size_t)width);
    const char *what = isnan(v) ? "NaN" : isinf(v) ? "infinite" : "beyond half-float range";
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "%s: not written: pixel (%d, %d) of channel \"%s\" is %s (%g)", path, x, y,
                    channel, what, (double)v);
  }
  return 0;
}
