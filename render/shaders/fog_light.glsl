// The fog's shadow on itself, T_s (render/fog_sun_shadow.h, docs/light.md), for the fog
// pass (fog_pass_fs.glsl includes it after the models). Specialisation constant:
//   #define FOG_SUN_SHADOW 0|1|2|3   (fog_sun_shadow_kind: none, the optical-depth volume,
//                                    the height fog's closed form, opaque)
// The sun's in-scatter of a view ray is a L_sun p(theta) int tau K T_s du. Written as
// (1 - tau) times the mean of T_s weighted by tau K (the weights integrate to 1 - tau), the
// transmittance tau stays the model's exact integral and with T_s = 1 the in-scatter is
// exactly (L_amb + a L_sun p) (1 - tau) (the identity of docs/light.md). The mean is taken
// over fog_shadow_steps equal segments of the ray's fog span, cut at quadric volumes'
// surfaces (fog_sun_mean_transmittance below: one or two samples each).
uniform sampler3D fog_sun_shadow_map;   // R32F optical depth towards the sun
uniform mat3 fog_sun_shadow_to_tex;     // fog_sun_shadow_tex_map's M
uniform vec3 fog_sun_shadow_tex_camera; // M (camera - origin) + offset, in double on the CPU
uniform int fog_shadow_steps;
// FOG_SHAFTS 1: V, the sun past the terrain and boxes, from the scene pass's shadow map
// (render/sun_shadow_map.h): light shafts and the shadows of hills in the fog.
#if FOG_SHAFTS
uniform sampler2DShadow fog_sun_visibility;
uniform mat4 fog_sun_visibility_from_relative;  // sun_shadow_map_matrix at the camera
uniform float fog_sun_visibility_bias;          // depth units: one texel's world size
float fog_sun_visible(vec3 p) {
  vec3 q = (fog_sun_visibility_from_relative * vec4(p, 1.0)).xyz;
  // Depth at most 1 (the map's far side): GL does not clamp the reference of a float depth
  // texture, and fog past the far side (beyond the scene's bounds, away from the sun) would
  // fail the compare against the cleared map and its border, 1, and stay dark.
  return texture(fog_sun_visibility, vec3(q.xy, min(q.z - fog_sun_visibility_bias, 1.0)));
}
#else
float fog_sun_visible(vec3 p) { return 1.0; }
#endif
// The view-ray march runs for T_s (the volume, the height fog's closed form) or for V.
#define FOG_LIGHT_MARCH \
  (FOG_SUN_SHADOW == 1 || FOG_SUN_SHADOW == 2 || (FOG_SUN_SHADOW == 0 && FOG_SHAFTS == 1))

// Optical depth from camera-relative point p towards the sun.
float fog_sun_optical_depth(vec3 p) {
// The quadrics beside the model add their exact depth towards the sun (the volume holds the
// model alone: fog_sun_optical_depth in C).
#if FOG_QUADRICS_BESIDE
#define FOG_SUN_BESIDE(p) fog_quadric_optical_depth_from(p, fog_sun_direction, 1e30)
#else
#define FOG_SUN_BESIDE(p) 0.0
#endif
#if FOG_SUN_SHADOW == 1
  return texture(fog_sun_shadow_map, fog_sun_shadow_tex_camera + fog_sun_shadow_to_tex * p).r +
         FOG_SUN_BESIDE(p);
#elif FOG_SUN_SHADOW == 2
  // int_0^inf K e^{-(y + s w_y - y0)/H} ds = K H e^{-(y - y0)/H} / w_y (w_y > 0)
  return fog_model_extinction * fog_model_scale_height *
             exp(-(p.y - fog_model_y0) / fog_model_scale_height) / fog_sun_direction.y +
         FOG_SUN_BESIDE(p);
#elif FOG_SUN_SHADOW == 3
  return FOG_INFINITY;
#else
  return 0.0;
#endif
}

