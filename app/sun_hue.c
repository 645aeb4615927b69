/* The sun's colour as a hue and a strength (app/sun_hue.h). */
#include "app/sun_hue.h"

void sun_hue_split(const double colour[3], float hue[3], float *strength) {
  float largest = 0.0f;
  for (int c = 0; c < 3; c++)
    if ((float)colour[c] > largest) largest = (float)colour[c];
  *strength = largest;
  if (largest > 0.0f)
    for (int c = 0; c < 3; c++) hue[c] = (float)colour[c] / largest;
}

void sun_hue_join(const float hue[3], float strength, double colour[3]) {
  for (int c = 0; c < 3; c++) colour[c] = (double)hue[c] * strength;
}
