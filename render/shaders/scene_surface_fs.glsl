#version 430 core
// Scene pass: lit surface colour (location 0), the Euclidean distance from the camera to
// the surface point (location 1), what the fog pass integrates up to, and the sun-lit share
// of the colour (location 2), which the fog's shadow on the ground dims (fog_pass_fs.glsl).
in vec3 v_relative;
in vec3 v_normal;
in vec3 v_albedo;

uniform vec3 sun_direction;  // unit, toward the sun
uniform vec3 sun_colour;
uniform vec3 ambient;        // sky light on an upward surface
// The sun's shadow map (render/sun_shadow_map.h): V, the sun past the terrain and boxes.
uniform sampler2DShadow sun_visibility;
uniform mat4 sun_from_relative;  // camera-relative point -> (u, v, depth), in double on the CPU
uniform float sun_normal_offset; // world: the lookup's step off the surface (no acne)
// Terrain LOD (render/terrain_lod.h): the drawn surface may lie below the full mesh the
// shadow map holds by up to its pixel budget, budget * distance / pixels_per_unit in world
// height; the lookup rises by that much, or the full mesh would shadow its own coarser copy.
uniform float lod_lift_per_distance;

layout(location = 0) out vec4 colour;
layout(location = 1) out float surface_distance;
layout(location = 2) out vec4 sun_share;

void main() {
  vec3 n = normalize(v_normal);
  float lambert = max(dot(n, sun_direction), 0.0);
  // Hemispherical ambient: full sky light facing up, a third of it facing down.
  vec3 sky_light = ambient * mix(0.33, 1.0, 0.5 + 0.5 * n.y);
  vec3 lift = vec3(0.0, lod_lift_per_distance * length(v_relative), 0.0);
  vec3 q = (sun_from_relative * vec4(v_relative + n * sun_normal_offset + lift, 1.0)).xyz;
  float visible = lambert > 0.0 ? texture(sun_visibility, q) : 0.0;
  vec3 sunlit = v_albedo * sun_colour * lambert * visible;
  colour = vec4(sunlit + v_albedo * sky_light, 1.0);
  sun_share = vec4(sunlit, 0.0);
  // The interpolated camera-relative position is the point on the triangle under the
  // pixel centre (perspective-correct), so this is the ray's hit distance.
  surface_distance = length(v_relative);
}