// The stretch [t0, t1] of the ray that holds the model's fog (finite), and K along it
// (the sun's march and the lamps, fog_lamps.glsl); with quadrics beside the model, the
// hull of both stretches (fog_light_span in C).
bool fog_model_light_span(fog_ray r, bool chords, out float t0, out float t1);
bool fog_span_of(fog_ray r, bool chords, out float t0, out float t1) {
  bool some = fog_model_light_span(r, chords, t0, t1);
#if FOG_QUADRICS_BESIDE
  float a, b;
  if (fog_slab(fog_quadric_union_lo, fog_quadric_union_hi, vec3(0.0), r.dir, a, b)) {
    a = max(a, 0.0);
    b = min(b, r.t_surface);
    if (a < b && b < 1e29) {
      if (some) a = min(a, t0), b = max(b, t1);
      t0 = a, t1 = b;
      return true;
    }
  }
#endif
  return some;
}
// the lamps' span (from the camera to the RBFs' reach) and the sun's (RBFs alone: their
// cull spheres' chords), fog_light_span and fog_sun_span in C
bool fog_light_span(fog_ray r, out float t0, out float t1) {
  return fog_span_of(r, false, t0, t1);
}
bool fog_sun_span(fog_ray r, out float t0, out float t1) { return fog_span_of(r, true, t0, t1); }
bool fog_model_light_span(fog_ray r, bool chords, out float t0, out float t1) {
#if FOG_MODEL_KIND == FOG_MODEL_FOGMAP
  t0 = float(max(r.t_in, 0.0));
  t1 = min(float(r.t_out), r.t_surface);
#elif FOG_MODEL_KIND == FOG_MODEL_VOLUME
  vec3 u0, du;
  if (!fog_grid3d_stretch(r.dir, r.t_surface, u0, du, t0, t1)) return false;
#elif FOG_MODEL_KIND == FOG_MODEL_HEIGHT
  // Up to the surface, or where the ray's optical depth reaches FOG_LIGHT_DEPTH (the rest
  // weighs < e^-20): D(L) = K e^{y0/H} H (1 - e^{-w_y L / H}) / w_y, inverted.
  const float FOG_LIGHT_DEPTH = FOG_LIGHT_SPAN_DEPTH;
  float H = fog_model_scale_height, k0 = fog_model_extinction * exp(fog_model_y0 / H);
  float dy = r.dir.y, reach;
  if (abs(dy) < 1e-6) {
    reach = FOG_LIGHT_DEPTH / k0;
  } else {
    float q = FOG_LIGHT_DEPTH * dy / (k0 * H);
    // -ln(1 - q) = q + q^2/2 + ...: by its series where 1 - q loses q in float (haze of
    // scale height 1e7: q ~ 1e-8, 1 - q = 1, the span empty and the sun through opaque fog);
    // the next term, q^4/5 of it, is below 2e-9 there
    float series = FOG_LIGHT_DEPTH / k0 * (1.0 + q * (0.5 + q * (1.0 / 3.0 + q * 0.25)));
    reach = q >= 1.0 ? fog_model_reach(r.dir)
          : abs(q) < 0.01 ? series : -H / dy * log(1.0 - q);
  }
  t0 = 0.0;
  t1 = min(r.t_surface, reach);
#elif FOG_MODEL_KIND == FOG_MODEL_QUADRIC
  if (!fog_slab(fog_quadric_union_lo, fog_quadric_union_hi, vec3(0.0), r.dir, t0, t1))
    return false;
  t0 = max(t0, 0.0);
  t1 = min(t1, r.t_surface);
#elif FOG_MODEL_KIND == FOG_MODEL_PERLIN
  if (!fog_slab(fog_perlin_lo, fog_perlin_hi, vec3(0.0), r.dir, t0, t1)) return false;
  t0 = max(t0, 0.0);
  t1 = min(t1, r.t_surface);
#elif FOG_MODEL_KIND == FOG_MODEL_LINEAR
  // nothing before start; opaque from end on
  t0 = max(fog_model_start, 0.0);
  t1 = min(r.t_surface, fog_model_end);
#elif FOG_MODEL_KIND == FOG_MODEL_EXP2
  // (a t)^2 reaches FOG_LIGHT_SPAN_DEPTH at sqrt(depth) / a
  t0 = 0.0;
  t1 = fog_model_extinction > 0.0 ? min(r.t_surface, sqrt(FOG_LIGHT_SPAN_DEPTH) / fog_model_extinction)
                                  : 0.0;
#elif FOG_MODEL_KIND == FOG_MODEL_RBF
  if (fog_model_extinction == 0.0 && chords) {
    // the sun's mean over Gaussians alone: the stretch of the ray inside their cull spheres
    // (the chords of the pixel's tile's Gaussians, in front of the camera; past a chord a
    // Gaussian adds under half the tiles' bound), so that the mean's segments lie on the
    // fog however far it is (fog_sun_span in C)
    t0 = 1e30;
    t1 = 0.0;
    uvec2 range = fog_rbf_tile_range();
    for (uint j = range.x; j < range.x + range.y; j++) {
      int i = int(texelFetch(fog_rbf_indices, int(j)).x);
      vec3 b = fog_rbf_centre(i).xyz;
      float R = fog_rbf_cull_radius(i), tc = dot(b, r.dir);
      vec3 w = b - tc * r.dir;
      float chord2 = R * R - dot(w, w);
      float half_chord = sqrt(max(chord2, 0.0));
      if (R > 0.0 && chord2 > 0.0 && tc + half_chord > 0.0) {
        t0 = min(t0, tc - half_chord);
        t1 = max(t1, tc + half_chord);
      }
    }
    t0 = max(t0, 0.0);
    t1 = min(t1, r.t_surface);
  } else if (fog_model_extinction == 0.0) {
    t0 = 0.0;  // the lamps': from the camera to the farthest Gaussian's reach
    t1 = min(r.t_surface, fog_model_reach(r.dir));
  } else {
    // the fog never ends (the base): to FOG_LIGHT_SPAN_DEPTH from the camera
    t0 = 0.0;
    t1 = min(r.t_surface, min(fog_model_reach(r.dir), FOG_LIGHT_SPAN_DEPTH / fog_model_extinction));
  }
#else
  t0 = 0.0;
  t1 = min(r.t_surface, fog_model_reach(r.dir));
#if FOG_MODEL_KIND == FOG_MODEL_HOMOGENEOUS
  // the fog never ends (a homogeneous fog or base): to FOG_LIGHT_SPAN_DEPTH from the camera
  if (fog_model_extinction > 0.0) t1 = min(t1, FOG_LIGHT_SPAN_DEPTH / fog_model_extinction);
#endif
#endif
  return t0 < t1 && t1 < 1e29;
}

