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

// K at camera-relative point p (zero outside the fogmap's box: the march to a lamp leaves it).
float fog_lamp_extinction(vec3 p) {
#if FOG_MODEL_KIND == FOG_MODEL_FOGMAP
  if (any(lessThan(p, vec3(fog_box_min))) || any(greaterThan(p, vec3(fog_box_max)))) return 0.0;
  return fog_extinction_scale *
         fog_extinction_at(fog_lod_method == FOG_LOD_SWITCH ? fog_levels : 0, p, 1.0);
#elif FOG_MODEL_KIND == FOG_MODEL_VOLUME
  return fog_grid3d_density(fog_grid3d_camera_index + fog_grid3d_index_from_world * p);
#else
  return fog_model_extinction_at(p);
#endif
}

// The analytic models' optical depths in closed form (fog_models.glsl): from the camera
// to distance t along the ray, and from point x along unit w for length len.
#define FOG_LAMP_EXACT_DEPTH (FOG_MODEL_KIND == FOG_MODEL_HOMOGENEOUS || \
                              FOG_MODEL_KIND == FOG_MODEL_HEIGHT || FOG_MODEL_KIND == FOG_MODEL_RBF || \
                              FOG_MODEL_KIND == FOG_MODEL_QUADRIC)
float fog_lamp_segment_depth(vec3 x, vec3 w, float len) {
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

// Lamp i's integral over the angle phi (t = t_s + h' tan phi) of tau K p S T, without the
// factor a I / h': Gauss-Legendre with 4 nodes on each piece of fog_lamp_method's union of
// equal steps in phi and in t. tau from fog_lamp_table and T by fog_lamp_shadow_steps
// midpoint steps towards the lamp, or for the analytic models both in closed form.
// base_only: the RBFs' homogeneous base alone, K, tau and T (Fogshop's base term: Sun et
// al.'s airlight, which the Gaussians do not shadow).
float fog_lamp_angle_integral(int i, fog_ray r, float t0, float t1, float ts, float hp,
                              bool base_only) {
  const float gx[4] = float[4](-0.86113631159405258, -0.33998104358485626,
                               0.33998104358485626, 0.86113631159405258);
  const float gw[4] = float[4](0.34785484513745386, 0.65214515486254614,
                               0.65214515486254614, 0.34785484513745386);
  vec3 s = fog_lamp_position[i];
  int steps = fog_lamp_depth_steps;
  float dt = (t1 - t0) / float(steps);
  float phi0 = atan((t0 - ts) / hp), phi1 = atan((t1 - ts) / hp), lamp_sum = 0.0;
  const int na = fog_lamp_angle_pieces, nt = fog_lamp_span_pieces;
  float phi_a = phi0;
  bool cut = !(phi0 < 0.0 && phi1 > 0.0);  // and a cut at phi = 0, the closest point
  for (int ia = 1, it = 1; ia <= na || it <= nt;) {
    float next_a = ia <= na ? phi0 + float(ia) * (phi1 - phi0) / float(na) : 1e30;
    float next_t = it <= nt ? atan((t0 + float(it) * (t1 - t0) / float(nt) - ts) / hp) : 1e30;
    float phi_b = min(next_a, next_t);
    if (!cut && phi_b > 0.0) {
      phi_b = 0.0;
      cut = true;
    } else if (next_a <= next_t) {
      ia++;
    } else {
      it++;
    }
    float dphi = phi_b - phi_a, sum = 0.0;
    for (int n = 0; n < 4 && dphi > 0.0; n++) {
      float phi = phi_a + 0.5 * (1.0 + gx[n]) * dphi;
      float t = ts + hp * tan(phi);
      vec3 x = t * r.dir;
      float k = base_only ? fog_model_extinction : fog_lamp_extinction(x);
      if (!(k > 0.0)) continue;
      vec3 to_lamp = s - x;
      float dist = length(to_lamp);
      float cos_theta = dist > 0.0 ? dot(to_lamp, r.dir) / dist : 1.0;
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
      sum += gw[n] * exp(-depth) * k * fog_phase_hg(fog_phase_g, cos_theta) *
             fog_lamp_spot(i, x) * exp(-shadow);
    }
    lamp_sum += 0.5 * dphi * sum;
    phi_a = phi_b;
  }
  return lamp_sum;
}

#if FOG_LAMP_INTEGRAL == 1
// Fogshop's approximation (Zhou et al. 2007, eq. 11; render/fog_lamp.h): each Gaussian's
// optical depth along the ray times tau p S T / falloff taken once, at the projection of its
// centre on the ray (clamped to the span), with the closed-form depths.
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
    float cos_theta = dist > 0.0 ? dot(to_lamp, r.dir) / dist : 1.0;
    float shadow = fog_lamp_shadow_depth(i, x);
    sum += depth * exp(-fog_lamp_segment_depth(vec3(0.0), r.dir, t) - shadow) *
           fog_phase_hg(fog_phase_g, cos_theta) * fog_lamp_spot(i, x) /
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
    if (!(k > 0.0)) continue;
    vec3 to_lamp = s - x;
    float dist = length(to_lamp);
    float cos_theta = dist > 0.0 ? dot(to_lamp, r.dir) / dist : 1.0;
    float shadow = fog_lamp_shadow_depth(i, x);
    sum += tau * k * fog_phase_hg(fog_phase_g, cos_theta) * fog_lamp_spot(i, x) *
           exp(-shadow) / (dist * dist + fog_lamp_cone[i].z);
  }
  return sum * dt;
}
#endif

// The lamps' in-scattered radiance of the pixel's ray: per lamp a I times its integral.
vec3 fog_lamps_light(fog_ray r) {
  float t0, t1;
  if (fog_lamp_count == 0 || !fog_light_span(r, t0, t1)) return vec3(0.0);
#if !FOG_LAMP_EXACT_DEPTH && FOG_LAMP_INTEGRAL == 0
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
