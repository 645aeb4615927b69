/* Sunlight in the fog without shadows (render/fog_light.h); GLSL twin in fog_pass_fs.glsl. */
#include "render/fog_light.h"

#include <math.h>

static const double pi = 3.14159265358979323846;

double fog_phase_hg(double g, double cos_theta) {
  const double denom = 1.0 + g * g - 2.0 * g * cos_theta;
  return (1.0 - g * g) / (4.0 * pi * denom * sqrt(denom));
}

double fog_sun_above_horizon(const double direction[3]) {
  const double edge = sin(FOG_SUN_ANGULAR_RADIUS);
  const double share = (direction[1] + edge) / (2.0 * edge);
  return share <= 0.0 ? 0.0 : share >= 1.0 ? 1.0 : share;
}

void fog_inscatter_unshadowed(double tau, const double ambient[3], const fog_sun *sun,
                              const double view_dir[3], double out[3]) {
  const double cos_theta = sun->direction[0] * view_dir[0] + sun->direction[1] * view_dir[1] +
                           sun->direction[2] * view_dir[2];
  const double p = fog_phase_hg(sun->phase_g, cos_theta) * fog_sun_above_horizon(sun->direction);
  for (int c = 0; c < 3; c++)
    out[c] = (ambient[c] + sun->albedo * sun->radiance[c] * p) * (1.0 - tau);
}