float fog_light_extinction(vec3 dir, float t) {
#if FOG_QUADRICS_BESIDE
  float beside = fog_quadric_extinction_at(t * dir);
#else
  const float beside = 0.0;
#endif
#if FOG_MODEL_KIND == FOG_MODEL_FOGMAP
  // A_J, the fog itself, for either LOD method (the sum of details at mu = 1 draws
  // A_0 + D_1..D_J = A_J; a draw at mu <= 0 is A_0 alone, in slot 0 with fog_levels 0), zero
  // outside the box (fog_extinction_point in C: beside quadrics the span reaches past it)
  vec3 p = t * dir;
  if (any(lessThan(p, vec3(fog_box_min))) || any(greaterThan(p, vec3(fog_box_max)))) return beside;
  return fog_extinction_scale *
         fog_extinction_at(fog_levels, dir, t) + beside;
#elif FOG_MODEL_KIND == FOG_MODEL_VOLUME
  return fog_grid3d_density(fog_grid3d_camera_index + t * (fog_grid3d_index_from_world * dir)) +
         beside;
#else
  return fog_model_extinction_at(t * dir) + beside;
#endif
}

// T_s V at distance t along unit dir.
float fog_sun_light_at(vec3 dir, float t) {
  return exp(-fog_sun_optical_depth(t * dir)) * fog_sun_visible(t * dir);
}

