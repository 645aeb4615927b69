/* The sun and sky with their defaults resolved (render/scene.h): one place for the
 * surfaces, the fog and the demo's time of day. No GL here (the config fuzzer links it). */
#include <math.h>

#include "render/scene.h"

#define DEG (3.14159265358979323846 / 180.0)

static void set_default3(float v[3], float a, float b, float c) {
  if (v[0] == 0 && v[1] == 0 && v[2] == 0) v[0] = a, v[1] = b, v[2] = c;
}

void scene_light_resolve(const scene_light *desc, scene_light *light, double sun_direction[3]) {
  scene_light *l = light;
  *l = *desc;
  if (l->sun_elevation == 0) l->sun_elevation = 35;
  set_default3(l->sun_colour, 1.9f, 1.8f, 1.6f);
  set_default3(l->ambient, 0.30f, 0.36f, 0.45f);
  set_default3(l->sky_horizon, 0.72f, 0.78f, 0.85f);
  set_default3(l->sky_zenith, 0.28f, 0.45f, 0.75f);
  double az = l->sun_azimuth * DEG, el = l->sun_elevation * DEG;
  sun_direction[0] = cos(el) * sin(az);
  sun_direction[1] = sin(el);
  sun_direction[2] = -cos(el) * cos(az);
}
