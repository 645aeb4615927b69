// The exact optical depth of the 2.5D fogmap model along a view ray: the GLSL twin of
// render/fog_integral_cpu.c. Same function names, same steps, same equation references;
// read the two side by side (render/fog_field.h has the model, the knots and the
// exactness argument). Differences: float instead of double; every quantity that could
// be large (fog placement, profile heights) arrives camera-relative from the CPU, where
// it was subtracted in double; coefficient grids are R32F textures; a uniform-step ray
// marcher (fog_optical_depth_march) sits beside the exact walk for the benchmark.
//
// Included (render/gl_util.h #include) by fog_pass_fs.glsl, which defines
//   FOG_FETCH_HARDWARE  0: texelFetch and the cell weights (exact); 1: hardware GL_LINEAR
//                       filtering (degree 1: one bilinear fetch; degree 2: the two-fetch-
//                       per-axis trick, 4 fetches; degree 0: texelFetch) - weights are
//                       quantised by the hardware (often to 1/256).
// and provides the uniforms below (set by render/fog_pass.c).
//
// Loops: llvmpipe (Mesa's CPU GL) caps the loop iterations of one shader invocation
// (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS = 65535; our reading of the measurements below:
// the cap looks shared by all loops of the invocation) and silently leaves the loop. A long ray crosses hundreds of knot cells, so everything inside
// the walk is written without data-dependent loops (per-degree formulas, constant-bound
// loops the compiler unrolls); the walk's own loop is the only long one. (Measured: the
// quadratic basis with exponential fog over 256 x 256 cells lost up to 0.17 in tau when
// the inner loops were loops.) The C twin keeps the loops.
//
// Speed on llvmpipe (docs/integral.md, Performance): llvmpipe runs 8 pixels per SIMD lane
// group and executes BOTH sides of every branch under a mask (only loops exit when no lane
// is left), so the per-piece code is written to be the same for every piece: the draw's
// settings are compile-time constants (FOG_DEGREE, FOG_PROFILE_KIND, ..., set per variant by
// render/fog_pass.c), the manual fetch reads one cell polynomial per piece (render/
// fog_cell_poly.h: one RGBA32F texel for degrees 0 and 1), and the exponential profile
// integrates every piece with one formula. What this makes the GLSL walk do differently
// from the C twin (same pieces' integrals, exact either way):
//   - f inside a cell is evaluated from the cell's monomial coefficients A_kl (computed in
//     double on the CPU, rounded once to float), not from the B-spline weights, and on a
//     piece it is expanded into monomials of the piece's parameter (fog_piece_monomials)
//     that every profile integrates in closed form (the B-spline profile above degree 1
//     keeps Gauss-Legendre);
//   - the exponential profile's breaks are y0 + k H/2 (not y0 alone), so |b| <= 1/4 and the
//     moments come from an 8-term series only (fog_exp_moments_walk), no closed form, and
//     the pieces below y0 use the same formula with c0 = b = 0 (no Gauss path);
//   - a pixel stops once its optical depth passes fog_depth_limit (early termination:
//     -ln of the transmittance cut-off, 9.2 for the product's 1e-4; the C twin has none);
//   - LOD draws read the grids as layers of one array texture (no sampler-array index),
//     and clip the ray to the box once per pixel (fog_optical_depth_inside per grid);
//     approximation switching sets its first walk up in double and starts each next one
//     where the last ended, in float (fog_walk_coarser), not one double set-up per segment.

// FOG_PROFILE_*, FOG_MAX_GRIDS, FOG_PROFILE_MAX_COEFFICIENTS: the C headers' values
// (render/fog_shader_text.c generates fog_constants.glsl from them).
#include "fog_constants.glsl"
#define FOG_INFINITY 1e30

