#version 430 core
// The fog pass (render/fog_pass.h): per pixel, the ray of render/camera.h, the optical depth
// through the fogmap pyramid with LOD by distance (docs/integral.md), and the blend
// L = tau L(P) + (L_amb + a L_sun p(theta)) (1 - tau): Giroud & Biri eq. 4 with the sun's
// single scattering, unshadowed (render/fog_light.h, docs/light.md). render/fog_pass.c inserts after the
// #version line:
//   #define FOG_FETCH_HARDWARE 0|1   (see fog_integral.glsl)
//   #define FOG_INTEGRATOR 0|1       (0: exact walk, 1: uniform ray marching)
//   #define FOG_LEVELS J              (0..7: the pyramid's level count, 0 for one grid)
//   #define FOG_REDUCED 1|2|4        (> 1: the reduced-resolution pass of fog_pass_params.
//                                    resolution_divisor; fragment k traces full-resolution
//                                    pixel k FOG_REDUCED + FOG_REDUCED/2 and writes its
//                                    optical depth and surface distance for
//                                    the upsampling pass, FOG_UPSAMPLE 1)
//   #define FOG_LAMPS 0|1            (1: point and spot lights, fog_lamps.glsl)
//   #define FOG_LAMP_SPOTS 0|1       (1: a spot among them: pieces cut at its cones)
//   #define FOG_SURFACE_LAMPS 0|1    (1: the fog dims the lamps' light on the surfaces)
//   #define FOG_FROXEL 0|1|2         (the froxel baseline's fill and lookup, fog_froxel.glsl)
//   #define FOG_SHADOW_NODES 1|2     (the light mean's nodes a segment or piece, fog_light.glsl)
//   #define FOG_SHADOW_PIECES 0|1    (1: the sun's mean per piece of the model's walk)
//   #define FOG_QUADRICS_BESIDE 0|1  (1: quadric volumes beside the model's fog: their
//                                    depth, extinction and shadow add; fog_models.glsl)
//   and the specialisation constants of fog_integral.glsl
uniform int fog_march_steps;  // FOG_INTEGRATOR 1: samples per ray (every model's marcher)
#include "fog_integral.glsl"
#include "fog_models.glsl"

layout(location = 0) out vec4 fog_out_colour;
layout(location = 1) out float fog_out_transmittance;
layout(location = 2) out vec4 fog_out_inscatter;  // discarded where the target has no buffer 2

