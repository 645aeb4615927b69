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
// Lamps (render/fog_lamp.h): each lights the surface with irradiance I cos / (d^2 + r^2)
// times its cone, Lambertian (albedo / pi, as the sun's sun_colour is its irradiance / pi).
// Not dimmed by the fog between lamp and surface (docs/light.md, Lamps: what is left).
const int SCENE_MAX_LAMPS = 16;
uniform int lamp_count;
uniform vec3 lamp_position[SCENE_MAX_LAMPS];   // camera-relative
uniform vec3 lamp_intensity[SCENE_MAX_LAMPS];  // I per channel
uniform vec4 lamp_axis[SCENE_MAX_LAMPS];       // xyz spot axis; w 1 spot, 0 point
uniform vec3 lamp_cone[SCENE_MAX_LAMPS];       // cos_outer, 1/(cos_inner - cos_outer), r^2

vec3 lamp_light(vec3 p, vec3 n) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < lamp_count; i++) {
    vec3 l = lamp_position[i] - p;
    float d2 = dot(l, l), d = sqrt(d2);
    float cos_n = max(dot(n, l) / max(d, 1e-6), 0.0), cone = 1.0;
    if (lamp_axis[i].w != 0.0) {
      float u = clamp((dot(-l, lamp_axis[i].xyz) / max(d, 1e-6) - lamp_cone[i].x) * lamp_cone[i].y,
                      0.0, 1.0);
      cone = u * u * (3.0 - 2.0 * u);
    }
    sum += lamp_intensity[i] * (cos_n * cone / (3.14159265358979 * (d2 + lamp_cone[i].z)));
  }
  return sum;
}

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
  colour = vec4(sunlit + v_albedo * (sky_light + lamp_light(v_relative, n)), 1.0);
  sun_share = vec4(sunlit, 0.0);
  // The interpolated camera-relative position is the point on the triangle under the
  // pixel centre (perspective-correct), so this is the ray's hit distance.
  surface_distance = length(v_relative);
}