// Grid slot k: texture fog_grids[k]; x(t) = fog_grid_x0[k].x + t dir.x fog_grid_scale[k],
// z(t) = fog_grid_x0[k].y + t dir.z fog_grid_scale[k] in that grid's coefficient units
// (fog_grid_x0 computed camera-relative in double on the CPU).
uniform sampler2D fog_grids[FOG_MAX_GRIDS];
uniform dvec2 fog_grid_x0[FOG_MAX_GRIDS];  // double: see fog_optical_depth_inside
uniform double fog_grid_scale[FOG_MAX_GRIDS];
uniform ivec2 fog_grid_size[FOG_MAX_GRIDS];
// Approximation slots l = 0..J are dyadic: u_l = u_{l+1} / 2 + fog_grid_dyadic[l] in grid
// units (fog_walk_coarser), from the slots' origins and spacings (render/fog_pass.c).
uniform vec2 fog_grid_dyadic[FOG_MAX_GRIDS];
// Specialisation (render/fog_pass.c compiles one variant per draw configuration): llvmpipe
// runs both sides of every branch under a mask, so a uniform degree or profile kind costs
// the code of every case; as compile-time constants the dead cases vanish. FOG_SINGLE_GRID:
// the draw reads slot 0 only (no LOD), so no dynamic index into the sampler array.
const int fog_degree = FOG_DEGREE;
#ifndef FOG_SINGLE_GRID
#define FOG_SINGLE_GRID 0
#endif
#if FOG_SINGLE_GRID
#define FOG_GRID(g) 0
#define FOG_FILTERED(g, uv) texture(fog_grids[0], (uv) / vec2(fog_grid_size[0])).r
#else
// LOD draws: the slots' grids as layers of one 2D array texture (render/fog_pass.c copies
// them in, zero beyond each grid's size), so the layer is an ordinary per-pixel coordinate.
// Indexing the sampler array with a non-constant slot made llvmpipe 2.5x slower.
uniform sampler2DArray fog_grid_layers;
uniform vec2 fog_grid_layer_size;
#define FOG_GRID(g) (g)
#define FOG_FILTERED(g, uv) texture(fog_grid_layers, vec3((uv) / fog_grid_layer_size, float(g))).r
#endif
// Manual fetch reads the grids as cell polynomials (render/fog_cell_poly.h: one RGBA32F
// texel per knot cell for degrees 0 and 1, three for degree 2): one fetch per cell crossed
// instead of (d+1)^2 coefficients, and no cell weights.
#if FOG_SINGLE_GRID
uniform sampler2D fog_cells;
#define FOG_CELL_TEXEL(g, ij) texelFetch(fog_cells, ij, 0)
#else
uniform sampler2DArray fog_cell_layers;
#define FOG_CELL_TEXEL(g, ij) texelFetch(fog_cell_layers, ivec3(ij, g), 0)
#endif
// Empty-space skipping (FOG_SKIP 1; render/fog_occupancy.h): per block of
// FOG_OCCUPANCY_BLOCK^2 knot cells a bound of |f|; the walk jumps over blocks whose bound is
// <= fog_skip_below (0: exact zeros only, the same sum bit for bit).
#ifndef FOG_SKIP
#define FOG_SKIP 0
#endif
uniform float fog_skip_below;
#if FOG_SINGLE_GRID
uniform sampler2D fog_occupancy;
#define FOG_OCCUPANCY_TEXEL(g, b) texelFetch(fog_occupancy, b, 0).r
#else
uniform sampler2DArray fog_occupancy_layers;
#define FOG_OCCUPANCY_TEXEL(g, b) texelFetch(fog_occupancy_layers, ivec3(b, g), 0).r
#endif
uniform ivec2 fog_occupancy_size[FOG_MAX_GRIDS];  // blocks per slot
// Early termination (fog_pass_params.transmittance_cutoff): the exact walks stop once the
// optical depth exceeds this, -ln(cutoff) (1e30: whole rays).
uniform float fog_depth_limit;
uniform dvec3 fog_box_min;  // camera-relative box (double: see fog_optical_depth_inside)
uniform dvec3 fog_box_max;
uniform float fog_extinction_scale;
// Profile, camera-relative heights.
const int fog_profile_kind = FOG_PROFILE_KIND;
uniform float fog_profile_y0;           // exponential: y0 - camera y
uniform float fog_profile_scale_height; // exponential: H
uniform float fog_profile_inv_scale_height; // 1 / H
uniform int fog_profile_count;
const int fog_profile_degree = FOG_PROFILE_DEGREE;
uniform float fog_profile_y_start;      // B-spline: (camera y - origin) / spacing
// The same two in double, for the walk's set-up (fog_walk_start): a camera high above the
// fog has large camera-relative heights, whose float difference lost the profile
// (100 km up: 3.6e-3 in tau).
uniform double fog_profile_y0_d, fog_profile_y_start_d, fog_profile_inv_spacing_d;
uniform float fog_profile_inv_spacing;  // B-spline: 1 / spacing
uniform float fog_profile_coefficients[FOG_PROFILE_MAX_COEFFICIENTS];

const float fog_gauss_nodes[10] = float[10](
    0.0,                                                  // m = 1 at [0]
    -0.57735026918962576, 0.57735026918962576,            // m = 2 at [1]
    -0.77459666924148338, 0.0, 0.77459666924148338,       // m = 3 at [3]
    -0.86113631159405258, -0.33998104358485626, 0.33998104358485626, 0.86113631159405258);
const float fog_gauss_weights[10] = float[10](
    2.0,
    1.0, 1.0,
    0.55555555555555556, 0.88888888888888889, 0.55555555555555556,
    0.34785484513745386, 0.65214515486254614, 0.65214515486254614, 0.34785484513745386);
// Slab test against the camera-relative box (Kay & Kajiya); dir components may be 0.
// Double (fog_optical_depth_inside), with one division per axis: GPUs without full-rate
// double run a division as a dozen operations. Branch-free: an axis the ray runs parallel
// to gives (-inf, inf) inside its slab and (inf, -inf), a miss, outside it, selected rather
// than branched on (a loop with an early return cost llvmpipe ~1 ms of a frame).
bool fog_box_entry_exit(dvec3 dir, out double t_enter, out double t_exit) {
  dvec3 inv = 1.0 / dir, ta = fog_box_min * inv, tb = fog_box_max * inv;
  bvec3 parallel = equal(dir, dvec3(0.0));
  bvec3 inside = bvec3(uvec3(lessThanEqual(fog_box_min, dvec3(0.0))) &
                       uvec3(greaterThanEqual(fog_box_max, dvec3(0.0))));
  dvec3 reach = mix(dvec3(-FOG_INFINITY), dvec3(FOG_INFINITY), inside);
  dvec3 lo = mix(min(ta, tb), -reach, parallel), hi = mix(max(ta, tb), reach, parallel);
  t_enter = max(max(lo.x, lo.y), lo.z);
  t_exit = min(min(hi.x, hi.y), hi.z);
  return t_enter <= t_exit;
}

