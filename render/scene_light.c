/* The sun and sky (render/scene.h): the defaults, and the sun's direction, one place for the
 * surfaces, the fog and the demo's time of day. No GL here (the config fuzzer links it). */
#include <math.h>

#include "render/scene.h"

#define DEG (3.14159265358979323846 / 180.0)

scene_light scene_light_default(void) {
  return (scene_light){.sun_azimuth = 0.0,
                       .sun_elevation = 35.0,
                       .sun_colour = {1.9f, 1.8f, 1.6f},
                       .ambient = {0.30f, 0.36f, 0.45f},
                       .sky_horizon = {0.72f, 0.78f, 0.85f},
                       .sky_zenith = {0.28f, 0.45f, 0.75f}};
}

void scene_light_sun_direction(const scene_light *l, double sun_direction[3]) {
  double az = l->sun_azimuth * DEG, el = l->sun_elevation * DEG;
  sun_direction[0] = cos(el) * sin(az);
  sun_direction[1] = sin(el);
  sun_direction[2] = -cos(el) * cos(az);
}
