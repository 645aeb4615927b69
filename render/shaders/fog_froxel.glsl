// The engines' froxel grid (fog_pass.h, FOG_INTEGRATOR_FROXEL; docs/light.md): the benchmark
// baseline our view-ray integral is measured against. Specialisation constant:
//   #define FOG_FROXEL 0|1|2   (0: not drawn; 1: the fill, one fragment per column of the
//                              grid; 2: the lookup, one fragment per pixel)
// The grid has fog_froxel_size.x x .y columns across the image and .z slices along each
// column's centre ray, their faces spaced exponentially from fog_froxel_near to
// fog_froxel_far (Wronski 2014). The fill samples the fog once per cell (at the slice's
// middle): K, and the light it scatters, L_amb + a L_sun p(theta) T_s V; it accumulates the
// slices front to back with the slice integral of constant K and source (Hillaire 2015:
// int over the slice of tau K s = tau s (1 - e^{-K dt})), and stores at slice k the
// in-scatter and the transmittance from the grid's near face to its far face. The lookup
// reads that trilinearly at the pixel's surface distance (the sky: the far face).
#if FOG_FROXEL
uniform ivec3 fog_froxel_size;  // columns, rows, slices
uniform float fog_froxel_near;  // the first and the last faces, distances along the ray
uniform float fog_froxel_far;

// The distance of face k (0..slices).
float fog_froxel_face(int k) {
  return fog_froxel_near * pow(fog_froxel_far / fog_froxel_near, float(k) / float(fog_froxel_size.z));
}
#endif

#if FOG_FROXEL == 1
layout(rgba32f) uniform writeonly image3D fog_froxel_image;

void fog_froxel_fill(ivec2 cell) {
  // the column's centre ray, as a pixel's (camera_ray)
  dvec2 ndc = 2.0 * (dvec2(cell) + 0.5) / dvec2(fog_froxel_size.xy) - 1.0;
  dvec3 dir_d = normalize(fog_camera_forward + ndc.x * fog_camera_right + ndc.y * fog_camera_up);
  vec3 dir = vec3(dir_d);
  fog_rbf_tile = ivec2((vec2(cell) + 0.5) * fog_viewport / vec2(fog_froxel_size.xy)) /
                 max(fog_rbf_tile_size, 1);
  vec3 sun = fog_sun_scatter * fog_phase_hg(fog_phase_g, dir, fog_sun_direction);
  vec3 light = vec3(0.0);
  float transmittance = 1.0, t_a = fog_froxel_near;
  for (int k = 0; k < fog_froxel_size.z; k++) {
    float t_b = fog_froxel_face(k + 1), t = 0.5 * (t_a + t_b);
    vec3 p = t * dir;
    float extinction = fog_light_extinction(dir, t);  // zero outside the fogmap's box
    float x = extinction * (t_b - t_a);
    vec3 source = fog_colour + sun * exp(-fog_sun_optical_depth(p)) * fog_sun_visible(p);
    light += transmittance * source * (x * fog_exprel(x));  // s (1 - e^{-x}), no cancellation
    transmittance *= exp(-x);
    imageStore(fog_froxel_image, ivec3(cell, k), vec4(light, transmittance));
    t_a = t_b;
  }
}
#endif

#if FOG_FROXEL == 2
uniform sampler3D fog_froxel_volume;

// In-scatter (rgb) and transmittance (a) from the camera to distance t_surface.
vec4 fog_froxel_lookup(ivec2 pixel, float t_surface) {
  float t = min(t_surface, fog_froxel_far);
  if (!(t > fog_froxel_near)) return vec4(0.0, 0.0, 0.0, 1.0);
  // faces passed (continuous); slice k's texel holds the sums to face k + 1
  float f = float(fog_froxel_size.z) * log(t / fog_froxel_near) / log(fog_froxel_far / fog_froxel_near);
  vec2 uv = (vec2(pixel) + 0.5) / fog_viewport;
  vec4 s = texture(fog_froxel_volume, vec3(uv, (max(f, 1.0) - 0.5) / float(fog_froxel_size.z)));
  return f >= 1.0 ? s : mix(vec4(0.0, 0.0, 0.0, 1.0), s, f);  // the first slice: linear
}
#endif