// The d+1 non-zero centred B-spline values at local coordinate s in [0, 1] of a knot cell;
// w[k] belongs to coefficient c - d/2 + k.
vec4 fog_cell_weights(int degree, float s) {
  float r = 1.0 - s;
  if (degree == 0) return vec4(1.0, 0.0, 0.0, 0.0);
  if (degree == 1) return vec4(r, s, 0.0, 0.0);
  if (degree == 2) return vec4(0.5 * r * r, 0.5 + s * r, 0.5 * s * s, 0.0);
  return vec4(r * r * r, 3.0 * s * s * s - 6.0 * s * s + 4.0,
              3.0 * r * r * r - 6.0 * r * r + 4.0, s * s * s) / 6.0;
}

// Cell c is [c + offset, c + 1 + offset]: half-integer knots for even degree.
float fog_knot_offset(int degree) { return (degree % 2 == 0) ? -0.5 : 0.0; }

// The polynomial of knot cell (cx, cz) of grid `grid`, whose coefficient grid is `size`
// (render/fog_cell_poly.h): column l = (A_0l, A_1l, A_2l), f = sum A_kl sx^k sz^l at local
// coordinates (sx, sz) in [0, 1]^2. Entries beyond the degree are constant zeros (folded
// away). Only cells inside the grid are ever asked for: every walk and every sample is
// clipped to the fog's box, which the grid's cells cover with half a cell to spare (its
// ghost ring, docs/transform.md), so the clamp only keeps texelFetch defined where float
// rounding lands on the box's edge. (A test for cells outside, with zero there, made the
// exact linear pass 10 % slower on llvmpipe: it masked the fetch.)
mat3 fog_cell_load(int grid, ivec2 size, int cx, int cz) {
  int d = fog_degree;
  ivec2 cells = size + d;
  ivec2 tc = clamp(ivec2(cx, cz) + (d - d / 2), ivec2(0), cells - 1);
  if (d == 0) return mat3(vec3(FOG_CELL_TEXEL(grid, tc).x, 0.0, 0.0), vec3(0.0), vec3(0.0));
  if (d == 1) {
    vec4 a = FOG_CELL_TEXEL(grid, tc);
    return mat3(vec3(a.xy, 0.0), vec3(a.zw, 0.0), vec3(0.0));
  }
  ivec2 t0 = ivec2(3 * tc.x, tc.y);
  return mat3(FOG_CELL_TEXEL(grid, t0).xyz, FOG_CELL_TEXEL(grid, t0 + ivec2(1, 0)).xyz,
              FOG_CELL_TEXEL(grid, t0 + ivec2(2, 0)).xyz);
}

// f = sum_{k,l} A_kl sx^k sz^l, Horner in both coordinates, written per degree.
float fog_cell_eval(mat3 a, float sx, float sz) {
  int d = fog_degree;
  if (d == 0) return a[0].x;
  if (d == 1) return a[0].x + a[0].y * sx + sz * (a[1].x + a[1].y * sx);
  return a[0].x + sx * (a[0].y + sx * a[0].z) +
         sz * (a[1].x + sx * (a[1].y + sx * a[1].z) + sz * (a[2].x + sx * (a[2].y + sx * a[2].z)));
}

// f at grid coordinates (x, z) in knot cell (cx, cz): docs/integral.md, Knots: the basis,
// f = sum c_ij phi_d(x - i) phi_d(z - j) with the cell's (d+1)^2 coefficients.
float fog_grid_value(int grid, int cx, int cz, float x, float z) {
  int d = fog_degree;
  float off = fog_knot_offset(d);
  vec4 wx = fog_cell_weights(d, x - (float(cx) + off));
  vec4 wz = fog_cell_weights(d, z - (float(cz) + off));
  int i0 = cx - d / 2, j0 = cz - d / 2;
#if FOG_FETCH_HARDWARE
  // Hardware bilinear filtering (border colour 0 = coefficients outside the grid).
  // Coefficient i is texel i, at texture coordinate (i + 0.5) / width.
  if (d == 1)
    return FOG_FILTERED(grid, vec2(float(i0) + wx.y, float(j0) + wz.y) + 0.5);
  if (d == 2) {
    // Two linear fetches per axis: w0 c0 + w1 c1 + w2 c2 =
    // (w0 + w1/2) lerp(c0, c1, (w1/2)/(w0 + w1/2)) + (w1/2 + w2) lerp(c1, c2, w2/(w1/2 + w2)).
    vec2 gx = vec2(wx.x + 0.5 * wx.y, 0.5 * wx.y + wx.z);
    vec2 gz = vec2(wz.x + 0.5 * wz.y, 0.5 * wz.y + wz.z);
    vec2 px = vec2(float(i0) + 0.5 * wx.y / gx.x, float(i0 + 1) + wx.z / gx.y) + 0.5;
    vec2 pz = vec2(float(j0) + 0.5 * wz.y / gz.x, float(j0 + 1) + wz.z / gz.y) + 0.5;
    return gz.x * (gx.x * FOG_FILTERED(grid, vec2(px.x, pz.x)) +
                   gx.y * FOG_FILTERED(grid, vec2(px.y, pz.x))) +
           gz.y * (gx.x * FOG_FILTERED(grid, vec2(px.x, pz.y)) +
                   gx.y * FOG_FILTERED(grid, vec2(px.y, pz.y)));
  }
#endif
  return fog_cell_eval(fog_cell_load(grid, fog_grid_size[FOG_GRID(grid)], cx, cz),
                       x - (float(cx) + off), z - (float(cz) + off));
}

