/* The sun's colour as a hue and a strength (app/sun_hue.h). */
#include "app/sun_hue.h"

#include <math.h>

#include "app/config.h"

void sun_hue_split(const double colour[3], float hue[3], float *strength) {
  float largest = 0.0f;
  for (int c = 0; c < 3; c++)
    if ((float)colour[c] > largest) largest = (float)colour[c];
  *strength = largest;
  if (largest > 0.0f)
    for (int c = 0; c < 3; c++) hue[c] = (float)colour[c] / largest;
}

void sun_hue_join(const float hue[3], float strength, double colour[3]) {
  /* at most what [light] sun_colour may hold: a hue channel typed past 1 (Ctrl+click) times
   * the strength passed it, and Ctrl+S refused the scene as a config that would not load */
  for (int c = 0; c < 3; c++)
    colour[c] = fmin((double)hue[c] * strength, SCENE_CONFIG_MAX_RADIANCE);
}
