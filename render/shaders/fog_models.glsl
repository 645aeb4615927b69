// The fog models besides the fogmap (homogeneous, height, Gaussian RBFs, a 3D volume,
// quadric volumes, the classic linear and exp2 factors): GLSL
// twins of render/fog_models_cpu.c (same names, same formulas; render/fog_models.h).
// Positions arrive camera-relative from the CPU, subtracted there in double.
// FOG_MODEL_*, FOG_MAX_RBFS and FOG_EXPREL_SWITCH come from the C headers
// (fog_constants.glsl, included by fog_integral.glsl).

const int fog_model = FOG_MODEL_KIND;  // specialised per variant (render/fog_pass.c)
uniform float fog_model_extinction;
uniform float fog_model_y0;            // y0 - camera y
uniform float fog_model_scale_height;
// FOG_MODEL_LINEAR: the factor's start and end distances (FOG_MODEL_EXP2: the density is
// fog_model_extinction); both media are radial about the camera (render/fog_classic_cpu.c)
uniform float fog_model_start, fog_model_end;
// FOG_MODEL_RBF (fog_pass_rbf_uniforms): Gaussian i is texels 2i (xyz: centre - camera,
// subtracted in double; w: 1/r) and 2i + 1 (x: density) of fog_rbf_data; the view ray of a
// pixel sums only its screen tile's list (render/fog_rbf_tiles.h: what it leaves out changes
// the ray's optical depth by < FOG_RBF_CULL_BOUND in all); rays from elsewhere (the lamps'
// transmittance) sum them all.
uniform int fog_rbf_count;
uniform samplerBuffer fog_rbf_data;
uniform usamplerBuffer fog_rbf_indices;  // the tiles' lists
uniform usampler2D fog_rbf_tiles;        // per tile: first index, count
uniform int fog_rbf_tile_size;
ivec2 fog_rbf_tile = ivec2(0);           // the pixel's tile (fog_pass_fs.glsl's main sets it)
// FOG_MODEL_PERLIN (render/fog_perlin.h; fog_pass_perlin_uniforms): octave i's texels at
// z in [i size, (i + 1) size) of fog_perlin_texels (R32F, texelFetch, wrapped by the mask);
// its texel coordinates at camera-relative p are fog_perlin_camera[i] + fog_perlin_scale[i] p
// (the camera's, drift included, wrapped into [0, size) in double on the CPU).
uniform sampler3D fog_perlin_texels;
uniform int fog_perlin_octaves, fog_perlin_size;
uniform float fog_perlin_scale[FOG_PERLIN_MAX_OCTAVES];
uniform vec3 fog_perlin_camera[FOG_PERLIN_MAX_OCTAVES];
uniform vec3 fog_perlin_lo, fog_perlin_hi;  // the box, camera-relative
uniform int fog_perlin_paper;               // 1: FOG_PERLIN_PAPER, the single sample
uniform float fog_perlin_mean;              // T's mean (fog_perlin.mean_turbulence)
uniform sampler3D fog_grid3d;                  // FOG_MODEL_VOLUME: RG32F, voxel i and i + 1
                                               // along x at texel i + 1 (a ring of zeros)
uniform mat3 fog_grid3d_index_from_world;      // index position u = M p + offset
uniform vec3 fog_grid3d_camera_index;          // u at the camera (double on the CPU)
uniform vec3 fog_grid3d_dims;
uniform float fog_grid3d_step;                 // world units (the march)
uniform sampler3D fog_grid3d_occupancy;        // R32F brick bounds (FOG_SKIP)
uniform ivec3 fog_grid3d_bricks;
// FOG_MODEL_QUADRIC (fog_pass_quadric_uniforms): Q at camera-relative p is
// p.(M p) + 2 g.p + c0, M symmetric, c0 = Q(camera) and g = M camera + l, computed in double
// on the CPU and kept in double here, M too: far from the camera Q's terms cancel, and M's
// float rounding, 6e-8 relative, grew by (distance/size)^2 there (a sheet 900 units off, 0.3
// thick, drawn with tau 0.39 where the ray misses it).
uniform int fog_quadric_count;
uniform dvec3 fog_quadric_diag[FOG_MAX_QUADRICS];  // M's diagonal
uniform dvec3 fog_quadric_off[FOG_MAX_QUADRICS];   // M's xy, yz, xz
uniform float fog_quadric_density[FOG_MAX_QUADRICS];
uniform float fog_quadric_edge[FOG_MAX_QUADRICS];
uniform float fog_quadric_noise[FOG_MAX_QUADRICS];  // the turbulence's share (fog_quadric.noise)
uniform dvec4 fog_quadric_grad_c0[FOG_MAX_QUADRICS];  // g; w: c0
uniform vec3 fog_quadric_lo[FOG_MAX_QUADRICS];     // the clip box, camera-relative
uniform vec3 fog_quadric_hi[FOG_MAX_QUADRICS];
uniform vec3 fog_quadric_union_lo, fog_quadric_union_hi;  // all the boxes

// (1 - e^{-x})/x, with the series sum_{n<=10} (-x)^n/(n+1)! below FOG_EXPREL_SWITCH.
float fog_exprel(float x) {
  if (abs(x) < FOG_EXPREL_SWITCH)
    return 1.0 + x * (-1.0 / 2.0 + x * (1.0 / 6.0 + x * (-1.0 / 24.0 + x * (1.0 / 120.0 +
           x * (-1.0 / 720.0 + x * (1.0 / 5040.0 + x * (-1.0 / 40320.0 +
           x * (1.0 / 362880.0 + x * (-1.0 / 3628800.0 + x * (1.0 / 39916800.0))))))))));
  return (1.0 - exp(-x)) / x;
}

