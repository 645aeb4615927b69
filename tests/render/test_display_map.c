/* The display transform (render/display.h) against its definitions, written out here in
 * double:
 *   - 0 stops, clamp: the value itself in [0, 1], clipped outside (today's PNGs, bit for
 *     bit), 0 for a negative value or NaN, 1 for +inf;
 *   - exposure e: the same as 0 stops on 2^e x (exact: a power of two);
 *   - ACES (Narkowicz 2015: x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clipped to 1)
 *     and Reinhard (x / (1 + x)) within float rounding over 1e-6 .. 1e6;
 *   - every curve non-decreasing, within [0, 1], and the filmic ones below white where
 *     clamp clips (x = 1.5: the point of them);
 *   - display_map_values maps in place like display_map one by one. */
#include <math.h>
#include <stdio.h>

#include "render/display.h"
#include "test_util.h"

static double aces(double x) {
  double y = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
  return y < 1.0 ? y : 1.0;
}

static double reinhard(double x) { return x / (1.0 + x); }

int main(void) {
  const display_transform none = display_transform_default();
  CHECK(none.exposure == 0.0 && none.tone_map == DISPLAY_CLAMP, "the default is not 0 stops, "
        "clamp");
  const float values[] = {0.0f, 1e-7f, 0.0031308f, 0.25f, 0.5f, 0.999f, 1.0f};
  for (size_t i = 0; i < sizeof values / sizeof values[0]; i++)
    CHECK(display_map(&none, values[i]) == values[i], "clamp changed %g to %g",
          (double)values[i], (double)display_map(&none, values[i]));
  CHECK(display_map(&none, 1.5f) == 1.0f && display_map(&none, -0.25f) == 0.0f &&
            display_map(&none, NAN) == 0.0f && display_map(&none, INFINITY) == 1.0f,
        "clamp outside [0, 1]");

  const display_tone_map maps[3] = {DISPLAY_CLAMP, DISPLAY_ACES, DISPLAY_REINHARD};
  double worst[3] = {0, 0, 0};
  for (int m = 0; m < 3; m++) {
    const display_transform at0 = {.exposure = 0.0, .tone_map = maps[m]};
    float previous = 0.0f;
    for (double x = 1e-6; x < 1e6; x *= 1.01) {
      const float y = display_map(&at0, (float)x);
      const double xf = (float)x;
      const double want = m == 0 ? fmin(xf, 1.0) : m == 1 ? aces(xf) : reinhard(xf);
      worst[m] = fmax(worst[m], fabs(y - want) / fmax(want, 1e-30));
      CHECK(y >= previous && y >= 0.0f && y <= 1.0f, "curve %d: %g at %g after %g", m,
            (double)y, x, (double)previous);
      previous = y;
      for (int e = -3; e <= 3; e++) {
        const display_transform exposed = {.exposure = e, .tone_map = maps[m]};
        const float scaled = (float)ldexp(xf, e);
        if (isfinite(scaled) && display_map(&exposed, (float)x) != display_map(&at0, scaled)) {
          CHECK(0, "curve %d: exposure %d at %g is not the curve at 2^%d x", m, e, x, e);
          break;
        }
      }
    }
    CHECK(m == 0 || display_map(&at0, 1.5f) < 0.99f, "curve %d clips 1.5 to %g", m,
          (double)display_map(&at0, 1.5f));
  }
  printf("against the definitions in double, 1e-6 .. 1e6: clamp %.1e, ACES %.1e, Reinhard "
         "%.1e (relative)\n", worst[0], worst[1], worst[2]);
  CHECK(worst[0] == 0.0 && worst[1] < 1e-5 && worst[2] < 1e-6, "off the definitions: %.3e "
        "%.3e %.3e", worst[0], worst[1], worst[2]);

  float in[6] = {0.1f, 2.0f, -1.0f, 0.7f, 40.0f, 1.0f}, out[6];
  const display_transform filmic = {.exposure = 0.5, .tone_map = DISPLAY_ACES};
  display_map_values(&filmic, in, out, 6);
  for (int i = 0; i < 6; i++)
    CHECK(out[i] == display_map(&filmic, in[i]), "display_map_values [%d]: %g", i,
          (double)out[i]);
  display_map_values(&filmic, in, in, 6);
  for (int i = 0; i < 6; i++) CHECK(in[i] == out[i], "in place [%d]", i);
  return test_finish("test_display_map");
}
