// The lamps' shadow cubes (render/lamp_shadow_map.h): V_i, lamp i's visibility past the
// terrain and boxes, for the surfaces (scene_surface_fs.glsl) and the fog (fog_lamps.glsl).
// Cube i is the cube-map array's layers 6 i .. 6 i + 5; a texel holds the distance to the
// first surface over lamp_shadow_inv_far's far.
uniform samplerCubeArrayShadow lamp_shadow_map;
uniform float lamp_shadow_inv_far[16];  // FOG_MAX_LAMPS
uniform float lamp_shadow_slack;        // LAMP_SHADOW_SLACK_TEXELS texels' angle (radians)

// V of lamp i at the point v from the lamp (point - lamp), 2 x 2 filtered (PCF).
float lamp_shadow_visible(int i, vec3 v) {
  float d = length(v), depth = d * (1.0 - lamp_shadow_slack) * lamp_shadow_inv_far[i];
  // past far (beyond every surface of the scene) nothing is in the way; the map, whose
  // texels hold at most 1, would call it shadowed
  if (!(d > 0.0) || depth >= 1.0) return 1.0;
  return texture(lamp_shadow_map, vec4(v, float(i)), depth);
}

// The same at a surface point v (from the lamp) with unit normal n: looked up from
// slack x d along the normal, past the texels the surface itself fills.
float lamp_shadow_visible_surface(int i, vec3 v, vec3 n) {
  return lamp_shadow_visible(i, v + (lamp_shadow_slack * length(v)) * n);
}