float fog_homogeneous_optical_depth(float extinction, float length) {
  if (extinction == 0.0) return 0.0;  // no fog, even to infinity (as the C twin)
  return extinction * length;  // OpenGL GL_EXP fog
}

// int_0^L k exp(-(y_c + t dir_y - y0)/H) dt = k e^{-(y_c - y0)/H} L exprel(dir_y L / H);
// camera-relative: y_c = 0, y0 = fog_model_y0. length >= 1e29 means no surface. A ray
// going down is taken from its lower end, k e^{-(y_c + dir_y L - y0)/H} L exprel(-dir_y L/H)
// (the same integral): seen from far above the fog, e^{-(y_c - y0)/H} underflows to 0 in
// float while exprel(dir_y L / H) overflows, and their product was NaN.
float fog_height_optical_depth(float extinction, float y0, float scale_height, float dir_y,
                               float length) {
  if (extinction == 0.0) return 0.0;  // no fog, even to infinity (as the C twin)
  float a = dir_y / scale_height;
  if (length >= 1e29) return a > 0.0 ? extinction * exp(y0 / scale_height) / a : 1e30;
  if (a < 0.0)
    return extinction * exp((y0 - dir_y * length) / scale_height) * length *
           fog_exprel(-a * length);
  return extinction * exp(y0 / scale_height) * length * fog_exprel(a * length);
}

// erfc(z) for z >= 0: Numerical Recipes' erfcc (a Chebyshev fit; relative error < 1.2e-7
// everywhere, float's own precision). GLSL has no erf; the C twin uses libm's.
float fog_erfc_nonnegative(float z) {
  z = min(z, 10.0);  // erfc(10) = 2e-45 is 0 in float; keeps z * z finite for the sky
  float t = 1.0 / (1.0 + 0.5 * z);
  return t * exp(-z * z - 1.26551223 + t * (1.00002368 + t * (0.37409196 + t * (0.09678418 +
         t * (-0.18628806 + t * (0.27886807 + t * (-1.13520398 + t * (1.48851587 +
         t * (-0.82215223 + t * 0.17087277)))))))));
}

// erf(x) for |x| <= 0.5: its Taylor series to x^13 (relative error < 2e-9 there).
float fog_erf_small(float x) {
  float x2 = x * x;
  return 1.12837916709551 * x *
         (1.0 + x2 * (-1.0 / 3.0 + x2 * (0.1 + x2 * (-1.0 / 42.0 + x2 * (1.0 / 216.0 +
          x2 * (-1.0 / 1320.0 + x2 * (1.0 / 9360.0)))))));
}

// erf(u1) - erf(u0) for u0 <= u1 (the C twin's cases): through erfc where both have the
// same sign, 2 - erfc(|u0|) - erfc(u1) across 0; where both lie within 0.5 of 0, by the
// series (there erfc is near 1 and a difference of two kept float's absolute 1e-7 only: a
// Gaussian much wider than the ray's stretch, radius 1e6 over 1000 units, lost 3e-4 of its
// depth).
float fog_erf_difference(float u0, float u1) {
  if (max(abs(u0), abs(u1)) <= 0.5) return fog_erf_small(u1) - fog_erf_small(u0);
  float e0 = fog_erfc_nonnegative(abs(u0)), e1 = fog_erfc_nonnegative(abs(u1));
  if (u0 >= 0.0) return e0 - e1;
  if (u1 <= 0.0) return e1 - e0;
  return 2.0 - e0 - e1;
}

// Gaussian i: xyz its centre - camera, w 1/r; and its density.
vec4 fog_rbf_centre(int i) { return texelFetch(fog_rbf_data, 2 * i); }
float fog_rbf_density(int i) { return texelFetch(fog_rbf_data, 2 * i + 1).x; }
float fog_rbf_cull_radius(int i) { return texelFetch(fog_rbf_data, 2 * i + 1).y; }

// Gaussian i's int_0^L c exp(-|origin + t dir - b|^2 / r^2) dt: e^{-h^2/r^2} r sqrt(pi)/2
// (erf(u1) - erf(u0)) (fog_rbf_optical_depth in C).
float fog_rbf_one(int i, vec3 origin, vec3 dir, float length) {
  vec4 g = fog_rbf_centre(i);
  vec3 v = g.xyz - origin;
  float inv_r = g.w, tc = dot(v, dir);
  vec3 w = v - tc * dir;  // from the ray's line to the centre
  float u0 = -tc * inv_r, u1 = (length - tc) * inv_r;
  return fog_rbf_density(i) * exp(-dot(w, w) * inv_r * inv_r) * (0.88622692545 / inv_r) *
         fog_erf_difference(u0, u1);
}

// The pixel's tile's list: first index and count.
uvec2 fog_rbf_tile_range() { return texelFetch(fog_rbf_tiles, fog_rbf_tile, 0).xy; }

// base L + every Gaussian along the ray from camera-relative point `origin` (the lamps'
// transmittance, fog_lamps.glsl).
float fog_rbf_optical_depth_from(float base, vec3 origin, vec3 dir, float length) {
  float sum = fog_homogeneous_optical_depth(base, length);
  for (int i = 0; i < fog_rbf_count; i++) sum += fog_rbf_one(i, origin, dir, length);
  return sum;
}
// base L + the Gaussians of the pixel's tile along its view ray (from the camera).
float fog_rbf_optical_depth(float base, vec3 dir, float length) {
  float sum = fog_homogeneous_optical_depth(base, length);
  uvec2 range = fog_rbf_tile_range();
  for (uint k = range.x; k < range.x + range.y; k++)
    sum += fog_rbf_one(int(texelFetch(fog_rbf_indices, int(k)).x), vec3(0.0), dir, length);
  return sum;
}