float fog_profile_coefficient(int i) {
  return (i >= 0 && i < fog_profile_count) ? fog_profile_coefficients[i] : 0.0;
}

// The d + 1 profile coefficients of knot cell cy (zero beyond the profile): fetched once
// per piece by the walk (a uniform array read with a per-pixel index is a gather here).
vec4 fog_profile_cell(int cy) {
  int i = cy - fog_profile_degree / 2;
  return vec4(fog_profile_coefficient(i), fog_profile_coefficient(i + 1),
              fog_profile_coefficient(i + 2), fog_profile_coefficient(i + 3));
}

// g at profile coordinate y in knot cell cy, from that cell's coefficients.
float fog_profile_cell_value(vec4 coefficients, int cy, float y) {
  int d = fog_profile_degree;
  return dot(fog_cell_weights(d, y - (float(cy) + fog_knot_offset(d))), coefficients);  // zero beyond d
}

// g of a B-spline profile at profile coordinate y in knot cell cy.
float fog_profile_bspline_value(int cy, float y) {
  return fog_profile_cell_value(fog_profile_cell(cy), cy, y);
}

// ---- exponential moments J_k = int_{-1}^{1} s^k e^{c0 + b s} ds, k = 0..4 ----------------

// The walk's moments (fog_piece_integral, |b| <= 1/4): the series to j = 7, as Horner
// polynomials in u = b^2 (J_k = e^{c0} sum_j b^j/j! int s^{k+j} ds; even k: 2 u^m /
// ((2m)! (2m+k+1)), odd k: 2 b u^m / ((2m+1)! (2m+k+2))); the next term is below
// 0.25^8/8! ~ 4e-10 of e^{c0}. Unused moments (k > 2d) fold away. GLSL only: the C twin
// keeps fog_exp_moments (closed form by parts, or the series below |b| = 1), which the
// walk's breaks every H/2 make unnecessary here.
void fog_exp_moments_walk(float c0, float b, out float m[5]) {
  float e2 = 2.0 * exp(c0), u = b * b;
  m[0] = e2 * (1.0 + u * (1.0 / 6.0 + u * (1.0 / 120.0 + u * (1.0 / 5040.0))));
  m[1] = e2 * b * (1.0 / 3.0 + u * (1.0 / 30.0 + u * (1.0 / 840.0 + u * (1.0 / 45360.0))));
  m[2] = e2 * (1.0 / 3.0 + u * (1.0 / 10.0 + u * (1.0 / 168.0 + u * (1.0 / 6480.0))));
  m[3] = e2 * b * (1.0 / 5.0 + u * (1.0 / 42.0 + u * (1.0 / 1080.0 + u * (1.0 / 55440.0))));
  m[4] = e2 * (1.0 / 5.0 + u * (1.0 / 14.0 + u * (1.0 / 216.0 + u * (1.0 / 7920.0))));
}

// Monomial coefficients of a polynomial of degree n (0, 2, 4) on [-1, 1] from its values at
// n+1 equispaced points (inverse Vandermonde, exact rationals).
void fog_monomials_from_samples(int n, float y[5], out float c[5]) {
  c = float[5](y[0], 0.0, 0.0, 0.0, 0.0);
  if (n == 2) {
    c[0] = y[1];
    c[1] = 0.5 * (y[2] - y[0]);
    c[2] = 0.5 * (y[2] + y[0]) - y[1];
  } else if (n == 4) {
    c[0] = y[2];
    c[1] = (y[0] - 8.0 * y[1] + 8.0 * y[3] - y[4]) * (1.0 / 6.0);
    c[2] = (-y[0] + 16.0 * y[1] - 30.0 * y[2] + 16.0 * y[3] - y[4]) * (1.0 / 6.0);
    c[3] = (-2.0 * y[0] + 4.0 * y[1] - 4.0 * y[3] + 2.0 * y[4]) * (1.0 / 3.0);
    c[4] = (2.0 * y[0] - 8.0 * y[1] + 12.0 * y[2] - 8.0 * y[3] + 2.0 * y[4]) * (1.0 / 3.0);
  }
}

// ---- the walk ---------------------------------------------------------------------------

// One axis of the 2D DDA (Amanatides & Woo 1987) over knot lines: x(t) = x0 + t dx, knot
// cell `cell`. The next crossing is computed from the knot position, not accumulated:
// t = (cell + next_edge) inv_dx, next_edge = (dx > 0 ? 1 + offset : offset) - x0, set once
// per ray so a step costs a convert, an add and a multiply. An axis the ray runs parallel
// to gets inv_dx = 1 and next_edge = FOG_INFINITY: it never crosses.
struct fog_axis {
  float x0, dx, offset;  // x(t) = x0 + t dx; knot cell c is [c + offset, c + 1 + offset]
  float next_edge, inv_dx;
  int cell, step;
};

// The same with 1/dx given (the walk's later segments, fog_walk_coarser: no division).
fog_axis fog_axis_start_inv(float x0, float dx, float inv_dx, float offset) {
  bool moving = dx != 0.0;
  float edge = (dx > 0.0 ? 1.0 + offset : offset) - x0;
  return fog_axis(x0, dx, offset, moving ? edge : FOG_INFINITY, moving ? inv_dx : 1.0,
                  int(floor(x0 - offset)), dx > 0.0 ? 1 : -1);
}

