// Lamps in the fog (render/fog_lamp.h, docs/light.md): point and spot lights, single
// scattering, for every model; fog_pass_fs.glsl includes it after fog_light.glsl and adds
// fog_lamps_light to the in-scatter. Specialisation constants FOG_LAMPS 0|1 and
// FOG_LAMP_INTEGRAL 0|1|2 (fog_lamp_integral: ours, Fogshop's for RBFs, marching). The CPU twin
// is render/fog_lamp_cpu.c, sample for sample.
#if FOG_LAMPS || FOG_SURFACE_LAMPS
uniform int fog_lamp_count;
uniform vec3 fog_lamp_position[FOG_MAX_LAMPS];  // camera-relative (subtracted in double)
uniform vec3 fog_lamp_scatter[FOG_MAX_LAMPS];   // a I per channel
uniform vec3 fog_lamp_intensity[FOG_MAX_LAMPS]; // I per channel (the surfaces' weights)
uniform vec4 fog_lamp_axis[FOG_MAX_LAMPS];      // xyz the spot's unit axis; w 1 spot, 0 point
uniform vec3 fog_lamp_cone[FOG_MAX_LAMPS];      // cos_outer, 1/(cos_inner - cos_outer), r^2
uniform int fog_lamp_angle_pieces;
uniform int fog_lamp_span_pieces;
uniform int fog_lamp_depth_steps;
uniform int fog_lamp_shadow_steps;
// V_i: the lamp past the terrain and boxes, from the scene pass's shadow cubes
// (FOG_LAMP_SHADOWS 1), at camera-relative point x.
#if FOG_LAMP_SHADOWS
#include "lamp_shadow.glsl"
float fog_lamp_visible(int i, vec3 x) { return lamp_shadow_visible(i, x - fog_lamp_position[i]); }
#else
float fog_lamp_visible(int i, vec3 x) { return 1.0; }
#endif

// K at camera-relative point p (zero outside the fogmap's box: the march to a lamp leaves it).
float fog_lamp_model_extinction(vec3 p) {
#if FOG_MODEL_KIND == FOG_MODEL_FOGMAP
  if (any(lessThan(p, vec3(fog_box_min))) || any(greaterThan(p, vec3(fog_box_max)))) return 0.0;
  return fog_extinction_scale *
         fog_extinction_at(fog_levels, p, 1.0);
#elif FOG_MODEL_KIND == FOG_MODEL_VOLUME
  return fog_grid3d_density(fog_grid3d_camera_index + fog_grid3d_index_from_world * p);
#else
  return fog_model_extinction_at(p);
#endif
}
float fog_lamp_extinction(vec3 p) {
#if FOG_QUADRICS_BESIDE
  return fog_lamp_model_extinction(p) + fog_quadric_extinction_at(p);
#else
  return fog_lamp_model_extinction(p);
#endif
}

// The analytic models' optical depths in closed form (fog_models.glsl): from the camera
// to distance t along the ray, and from point x along unit w for length len.
#define FOG_LAMP_EXACT_DEPTH (FOG_MODEL_KIND == FOG_MODEL_HOMOGENEOUS || \
                              FOG_MODEL_KIND == FOG_MODEL_HEIGHT || FOG_MODEL_KIND == FOG_MODEL_RBF || \
                              FOG_MODEL_KIND == FOG_MODEL_QUADRIC)
float fog_lamp_model_segment_depth(vec3 x, vec3 w, float len);
float fog_lamp_segment_depth(vec3 x, vec3 w, float len) {
#if FOG_QUADRICS_BESIDE
  return fog_lamp_model_segment_depth(x, w, len) + fog_quadric_optical_depth_from(x, w, len);
#else
  return fog_lamp_model_segment_depth(x, w, len);
#endif
}
float fog_lamp_model_segment_depth(vec3 x, vec3 w, float len) {
#if FOG_MODEL_KIND == FOG_MODEL_HOMOGENEOUS
  return fog_homogeneous_optical_depth(fog_model_extinction, len);
#elif FOG_MODEL_KIND == FOG_MODEL_HEIGHT
  return fog_height_optical_depth(fog_model_extinction, fog_model_y0 - x.y,
                                  fog_model_scale_height, w.y, len);
#elif FOG_MODEL_KIND == FOG_MODEL_RBF
  return fog_rbf_optical_depth_from(fog_model_extinction, x, w, len);
#elif FOG_MODEL_KIND == FOG_MODEL_QUADRIC
  return fog_quadric_optical_depth_from(x, w, len);
#else
  return 0.0;
#endif
}