// The segments' nodes see T_s alone when V has points of its own (FOG_SHAFT_SAMPLES > 1,
// a specialisation constant: 1 keeps V at the nodes, as fog_sun_light_at).
#if FOG_SHAFTS == 1 && FOG_SHAFT_SAMPLES > 1
float fog_sun_node_light(vec3 dir, float t) { return exp(-fog_sun_optical_depth(t * dir)); }
// V's mean over FOG_SHAFT_SAMPLES equally spaced points of the segment centred at mid.
float fog_sun_segment_visible(vec3 dir, float mid, float dt) {
  float seen = 0.0;
  for (int k = 0; k < FOG_SHAFT_SAMPLES; k++)
    seen += fog_sun_visible((mid + ((float(k) + 0.5) / float(FOG_SHAFT_SAMPLES) - 0.5) * dt) * dir);
  return seen / float(FOG_SHAFT_SAMPLES);
}
#else
float fog_sun_node_light(vec3 dir, float t) { return fog_sun_light_at(dir, t); }
float fog_sun_segment_visible(vec3 dir, float mid, float dt) { return 1.0; }
#endif

#if FOG_MODEL_KIND == FOG_MODEL_PERLIN || FOG_MODEL_KIND == FOG_MODEL_VOLUME || \
    FOG_MODEL_KIND == FOG_MODEL_FOGMAP
#if FOG_SHAFTS == 1 && FOG_SHAFT_SAMPLES > 1
// V for the per-piece means (shaft_line and shaft_visible in fog_sun_light_cpu.c): linear
// between fog_shadow_steps x FOG_SHAFT_SAMPLES equally spaced points of the ray's fog span,
// the pieces' nodes reading it. The points follow the span, not the fog's cells: V at the nodes, pinned to the cells'
// planes, drew the cells' outlines into the shadows as jagged bands. One ray's line at a
// time; the nodes come in increasing t, so each point is looked up about once.
float fog_shaft_t0, fog_shaft_dv, fog_shaft_lo, fog_shaft_hi;
int fog_shaft_count, fog_shaft_k;
void fog_shaft_begin(vec3 dir, float t0, float t1) {
  fog_shaft_count = fog_shadow_steps * FOG_SHAFT_SAMPLES;
  fog_shaft_t0 = t0;
  fog_shaft_dv = (t1 - t0) / float(fog_shaft_count);
  fog_shaft_k = -2;
}
float fog_shaft_point(vec3 dir, int k) {
  return fog_sun_visible((fog_shaft_t0 + (float(k) + 0.5) * fog_shaft_dv) * dir);
}
float fog_shaft_visible(vec3 dir, float t) {
  float u = clamp((t - fog_shaft_t0) / fog_shaft_dv - 0.5, 0.0, float(fog_shaft_count - 1));
  int k = min(int(u), fog_shaft_count - 2);
  if (k != fog_shaft_k) {
    fog_shaft_lo = k == fog_shaft_k + 1 ? fog_shaft_hi : fog_shaft_point(dir, k);
    fog_shaft_hi = fog_shaft_point(dir, k + 1);
    fog_shaft_k = k;
  }
  return mix(fog_shaft_lo, fog_shaft_hi, u - float(k));
}
#else
void fog_shaft_begin(vec3 dir, float t0, float t1) {}
float fog_shaft_visible(vec3 dir, float t) { return 1.0; }
#endif
#endif

#if FOG_MODEL_KIND == FOG_MODEL_PERLIN || FOG_MODEL_KIND == FOG_MODEL_VOLUME || \
    FOG_MODEL_KIND == FOG_MODEL_FOGMAP
const int fog_piece_nodes = FOG_SHADOW_NODES > 0 ? FOG_SHADOW_NODES : 1;
uniform float fog_piece_x[4], fog_piece_w[4];
uniform mat4 fog_piece_partial;

