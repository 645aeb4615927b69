#version 430 core
// Sky behind the scene: a horizon-to-zenith gradient and a sun disc; distance = "none".
uniform vec3 camera_right;    // camera_basis(): scaled by the image half-extent
uniform vec3 camera_up;
uniform vec3 camera_forward;
uniform vec2 viewport_size;
uniform vec3 sky_horizon;
uniform vec3 sky_zenith;
uniform vec3 sun_direction;
uniform vec3 sun_colour;

layout(location = 0) out vec4 colour;
layout(location = 1) out float surface_distance;
layout(location = 2) out vec4 sun_share;  // the sky is not shadowed by the fog

void main() {
  // The ray of camera_ray() (render/camera.h).
  vec2 ndc = 2.0 * gl_FragCoord.xy / viewport_size - 1.0;
  vec3 dir = normalize(camera_forward + ndc.x * camera_right + ndc.y * camera_up);
  // Brightest at the horizon and smooth through it: sqrt(up) above and a linear darkening
  // below met there at a kink, which read as a bright line drawn along every horizon.
  // Both sides now leave the horizon colour with zero slope: a haze band that turns to
  // the zenith colour above (3/4 of the way by 15 degrees, 93 % by 20), and darkens to 0.6
  // of it by ~15 degrees below.
  vec3 sky;
  if (dir.y >= 0.0)
    sky = mix(sky_horizon, sky_zenith, 1.0 - exp(-(dir.y * dir.y) / 0.045));
  else
    sky = sky_horizon * mix(1.0, 0.6, smoothstep(0.0, 0.25, -dir.y));
  float c = dot(dir, sun_direction);
  sky += sun_colour * (0.25 * pow(max(c, 0.0), 64.0) + 4.0 * smoothstep(0.99985, 0.99992, c));
  colour = vec4(sky, 1.0);
  surface_distance = 1e30;  // SCENE_SKY_DISTANCE
  sun_share = vec4(0.0);
}