// The line origin + t dir against the box [lo, hi] (Kay & Kajiya; parallel axes selected,
// not branched on): the entry and exit parameters, false when it misses.
bool fog_slab(vec3 lo, vec3 hi, vec3 origin, vec3 dir, out float t0, out float t1) {
  vec3 ta = (lo - origin) / dir, tb = (hi - origin) / dir;
  bvec3 parallel = equal(dir, vec3(0.0));
  bvec3 inside = bvec3(uvec3(greaterThanEqual(origin, lo)) & uvec3(lessThanEqual(origin, hi)));
  vec3 reach = mix(vec3(-1e30), vec3(1e30), inside);
  vec3 a = mix(min(ta, tb), -reach, parallel), b = mix(max(ta, tb), reach, parallel);
  t0 = max(max(a.x, a.y), a.z);
  t1 = min(min(b.x, b.y), b.z);
  return t0 <= t1;
}

// Quadric volume i's symmetric matrix M.
dmat3 fog_quadric_matrix(int i) {
  dvec3 d = fog_quadric_diag[i], o = fog_quadric_off[i];
  return dmat3(d.x, o.x, o.z, o.x, d.y, o.y, o.z, o.y, d.z);
}

// The roots of a t^2 + 2 b t + c = 0 without cancellation (fog_quadric_cpu.c's
// quadratic_roots): the count, a double root once.
int fog_quadratic_roots(float a, float b, float c, out float r0, out float r1) {
  r0 = r1 = 0.0;
  if (a == 0.0) {
    if (b == 0.0) return 0;
    r0 = -c / (2.0 * b);
    return 1;
  }
  float disc = b * b - a * c;
  if (disc < 0.0) return 0;
  float q = -(b + (b < 0.0 ? -sqrt(disc) : sqrt(disc)));
  if (q == 0.0) return 1;
  r0 = q / a;
  r1 = c / q;
  return 2;
}

// The roots of Q(t) = -level strictly inside (t0, t1), the others (and missing ones) at t1.
vec2 fog_quadric_breaks(float a, float b, float c, float t0, float t1) {
  float r0, r1;
  int k = fog_quadratic_roots(a, b, c, r0, r1);
  return vec2(k > 0 && r0 > t0 && r0 < t1 ? r0 : t1, k > 1 && r1 > t0 && r1 < t1 ? r1 : t1);
}

// Defined with the Perlin fog below.
float fog_quadric_weighted_turbulence(vec3 start, vec3 dir, float ta, float tb, vec3 w);
float fog_perlin_turbulence(vec3 p);

// int_{t0}^{t1} of one volume's K along Q(t) = a t^2 + 2 b t + c (the ray start + t dir): the
// breaks at Q = 0 and Q = -edge sorted by a network of min/max (no dynamic indexing), then
// per piece 0, the density, or density (-Q/edge) by Simpson's rule (exact); with noise, that
// weight times the turbulence's share (fog_quadric_weighted_turbulence).
float fog_quadric_span(float a, float b, float c, float density, float edge, float amount,
                       vec3 start, vec3 dir, float t0, float t1) {
  vec4 s = vec4(fog_quadric_breaks(a, b, c, t0, t1),
                edge > 0.0 ? fog_quadric_breaks(a, b, c + edge, t0, t1) : vec2(t1));
  s = vec4(min(s.x, s.y), max(s.x, s.y), min(s.z, s.w), max(s.z, s.w));
  s = vec4(min(s.x, s.z), min(s.y, s.w), max(s.x, s.z), max(s.y, s.w));
  s = vec4(s.x, min(s.y, s.z), max(s.y, s.z), s.w);
  float cut[6] = float[6](t0, s.x, s.y, s.z, s.w, t1);
  float sum = 0.0, plain = 1.0 - amount, turbulent = amount / fog_perlin_mean;
  for (int i = 0; i < 5; i++) {
    float ta = cut[i], tb = cut[i + 1], tm = 0.5 * (ta + tb);
    float qm = (a * tm + 2.0 * b) * tm + c;
    if (!(tb > ta) || qm >= 0.0) continue;
    bool core = edge == 0.0 || qm <= -edge;
    if (core) {
      sum += plain * density * (tb - ta);
    } else {
      float qa = (a * ta + 2.0 * b) * ta + c, qb = (a * tb + 2.0 * b) * tb + c;
      sum -= plain * density / edge * (tb - ta) * (qa + 4.0 * qm + qb) / 6.0;
    }
#if FOG_QUADRIC_NOISE
    if (amount > 0.0)
      sum += turbulent * fog_quadric_weighted_turbulence(
                             start, dir, ta, tb,
                             core ? vec3(density, 0.0, 0.0) : -density / edge * vec3(c, 2.0 * b, a));
#endif
  }
  return sum;
}

// The quadric volumes' exact optical depth from camera-relative `origin` along unit dir
// for length (>= 1e29: through every box): fog_quadric_optical_depth in C. Q along the ray
// is set up in double and re-centred on the stretch's start t0 (Q(t0 + s) = a s^2 + 2 b' s +
// c'): far from the camera Q's terms are large and cancel (c0 ~ (distance/size)^2), and in
// float a grazing ray's roots moved by ~1e-2 units; re-centred, the float pieces see Q's own
// range.
float fog_quadric_optical_depth_from(vec3 origin, vec3 dir, float length) {
  float sum = 0.0;
  for (int i = 0; i < fog_quadric_count; i++) {
    float t0, t1, density = fog_quadric_density[i];
    if (!(density > 0.0) ||
        !fog_slab(fog_quadric_lo[i], fog_quadric_hi[i], origin, dir, t0, t1)) continue;
    t0 = max(t0, 0.0);
    t1 = min(t1, length);
    if (!(t1 > t0)) continue;
    dmat3 m = fog_quadric_matrix(i);
    dvec3 g = fog_quadric_grad_c0[i].xyz, x = dvec3(origin), w = dvec3(dir);
    double a = dot(w, m * w), b = dot(w, m * x + g);
    double c = dot(x, m * x) + 2.0 * dot(g, x) + fog_quadric_grad_c0[i].w;
    double s = double(t0);
    sum += fog_quadric_span(float(a), float(b + a * s), float((a * s + 2.0 * b) * s + c), density,
                            fog_quadric_edge[i], fog_quadric_noise[i], origin + t0 * dir, dir,
                            0.0, t1 - t0);
  }
  return sum;
}