// One piece of a per-piece mean (fog_piece_light in C): K at the piece's fog_piece_nodes
// Gauss nodes, its half-length h and centre `at` along dir. The piece's share of the light
// is e^{-D}(1 - e^{-dD}) exactly, dD its Gauss depth, times T_s V's mean weighted by tau K at
// the nodes (tau from the partial integral of K's polynomial, fog_piece_partial; a negative
// K weighs nothing): a ray lit throughout has a mean of 1 however thick its pieces. Adds
// the share to S and returns dD.
float fog_piece_light(float K[4], float h, float at, vec3 dir, float D, inout float S) {
  float piece = 0.0, weight = 0.0, weighted = 0.0, plain = 0.0, hd[4], least = 3.0e38;
  for (int j = 0; j < fog_piece_nodes; j++) {
    float dj = 0.0;
    for (int q = 0; q < fog_piece_nodes; q++) dj += fog_piece_partial[j][q] * K[q];
    hd[j] = h * dj;
    // tau relative to the largest of the nodes that weigh (K > 0): no underflow (relative
    // to an empty node's, a dense node's weight underflowed and the piece drew half-lit)
    if (K[j] > 0.0) least = min(least, hd[j]);
  }
  for (int j = 0; j < fog_piece_nodes; j++) {
    float tj = at + h * fog_piece_x[j];
    float f = fog_sun_node_light(dir, tj) * fog_shaft_visible(dir, tj);
    // 0 for an empty node: e^{least - hd} may overflow there (0 x inf is NaN)
    float wk = K[j] > 0.0 ? fog_piece_w[j] * K[j] * exp(least - hd[j]) : 0.0;
    weight += wk;
    weighted += wk * f;
    plain += fog_piece_w[j] * f;
    piece += h * fog_piece_w[j] * K[j];
  }
  float mean = weight > 0.0 ? weighted / weight : 0.5 * plain;  // the weights sum to 2
  S += exp(-D) * (piece * fog_exprel(piece)) * mean;
  return piece;
}
#endif

#if FOG_MODEL_KIND == FOG_MODEL_FOGMAP
// The fogmap's mean per piece of its exact walk (fog_fogmap_light_integral in C): the
// walk's own pieces through the approximation fog_light_extinction reads (the knot cells
// crossed, the profile's knots or the exponential's y0 + k H/2), fog_piece_nodes Gauss
// nodes each, tau at a node from the running depth and the piece's polynomial through its
// nodes; S / (1 - e^{-D}) of the same walk. Nothing to alias: the pieces follow the fog.
float fog_fogmap_sun_mean(fog_ray r) {
  float t0, t1;
  if (!fog_sun_span(r, t0, t1)) return 1.0;
  fog_shaft_begin(r.dir, t0, t1);
  fog_ray_walk w = fog_walk_start(fog_levels, r.dir_d,
                                  double(t0));
  float len = t1 - t0, t = 0.0, D = 0.0, S = 0.0;
  for (int guard = 0; t < len && D < fog_depth_limit && guard < 65536; guard++) {
    float tx = fog_axis_next(w.x), tz = fog_axis_next(w.z);
    float ty = fog_profile_next(w.y);
    float tn = min(min(len, tx), min(tz, ty));
    if (tn > t) {
#if FOG_FETCH_HARDWARE
      mat3 cell = mat3(0.0);
#else
      mat3 cell = fog_cell_load(w.grid, w.size, w.x.cell, w.z.cell);
#endif
      float h = 0.5 * (tn - t), mid = 0.5 * (tn + t), K[4];
      for (int j = 0; j < fog_piece_nodes; j++) {
        float tj = mid + h * fog_piece_x[j], g = 1.0;
        if (fog_profile_kind == FOG_PROFILE_EXPONENTIAL) {
          float y = w.y_entry + tj * w.dir_y;  // above y0
          g = y > 0.0 ? exp(-y * fog_profile_inv_scale_height) : 1.0;
        } else if (fog_profile_kind == FOG_PROFILE_BSPLINE) {
          g = fog_profile_bspline_value(w.y.cell, w.y.x0 + tj * w.y.dx);
        }
        // a negative K (ringing) weighs nothing, as in the segments' mean
        K[j] = max(fog_extinction_scale * fog_walk_value(w, cell, tj) * g, 0.0);
      }
      D += fog_piece_light(K, h, t0 + mid, r.dir, D, S);
    }
    if (tx <= tn) w.x.cell += w.x.step;
    if (tz <= tn) w.z.cell += w.z.step;
    if (ty <= tn) w.y.cell += w.y.step;
    t = max(t, tn);
  }
  return D > 0.0 ? S / (D * fog_exprel(D)) : 1.0;
}
#endif