// The spot's cone at camera-relative point p (1 for a point lamp): smoothstep.
float fog_lamp_spot(int i, vec3 p) {
  if (fog_lamp_axis[i].w == 0.0) return 1.0;
  vec3 v = p - fog_lamp_position[i];
  float len = length(v);
  if (!(len > 0.0)) return 1.0;
  float u = clamp((dot(v, fog_lamp_axis[i].xyz) / len - fog_lamp_cone[i].x) * fog_lamp_cone[i].y,
                  0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

// The optical depth from camera-relative point x to lamp i: the closed form, or
// fog_lamp_shadow_steps midpoint steps (the in-scatter's T, and the surfaces').
float fog_lamp_shadow_depth(int i, vec3 x) {
  vec3 to_lamp = fog_lamp_position[i] - x;
  float dist = length(to_lamp);
  if (!(dist > 0.0)) return 0.0;
#if FOG_LAMP_EXACT_DEPTH
  return fog_lamp_segment_depth(x, to_lamp / dist, dist);
#else
  float shadow = 0.0, ds = dist / float(fog_lamp_shadow_steps);
  for (int j = 0; j < fog_lamp_shadow_steps; j++)
    shadow += fog_lamp_extinction(x + ((float(j) + 0.5) / float(fog_lamp_shadow_steps)) * to_lamp) * ds;
  return shadow;
#endif
}

// The lamps' light on a surface point p (camera-relative, unit normal n) dimmed by the fog
// between each lamp and p: the factor per channel, sum_i I_i g_i T_i / sum_i I_i g_i, g_i the
// scene pass's geometry (cos / (d^2 + r^2), the spot's cone). Exact for any number of lamps:
// the scene pass's lamp share is albedo sum_i I_i g_i / pi.
vec3 fog_lamps_surface(vec3 p, vec3 n) {
  vec3 num = vec3(0.0), den = vec3(0.0);
  for (int i = 0; i < fog_lamp_count; i++) {
    vec3 l = fog_lamp_position[i] - p;
    float d2 = dot(l, l), d = sqrt(d2);
    float g = max(dot(n, l) / max(d, 1e-6), 0.0) * fog_lamp_spot(i, p) / (d2 + fog_lamp_cone[i].z);
#if FOG_LAMP_SHADOWS
    if (g > 0.0) g *= lamp_shadow_visible_surface(i, -l, n, length(p));  // as the scene pass
#endif
    if (!(g > 0.0)) continue;
    vec3 w = fog_lamp_intensity[i] * g;
    num += w * exp(-fog_lamp_shadow_depth(i, p));
    den += w;
  }
  return vec3(den.x > 0.0 ? num.x / den.x : 1.0, den.y > 0.0 ? num.y / den.y : 1.0,
              den.z > 0.0 ? num.z / den.z : 1.0);
}
#endif

#if FOG_LAMPS
// The optical depth from the camera at the ends of fog_lamp_depth_steps equal segments of
// the span (fogmap and volume; a global: no array copied into calls).
float fog_lamp_table[FOG_LAMP_MAX_DEPTH_STEPS + 1];

const float FOG_LAMP_GX[4] = float[4](-0.86113631159405258, -0.33998104358485626,
                                      0.33998104358485626, 0.86113631159405258);
const float FOG_LAMP_GW[4] = float[4](0.34785484513745386, 0.65214515486254614,
                                      0.65214515486254614, 0.34785484513745386);

// The angle of node n of the piece [phi_a, phi_b].
float fog_lamp_node(float phi_a, float phi_b, int n) {
  return phi_a + 0.5 * (1.0 + FOG_LAMP_GX[n]) * (phi_b - phi_a);
}

// The integrand tau K p S T (V apart) of lamp i's integral over the angle phi (t = t_s +
// h' tan phi), without the factor a I / h', at the 4 Gauss-Legendre nodes of the piece
// [phi_a, phi_b] where `need` asks (0 elsewhere). tau from fog_lamp_table and T by
// fog_lamp_shadow_steps midpoint steps towards the lamp, or for the analytic models both in
// closed form. base_only: the RBFs' homogeneous base alone, K, tau and T (Fogshop's base
// term: Sun et al.'s airlight, which the Gaussians do not shadow).
vec4 fog_lamp_node_values(int i, fog_ray r, float phi_a, float phi_b, float t0, float dt,
                          float ts, float hp, bool base_only, bvec4 need) {
  vec3 s = fog_lamp_position[i];
  int steps = fog_lamp_depth_steps;
  vec4 f = vec4(0.0);
  for (int n = 0; n < 4; n++) {
    if (!need[n]) continue;
    // within the span: by a lamp of tiny radius on the ray (h' ~ 1e-7 of it) atan rounds
    // past pi/2, where tan turns negative and the node fell far behind the camera (NaN)
    float t = clamp(ts + hp * tan(fog_lamp_node(phi_a, phi_b, n)), t0,
                    t0 + dt * float(fog_lamp_depth_steps));
    vec3 x = t * r.dir;
    float spot = fog_lamp_spot(i, x);
    if (!(spot > 0.0)) continue;
    float k = base_only ? fog_model_extinction : fog_lamp_extinction(x);
    if (!(k > 0.0)) continue;
    vec3 to_lamp = s - x;
    float dist = length(to_lamp);
    vec3 towards_lamp = dist > 0.0 ? to_lamp / dist : r.dir;  // at the lamp: cos theta 1
#if FOG_LAMP_EXACT_DEPTH
    float depth = fog_lamp_segment_depth(vec3(0.0), r.dir, t);
    float shadow = fog_lamp_shadow_depth(i, x);
    if (base_only) {  // Sun et al.'s homogeneous medium: the base alone
      depth = fog_model_extinction * max(t, 0.0);
      shadow = fog_model_extinction * dist;
    }
#else
#if FOG_MODEL_KIND == FOG_MODEL_LINEAR
    float depth = fog_linear_depth(t);  // the factor itself (K grows without bound at end)
#elif FOG_MODEL_KIND == FOG_MODEL_EXP2
    float depth = fog_exp2_depth(t);
#else
    float u = clamp((t - t0) / dt, 0.0, float(steps));
    int c = min(int(floor(u)), steps - 1);
    float depth = fog_lamp_table[c] +
                  clamp(u - float(c), 0.0, 1.0) * (fog_lamp_table[c + 1] - fog_lamp_table[c]);
#endif
    // at the linear fog's end (K "infinite", tau 0, rounding either way) no light comes back
    if (depth >= 1e29 || k >= 1e29) continue;
    float shadow = fog_lamp_shadow_depth(i, x);
#endif
    f[n] = exp(-depth) * k * fog_phase_hg(fog_phase_g, towards_lamp, r.dir) * spot * exp(-shadow);
  }
  return f;
}

// One piece with V given at its nodes: 4 nodes of f V.
float fog_lamp_piece(int i, fog_ray r, float phi_a, float phi_b, float t0, float dt, float ts,
                     float hp, bool base_only, vec4 visible) {
  if (!(phi_b > phi_a)) return 0.0;
  vec4 f = fog_lamp_node_values(i, r, phi_a, phi_b, t0, dt, ts, hp, base_only,
                                greaterThan(visible, vec4(0.0)));
  return 0.5 * (phi_b - phi_a) *
         dot(vec4(FOG_LAMP_GW[0], FOG_LAMP_GW[1], FOG_LAMP_GW[2], FOG_LAMP_GW[3]), f * visible);
}

#if FOG_LAMP_SHADOWS
// V of lamp i at the ray's point at angle phi.
float fog_lamp_visible_at(int i, fog_ray r, float phi, float ts, float hp) {
  return fog_lamp_visible(i, (ts + hp * tan(phi)) * r.dir);
}

// V at the 4 nodes of [phi_a, phi_b].
vec4 fog_lamp_node_visibility(int i, fog_ray r, float phi_a, float phi_b, float ts, float hp) {
  vec4 v;
  for (int n = 0; n < 4; n++) v[n] = fog_lamp_visible_at(i, r, fog_lamp_node(phi_a, phi_b, n), ts, hp);
  return v;
}

// The integrals over [u0, u1] (in [-1, 1]) of the Lagrange polynomials through the 4 Gauss-
// Legendre nodes (render/fog_lamp.h, fog_lamp_lagrange_integrals): L_n(u) = sum_j c_nj u^j.
vec4 fog_lamp_lagrange_integrals(float u0, float u1) {
  const mat4 c = mat4(-0.09232659844072881, 0.10721484763523989, 0.7987620630283673, -0.9275675085048682,
                      0.5923265984407289, -1.7422341910450936, -0.7987620630283672, 2.3494311759443827,
                      0.5923265984407288, 1.742234191045094, -0.7987620630283674, -2.349431175944382,
                      -0.0923265984407288, -0.1072148476352399, 0.7987620630283672, 0.927567508504868);
  vec4 m = vec4(u1 - u0, (u1 * u1 - u0 * u0) / 2.0, (u1 * u1 * u1 - u0 * u0 * u0) / 3.0,
                (u1 * u1 * u1 * u1 - u0 * u0 * u0 * u0) / 4.0);
  return m * c;  // row n: column n of the GLSL matrix dotted with m
}

// A piece with V known at its ends and nodes (lit: bit 0 the start, 1-4 the nodes, 5 the
// end, set where V >= 1/2). All dark (and V 0 at the nodes): nothing. All lit: its 4 nodes of
// f V. Else a shadow's edge crosses it: between two of those points on different sides of
// V = 1/2 the edge is found by FOG_LAMP_EDGE_BISECTIONS bisections, and f (smooth: V apart)
// is integrated over the lit stretches as the cubic through its 4 nodes (V 1 there, 0 on
// the dark ones). Without the cut the edge is a jump the nodes sample: rings of error
// around the lamp where it crosses a node.
float fog_lamp_piece_shadowed(int i, fog_ray r, float phi_a, float phi_b, float t0, float dt,
                              float ts, float hp, uint lit, vec4 visible) {
  const bool any_visible = any(greaterThan(visible, vec4(0.0)));
  if (lit == 0u && !any_visible) return 0.0;
  // The nodes' values are taken once, for both cases below: llvmpipe runs both branches of
  // a lane group that mixes them, and the nodes (K, tau, T's walk) are the piece's cost.
  const bool whole = lit == 63u || lit == 0u;
  vec4 f = fog_lamp_node_values(i, r, phi_a, phi_b, t0, dt, ts, hp, false,
                                whole ? greaterThan(visible, vec4(0.0)) : bvec4(true));
  if (whole) /* all lit, or dark with V > 0 at a node: its 4 nodes of f V (fog_lamp_piece) */
    return 0.5 * (phi_b - phi_a) *
           dot(vec4(FOG_LAMP_GW[0], FOG_LAMP_GW[1], FOG_LAMP_GW[2], FOG_LAMP_GW[3]), f * visible);
  float dphi = phi_b - phi_a, start = -1.0, before_at = phi_a, total = 0.0;
  for (int k = 1; k <= 5; k++) {
    float at = k == 5 ? phi_b : fog_lamp_node(phi_a, phi_b, k - 1);
    bool before = ((lit >> (k - 1)) & 1u) != 0u, now = ((lit >> k) & 1u) != 0u;
    if (now != before) {
      float lo = before_at, hi = at;  // lo on `before`'s side
      for (int b = 0; b < FOG_LAMP_EDGE_BISECTIONS; b++) {
        float mid = 0.5 * (lo + hi);
        if ((fog_lamp_visible_at(i, r, mid, ts, hp) >= 0.5) == before) lo = mid; else hi = mid;
      }
      float edge = 2.0 * (0.5 * (lo + hi) - phi_a) / dphi - 1.0;
      if (before) total += dot(f, fog_lamp_lagrange_integrals(start, edge));
      start = edge;
    }
    before_at = at;
  }
  if ((lit & 32u) != 0u) total += dot(f, fog_lamp_lagrange_integrals(start, 1.0));
  return 0.5 * dphi * total;
}
#endif

// The angles phi where the ray crosses spot i's cones cos = cos_outer and cos = cos_inner
// (lamp_cone_cuts in C: the smoothstep's kinks, and a narrow beam's edges, which fell between
// a piece's nodes); 1e30 for none, and for a point lamp. w = t dir - s: A t^2 + 2 B t + E = 0,
// A = alpha^2 - c^2, B = c^2 ts - alpha beta, E = beta^2 - c^2 |s|^2, a root counting where
// w.a has c's sign; B^2 - A E = c^2 (|beta dir - alpha s|^2 - c^2 h^2) from the vectors'
// lengths (as B^2 - A E it cancelled in float for a ray grazing the cone near the lamp).
vec4 fog_lamp_cone_cuts(int i, fog_ray r, float ts, float hp) {
  vec4 cuts = vec4(1e30);
#if FOG_LAMP_SPOTS  // point lamps alone: none (the code skipped: llvmpipe runs it masked)
  if (fog_lamp_axis[i].w == 0.0) return cuts;
  vec3 s = fog_lamp_position[i], axis = fog_lamp_axis[i].xyz;
  float alpha = dot(r.dir, axis), beta = dot(s, axis), sigma = dot(s, s);
  vec3 u = beta * r.dir - alpha * s, h = s - ts * r.dir;
  float u2 = dot(u, u), h2 = dot(h, h);
  for (int cone = 0; cone < 2; cone++) {  // constant bound: unrolled
    float c = fog_lamp_cone[i].x + (cone == 1 ? 1.0 / fog_lamp_cone[i].y : 0.0), c2 = c * c;
    float a = alpha * alpha - c2, b = c2 * ts - alpha * beta, e = beta * beta - c2 * sigma;
    float disc = c2 * (u2 - c2 * h2);
    float q = -(b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(max(disc, 0.0)));
    vec2 roots = vec2(a != 0.0 ? q / a : 1e30, q != 0.0 ? e / q : 1e30);
    for (int k = 0; k < 2; k++) {
      float t = roots[k];
      if (disc >= -1e-4 * c2 * u2 && abs(t) < 1e29 && (t * alpha - beta) * c >= 0.0)
        cuts[2 * cone + k] = atan((t - ts) / hp);
    }
  }
#endif
  return cuts;
}

// Lamp i's integral over the angle phi, without the factor a I / h': fog_lamp_piece on each
// piece of fog_lamp_method's union of equal steps in phi and in t (with the shadow cubes,
// fog_lamp_piece_shadowed: cut at V's edges).
float fog_lamp_angle_integral(int i, fog_ray r, float t0, float t1, float ts, float hp,
                              bool base_only) {
  float dt = (t1 - t0) / float(fog_lamp_depth_steps);
  float phi0 = atan((t0 - ts) / hp), phi1 = atan((t1 - ts) / hp), lamp_sum = 0.0;
  const int na = fog_lamp_angle_pieces, nt = fog_lamp_span_pieces;
  float phi_a = phi0;
  // and cuts at phi = 0, the closest point, at a spot's cone crossings, and where the ray
  // crosses a quadric volume's surface (K's steps and kinks: fog_lamp_cpu.c's lamp_unit)
  vec4 cuts = fog_lamp_cone_cuts(i, r, ts, hp);
#if FOG_MODEL_KIND == FOG_MODEL_QUADRIC || FOG_QUADRICS_BESIDE
  float quadric_cuts[FOG_QUADRIC_MAX_CUTS];
  int quadric_cut_count = base_only ? 0 : fog_quadric_cuts(r.dir, t0, t1, quadric_cuts);
  for (int c = 0; c < quadric_cut_count; c++) quadric_cuts[c] = atan((quadric_cuts[c] - ts) / hp);
#endif
#if FOG_LAMP_SHADOWS
  bool lit_a = !base_only && fog_lamp_visible_at(i, r, phi0, ts, hp) >= 0.5;  // at the start
#endif
  for (int ia = 1, it = 1; ia <= na || it <= nt;) {
    float next_a = ia <= na ? phi0 + float(ia) * (phi1 - phi0) / float(na) : 1e30;
    float next_t = it <= nt ? atan((t0 + float(it) * (t1 - t0) / float(nt) - ts) / hp) : 1e30;
    float phi_b = min(next_a, next_t);
#if FOG_LAMP_SPOTS
    vec4 ahead = mix(vec4(1e30), cuts, greaterThan(cuts, vec4(phi_a)));
    float next_cut = min(min(min(ahead.x, ahead.y), min(ahead.z, ahead.w)),
                         0.0 > phi_a ? 0.0 : 1e30);
#else
    float next_cut = 0.0 > phi_a ? 0.0 : 1e30;
#endif
#if FOG_MODEL_KIND == FOG_MODEL_QUADRIC || FOG_QUADRICS_BESIDE
    for (int c = 0; c < quadric_cut_count; c++)
      if (quadric_cuts[c] > phi_a && quadric_cuts[c] < next_cut) next_cut = quadric_cuts[c];
#endif
    if (next_cut < phi_b) {
      phi_b = next_cut;
    } else if (next_a <= next_t) {
      ia++;
    } else {
      it++;
    }
#if FOG_LAMP_SHADOWS
    if (!base_only && phi_b > phi_a) {
      // V at the nodes and the piece's end (the next one's start): an edge anywhere between
      // two of them is found
      vec4 v = fog_lamp_node_visibility(i, r, phi_a, phi_b, ts, hp);
      bool lit_b = fog_lamp_visible_at(i, r, phi_b, ts, hp) >= 0.5;
      uint lit = (lit_a ? 1u : 0u) | (lit_b ? 32u : 0u);
      for (int n = 0; n < 4; n++) lit |= v[n] >= 0.5 ? 2u << n : 0u;
      lamp_sum += fog_lamp_piece_shadowed(i, r, phi_a, phi_b, t0, dt, ts, hp, lit, v);
      lit_a = lit_b;
      phi_a = phi_b;
      continue;
    }
#endif
    lamp_sum += fog_lamp_piece(i, r, phi_a, phi_b, t0, dt, ts, hp, base_only, vec4(1.0));
    phi_a = phi_b;
  }
  return lamp_sum;
}

#if FOG_LAMP_INTEGRAL == 1
// Fogshop's approximation (Zhou et al. 2007, eq. 11; render/fog_lamp.h): each Gaussian's
// optical depth along the ray times tau p S T / falloff taken once, at the projection of its
// centre on the ray (clamped to the span), with the closed-form depths. As in the paper, no
// shadows of the scene's surfaces (V = 1).
float fog_lamp_fogshop_gaussians(int i, fog_ray r, float t0, float t1) {
  vec3 s = fog_lamp_position[i];
  float sum = 0.0;
  for (int g = 0; g < fog_rbf_count; g++) {
    vec3 v = fog_rbf_centre(g).xyz;
    float inv_r = fog_rbf_centre(g).w, tc = dot(v, r.dir);
    vec3 w = v - tc * r.dir;
    float depth = fog_rbf_density(g) * exp(-dot(w, w) * inv_r * inv_r) * (0.88622692545 / inv_r) *
                  fog_erf_difference((t0 - tc) * inv_r, (t1 - tc) * inv_r);
    if (!(depth > 0.0)) continue;
    float t = clamp(tc, t0, t1);
    vec3 x = t * r.dir, to_lamp = s - x;
    float dist = length(to_lamp);
    vec3 towards_lamp = dist > 0.0 ? to_lamp / dist : r.dir;  // at the lamp: cos theta 1
    float shadow = fog_lamp_shadow_depth(i, x);
    sum += depth * exp(-fog_lamp_segment_depth(vec3(0.0), r.dir, t) - shadow) *
           fog_phase_hg(fog_phase_g, towards_lamp, r.dir) * fog_lamp_spot(i, x) /
           (dist * dist + fog_lamp_cone[i].z);
  }
  return sum;
}
#endif

#if FOG_LAMP_INTEGRAL == 2
uniform int fog_lamp_march_steps;
// Uniform ray marching (FOG_LAMP_MARCH, the bench's baseline): midpoint samples of t, tau
// summed along them, T as the angle integral's.
float fog_lamp_march(int i, fog_ray r, float t0, float t1) {
  vec3 s = fog_lamp_position[i];
  int n = fog_lamp_march_steps;
  float dt = (t1 - t0) / float(n), before = 0.0, sum = 0.0;
  for (int j = 0; j < n; j++) {
    float t = t0 + (float(j) + 0.5) * dt;
    vec3 x = t * r.dir;
    float k = fog_lamp_extinction(x);
    float tau = exp(-(before + 0.5 * k * dt));
    before += k * dt;
    float lit = fog_lamp_spot(i, x) * fog_lamp_visible(i, x);
    if (!(k > 0.0) || !(lit > 0.0)) continue;
    vec3 to_lamp = s - x;
    float dist = length(to_lamp);
    vec3 towards_lamp = dist > 0.0 ? to_lamp / dist : r.dir;  // at the lamp: cos theta 1
    float shadow = fog_lamp_shadow_depth(i, x);
    sum += tau * k * fog_phase_hg(fog_phase_g, towards_lamp, r.dir) * lit *
           exp(-shadow) / (dist * dist + fog_lamp_cone[i].z);
  }
  return sum * dt;
}
#endif

// The lamps' in-scattered radiance of the pixel's ray: per lamp a I times its integral.
vec3 fog_lamps_light(fog_ray r) {
  float t0, t1;
  if (fog_lamp_count == 0 || !fog_light_span(r, t0, t1)) return vec3(0.0);
// the table of depth from the camera; not for the classic factors (their closed form)
#if !FOG_LAMP_EXACT_DEPTH && FOG_LAMP_INTEGRAL == 0 && FOG_MODEL_KIND != FOG_MODEL_LINEAR && \
    FOG_MODEL_KIND != FOG_MODEL_EXP2
  int steps = fog_lamp_depth_steps;
  float dt = (t1 - t0) / float(steps);
  fog_lamp_table[0] = 0.0;
  for (int k = 0; k < steps; k++)
    fog_lamp_table[k + 1] =
        fog_lamp_table[k] + fog_lamp_extinction((t0 + (float(k) + 0.5) * dt) * r.dir) * dt;
#endif
  vec3 total = vec3(0.0);
  for (int i = 0; i < fog_lamp_count; i++) {
    vec3 s = fog_lamp_position[i];
    float ts = dot(s, r.dir);
    vec3 hv = s - ts * r.dir;
    float hp = sqrt(dot(hv, hv) + fog_lamp_cone[i].z);
#if FOG_LAMP_INTEGRAL == 2
    float unit = fog_lamp_march(i, r, t0, t1);
#elif FOG_LAMP_INTEGRAL == 1
    float unit = (fog_model_extinction > 0.0
                      ? fog_lamp_angle_integral(i, r, t0, t1, ts, hp, true) / hp : 0.0) +
                 fog_lamp_fogshop_gaussians(i, r, t0, t1);
#else
    float unit = fog_lamp_angle_integral(i, r, t0, t1, ts, hp, false) / hp;
#endif
    total += fog_lamp_scatter[i] * unit;
  }
  return total;
}
#else
vec3 fog_lamps_light(fog_ray r) { return vec3(0.0); }
#endif