fog_axis fog_axis_start(float x0, float dx, float offset) {
  return fog_axis_start_inv(x0, dx, dx != 0.0 ? 1.0 / dx : 1.0, offset);
}

float fog_axis_next(fog_axis a) { return (float(a.cell) + a.next_edge) * a.inv_dx; }

// The exponential profile's breaks y0 + k H/2 (k: the y axis's cell): none below y0, where
// g = 1 (cell -1 stands for all of it), and none past FOG_EXP_TOP half-heights above it,
// where e^{-(y - y0)/H} < e^{-105} is below float's least (cell FOG_EXP_TOP stands for all
// of that, and integrates to 0). A ray crossing many scale heights (H = 0.001 in a box 100
// high: 2e5 breaks) ran past the walk's 65536 steps, and its fog vanished. The C twin
// breaks at y0 alone.
const int FOG_EXP_TOP = 210;
void fog_profile_clamp(inout fog_axis y) {
  if (fog_profile_kind == FOG_PROFILE_EXPONENTIAL) y.cell = clamp(y.cell, -1, FOG_EXP_TOP);
}
float fog_profile_next(fog_axis y) {
  if (fog_profile_kind == FOG_PROFILE_SLAB) return FOG_INFINITY;
  if (fog_profile_kind == FOG_PROFILE_EXPONENTIAL &&
      ((y.cell <= -1 && y.step < 0) || (y.cell >= FOG_EXP_TOP && y.step > 0)))
    return FOG_INFINITY;
  return fog_axis_next(y);
}

struct fog_ray_walk {
  int grid;
  ivec2 size;        // fog_grid_size[grid]
  fog_axis x, z, y;  // y: B-spline profile knots, or the exponential profile's breaks
  float y_entry;     // exponential profile: the height above y0 where the walk starts (t' =
                     // 0: the box entry), from the double set-up; unused by the others
  float dir_y;
};

// f at parameter t of the current piece: the cell's polynomial (manual fetch: `cell`, loaded
// once per piece) or fog_grid_value (hardware filtering fetches per point).
float fog_walk_value(fog_ray_walk w, mat3 cell, float t) {
  float x = w.x.x0 + t * w.x.dx, z = w.z.x0 + t * w.z.dx;
#if FOG_FETCH_HARDWARE
  return fog_grid_value(w.grid, w.x.cell, w.z.cell, x, z);
#else
  return fog_cell_eval(cell, x - (float(w.x.cell) + w.x.offset), z - (float(w.z.cell) + w.z.offset));
#endif
}

// The monomial coefficients c_0..c_2d of f(mid + half s), s in [-1, 1], on the current piece.
// With the cell polynomial (manual fetch): directly, from the cell's A_kl and the local
// coordinates at the piece's middle, sx = sxm + hx s and sz = szm + hz s in
// f = sum A_kl sx^k sz^l; with hardware filtering, from f at 2d + 1 equispaced points.
void fog_piece_monomials(fog_ray_walk w, mat3 cell, float mid, float half_len, out float c[5]) {
  int d = fog_degree, n = 2 * d;
#if !FOG_FETCH_HARDWARE
  float sxm = w.x.x0 + mid * w.x.dx - (float(w.x.cell) + w.x.offset), hx = half_len * w.x.dx;
  float szm = w.z.x0 + mid * w.z.dx - (float(w.z.cell) + w.z.offset), hz = half_len * w.z.dx;
  if (d <= 1) {
    c = float[5](cell[0].x + cell[0].y * sxm + szm * (cell[1].x + cell[1].y * sxm),
                 cell[0].y * hx + cell[1].x * hz + cell[1].y * (sxm * hz + hx * szm),
                 cell[1].y * hx * hz, 0.0, 0.0);
    return;
  }
  // Degree 2: p_l(s) = A_0l + A_1l sx + A_2l sx^2 (column l of the cell), a quadratic in s;
  // r = p_1 + sz p_2 (cubic), f = p_0 + sz r (quartic). ~45 operations against five
  // evaluations of f and the inverse Vandermonde (~120).
  vec3 p[3];
  for (int l = 0; l < 3; l++)  // constant bound: unrolled
    p[l] = vec3(cell[l].x + sxm * (cell[l].y + sxm * cell[l].z),
                hx * (cell[l].y + 2.0 * sxm * cell[l].z), hx * hx * cell[l].z);
  vec4 r = vec4(p[1] + szm * p[2], 0.0) + hz * vec4(0.0, p[2]);
  c = float[5](p[0].x + szm * r.x, p[0].y + szm * r.y + hz * r.x, p[0].z + szm * r.z + hz * r.y,
               szm * r.w + hz * r.z, hz * r.w);
  return;
#endif
  float samples[5];
  for (int i = 0; i < 5; i++) {  // constant bound and n: unrolled, i > n folded away
    float s = (n > 0) ? -1.0 + 2.0 * float(i) / float(n) : 0.0, t = mid + half_len * s;
    samples[i] = (i <= n) ? fog_walk_value(w, cell, t) : 0.0;
  }
  fog_monomials_from_samples(n, samples, c);
}

