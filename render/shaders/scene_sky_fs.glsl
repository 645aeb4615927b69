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
  float up = max(dir.y, 0.0);
  vec3 sky = mix(sky_horizon, sky_zenith, sqrt(up));
  if (dir.y < 0.0) sky = sky_horizon * mix(1.0, 0.6, min(-dir.y * 4.0, 1.0));
  float c = dot(dir, sun_direction);
  sky += sun_colour * (0.25 * pow(max(c, 0.0), 64.0) + 4.0 * smoothstep(0.99985, 0.99992, c));
  colour = vec4(sky, 1.0);
  surface_distance = 1e30;  // SCENE_SKY_DISTANCE
  sun_share = vec4(0.0);
}
