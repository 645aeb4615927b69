// The lamps' shadow cubes (render/lamp_shadow_map.h): V_i, lamp i's visibility past the
// terrain and boxes, for the surfaces (scene_surface_fs.glsl) and the fog (fog_lamps.glsl).
// Cube i is the cube-map array's layers 6 i .. 6 i + 5; a texel holds the distance to the
// first surface over lamp_shadow_inv_far's far.
uniform samplerCubeArrayShadow lamp_shadow_map;
uniform float lamp_shadow_inv_far[16];  // FOG_MAX_LAMPS
uniform float lamp_shadow_slack;        // LAMP_SHADOW_SLACK_TEXELS texels' angle (radians)

// V of lamp i at the point v from the lamp (point - lamp), 2 x 2 filtered (PCF).
float lamp_shadow_visible(int i, vec3 v) {
  if (!(dot(v, v) > 0.0)) return 1.0;
  // a point past far (beyond every surface) compares as far itself: lit where the texel is
  // empty (1), in shadow behind a surface (< 1); GL does not clamp the reference for a
  // float depth format, and a reference above 1 would fail against the empty texels
  float depth = min(length(v) * (1.0 - lamp_shadow_slack) * lamp_shadow_inv_far[i], 1.0);
  return texture(lamp_shadow_map, vec4(v, float(i)), depth);
}

uniform float lamp_shadow_lift;  // lamp_shadow_maps.lift_per_distance (terrain LOD)

// The same at a surface point v (from the lamp) with unit normal n, `camera_distance` from
// the camera: looked up from slack x d along the normal, past the texels the surface itself
// fills, and raised by the terrain LOD's height error there.
float lamp_shadow_visible_surface(int i, vec3 v, vec3 n, float camera_distance) {
  vec3 lift = vec3(0.0, lamp_shadow_lift * camera_distance, 0.0);
  return lamp_shadow_visible(i, v + (lamp_shadow_slack * length(v)) * n + lift);
}