// Integral of f g over one piece [ta, tb] inside one knot cell of every axis.
float fog_piece_integral(fog_ray_walk w, float ta, float tb) {
  float half_len = 0.5 * (tb - ta), mid = 0.5 * (ta + tb);
  int d = fog_degree;
#if FOG_FETCH_HARDWARE
  mat3 cell = mat3(0.0);
#else
  mat3 cell = fog_cell_load(w.grid, w.size, w.x.cell, w.z.cell);
#endif
  if (fog_profile_kind == FOG_PROFILE_EXPONENTIAL) {
    // f(t) e^{-(y(t) - y0)/H} above y0, f(t) below: f is a polynomial of degree n = 2d in
    // s = (t - mid)/half, int = half * sum_k c_k J_k(c0, b), c0 = -(y(mid) - y0)/H,
    // b = -dir_y half/H; below y0 c0 = b = 0 (J_k = int s^k ds), so both kinds of piece take
    // the same code (no masked second path). |b| <= 1/4 by the walk's breaks every H/2, so
    // the short series alone is exact (fog_exp_moments_walk).
    bool above = w.y_entry + mid * w.dir_y > 0.0;
    float c0 = above ? -(w.y_entry + mid * w.dir_y) * fog_profile_inv_scale_height
                     : 0.0;
    float b = above ? -w.dir_y * half_len * fog_profile_inv_scale_height : 0.0;
    // Past FOG_EXP_TOP the piece is long (|b| unbounded) and e^{c0} below float's least:
    // its moments are e^{-200} x 0 = 0 (selects, not an early return: llvmpipe runs the
    // rest of the walk's body under a mask after one, 30 % slower).
    bool capped = w.y.cell >= FOG_EXP_TOP;
    c0 = capped ? -200.0 : c0;
    b = capped ? 0.0 : b;
    float c[5], moments[5];
    fog_piece_monomials(w, cell, mid, half_len, c);
    fog_exp_moments_walk(c0, b, moments);
    // c[k] = 0 beyond n, so all five terms can be summed.
    float sum = c[0] * moments[0] + c[1] * moments[1] + c[2] * moments[2] +
                c[3] * moments[3] + c[4] * moments[4];
    return half_len * sum;
  }
#if !FOG_FETCH_HARDWARE
  if (fog_profile_kind == FOG_PROFILE_SLAB) {
    // int_{-1}^{1} sum c_k s^k ds = 2 c0 + 2 c2 / 3 + 2 c4 / 5 (c4 = 0 below degree 2).
    float c[5];
    fog_piece_monomials(w, cell, mid, half_len, c);
    return half_len * (2.0 * c[0] + (2.0 / 3.0) * c[2] + (2.0 / 5.0) * c[4]);
  }
  if (fog_profile_kind == FOG_PROFILE_BSPLINE && fog_profile_degree <= 1) {
    // g is linear in s on the piece (a box or hat profile, as `fogpipe import` fits):
    // g = g0 + g1 s from the profile cell's coefficients, and
    // int_{-1}^{1} (sum c_k s^k)(g0 + g1 s) ds
    //   = 2 c0 g0 + 2 (c2 g0 + c1 g1) / 3 + 2 (c4 g0 + c3 g1) / 5.
    float c[5];
    fog_piece_monomials(w, cell, mid, half_len, c);
    vec4 profile = fog_profile_cell(w.y.cell);
    float um = w.y.x0 + mid * w.y.dx - (float(w.y.cell) + fog_knot_offset(fog_profile_degree));
    float slope = (fog_profile_degree == 1) ? profile.y - profile.x : 0.0;
    float g0 = profile.x + slope * um, g1 = slope * half_len * w.y.dx;
    return half_len * (2.0 * c[0] * g0 + (2.0 / 3.0) * (c[2] * g0 + c[1] * g1) +
                       (2.0 / 5.0) * (c[4] * g0 + c[3] * g1));
  }
#endif
  // Polynomial piece: degree 2d + p in t, exact with m = d + p/2 + 1 Gauss nodes.
  int pd = (fog_profile_kind == FOG_PROFILE_BSPLINE) ? fog_profile_degree : 0;
  int m = (2 * d + pd) / 2 + 1;
  int first = (m * (m - 1)) / 2;  // offset of the m-point rule in the packed tables
  float sum = 0.0;
  vec4 profile = (fog_profile_kind == FOG_PROFILE_BSPLINE) ? fog_profile_cell(w.y.cell)
                                                          : vec4(0.0);
  for (int i = 0; i < 4; i++) {  // constant bound: unrolled (loop budget, see the top)
    if (i >= m) break;
    float t = mid + half_len * fog_gauss_nodes[first + i];
    float f = fog_walk_value(w, cell, t);
    float gy = (fog_profile_kind == FOG_PROFILE_BSPLINE)
                   ? fog_profile_cell_value(profile, w.y.cell, w.y.x0 + t * w.y.dx)
                   : 1.0;
    sum += fog_gauss_weights[first + i] * f * gy;
  }
  return half_len * sum;
}

// ---- empty-space skipping (the C twin's fog_axis_sync, fog_axis_block_exit) ------------

// The cell the DDA would be in after walking to t: every crossing at or before t stepped.
// From the position's floor, then corrected (at most one cell each way, unrolled) with the
// crossings themselves, so a jump lands where the steps would have.
void fog_axis_sync(inout fog_axis a, float t) {
  if (a.dx == 0.0) return;
  a.cell = int(floor(a.x0 + t * a.dx - a.offset));
  if (fog_axis_next(a) <= t) a.cell += a.step;
  fog_axis previous = a;
  previous.cell -= a.step;
  if (fog_axis_next(previous) > t) a.cell = previous.cell;
}