#if FOG_MODEL_KIND == FOG_MODEL_VOLUME
// The volume's mean per lattice cell of its exact walk (fog_grid3d_light_integral in C):
// fog_piece_nodes Gauss nodes a cell piece, tau at a node from the running depth and the
// piece's polynomial through its nodes; S / (1 - e^{-D}) of the same walk.
float fog_grid3d_sun_mean(fog_ray r) {
  vec3 u0, du;
  float t0, t1;
  if (!fog_grid3d_stretch(r.dir, r.t_surface, u0, du, t0, t1)) return 1.0;
  fog_shaft_begin(r.dir, t0, t1);
  vec3 ue = u0 + t0 * du;
  fog_axis ax = fog_axis_start(ue.x, du.x, 0.0), ay = fog_axis_start(ue.y, du.y, 0.0),
           az = fog_axis_start(ue.z, du.z, 0.0);
  float len = t1 - t0, t = 0.0, D = 0.0, S = 0.0;
  for (int guard = 0; t < len && D < fog_depth_limit && guard < 65536; guard++) {
    float tx = fog_axis_next(ax), ty = fog_axis_next(ay), tz = fog_axis_next(az);
    float tn = min(min(len, tx), min(ty, tz));
    if (tn > t) {
      ivec3 c = ivec3(ax.cell, ay.cell, az.cell);
      fog_grid3d_cell cell = fog_grid3d_cell_load(c);
      vec3 f = ue - vec3(c);
      float h = 0.5 * (tn - t), mid = 0.5 * (tn + t), K[4];
      for (int j = 0; j < fog_piece_nodes; j++)
        K[j] = fog_grid3d_cell_value(cell, f + (mid + h * fog_piece_x[j]) * du);
      D += fog_piece_light(K, h, t0 + mid, r.dir, D, S);
    }
    if (tx <= tn) ax.cell += ax.step;
    if (ty <= tn) ay.cell += ay.step;
    if (tz <= tn) az.cell += az.step;
    t = max(t, tn);
  }
  return D > 0.0 ? S / (D * fog_exprel(D)) : 1.0;
}
#endif

#if FOG_MODEL_KIND == FOG_MODEL_PERLIN
// Perlin fog's mean per piece of its exact walk (fog_perlin_light_integral in C): every
// octave walked at once, fog_piece_nodes Gauss nodes on each piece between texel planes of
// any octave (cut where the height exponent moves by 1/2), tau at a node from the walk's
// running depth and the piece's polynomial through its nodes (fog_piece_partial[j][k]);
// the mean is S / (1 - e^{-D}) of the same walk.
float fog_perlin_sun_mean(fog_ray r) {
  float t0, t1;
  if (fog_model_extinction == 0.0 ||
      !fog_slab(fog_perlin_lo, fog_perlin_hi, vec3(0.0), r.dir, t0, t1))
    return 1.0;
  t0 = max(t0, 0.0);
  t1 = min(t1, r.t_surface);
  if (!(t1 > t0)) return 1.0;
  fog_shaft_begin(r.dir, t0, t1);
  vec3 dir = r.dir;
  vec3 ue[FOG_PERLIN_MAX_OCTAVES], du[FOG_PERLIN_MAX_OCTAVES];
  vec3 next[FOG_PERLIN_MAX_OCTAVES], delta[FOG_PERLIN_MAX_OCTAVES];
  for (int i = 0; i < fog_perlin_octaves; i++) {
    float s = fog_perlin_scale[i];
    ue[i] = fog_perlin_camera[i] + t0 * s * dir;
    du[i] = s * dir;
    vec3 c = floor(ue[i]);
    for (int a = 0; a < 3; a++) {
      if (du[i][a] > 0.0) {
        delta[i][a] = 1.0 / du[i][a];
        next[i][a] = (c[a] + 1.0 - ue[i][a]) / du[i][a];
      } else if (du[i][a] < 0.0) {
        delta[i][a] = -1.0 / du[i][a];
        next[i][a] = (c[a] - ue[i][a]) / du[i][a];
      } else {
        delta[i][a] = FOG_INFINITY;
        next[i][a] = FOG_INFINITY;
      }
    }
  }
  float len = t1 - t0, t = 0.0, D = 0.0, S = 0.0, y_entry = t0 * dir.y;
  float inv_h = 1.0 / fog_model_scale_height;
  for (int guard = 0; t < len && D < fog_depth_limit && guard < 65536; guard++) {
    float tn = len;
    for (int i = 0; i < fog_perlin_octaves; i++)
      tn = min(tn, min(next[i].x, min(next[i].y, next[i].z)));
    if (tn > t) {
      fog_perlin_cell cells[FOG_PERLIN_MAX_OCTAVES];
      vec3 f0[FOG_PERLIN_MAX_OCTAVES];
      for (int i = 0; i < fog_perlin_octaves; i++) {
        vec3 c = floor(ue[i] + (0.5 * (t + tn)) * du[i]);
        cells[i] = fog_perlin_cell_load(i, ivec3(c));
        f0[i] = ue[i] - c;
      }
      int cuts = max(int(ceil(abs(dir.y) * (tn - t) * inv_h * 2.0)), 1);
      float h = 0.5 * (tn - t) / float(cuts);
      for (int k = 0; k < cuts; k++) {
        float centre = t + float(2 * k + 1) * h;
        float K[4];
        for (int j = 0; j < fog_piece_nodes; j++) {
          float tj = centre + h * fog_piece_x[j], turbulence = 0.0;
          for (int i = 0; i < fog_perlin_octaves; i++)
            turbulence += exp2(-float(i)) * fog_perlin_cell_value(cells[i], f0[i] + tj * du[i]);
          K[j] = fog_model_extinction * exp(-(y_entry + tj * dir.y - fog_model_y0) * inv_h) *
                 turbulence;
        }
        D += fog_piece_light(K, h, t0 + centre, dir, D, S);
      }
    }
    for (int i = 0; i < fog_perlin_octaves; i++) {
      if (next[i].x <= tn) next[i].x += delta[i].x;
      if (next[i].y <= tn) next[i].y += delta[i].y;
      if (next[i].z <= tn) next[i].z += delta[i].z;
    }
    t = max(t, tn);
  }
  return D > 0.0 ? S / (D * fog_exprel(D)) : 1.0;  // 1 - e^{-D} without cancellation
}
#endif