// Where the view ray (from the camera, unit dir) crosses the volumes' surfaces inside
// (t0, t1): Q = 0, Q = -edge, and the clip box's faces where Q < 0 there (K jumps or kinks
// at each): fog_quadric_cuts in C. Unsorted; returns how many. The sun's mean cuts its
// segments there.
#define FOG_QUADRIC_MAX_CUTS (6 * FOG_MAX_QUADRICS)
int fog_quadric_cuts(vec3 dir, float t0, float t1, out float cuts[FOG_QUADRIC_MAX_CUTS]) {
  int n = 0;
  for (int i = 0; i < fog_quadric_count; i++) {
    float s0, s1;
    if (!(fog_quadric_density[i] > 0.0) ||
        !fog_slab(fog_quadric_lo[i], fog_quadric_hi[i], vec3(0.0), dir, s0, s1)) continue;
    float a0 = max(s0, t0), a1 = min(s1, t1);
    if (!(a1 > a0)) continue;
    // Q(a0 + u) = a u^2 + 2 b u + c, re-centred in double (fog_quadric_optical_depth_from)
    dmat3 m = fog_quadric_matrix(i);
    dvec3 w = dvec3(dir);
    double qa = dot(w, m * w), qb = dot(w, fog_quadric_grad_c0[i].xyz), s = double(a0);
    float a = float(qa), b = float(qb + qa * s),
          c = float((qa * s + 2.0 * qb) * s + fog_quadric_grad_c0[i].w), len = a1 - a0;
    if (s0 > t0 && c < 0.0) cuts[n++] = a0;
    if (s1 < t1 && (a * len + 2.0 * b) * len + c < 0.0) cuts[n++] = a1;
    for (int level = 0; level < (fog_quadric_edge[i] > 0.0 ? 2 : 1); level++) {
      float r0, r1;
      int k = fog_quadratic_roots(a, b, level == 1 ? c + fog_quadric_edge[i] : c, r0, r1);
      if (k > 0 && r0 > 0.0 && r0 < len) cuts[n++] = a0 + r0;
      if (k > 1 && r1 > 0.0 && r1 < len) cuts[n++] = a0 + r1;
    }
  }
  return n;
}

// K at camera-relative p: the volumes' extinctions summed (fog_quadric_extinction_at).
float fog_quadric_extinction_at(vec3 p) {
  // K = sum c_i w_i (1 - n_i + n_i T/T_mean) = sum c_i w_i + (T/T_mean - 1) sum c_i w_i n_i:
  // T once, after the loop (inside it, llvmpipe paid it per volume, every branch masked)
  float k = 0.0, noisy = 0.0;
  for (int i = 0; i < fog_quadric_count; i++) {
    if (any(lessThan(p, fog_quadric_lo[i])) || any(greaterThan(p, fog_quadric_hi[i]))) continue;
    // in double: Q's terms far from the camera cancel (fog_quadric_optical_depth_from)
    dvec3 x = dvec3(p), g = fog_quadric_grad_c0[i].xyz;
    float q = float(dot(x, fog_quadric_matrix(i) * x) + 2.0 * dot(g, x) +
                    fog_quadric_grad_c0[i].w);
    if (!(q < 0.0)) continue;
    float edge = fog_quadric_edge[i], density = fog_quadric_density[i];
    float ki = edge > 0.0 ? density * min(1.0, -q / edge) : density;
    k += ki;
    noisy += ki * fog_quadric_noise[i];
  }
#if FOG_QUADRIC_NOISE
  for (int turn = noisy > 0.0 ? 0 : 1; turn < 1; turn++)  // a loop: skipped when no lane needs it
    k += noisy * (fog_perlin_turbulence(p) / fog_perlin_mean - 1.0);
#endif
  return k;
}

// The ray's stretch [t0, t1] inside the volume's support (index coordinates in [-1, dim])
// and [0, length], with index position u0 + t du (the C twin's grid3d_stretch). Parallel
// axes are selected, not branched on, as in fog_box_entry_exit.
bool fog_grid3d_stretch(vec3 dir, float length, out vec3 u0, out vec3 du, out float t0,
                        out float t1) {
  du = fog_grid3d_index_from_world * dir;
  u0 = fog_grid3d_camera_index;
  vec3 ta = (-1.0 - u0) / du, tb = (fog_grid3d_dims - u0) / du;
  bvec3 parallel = equal(du, vec3(0.0));
  bvec3 inside = bvec3(uvec3(greaterThanEqual(u0, vec3(-1.0))) &
                       uvec3(lessThanEqual(u0, fog_grid3d_dims)));
  vec3 reach = mix(vec3(-1e30), vec3(1e30), inside);
  vec3 lo = mix(min(ta, tb), -reach, parallel), hi = mix(max(ta, tb), reach, parallel);
  t0 = max(max(max(lo.x, lo.y), lo.z), 0.0);
  t1 = min(min(min(hi.x, hi.y), hi.z), length);
  return t0 < t1;
}

// The hardware's trilinear filter at index position u (the march).
float fog_grid3d_density(vec3 u) {
  return texture(fog_grid3d, (u + 1.5) / (fog_grid3d_dims + 2.0)).r;
}