// The texel column of the axis's knot cell (fog_cell_poly.h) and where the axis leaves the
// occupancy block holding it (the crossing of the block's last cell in its direction).
float fog_axis_block_exit(fog_axis a, int shift) {
  int tx = a.cell + shift;
  int first = (tx >= 0 ? tx / FOG_OCCUPANCY_BLOCK : -((FOG_OCCUPANCY_BLOCK - 1 - tx) / FOG_OCCUPANCY_BLOCK)) * FOG_OCCUPANCY_BLOCK;
  fog_axis last = a;
  last.cell = (a.step > 0 ? first + FOG_OCCUPANCY_BLOCK - 1 : first) - shift;
  return fog_axis_next(last);  // FOG_INFINITY for an axis the ray runs parallel to
}

// The walk over [t, t_end] (t_end a knot crossing or t1, so no piece is cut short): walk
// the knot cells of x, z (2D DDA) and the profile's breaks, one exact piece at a time;
// every axis whose break ends the piece steps (as in the C twin). Leaves early once the sum
// exceeds `limit` (the optical depth cut-off, fog_optical_depth_inside).
void fog_walk_cells(inout fog_ray_walk w, inout float t, float t_end, float t1,
                    inout float sum, float limit) {
  for (int guard = 0; t < t_end && sum < limit && guard < 65536; guard++) {
    float tx = fog_axis_next(w.x), tz = fog_axis_next(w.z);
    float ty = fog_profile_next(w.y);
    float t_next = min(min(t1, tx), min(tz, ty));
    if (t_next > t) sum += fog_piece_integral(w, t, t_next);
    if (tx <= t_next) w.x.cell += w.x.step;
    if (tz <= t_next) w.z.cell += w.z.step;
    if (ty <= t_next) w.y.cell += w.y.step;
    t = max(t, t_next);
  }
}

// int_{t0}^{t1} f g dt for [t0, t1] inside the box. With FOG_SKIP the ray is walked block
// by block of the occupancy map: an empty block (bound <= fog_skip_below) is jumped in one
// step, every axis synced to where the ray leaves it; any other block is walked cell by
// cell up to that exit, which is a knot crossing, so the pieces and their sum are those of
// the plain walk (bit for bit with threshold 0). Two loops, not a test inside the cell
// loop: llvmpipe runs every branch's code under a mask, so a per-cell test cost every
// piece its price (2.1x on fog without empty blocks); per block it is paid once per
// FOG_OCCUPANCY_BLOCK cells.
float fog_walk_integral(inout fog_ray_walk w, float t0, float t1, float limit) {
  float sum = 0.0, t = t0;
#if FOG_SKIP
  const int shift = fog_degree - fog_degree / 2;
  // Every crossing at the start stepped first (a walk starting on a block's edge, moving
  // back across it, has its block exit at t: the block test below never held, and the
  // whole ray was walked cell by cell). Only zero-length pieces go: the sum is unchanged.
  fog_axis_sync(w.x, t);
  fog_axis_sync(w.z, t);
  if (fog_profile_kind != FOG_PROFILE_SLAB) fog_axis_sync(w.y, t), fog_profile_clamp(w.y);
  for (int guard = 0; t < t1 && sum < limit && guard < 65536; guard++) {
    // the block index clamped into the map (cells beyond it are zero)
    ivec2 block = clamp((ivec2(w.x.cell, w.z.cell) + shift) / FOG_OCCUPANCY_BLOCK, ivec2(0),
                        fog_occupancy_size[FOG_GRID(w.grid)] - 1);
    float tb = min(t1, min(fog_axis_block_exit(w.x, shift), fog_axis_block_exit(w.z, shift)));
    bool empty = FOG_OCCUPANCY_TEXEL(w.grid, block) <= fog_skip_below && tb > t;
    if (empty) {
      t = tb;
      fog_axis_sync(w.x, t);
      fog_axis_sync(w.z, t);
      if (fog_profile_kind != FOG_PROFILE_SLAB) fog_axis_sync(w.y, t), fog_profile_clamp(w.y);
    } else {
      fog_walk_cells(w, t, tb > t ? tb : t1, t1, sum, limit);
    }
  }
#else
  fog_walk_cells(w, t, t1, t1, sum, limit);
#endif
  return sum;
}

