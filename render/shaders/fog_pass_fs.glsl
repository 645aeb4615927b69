#version 430 core
// The fog pass (render/fog_pass.h): per pixel, the ray of render/camera.h, the optical depth
// through the fogmap pyramid with LOD by distance (DESIGN §4), and the blend
// L = tau L(P) + L_fog (1 - tau) (Giroud & Biri eq. 4). render/fog_pass.c inserts after the
// #version line:
//   #define FOG_FETCH_HARDWARE 0|1   (see fog_integral.glsl)
//   #define FOG_INTEGRATOR 0|1       (0: exact walk, 1: uniform ray marching)
#include "fog_integral.glsl"
#include "fog_models.glsl"

layout(location = 0) out vec4 fog_out_colour;
layout(location = 1) out float fog_out_transmittance;

uniform sampler2D fog_surface_colour;    // linear RGBA, the scene without fog
uniform sampler2D fog_surface_distance;  // R32F: distance along the ray to the first surface
uniform vec2 fog_viewport;               // width, height
uniform vec3 fog_camera_right;           // camera_basis(): scaled right, up; unit forward
uniform vec3 fog_camera_up;
uniform vec3 fog_camera_forward;
uniform vec3 fog_colour;
uniform int fog_levels;                  // J; 0: one grid (slot 0)
uniform int fog_lod_method;              // 0: sum of details (paper), 1: approximation switching
uniform float fog_mu;
uniform int fog_march_steps;
uniform int fog_march_jitter;            // 0: midpoints; 1: per-pixel jitter
uniform uint fog_frame;

// Detail band l (1..J) lives in slot J + l; approximation A_l in slot l.
float fog_grid_integral(int grid, vec3 dir, float t_start, float t_stop, float jitter) {
#if FOG_INTEGRATOR == 1
  return fog_optical_depth_march(grid, dir, t_start, t_stop, fog_march_steps, jitter);
#else
  return fog_optical_depth(grid, dir, t_start, t_stop);
#endif
}

// ||OP||: the first surface or the box exit, whichever comes first (fog_lod_ray_length).
float fog_lod_ray_length(vec3 dir, float t_surface) {
  float t0, t1;
  if (!fog_box_entry_exit(dir, t0, t1) || t1 <= 0.0) return 0.0;
  return min(t1, t_surface);
}

// LOD by distance, both methods (fog_optical_depth_lod in render/fog_integral_cpu.c).
float fog_optical_depth_lod(vec3 dir, float t_surface, float jitter) {
  float op = fog_lod_ray_length(dir, t_surface);
  if (op <= 0.0) return 0.0;
  int J = fog_levels;
  if (fog_lod_method == 0) {
    // Giroud & Biri §4.4: A_0 over the whole ray, detail band l up to d_l = ||OP|| mu^l.
    float sum = fog_grid_integral(0, dir, 0.0, op, jitter);
    float d_l = op;
    for (int l = 1; l <= J; l++) {
      d_l *= fog_mu;
      if (d_l <= 0.0) break;
      sum += fog_grid_integral(J + l, dir, 0.0, d_l, jitter);
    }
    return sum;
  }
  // Approximation switching: segment (d_{l+1}, d_l] sees A_l; A_J on [0, d_J].
  float sum = 0.0, far_t = op, d_l = op;
  for (int l = 0; l < J; l++) {
    float near_t = d_l * fog_mu;
    if (far_t > near_t) sum += fog_grid_integral(l, dir, near_t, far_t, jitter);
    far_t = near_t;
    d_l = near_t;
  }
  if (far_t > 0.0) sum += fog_grid_integral(J, dir, 0.0, far_t, jitter);
  return sum;
}

// A per-pixel hash in [0, 1) for the marcher's jitter (PCG-style integer hash).
float fog_hash(uvec2 p, uint frame) {
  uint h = p.x * 1973u + p.y * 9277u + frame * 26699u;
  h = (h ^ (h >> 16)) * 0x7feb352du;
  h = (h ^ (h >> 15)) * 0x846ca68bu;
  h ^= h >> 16;
  return float(h >> 8) * (1.0 / 16777216.0);
}

void main() {
  // camera_ray(): ndc from the fragment centre, y up; dir = normalize(f + x r + y u).
  vec2 ndc = 2.0 * gl_FragCoord.xy / fog_viewport - 1.0;
  vec3 dir = normalize(fog_camera_forward + ndc.x * fog_camera_right + ndc.y * fog_camera_up);
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 surface = texelFetch(fog_surface_colour, pixel, 0);
  float t_surface = texelFetch(fog_surface_distance, pixel, 0).r;
  float jitter = (fog_march_jitter != 0) ? fog_hash(uvec2(pixel), fog_frame) : 0.5;
  float optical_depth;
  if (fog_model == FOG_MODEL_HOMOGENEOUS)
    optical_depth = fog_homogeneous_optical_depth(fog_model_extinction, t_surface);
  else if (fog_model == FOG_MODEL_HEIGHT)
    optical_depth = fog_height_optical_depth(fog_model_extinction, fog_model_y0,
                                             fog_model_scale_height, dir.y, t_surface);
  else
    optical_depth = fog_optical_depth_lod(dir, t_surface, jitter);
  float tau = exp(-optical_depth);
  // Giroud & Biri eq. 4.
  fog_out_colour = vec4(tau * surface.rgb + fog_colour * (1.0 - tau), surface.a);
  fog_out_transmittance = tau;
}