// The 8 corner voxels of lattice cell c (u in [c, c + 1]^3), read exactly (texelFetch: no
// weights quantised to a GPU's 8 bits), two per texel (a voxel and its +x neighbour);
// beyond the grid they are the zero ring's.
struct fog_grid3d_cell {
  vec4 z0, z1;  // (c000, c100, c010, c110) and the same one layer up
};

fog_grid3d_cell fog_grid3d_cell_load(ivec3 c) {
  ivec3 t = clamp(c + 1, ivec3(0), ivec3(fog_grid3d_dims));  // the walk stays in the ring
  vec2 a = texelFetch(fog_grid3d, t, 0).rg, b = texelFetch(fog_grid3d, t + ivec3(0, 1, 0), 0).rg;
  vec2 e = texelFetch(fog_grid3d, t + ivec3(0, 0, 1), 0).rg;
  vec2 g = texelFetch(fog_grid3d, t + ivec3(0, 1, 1), 0).rg;
  return fog_grid3d_cell(vec4(a, b), vec4(e, g));
}

// Trilinear in the cell at local coordinates f in [0, 1]^3.
float fog_grid3d_cell_value(fog_grid3d_cell cell, vec3 f) {
  vec4 z = mix(cell.z0, cell.z1, f.z);         // (x0y0, x1y0, x0y1, x1y1)
  vec2 y = mix(z.xy, z.zw, f.y);               // (x0, x1)
  return mix(y.x, y.y, f.x);
}

// The volume's exact optical depth (fog_grid3d_optical_depth in C): trilinear between voxel
// centres is a cubic in t inside each cell of index space's integer lattice, so a 3D DDA
// over those cells (the walk's fog_axis, from the entry) with two Gauss-Legendre nodes per
// piece integrates it exactly. Manual fetch (the default) reads each piece's cell corners
// once for both nodes; hardware filtering samples the two nodes with texture(): ~20 %
// faster on llvmpipe, whose 3D weights are float, but a GPU's are 8-bit (~1e-3 in tau).
// The lattice cells over [t, t_end] (t_end a lattice crossing or len: no piece cut short).
void fog_grid3d_cells(inout fog_axis ax, inout fog_axis ay, inout fog_axis az, vec3 ue,
                      vec3 du, inout float t, float t_end, float len, inout float sum) {
  for (int guard = 0; t < t_end && sum < fog_depth_limit && guard < 65536; guard++) {
    float tx = fog_axis_next(ax), ty = fog_axis_next(ay), tz = fog_axis_next(az);
    float tn = min(min(len, tx), min(ty, tz));
    float half_len = 0.5 * (tn - t), mid = 0.5 * (tn + t), off = 0.57735026918962576 * half_len;
    if (tn > t) {
#if FOG_FETCH_HARDWARE
      sum += half_len * (fog_grid3d_density(ue + (mid - off) * du) +
                         fog_grid3d_density(ue + (mid + off) * du));
#else
      ivec3 c = ivec3(ax.cell, ay.cell, az.cell);
      fog_grid3d_cell cell = fog_grid3d_cell_load(c);
      vec3 f = ue - vec3(c);
      sum += half_len * (fog_grid3d_cell_value(cell, f + (mid - off) * du) +
                         fog_grid3d_cell_value(cell, f + (mid + off) * du));
#endif
    }
    if (tx <= tn) ax.cell += ax.step;
    if (ty <= tn) ay.cell += ay.step;
    if (tz <= tn) az.cell += az.step;
    t = max(t, tn);
  }
}

float fog_grid3d_optical_depth(vec3 dir, float length) {
  vec3 u0, du;
  float t0, t1;
  if (!fog_grid3d_stretch(dir, length, u0, du, t0, t1)) return 0.0;
  vec3 ue = u0 + t0 * du;  // the entry: small index coordinates from here on
  fog_axis ax = fog_axis_start(ue.x, du.x, 0.0), ay = fog_axis_start(ue.y, du.y, 0.0),
           az = fog_axis_start(ue.z, du.z, 0.0);
  float len = t1 - t0, t = 0.0, sum = 0.0;
  // Early termination: the walks stop once the depth passes fog_depth_limit.
#if FOG_SKIP
  fog_axis_sync(ax, t);  // crossings at the start stepped first (fog_walk_integral)
  fog_axis_sync(ay, t);
  fog_axis_sync(az, t);
  // Brick by brick (render/fog_occupancy.h, fog_bricks_build), as the fogmap's walk goes
  // block by block (fog_walk_integral): an empty brick is jumped to where the ray leaves
  // it, every axis synced there; any other is walked cell by cell up to that exit.
  for (int guard = 0; t < len && sum < fog_depth_limit && guard < 65536; guard++) {
    ivec3 brick = clamp((ivec3(ax.cell, ay.cell, az.cell) + 1) / FOG_OCCUPANCY_BLOCK,
                        ivec3(0), fog_grid3d_bricks - 1);
    float tb = min(min(len, fog_axis_block_exit(ax, 1)),
                   min(fog_axis_block_exit(ay, 1), fog_axis_block_exit(az, 1)));
    if (texelFetch(fog_grid3d_occupancy, brick, 0).r <= fog_skip_below && tb > t) {
      t = tb;
      fog_axis_sync(ax, t);
      fog_axis_sync(ay, t);
      fog_axis_sync(az, t);
    } else {
      fog_grid3d_cells(ax, ay, az, ue, du, t, tb > t ? tb : len, len, sum);
    }
  }
#else
  fog_grid3d_cells(ax, ay, az, ue, du, t, len, len, sum);
#endif
  return sum;
}