// The tau K-weighted mean of T_s V along the ray (1 where the ray holds no fog), over
// fog_shadow_steps equal segments, cut at the quadrics' surfaces, of fog_shadow_nodes
// samples (fog_sun_mean_light in C):
// 1, the midpoint; 2, the Gauss-Legendre nodes m -+ dt/(2 sqrt 3), the segment's depth
// their 2-node sum and its T_s V theirs weighted by K e^{-d} (d from the segment's start to
// the node, K linear through the nodes; taken relative to node a's). Segment i weighs e^{-D_i} (1 - e^{-dD_i}) either
// way, so with T_s V = 1 the mean is 1.
// FOG_SHADOW_NODES (1 or 2) and FOG_SHADOW_PIECES are specialisation constants: as a
// uniform, the two-node branch cost the one-node loop 40 % on llvmpipe.
float fog_sun_mean_transmittance(fog_ray r) {
#if FOG_SUN_SHADOW == 3
  return 0.0;
#elif !FOG_LIGHT_MARCH
  return 1.0;
#else
#if FOG_MODEL_KIND == FOG_MODEL_PERLIN && FOG_SHADOW_PIECES
  return fog_perlin_sun_mean(r);
#elif FOG_MODEL_KIND == FOG_MODEL_VOLUME && FOG_SHADOW_PIECES
  return fog_grid3d_sun_mean(r);
#elif FOG_MODEL_KIND == FOG_MODEL_FOGMAP && FOG_SHADOW_PIECES
  return fog_fogmap_sun_mean(r);
#endif
  float t0, t1;
  if (!fog_sun_span(r, t0, t1)) return 1.0;
  // A negative K (wavelet ringing, rounding) weighs nothing (fog_sun_mean_light in C).
  const float g = 0.28867513459481288;  // 1/(2 sqrt 3)
  float dt = (t1 - t0) / float(fog_shadow_steps), before = 0.0, weights = 0.0, lit = 0.0;
  float start = t0;
#if FOG_MODEL_KIND == FOG_MODEL_QUADRIC || FOG_QUADRICS_BESIDE
  // segments cut where the ray crosses a quadric's surface: K jumps or kinks there (a hard
  // edge inside a segment drew rings; fog_sun_mean_light in C)
  float cuts[FOG_QUADRIC_MAX_CUTS];
  int cut_count = fog_quadric_cuts(r.dir, t0, t1, cuts);
#else
  float cuts[1];
  const int cut_count = 0;
#endif
  // Past an optical depth of fog_depth_limit (early termination) the rest weighs less than
  // the transmittance cut-off: stop there.
  // A piece deeper than FOG_SUN_PIECE_MAX_DEPTH is cut where its estimated depth reaches
  // it, until it is not, at most fog_shadow_steps cuts a ray (fog_sun_mean_light in C:
  // thick fog's weight lies in the first units past its start, which two nodes missed; the
  // cut meets the piece's end at the limit, so the mean stays continuous across pixels).
  const float max_depth = 1.0;  // FOG_SUN_PIECE_MAX_DEPTH (render/fog_sun_shadow.h)
  int deep_cuts = 0;
  for (int i = 0; i < fog_shadow_steps && before < fog_depth_limit;) {
    // [start, end]: the rest of equal segment i up to the next cut
    float step_end = i + 1 < fog_shadow_steps ? t0 + float(i + 1) * dt : t1, end = step_end;
    for (int c = 0; c < cut_count; c++)
      if (cuts[c] > start && cuts[c] < end) end = cuts[c];
    float len, mid, step_depth, ka = 0.0, kb = 0.0, light;
    for (;;) {
      len = end - start;
      mid = 0.5 * (start + end);
#if FOG_SHADOW_NODES == 2
      ka = max(fog_light_extinction(r.dir, mid - g * len), 0.0);
      kb = max(fog_light_extinction(r.dir, mid + g * len), 0.0);
      step_depth = 0.5 * len * (ka + kb);
#else
      step_depth = max(fog_light_extinction(r.dir, mid), 0.0) * len;
#endif
      if (!(step_depth > max_depth) || deep_cuts >= fog_shadow_steps) break;
      end = start + len * max(max_depth / step_depth, 1.0 / 64.0);  // >= 1/64: no empty pieces
      deep_cuts++;
    }
    if (end >= step_end) i++;
    start = end;
#if FOG_SHADOW_NODES == 2
    {
      float ta = mid - g * len, tb = mid + g * len;
      // the nodes' weights relative to node a's, K_a : K_b e^{-g len (K_a + K_b)}: absolute
      // ones (e^{-d} from the segment's start) underflowed together past d ~ 90 and a dense
      // segment drew no light (fog_sun_mean_light in C)
      float sa = ka, sb = kb * exp(-g * len * (ka + kb));
      float lb = fog_sun_node_light(r.dir, tb);
      light = sa + sb > 0.0 ? (sa * fog_sun_node_light(r.dir, ta) + sb * lb) / (sa + sb) : lb;
    }
#else
    light = fog_sun_node_light(r.dir, mid);
#endif
    light *= fog_sun_segment_visible(r.dir, mid, len);
    float w = exp(-before) * step_depth * fog_exprel(step_depth);  // 1 - e^-x, no cancellation
    weights += w;
    lit += w * light;
    before += step_depth;
  }
  return weights > 0.0 ? lit / weights : 1.0;
#endif
}

// The light's own set-up of the pixel's view ray (unit dir_d, surface at t_surface), for
// the sun's mean and the lamps: the fogmap's box span (the upsampling pass skips the
// walk's).
fog_ray fog_light_ray(dvec3 dir_d, float t_surface) {
  double t_in = 1.0, t_out = 0.0;
#if FOG_MODEL_KIND == FOG_MODEL_FOGMAP
  if (!fog_box_entry_exit(dir_d, t_in, t_out)) t_in = 1.0, t_out = 0.0;
#endif
  return fog_ray(dir_d, vec3(dir_d), t_in, t_out, t_surface, 0.5);
}

// The sun's share of the in-scatter of the pixel's view ray: the mean above.
float fog_sun_light(dvec3 dir_d, float t_surface) {
#if FOG_LIGHT_MARCH
  return fog_sun_mean_transmittance(fog_light_ray(dir_d, t_surface));
#else
  return fog_sun_mean_transmittance(fog_ray(dir_d, vec3(dir_d), 1.0, 0.0, t_surface, 0.5));
#endif
}
