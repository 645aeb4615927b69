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
// times its cone and its shadow, Lambertian (albedo / pi, as the sun's sun_colour is its irradiance / pi).
// Their share of the colour goes to location 3 with the normal, and the fog pass dims it by
// the fog between each lamp and the surface (fog_lamps.glsl, fog_lamps_surface).
const int SCENE_MAX_LAMPS = 16;
uniform int lamp_count;
uniform vec3 lamp_position[SCENE_MAX_LAMPS];   // camera-relative
uniform vec3 lamp_intensity[SCENE_MAX_LAMPS];  // I per channel
uniform vec4 lamp_axis[SCENE_MAX_LAMPS];       // xyz spot axis; w 1 spot, 0 point
uniform vec3 lamp_cone[SCENE_MAX_LAMPS];       // cos_outer, 1/(cos_inner - cos_outer), r^2
// Each lamp's shadow of the terrain and boxes (render/lamp_shadow_map.h), when on.
uniform bool lamp_shadows_on;
#include "lamp_shadow.glsl"

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
    if (lamp_shadows_on && cos_n * cone > 0.0)
      cone *= lamp_shadow_visible_surface(i, -l, n, length(p));
    sum += lamp_intensity[i] * (cos_n * cone / (3.14159265358979 * (d2 + lamp_cone[i].z)));
  }
  return sum;
}

layout(location = 0) out vec4 colour;
layout(location = 1) out float surface_distance;
layout(location = 2) out vec4 sun_share;
// rgb: the lamps' share of the colour; a: the unit normal, octahedral, 12 bits a component
// packed into one float (exact below 2^24)
layout(location = 3) out vec4 lamp_share;

float pack_normal(vec3 n) {
  vec2 o = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  if (n.z < 0.0) o = (1.0 - abs(o.yx)) * vec2(o.x >= 0.0 ? 1.0 : -1.0, o.y >= 0.0 ? 1.0 : -1.0);
  uvec2 q = uvec2(round(clamp(o * 0.5 + 0.5, 0.0, 1.0) * 4095.0));
  return float(q.x * 4096u + q.y);
}

void main() {
  vec3 n = normalize(v_normal);
  // The side the camera sees: the boxes are drawn two-sided (a camera inside one sees its
  // inner faces), and their faces' windings differ, so by geometry rather than
  // gl_FrontFacing: the triangle's own normal turned towards the camera. An inner face
  // lit as its outer face would take the sun through the box and no light from a lamp
  // inside it.
  vec3 face = cross(dFdx(v_relative), dFdy(v_relative));
  if (dot(face, v_relative) > 0.0) face = -face;
  if (dot(n, face) < 0.0) n = -n;
  float lambert = max(dot(n, sun_direction), 0.0);
  // Hemispherical ambient: full sky light facing up, a third of it facing down.
  vec3 sky_light = ambient * mix(0.33, 1.0, 0.5 + 0.5 * n.y);
  vec3 lift = vec3(0.0, lod_lift_per_distance * length(v_relative), 0.0);
  vec3 q = (sun_from_relative * vec4(v_relative + n * sun_normal_offset + lift, 1.0)).xyz;
  float visible = lambert > 0.0 ? texture(sun_visibility, q) : 0.0;
  vec3 sunlit = v_albedo * sun_colour * lambert * visible;
  vec3 lamplit = v_albedo * lamp_light(v_relative, n);
  colour = vec4(sunlit + v_albedo * sky_light + lamplit, 1.0);
  sun_share = vec4(sunlit, 0.0);
  lamp_share = vec4(lamplit, pack_normal(n));
  // The interpolated camera-relative position is the point on the triangle under the
  // pixel centre (perspective-correct), so this is the ray's hit distance.
  surface_distance = length(v_relative);
}