// The volume marched (fog_grid3d_optical_depth_march in C): the stretch cut into
// n = ceil(stretch / step) equal steps, trilinear samples at their midpoints.
float fog_grid3d_optical_depth_march(vec3 dir, float length) {
  vec3 u0, du;
  float t0, t1;
  if (!fog_grid3d_stretch(dir, length, u0, du, t0, t1)) return 0.0;
  // at most 16384 samples a ray (docs/config.md, volume_step): a finer step overflowed the
  // count and summed away its own terms in float
  int n = int(clamp(ceil((t1 - t0) / fog_grid3d_step), 1.0, 16384.0));
  float dt = (t1 - t0) / float(n), sum = 0.0;
  for (int s = 0; s < n; s++) sum += fog_grid3d_density(u0 + (t0 + (float(s) + 0.5) * dt) * du);
  return sum * dt;
}

// ---- Perlin turbulence fog (fog_perlin.c's twins) ----------------------------------------

struct fog_perlin_cell {
  vec4 a, b;  // corners (x, y, z) = (k & 1, (k >> 1) & 1, k >> 2): a k = 0..3, b k = 4..7
};

fog_perlin_cell fog_perlin_cell_load(int i, ivec3 c) {
  int mask = fog_perlin_size - 1, zo = i * fog_perlin_size;
  ivec3 c0 = c & mask, c1 = (c + 1) & mask;
  float v[8];
  for (int k = 0; k < 8; k++) {
    ivec3 q = ivec3((k & 1) != 0 ? c1.x : c0.x, (k & 2) != 0 ? c1.y : c0.y,
                    (k & 4) != 0 ? c1.z : c0.z);
    v[k] = texelFetch(fog_perlin_texels, ivec3(q.xy, q.z + zo), 0).r;
  }
  return fog_perlin_cell(vec4(v[0], v[1], v[2], v[3]), vec4(v[4], v[5], v[6], v[7]));
}

float fog_perlin_cell_value(fog_perlin_cell cell, vec3 f) {
  vec4 z = mix(cell.a, cell.b, f.z);  // (x0y0, x1y0, x0y1, x1y1)
  vec2 y = mix(z.xy, z.zw, f.y);
  return mix(y.x, y.y, f.x);
}

// T at camera-relative p.
float fog_perlin_turbulence(vec3 p) {
  float sum = 0.0;
  for (int i = 0; i < fog_perlin_octaves; i++) {
    vec3 u = fog_perlin_camera[i] + fog_perlin_scale[i] * p, c = floor(u);
    sum += fog_perlin_cell_value(fog_perlin_cell_load(i, ivec3(c)), u - c) * exp2(-float(i));
  }
  return sum;
}

bool fog_perlin_inside(vec3 p) {
  return all(greaterThanEqual(p, fog_perlin_lo)) && all(lessThanEqual(p, fog_perlin_hi));
}

// Octave i's texel cells along origin + t dir (origin camera-relative): the DDA that the
// Perlin fog's walk and the noisy quadric volumes' walk both take.
struct fog_perlin_walk {
  int octave;
  vec3 ue, du;  // texel coordinates at t = 0, and per unit of t
  fog_axis x, y, z;
};

fog_perlin_walk fog_perlin_walk_start(int i, vec3 origin, vec3 dir) {
  float s = fog_perlin_scale[i];
  vec3 ue = fog_perlin_camera[i] + s * origin, du = s * dir;
  return fog_perlin_walk(i, ue, du, fog_axis_start(ue.x, du.x, 0.0),
                         fog_axis_start(ue.y, du.y, 0.0), fog_axis_start(ue.z, du.z, 0.0));
}

// The next crossing of a cell face after the current cell's entry, at most len.
float fog_perlin_walk_next(fog_perlin_walk w, float len) {
  return min(min(len, fog_axis_next(w.x)), min(fog_axis_next(w.y), fog_axis_next(w.z)));
}

// The cell of the piece [t, tn] (from its middle), and the walk's t = 0 in its frame.
fog_perlin_cell fog_perlin_walk_cell(fog_perlin_walk w, float t, float tn, out vec3 f0) {
  vec3 c = floor(w.ue + (0.5 * (t + tn)) * w.du);
  f0 = w.ue - c;
  return fog_perlin_cell_load(w.octave, ivec3(c));
}

// Past the faces crossed at tn.
void fog_perlin_walk_step(inout fog_perlin_walk w, float tn) {
  if (fog_axis_next(w.x) <= tn) w.x.cell += w.x.step;
  if (fog_axis_next(w.y) <= tn) w.y.cell += w.y.step;
  if (fog_axis_next(w.z) <= tn) w.z.cell += w.z.step;
}

// Octave i over [t0, t1] of the ray (fog_perlin.c's octave_depth): a DDA over its texel
// cells, each piece's cell from its middle, cut so that the height exponent moves by at
// most 1/2, 4 Gauss-Legendre nodes each. Stops once `budget` is passed.
float fog_perlin_octave_depth(int i, vec3 dir, float t0, float t1, float budget) {
  const float x1 = 0.33998104358485626, x2 = 0.86113631159405258;
  const float w1 = 0.65214515486254614, w2 = 0.34785484513745386;
  fog_perlin_walk w = fog_perlin_walk_start(i, t0 * dir, dir);
  vec3 du = w.du;
  float len = t1 - t0, t = 0.0, sum = 0.0, y_entry = t0 * dir.y;
  float inv_h = 1.0 / fog_model_scale_height;
  for (int guard = 0; t < len && sum < budget && guard < 65536; guard++) {
    float tn = fog_perlin_walk_next(w, len);
    if (tn > t) {
      vec3 f0;
      fog_perlin_cell cell = fog_perlin_walk_cell(w, t, tn, f0);
      int cuts = max(int(ceil(abs(dir.y) * (tn - t) * inv_h * 2.0)), 1);
      float h = (tn - t) / float(cuts);
      for (int k = 0; k < cuts; k++) {
        float half_h = 0.5 * h, centre = t + (float(k) + 0.5) * h;
        float ta = centre - x2 * half_h, tb = centre - x1 * half_h, tc = centre + x1 * half_h,
              td = centre + x2 * half_h;
        sum += half_h * (w2 * fog_perlin_cell_value(cell, f0 + ta * du) *
                             exp(-(y_entry + ta * dir.y - fog_model_y0) * inv_h) +
                         w1 * fog_perlin_cell_value(cell, f0 + tb * du) *
                             exp(-(y_entry + tb * dir.y - fog_model_y0) * inv_h) +
                         w1 * fog_perlin_cell_value(cell, f0 + tc * du) *
                             exp(-(y_entry + tc * dir.y - fog_model_y0) * inv_h) +
                         w2 * fog_perlin_cell_value(cell, f0 + td * du) *
                             exp(-(y_entry + td * dir.y - fog_model_y0) * inv_h));
      }
    }
    fog_perlin_walk_step(w, tn);
    t = max(t, tn);
  }
  return sum;
}