uniform sampler2D fog_surface_colour;    // linear RGBA, the scene without fog
uniform sampler2D fog_surface_distance;  // R32F: distance along the ray to the first surface
uniform vec2 fog_viewport;               // width, height
uniform dvec3 fog_camera_right;          // camera_basis(): scaled right, up; unit forward
uniform dvec3 fog_camera_up;             // (double: fog_optical_depth_inside)
uniform dvec3 fog_camera_forward;
uniform vec3 fog_colour;                 // L_amb
uniform vec3 fog_sun_direction;          // unit, towards the sun
uniform vec3 fog_sun_scatter;            // a L_sun
uniform float fog_phase_g;               // Henyey-Greenstein g
#if FOG_SURFACE_SUN
// The scene pass's sun-lit share of each surface's colour (its attachment 2): the fog's
// shadow on the surfaces takes (1 - T_s(P)) of it away.
uniform sampler2D fog_surface_sun;
#endif
#if FOG_SURFACE_LAMPS
// The scene pass's attachment 3: the lamps' share of the colour and the surface's normal,
// octahedral, 12 bits a component packed into one float (scene_surface_fs.glsl).
uniform sampler2D fog_surface_lamps;
vec3 fog_unpack_normal(float code) {
  uint v = uint(code);
  vec2 o = vec2(float(v / 4096u), float(v % 4096u)) / 4095.0 * 2.0 - 1.0;
  vec3 n = vec3(o, 1.0 - abs(o.x) - abs(o.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}
#endif
const int fog_levels = FOG_LEVELS;       // J; 0: one grid (slot 0). Specialised per variant
// 0: sum of details (paper), 1: approximation switching; specialised per variant
const int fog_lod_method = FOG_LOD_METHOD;
uniform double fog_mu;
uniform int fog_march_jitter;            // 0: midpoints; 1: per-pixel jitter
uniform uint fog_frame;

// Detail band l (1..J) lives in slot J + l; approximation A_l in slot l. [t0, t1] is
// already clipped to the box (t0 < t1): a pixel clips once, not once per grid (that took
// ~3 ms off a 38 ms LOD draw on llvmpipe).
// limit: the exact walk may stop once its own sum exceeds it (the caller's remaining budget).
float fog_grid_integral(int grid, dvec3 dir, double t0, double t1, float jitter, float limit) {
#if FOG_INTEGRATOR == 1
  return fog_optical_depth_march(grid, vec3(dir), float(t0), float(t1), fog_march_steps, jitter);
#else
  return fog_optical_depth_inside(grid, dir, t0, t1, limit);
#endif
}

// FOG_MAX_LEVELS (fog_constants.glsl): slots 0..J and J+1..2J

// The levels below are straight-line code, one call per level l = 1..FOG_MAX_LEVELS guarded
// by l <= J, not a loop: with J a compile-time constant (FOG_LEVELS) the levels beyond it
// fold away and d_l and the slots' uniforms get constant indices. A loop over the levels
// stays a loop whatever J is, because it holds the walks' loops (Mesa unrolls only loops
// without loops inside), and llvmpipe then keeps d_l in memory and gathers the uniforms
// lane by lane: ~1.5 ms of a 30 ms switching frame (docs/integral.md, Performance).

// Sum of details, band l (1..J): D_l (slot J + l) over [start, d_l]; nothing once
// d_l <= start (the bands get shorter with l).
float fog_sum_band(int l, dvec3 dir, double start, double d_l, float jitter) {
  if (l > fog_levels || !(d_l > start)) return 0.0;
  return fog_grid_integral(fog_levels + l, dir, start, d_l, jitter, FOG_INFINITY);
}

// Approximation switching, level l < J: A_l on (d_{l+1}, d_l], walked on from where the
// walk `w` of level l + 1 ended (at `end`, after `len`); updates all three and the sum.
void fog_switch_segment(int l, double d_l, inout double end, inout fog_ray_walk w,
                        inout float len, inout float sum) {
  if (l >= fog_levels) return;
  double a = end;
  end = max(a, d_l);
  w = fog_walk_coarser(w, l, len);
  len = float(end - a);
  sum += fog_walk_depth(w, len, fog_depth_limit - sum);
}

// LOD by distance, both methods (fog_optical_depth_lod in render/fog_integral_cpu.c).
// [t_in, t_out]: the ray's span in the fog's box (fog_box_entry_exit, done once in main).
float fog_optical_depth_lod(dvec3 dir, double t_in, double t_out, float t_surface,
                            float jitter) {
  // ||OP|| (fog_lod_ray_length): the first surface or the box exit, whichever comes first;
  // the walks start where the ray is inside the box, at `start`. Double, as the walks'
  // set-up (fog_optical_depth_inside): in float, the segment ends d_l of a camera 50 km
  // away move by millimetres, 3e-5 in tau (test_gpu_far_camera).
  if (t_out <= 0.0) return 0.0;
  double op = min(t_out, double(t_surface)), start = max(t_in, 0.0);
  if (op <= start) return 0.0;
#if FOG_SINGLE_GRID
  // One grid (no LOD, or an LOD draw that reduces to one level): the walk alone.
  return fog_grid_integral(0, dir, start, op, jitter, fog_depth_limit);
#else
  const int J = fog_levels;
  double d[FOG_MAX_LEVELS + 1];  // d_l = ||OP|| mu^l, as fog_optical_depth_lod computes them
  d[0] = op;
  for (int l = 1; l <= FOG_MAX_LEVELS; l++) d[l] = d[l - 1] * fog_mu;  // unrolled
  if (fog_lod_method == 0) {
    // Giroud & Biri §4.4: A_0 over the whole ray, detail band l up to d_l = ||OP|| mu^l.
    // The details are signed, so no partial sum bounds the total: no early exit here.
    float sum = fog_grid_integral(0, dir, start, op, jitter, FOG_INFINITY);
    sum += fog_sum_band(1, dir, start, d[1], jitter) + fog_sum_band(2, dir, start, d[2], jitter);
    sum += fog_sum_band(3, dir, start, d[3], jitter) + fog_sum_band(4, dir, start, d[4], jitter);
    sum += fog_sum_band(5, dir, start, d[5], jitter) + fog_sum_band(6, dir, start, d[6], jitter);
    sum += fog_sum_band(7, dir, start, d[7], jitter);
    return sum;
  }
  // Approximation switching: segment (d_{l+1}, d_l] sees A_l; A_J on [0, d_J]. Walked near
  // to far (A_J first), each segment with the budget the nearer ones left: the
  // approximations are non-negative fog, so once the sum passes fog_depth_limit the pixel
  // is opaque (tau < e^-limit) whatever the farther segments add. The segments follow
  // each other along the ray, clipped to [start, op] (empty ones have length 0), so each
  // walk starts where the last ended (fog_walk_coarser): one double set-up per pixel. No
  // branch on empty segments either: llvmpipe would run both sides.
#if FOG_INTEGRATOR == 1
  float sum = 0.0;  // the marcher: each segment on its own, never cut (as its C twin)
  for (int l = J; l >= 0; l--) {
    double near_t = max((l == J) ? 0.0 : d[l + 1], start), far_t = d[l];
    if (far_t > near_t) sum += fog_grid_integral(l, dir, near_t, far_t, jitter, FOG_INFINITY);
  }
  return sum;
#else
  double end = max(start, d[J]);
  fog_ray_walk w = fog_walk_start(J, dir, start);
  float len = float(end - start);
  float sum = fog_walk_depth(w, len, fog_depth_limit);
  fog_switch_segment(6, d[6], end, w, len, sum);
  fog_switch_segment(5, d[5], end, w, len, sum);
  fog_switch_segment(4, d[4], end, w, len, sum);
  fog_switch_segment(3, d[3], end, w, len, sum);
  fog_switch_segment(2, d[2], end, w, len, sum);
  fog_switch_segment(1, d[1], end, w, len, sum);
  fog_switch_segment(0, d[0], end, w, len, sum);
  return sum;
#endif
#endif
}

// d(optical depth)/dt at the surface t (inside the box) of the fogmap's integral, for the
// reduced pass's first-order term: one grid, its K there; with LOD the segment ends
// d_l = t mu^l move with t, so (d_l > start)
//   switching:           A_0(t) + sum_l mu^l (A_l(d_l) - A_{l-1}(d_l)),
//   the sum of details:  A_0(t) + sum_l mu^l D_l(d_l)   (at mu = 1: A_J(t)).
// Until the fifteenth session it was A_0(t) for both: the sum at mu = 1 lacked its details.
float fog_lod_depth_rate(vec3 dir, float t, double start) {
  float rate = fog_extinction_at(0, dir, t);
#if !FOG_SINGLE_GRID
  float m = 1.0;
  for (int l = 1; l <= FOG_MAX_LEVELS; l++) {  // constant bound: unrolled
    m *= float(fog_mu);
    float dl = t * m;
    if (l <= fog_levels && double(dl) > start)
      rate += m * (fog_lod_method == 0 ? fog_extinction_at(fog_levels + l, dir, dl)
                                       : fog_extinction_at(l, dir, dl) -
                                             fog_extinction_at(l - 1, dir, dl));
  }
#endif
  return rate;
}

// A per-pixel hash in [0, 1) for the marcher's jitter (PCG-style integer hash).
float fog_hash(uvec2 p, uint frame) {
  uint h = p.x * 1973u + p.y * 9277u + frame * 26699u;
  h = (h ^ (h >> 16)) * 0x7feb352du;
  h = (h ^ (h >> 15)) * 0x846ca68bu;
  h ^= h >> 16;
  return float(h >> 8) * (1.0 / 16777216.0);
}

// The fogmap's twins of the model table (its marcher is the same walk with FOG_INTEGRATOR 1).
float fog_model_depth_fogmap(fog_ray r) {
  return fog_optical_depth_lod(r.dir_d, r.t_in, r.t_out, r.t_surface, r.jitter);
}
float fog_model_march_fogmap(fog_ray r) { return fog_model_depth_fogmap(r); }

#include "fog_model_table.glsl"
#include "fog_light.glsl"


#if FOG_UPSAMPLE
// The reduced-resolution fog, second half (fog_pass_params.resolution_divisor): a joint
// bilateral upsampling (Kopf et al. 2007) of the reduced pass's optical depth, guided by the
// full-resolution surface distance. Reduced sample k holds the optical depth of full-
// resolution pixel k D + D/2 and that pixel's surface distance t_k. The pixel takes its
// 2 x 2 nearest samples with bilinear weights times a range weight exp(-(rel/sigma)^2),
// rel = |t_k - t| / min(t_k, t): samples on another surface (an object's edge, the sky
// behind a hill) get no weight, so fog does not bleed across depth edges. Each sample's
// depth is carried to the pixel's distance to first order, depth_k + K_k (t - t_k), K_k the
// extinction where sample k's ray meets its surface (a ground seen at a grazing angle
// changes distance quickly from pixel to pixel; the fog along neighbouring rays does not).
// Where no sample is on the pixel's surface (weight sum below FOG_UPSAMPLE_MIN_WEIGHT) the
// pixel walks its own ray (main): exact there, at the cost of the edge pixels only.
uniform sampler2D fog_reduced;  // RGBA32F: optical depth, surface distance, K there
#if FOG_LAMPS
// RGBA32F: the lamps' in-scatter of the sample's ray (fog_lamps.glsl), rgb: upsampled with
// the same weights as the depth (no first-order term: the lamps' light grows with distance
// far more slowly than it varies across a halo)
uniform sampler2D fog_reduced_lamps;
#endif
uniform int fog_divisor;
const float FOG_UPSAMPLE_SIGMA = 0.02;  // a relative distance difference of one "sigma"
const float FOG_UPSAMPLE_MIN_WEIGHT = 0.25;
const float FOG_UPSAMPLE_LAMP_SPREAD = 0.25;  // the lamps' light: samples within 25 %

bool fog_upsampled_depth(ivec2 pixel, float t, out float optical_depth, out float sun_light,
                         out vec3 lamp_light) {
  ivec2 size = textureSize(fog_reduced, 0);
  vec2 q = (vec2(pixel) - float(fog_divisor / 2)) / float(fog_divisor);
  ivec2 q0 = ivec2(floor(q));
  vec2 f = q - vec2(q0);
  float weight_sum = 0.0, depth_sum = 0.0, sun_sum = 0.0;
  vec3 lamp_sum = vec3(0.0), lamp_lo = vec3(1e30), lamp_hi = vec3(0.0);
  for (int k = 0; k < 4; k++) {  // constant bound: unrolled
    ivec2 o = ivec2(k & 1, k >> 1);
    ivec2 at = clamp(q0 + o, ivec2(0), size - 1);
    vec4 s = texelFetch(fog_reduced, at, 0);
    float wb = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    float rel = abs(s.y - t) / max(min(s.y, t), 1e-3);  // both sky (1e30): 0
    float w = wb * exp(-(rel * rel) / (FOG_UPSAMPLE_SIGMA * FOG_UPSAMPLE_SIGMA));
    weight_sum += w;
    depth_sum += w * max(s.x + s.z * (t - s.y), 0.0);  // w = 0 wherever t - s.y is huge
    sun_sum += w * s.w;  // the sample's T_s mean (fog_light.glsl): smooth, interpolated
#if FOG_LAMPS
    vec3 lamp = texelFetch(fog_reduced_lamps, at, 0).rgb;
    lamp_sum += w * lamp;
    if (w > 1e-3 * wb) lamp_lo = min(lamp_lo, lamp), lamp_hi = max(lamp_hi, lamp);
#endif
  }
  optical_depth = depth_sum / max(weight_sum, 1e-30);
  sun_light = sun_sum / max(weight_sum, 1e-30);
  lamp_light = lamp_sum / max(weight_sum, 1e-30);
#if FOG_LAMPS
  // A lamp's halo changes by more than FOG_UPSAMPLE_LAMP_SPREAD between the samples (its
  // 1/d^2 core, which samples a reduced pixel apart miss): the pixel walks its own ray.
  if (any(greaterThan(lamp_hi - lamp_lo, FOG_UPSAMPLE_LAMP_SPREAD * lamp_hi + 1e-6))) return false;
#endif
  return weight_sum >= FOG_UPSAMPLE_MIN_WEIGHT;
}
#endif

// Henyey-Greenstein, per steradian (fog_phase_hg in render/fog_light.c), between the unit
// directions u and v (cos theta = u . v): 1 + g^2 - 2 g cos theta as (1 - g)^2 + g |u - v|^2,
// or (1 + g)^2 - g |u + v|^2 for g < 0, the same in exact arithmetic. The sum of three
// terms cancels in float where the peak is (g near +-1, u near +-v): at g = 0.999 looking
// at the sun it lost 10 % of the glow.
float fog_phase_hg(float g, vec3 u, vec3 v) {
  vec3 d = g >= 0.0 ? u - v : u + v;
  float s = 1.0 - abs(g);
  float denom = s * s + abs(g) * dot(d, d);
  return s * (1.0 + abs(g)) / (4.0 * 3.14159265358979 * denom * sqrt(denom));
}

#include "fog_lamps.glsl"
#include "fog_froxel.glsl"


void main() {
#if FOG_FROXEL == 1
  fog_froxel_fill(ivec2(gl_FragCoord.xy));  // writes the grid; the framebuffer has no attachments
  return;
#endif
  // camera_ray(): ndc from the fragment centre, y up; dir = normalize(f + x r + y u).
#if FOG_REDUCED > 1
  ivec2 pixel = min(ivec2(gl_FragCoord.xy) * FOG_REDUCED + FOG_REDUCED / 2,
                    ivec2(fog_viewport) - 1);
  dvec2 ndc = 2.0 * (dvec2(pixel) + 0.5) / dvec2(fog_viewport) - 1.0;
#else
  dvec2 ndc = 2.0 * dvec2(gl_FragCoord.xy) / dvec2(fog_viewport) - 1.0;
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#endif
  fog_rbf_tile = pixel / max(fog_rbf_tile_size, 1);
  vec4 surface = texelFetch(fog_surface_colour, pixel, 0);
  float t_surface = texelFetch(fog_surface_distance, pixel, 0).r;
  float optical_depth = 0.0, k_end = 0.0;
  // the pixel's view direction: its angle to the sun is constant along the ray
  dvec3 view_dir = normalize(fog_camera_forward + ndc.x * fog_camera_right + ndc.y * fog_camera_up);
  bool walk = FOG_FROXEL == 0;  // the froxel lookup walks nothing
  float sun_light = 1.0;  // the T_s mean of the ray (fog_light.glsl)
  vec3 lamp_light = vec3(0.0);  // the lamps' in-scatter, upsampled (or walked below)
#if FOG_UPSAMPLE
  walk = !fog_upsampled_depth(pixel, t_surface, optical_depth, sun_light, lamp_light);
#endif
  // The ray's own integral. llvmpipe runs the body of an `if` under a mask for every lane
  // but leaves a loop as soon as no lane is in it: as a loop of at most one turn, the
  // ray's set-up and walk cost nothing in the upsampling pass's lane groups whose samples
  // all matched (the other passes take it once for every pixel).
  for (int turn = walk ? 0 : 1; turn < 1; turn++) {
    // in double (fog_optical_depth_inside); the rest of the pass takes it rounded to float
    dvec3 dir_d =
        normalize(fog_camera_forward + ndc.x * fog_camera_right + ndc.y * fog_camera_up);
    vec3 dir = vec3(dir_d);
    float jitter = (fog_march_jitter != 0) ? fog_hash(uvec2(pixel), fog_frame) : 0.5;
    // The ray's span in the fog's box, for the walk and the reduced pass's k_end; a miss
    // leaves it empty.
    double t_in = 1.0, t_out = 0.0;
    if (!fog_box_entry_exit(dir_d, t_in, t_out)) t_in = 1.0, t_out = 0.0;
    // The variant's model (fog_model_table.glsl, generated from render/fog_models.def).
    optical_depth = fog_model_optical_depth(fog_ray(dir_d, dir, t_in, t_out, t_surface, jitter));
#if FOG_QUADRICS_BESIDE
    // quadric volumes beside the model's fog: their exact depth adds
    optical_depth += fog_quadric_optical_depth_from(vec3(0.0), dir, t_surface);
#endif
#if FOG_REDUCED > 1
    // And the extinction where the ray meets the surface (the fogmap's A_0, 0 outside its
    // box; the other models' pointwise K; 0 for the sky): d(optical depth)/dt there, for the
    // upsampling's first-order distance correction.
#if FOG_MODEL_KIND == FOG_MODEL_FOGMAP
    if (t_surface < 1e29 && t_surface >= t_in && t_surface <= t_out)
      k_end = fog_extinction_scale * fog_lod_depth_rate(dir, t_surface, max(t_in, 0.0));
#if FOG_QUADRICS_BESIDE
    if (t_surface < 1e29) k_end += fog_quadric_extinction_at(t_surface * dir);
#endif
#else
    if (t_surface < 1e29) k_end = fog_light_extinction(dir, t_surface);
#endif
#endif
  }
#if FOG_REDUCED > 1
  fog_out_colour = vec4(optical_depth, t_surface, k_end, fog_sun_light(view_dir, t_surface));
#if FOG_LAMPS
  fog_out_inscatter = vec4(fog_lamps_light(fog_light_ray(view_dir, t_surface)), 0.0);
#endif
  return;
#endif
  // The pixel's own T_s mean where it walked its own ray (a loop of at most one turn, as
  // above: the upsampled pixels' lane groups skip it).
  for (int turn = walk ? 0 : 1; turn < 1; turn++) sun_light = fog_sun_light(view_dir, t_surface);
#if FOG_FROXEL == 2
  vec4 froxel = fog_froxel_lookup(pixel, t_surface);
  float tau = froxel.a;
#else
  // Extinction is never negative: a sum of signed detail bands (lod = sum) or a ringing
  // basis may cancel below 0 in float, which drew transmittance above 1 and, past a density
  // of ~1e7, NaN (fog_transmittance in C)
  float tau = exp(-max(optical_depth, 0.0));
#endif
#if FOG_SURFACE_SUN
  // Fog shadows on the ground: the sun reaching P is attenuated by T_s(P).
  if (t_surface < 1e29)
    surface.rgb -= (1.0 - exp(-fog_sun_optical_depth(t_surface * vec3(view_dir)))) *
                   texelFetch(fog_surface_sun, pixel, 0).rgb;
#endif
#if FOG_SURFACE_LAMPS
  // The lamps' light on the ground crossed the fog between each lamp and P (Fogshop §4).
  if (t_surface < 1e29) {
    vec4 lamp_share = texelFetch(fog_surface_lamps, pixel, 0);
    if (any(greaterThan(lamp_share.rgb, vec3(0.0))))
      surface.rgb -= lamp_share.rgb * (1.0 - fog_lamps_surface(t_surface * vec3(view_dir),
                                                               fog_unpack_normal(lamp_share.a)));
  }
#endif
  // Giroud & Biri eq. 4 with L_fog = L_amb + a L_sun p(theta) T_s-mean (fog_light.glsl):
  // with a = 0 the same image, with T_s = 1 the identity of docs/light.md.
#if FOG_FROXEL == 2
  vec3 inscatter = froxel.rgb;
#else
  vec3 inscatter =
      (fog_colour + fog_sun_scatter * fog_phase_hg(fog_phase_g, vec3(view_dir), fog_sun_direction) * sun_light) * (1.0 - tau);
#endif
#if FOG_LAMPS
  // the lamps: upsampled from the reduced pass, or the pixel's own (a loop of at most one
  // turn, as above)
  for (int turn = walk ? 0 : 1; turn < 1; turn++)
    lamp_light = fog_lamps_light(fog_light_ray(view_dir, t_surface));
  inscatter += lamp_light;
#endif
  fog_out_colour = vec4(tau * surface.rgb + inscatter, surface.a);
  fog_out_transmittance = tau;
  fog_out_inscatter = vec4(inscatter, 1.0);
}