// The exact optical depth int_{t0}^{t1} K dt along the unit direction dir from the camera,
// through grid slot `grid`, for [t0, t1] already clipped to the fog's box and not empty
// (the C twin's fog_optical_depth after its box clip; the pass clips once per pixel, in
// fog_optical_depth_lod). Pixels whose optical depth exceeds `limit` (tau < e^-limit) stop
// early with a partial sum.
// The set-up is double, the walk float: the walk runs in t' = t - t0 from the box entry,
// in grid coordinates that stay within the grid, so its numbers are small; what is large
// is the way there. A camera 50 km away sees the fog along a float direction rounded by
// 6e-8 (3 mm sideways there), from grid coordinates of 2e4 cells (float keeps 2e-3 of a
// cell): the pixel's direction, the box entry and the entry's grid coordinates are
// therefore computed in double (a few operations per walk) and rounded once, small.
// test_gpu_far_camera at 50 km: max |dtau| 2.3e-4 with a float set-up, 2.8e-6 with this.
fog_ray_walk fog_walk_start(int grid, dvec3 dir, double t0) {
  float off = fog_knot_offset(fog_degree);
  fog_ray_walk w;
  w.grid = grid;
  w.size = fog_grid_size[FOG_GRID(grid)];
  double dxd = dir.x * fog_grid_scale[FOG_GRID(grid)], dzd = dir.z * fog_grid_scale[FOG_GRID(grid)];
  float dx = float(dxd), dz = float(dzd);
  w.x = fog_axis_start(float(fog_grid_x0[FOG_GRID(grid)].x + t0 * dxd), dx, off);
  w.z = fog_axis_start(float(fog_grid_x0[FOG_GRID(grid)].y + t0 * dzd), dz, off);
  w.y_entry = float(t0 * dir.y - fog_profile_y0_d);
  float dir_y = float(dir.y);
  if (fog_profile_kind == FOG_PROFILE_EXPONENTIAL)
    // Breaks at y0 + k H/2: y0 (where g changes form) and, above it, pieces whose
    // exponent spans at most 1/2, |b| <= 1/4, where the moments' series (8 terms) is exact
    // in float (fog_piece_integral); the closed form is not needed.
    w.y = fog_axis_start(w.y_entry * 2.0 * fog_profile_inv_scale_height,
                         dir_y * 2.0 * fog_profile_inv_scale_height, 0.0);
  else
    w.y = fog_axis_start(float(fog_profile_y_start_d + t0 * dir.y * fog_profile_inv_spacing_d),
                         dir_y * fog_profile_inv_spacing, fog_knot_offset(fog_profile_degree));
  fog_profile_clamp(w.y);
  w.dir_y = dir_y;
  return w;
}

// The optical depth of a walk from its start over `len` (fog_walk_integral times the
// extinction scale; it stops once past `limit`, an optical depth).
float fog_walk_depth(inout fog_ray_walk w, float len, float limit) {
  return fog_extinction_scale * fog_walk_integral(w, 0.0, len, limit / fog_extinction_scale);
}

float fog_optical_depth_inside(int grid, dvec3 dir, double t0, double t1, float limit) {
  fog_ray_walk w = fog_walk_start(grid, dir, t0);
  return fog_walk_depth(w, float(t1 - t0), limit);
}

// Approximation switching's next segment (fog_pass_fs.glsl): the walk of approximation
// slot `grid` starting where `w` (slot grid + 1, the next finer level) ends, t' = len.
// The set-up is float and cheap: the point is inside the box, in small grid coordinates,
// and the levels are dyadic (u_l = u_{l+1}/2 + c_l, dx halves exactly), so the double
// set-up of fog_walk_start is needed once per pixel, not once per segment; the profile's
// axis carries on (the same breaks on every level).
fog_ray_walk fog_walk_coarser(fog_ray_walk w, int grid, float len) {
  float off = fog_knot_offset(fog_degree);
  vec2 c = fog_grid_dyadic[FOG_GRID(grid)];
  fog_ray_walk n;
  n.grid = grid;
  n.size = fog_grid_size[FOG_GRID(grid)];
  n.x = fog_axis_start_inv((w.x.x0 + len * w.x.dx) * 0.5 + c.x, 0.5 * w.x.dx, 2.0 * w.x.inv_dx,
                           off);
  n.z = fog_axis_start_inv((w.z.x0 + len * w.z.dx) * 0.5 + c.y, 0.5 * w.z.dx, 2.0 * w.z.inv_dx,
                           off);
  n.y = fog_axis_start_inv(w.y.x0 + len * w.y.dx, w.y.dx, w.y.inv_dx, w.y.offset);
  fog_profile_clamp(n.y);
  n.y_entry = w.y_entry + len * w.dir_y;
  n.dir_y = w.dir_y;
  return n;
}

// ---- uniform ray marching (the benchmark's alternative integrator) ------------------------

// K / extinction at parameter t (inside the box): the cell from floor, then the same
// pointwise formulas.
float fog_extinction_at(int grid, vec3 dir, float t) {
  float off = fog_knot_offset(fog_degree);
  // float, as the marcher has always been: the approximation this bench compares against
  vec2 x0 = vec2(fog_grid_x0[FOG_GRID(grid)]);
  float scale = float(fog_grid_scale[FOG_GRID(grid)]);
  float x = x0.x + t * dir.x * scale, z = x0.y + t * dir.z * scale;
  float f = fog_grid_value(grid, int(floor(x - off)), int(floor(z - off)), x, z);
  float y = t * dir.y;  // camera-relative height
  if (fog_profile_kind == FOG_PROFILE_EXPONENTIAL)
    return f * ((y > fog_profile_y0) ? exp(-(y - fog_profile_y0) / fog_profile_scale_height) : 1.0);
  if (fog_profile_kind == FOG_PROFILE_BSPLINE) {
    float yp = fog_profile_y_start + t * dir.y * fog_profile_inv_spacing;
    return f * fog_profile_bspline_value(int(floor(yp - fog_knot_offset(fog_profile_degree))), yp);
  }
  return f;
}

// Midpoint rule with `steps` equal steps over [t0, t1], already clipped to the box (as the
// exact walk's, by the caller: fog_pass_fs.glsl); jitter in [0, 1) shifts the samples
// (0.5 = midpoint) to trade banding for noise.
float fog_optical_depth_march(int grid, vec3 dir, float t0, float t1, int steps,
                              float jitter) {
  if (!(t0 < t1)) return 0.0;
  float dt = (t1 - t0) / float(steps), sum = 0.0;
  for (int i = 0; i < steps; i++) sum += fog_extinction_at(grid, dir, t0 + (float(i) + jitter) * dt);
  return fog_extinction_scale * sum * dt;
}