// int over [ta, tb] of w(t) T(start + t dir), w = w.x + w.y t + w.z t^2 (fog_quadric_cpu.c's
// weighted_turbulence, per octave here): each octave's DDA over its texel cells, where N_i
// is trilinear (a cubic along the ray), 3 Gauss-Legendre nodes per piece (exact for w N_i).
float fog_quadric_weighted_turbulence(vec3 start, vec3 dir, float ta, float tb, vec3 w) {
  const float x3 = 0.77459666924148338, w_end = 5.0 / 9.0, w_mid = 8.0 / 9.0;
  float sum = 0.0, len = tb - ta;
  for (int i = 0; i < fog_perlin_octaves; i++) {
    fog_perlin_walk walk = fog_perlin_walk_start(i, start + ta * dir, dir);
    float t = 0.0, octave = 0.0;
    for (int guard = 0; t < len && guard < 65536; guard++) {
      float tn = fog_perlin_walk_next(walk, len);
      if (tn > t) {
        vec3 f0;
        fog_perlin_cell cell = fog_perlin_walk_cell(walk, t, tn, f0);
        float half_h = 0.5 * (tn - t), mid = t + half_h, piece = 0.0;
        for (int k = -1; k <= 1; k++) {
          float tk = mid + float(k) * x3 * half_h, x = ta + tk;
          piece += (k == 0 ? w_mid : w_end) * ((w.z * x + w.y) * x + w.x) *
                   fog_perlin_cell_value(cell, f0 + tk * walk.du);
        }
        octave += half_h * piece;
      }
      fog_perlin_walk_step(walk, tn);
      t = max(t, tn);
    }
    sum += exp2(-float(i)) * octave;
  }
  return sum;
}

// The exact optical depth up to length, or the paper's: T once at the stretch's last point
// times the height fog over the stretch.
float fog_perlin_optical_depth(vec3 dir, float length) {
  float t0, t1;
  if (fog_model_extinction == 0.0 || !fog_slab(fog_perlin_lo, fog_perlin_hi, vec3(0.0), dir, t0, t1))
    return 0.0;
  t0 = max(t0, 0.0);
  t1 = min(t1, length);
  if (!(t1 > t0)) return 0.0;
  if (fog_perlin_paper != 0) /* the height fog from t0 on (no 0 * inf from far above) */
    return fog_perlin_turbulence(t1 * dir) *
           fog_height_optical_depth(fog_model_extinction, fog_model_y0 - t0 * dir.y,
                                    fog_model_scale_height, dir.y, t1 - t0);
  // sum is the depth over the extinction: what is left of the opacity budget, in octave i's
  // units, is (limit / K - sum) 2^i (not (limit - sum) / K 2^i, which mixed the units and
  // dropped the finer octaves wherever K < 1 and the fog was thin: up to 5.8e-2 in tau)
  float sum = 0.0;
  for (int i = 0; i < fog_perlin_octaves; i++)
    sum += exp2(-float(i)) *
           fog_perlin_octave_depth(i, dir, t0, t1,
                                   (fog_depth_limit / fog_model_extinction - sum) * exp2(float(i)));
  return fog_model_extinction * sum;
}

// ---- uniform ray marching of the analytic models (the benchmark's alternative) ----------

// K at camera-relative point p, pointwise (the marcher's integrand).
float fog_model_extinction_at(vec3 p) {
  if (fog_model == FOG_MODEL_HOMOGENEOUS) return fog_model_extinction;
  if (fog_model == FOG_MODEL_LINEAR) {
    float r = length(p);
    return r <= fog_model_start ? 0.0 : (r < fog_model_end ? 1.0 / (fog_model_end - r) : 1e30);
  }
  if (fog_model == FOG_MODEL_EXP2)
    return 2.0 * fog_model_extinction * fog_model_extinction * length(p);
  if (fog_model == FOG_MODEL_QUADRIC) return fog_quadric_extinction_at(p);
  if (fog_model == FOG_MODEL_PERLIN)
    return fog_perlin_inside(p) ? fog_model_extinction *
                                      exp(-(p.y - fog_model_y0) / fog_model_scale_height) *
                                      fog_perlin_turbulence(p)
                                : 0.0;
  if (fog_model == FOG_MODEL_HEIGHT)
    return fog_model_extinction * exp(-(p.y - fog_model_y0) / fog_model_scale_height);
  // RBFs at points of the pixel's view ray (the march, the light's samples): its tile's list
  float k = fog_model_extinction;
  uvec2 range = fog_rbf_tile_range();
  for (uint j = range.x; j < range.x + range.y; j++) {
    int i = int(texelFetch(fog_rbf_indices, int(j)).x);
    vec4 g = fog_rbf_centre(i);
    vec3 d = p - g.xyz;
    k += fog_rbf_density(i) * exp(-dot(d, d) * g.w * g.w);
  }
  return k;
}

