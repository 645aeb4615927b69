#version 430 core
// Scene pass: lit surface colour (location 0) and the Euclidean distance from the camera
// to the surface point (location 1), what the fog pass integrates up to.
in vec3 v_relative;
in vec3 v_normal;
in vec3 v_albedo;

uniform vec3 sun_direction;  // unit, toward the sun
uniform vec3 sun_colour;
uniform vec3 ambient;        // sky light on an upward surface

layout(location = 0) out vec4 colour;
layout(location = 1) out float surface_distance;

void main() {
  vec3 n = normalize(v_normal);
  float lambert = max(dot(n, sun_direction), 0.0);
  // Hemispherical ambient: full sky light facing up, a third of it facing down.
  vec3 sky_light = ambient * mix(0.33, 1.0, 0.5 + 0.5 * n.y);
  colour = vec4(v_albedo * (sun_colour * lambert + sky_light), 1.0);
  // The interpolated camera-relative position is the point on the triangle under the
  // pixel centre (perspective-correct), so this is the ray's hit distance.
  surface_distance = length(v_relative);
}
