/* The window's sun colour as a hue and a strength (app/sun_hue.h): colour = hue x strength
 * back again, the hue's largest channel 1; and a sun dimmed to strength 0 and up again
 * comes back in its own hue. The panel splits the stored colour every frame, and a black
 * colour had turned the hue white: a sunset dragged to 0 and back came back white. */
#include <math.h>
#include <stdio.h>

#include "app/sun_hue.h"
#include "test_util.h"

int main(void) {
  const double sunset[3] = {1.8, 0.9, 0.36};
  float hue[3] = {1.0f, 1.0f, 1.0f}, strength = -1.0f;
  sun_hue_split(sunset, hue, &strength);
  CHECK(strength == 1.8f, "strength %g, expected the largest channel 1.8", strength);
  CHECK(hue[0] == 1.0f && fabsf(hue[1] - 0.5f) < 1e-7f && fabsf(hue[2] - 0.2f) < 1e-7f,
        "hue %g %g %g, expected 1 0.5 0.2", hue[0], hue[1], hue[2]);
  double back[3];
  sun_hue_join(hue, strength, back);
  for (int c = 0; c < 3; c++)
    CHECK(fabs(back[c] - sunset[c]) < 1e-6 * sunset[c], "channel %d: %g back, %g given", c,
          back[c], sunset[c]);

  /* the panel's loop: strength dragged to 0, the colour stored (black), split again next
   * frame, then the strength dragged up to 2 */
  double stored[3];
  sun_hue_join(hue, 0.0f, stored);
  CHECK(stored[0] == 0 && stored[1] == 0 && stored[2] == 0, "strength 0 is not black");
  sun_hue_split(stored, hue, &strength);
  CHECK(strength == 0.0f, "black has strength %g", strength);
  sun_hue_join(hue, 2.0f, stored);
  printf("sunset dimmed to 0 and up to 2: %g %g %g\n", stored[0], stored[1], stored[2]);
  CHECK(fabs(stored[0] - 2.0) < 1e-6 && fabs(stored[1] - 1.0) < 1e-6 &&
            fabs(stored[2] - 0.4) < 1e-6,
        "the sunset came back as %g %g %g, expected 2 1 0.4", stored[0], stored[1], stored[2]);
  /* a hue channel typed to 1e4 (the panel holds a typed channel to the configs' range)
   * at strength 10: the colour stays within what sun_colour may hold */
  const float typed[3] = {1e4f, 1.0f, 0.5f};
  sun_hue_join(typed, 10.0f, stored);
  CHECK(stored[0] == 1e4 && stored[1] == 10.0 && stored[2] == 5.0,
        "typed hue x 10: %g %g %g, expected 1e4 10 5", stored[0], stored[1], stored[2]);
  return test_finish("test_sun_hue");
}