// How far along dir a marcher must go for the sky (no surface): where the model's fog has
// fallen below e^-36 of its peak (RBFs: 6 radii past the farthest centre; height fog going
// up: 36 scale heights above y0; quadrics: where the ray leaves their boxes). Infinite where the fog does not end (a homogeneous base,
// height fog level or going down): the marcher then reports it opaque, as the exact
// integral is (clear where the extinction is 0).
float fog_model_reach(vec3 dir) {
  if (fog_model == FOG_MODEL_LINEAR) return fog_model_end;  // opaque from there on
  if (fog_model == FOG_MODEL_HEIGHT)
    return dir.y > 0.0 ? max(fog_model_y0 + 36.0 * fog_model_scale_height, 0.0) / dir.y : 1e30;
  if (fog_model == FOG_MODEL_RBF && fog_model_extinction == 0.0) {
    float reach = 0.0;  // the pixel's tile's Gaussians: the others are not seen
    uvec2 range = fog_rbf_tile_range();
    for (uint j = range.x; j < range.x + range.y; j++) {
      vec4 g = fog_rbf_centre(int(texelFetch(fog_rbf_indices, int(j)).x));
      reach = max(reach, dot(g.xyz, dir) + 6.0 / g.w);
    }
    return reach;
  }
  if (fog_model == FOG_MODEL_QUADRIC) {
    float t0, t1;
    return fog_slab(fog_quadric_union_lo, fog_quadric_union_hi, vec3(0.0), dir, t0, t1)
               ? max(t1, 0.0) : 0.0;
  }
  if (fog_model == FOG_MODEL_PERLIN) {
    float t0, t1;
    return fog_slab(fog_perlin_lo, fog_perlin_hi, vec3(0.0), dir, t0, t1) ? max(t1, 0.0) : 0.0;
  }
  return 1e30;
}

// Midpoint rule with `steps` equal steps over [0, min(surface, reach)]; jitter in [0, 1)
// shifts the samples (0.5 = midpoint), as fog_optical_depth_march does for the fogmap.
float fog_model_optical_depth_march(vec3 dir, float t_surface, int steps, float jitter) {
  float length = min(t_surface, fog_model_reach(dir));
  if (length >= 1e29) return fog_model_extinction > 0.0 ? 1e30 : 0.0;  // no fog: clear sky
  float dt = length / float(steps), sum = 0.0;
  for (int i = 0; i < steps; i++)
    sum += fog_model_extinction_at((float(i) + jitter) * dt * dir);
  return sum * dt;
}

// ---- the table's twins (render/fog_models.def): one ray, every model's signature -------

// The ray of one pixel: the direction in double (fog_optical_depth_inside) and rounded, its
// span in the fog's box (fogmap), the surface distance and the marcher's jitter.
struct fog_ray {
  dvec3 dir_d;
  vec3 dir;
  double t_in, t_out;
  float t_surface, jitter;
};

float fog_model_depth_homogeneous(fog_ray r) {
  return fog_homogeneous_optical_depth(fog_model_extinction, r.t_surface);
}
float fog_model_depth_height(fog_ray r) {
  return fog_height_optical_depth(fog_model_extinction, fog_model_y0, fog_model_scale_height,
                                  r.dir.y, r.t_surface);
}
float fog_model_depth_rbf(fog_ray r) {
  return fog_rbf_optical_depth(fog_model_extinction, r.dir, r.t_surface);
}
float fog_model_depth_volume(fog_ray r) { return fog_grid3d_optical_depth(r.dir, r.t_surface); }
float fog_model_depth_quadric(fog_ray r) {
  return fog_quadric_optical_depth_from(vec3(0.0), r.dir, r.t_surface);
}
// The classic factors from the camera (Zdrojewska eq. 2, 4): -ln f(d).
float fog_linear_depth(float d) {
  if (d <= fog_model_start) return 0.0;
  if (d >= fog_model_end) return 1e30;
  return log((fog_model_end - fog_model_start) / (fog_model_end - d));
}
float fog_exp2_depth(float d) {
  if (fog_model_extinction == 0.0) return 0.0;
  if (d >= 1e29) return 1e30;
  float x = fog_model_extinction * d;
  return x * x;
}
float fog_model_depth_linear(fog_ray r) { return fog_linear_depth(r.t_surface); }
float fog_model_depth_exp2(fog_ray r) { return fog_exp2_depth(r.t_surface); }

float fog_model_march_homogeneous(fog_ray r) {
  return fog_model_optical_depth_march(r.dir, r.t_surface, fog_march_steps, r.jitter);
}
float fog_model_march_height(fog_ray r) { return fog_model_march_homogeneous(r); }
float fog_model_march_rbf(fog_ray r) { return fog_model_march_homogeneous(r); }
float fog_model_march_quadric(fog_ray r) { return fog_model_march_homogeneous(r); }
float fog_model_march_linear(fog_ray r) {  // opaque from end on, however it is marched
  return r.t_surface >= fog_model_end ? 1e30 : fog_model_march_homogeneous(r);
}
float fog_model_march_exp2(fog_ray r) { return fog_model_march_homogeneous(r); }
float fog_model_depth_perlin(fog_ray r) { return fog_perlin_optical_depth(r.dir, r.t_surface); }
float fog_model_march_perlin(fog_ray r) { return fog_model_march_homogeneous(r); }
float fog_model_march_volume(fog_ray r) {
  return fog_grid3d_optical_depth_march(r.dir, r.t_surface);
}
