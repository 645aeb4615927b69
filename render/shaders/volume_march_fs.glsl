#version 430 core
// The GL ray march of a dense 3D grid (render/volume_march.h): fragment (ix, side-1-iz) is
// ray (ix, iz) of one orthographic view; the same origins, clipping and midpoint samples as
// the CPU march in sim/vdb_report.c, trilinear by the hardware (zero border).
layout(location = 0) out float march_out_depth;

uniform sampler3D march_density;
uniform mat3 march_index_from_world;  // u = M p + offset, u in voxel-centre units
uniform vec3 march_index_offset;
uniform vec3 march_dims;
uniform vec3 march_lo;
uniform vec3 march_hi;
uniform vec3 march_dir;
uniform float march_y_mid;
uniform int march_side;
uniform float march_step;

void main() {
  int ix = int(gl_FragCoord.x), iz = march_side - 1 - int(gl_FragCoord.y);
  vec3 o = vec3(march_lo.x + (float(ix) + 0.5) * (march_hi.x - march_lo.x) / float(march_side),
                march_y_mid,
                march_lo.z + (float(iz) + 0.5) * (march_hi.z - march_lo.z) / float(march_side));
  // Slab clip of the whole line (sim/ray_box.c).
  float t0 = -1e30, t1 = 1e30;
  for (int a = 0; a < 3; a++) {
    if (abs(march_dir[a]) < 1e-15) {
      if (o[a] < march_lo[a] || o[a] > march_hi[a]) t1 = -1e30;
      continue;
    }
    float ta = (march_lo[a] - o[a]) / march_dir[a], tb = (march_hi[a] - o[a]) / march_dir[a];
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  if (!(t0 <= t1)) {
    march_out_depth = -1.0;
    return;
  }
  int n = int(ceil((t1 - t0) / march_step));
  float dt = (t1 - t0) / float(max(n, 1)), sum = 0.0;
  // Index position along the ray is affine in t: u(t) = u(o) + t M dir.
  vec3 u0 = march_index_from_world * o + march_index_offset;
  vec3 du = march_index_from_world * march_dir;
  for (int s = 0; s < n; s++) {
    float t = t0 + (float(s) + 0.5) * dt;
    sum += texture(march_density, (u0 + t * du + 0.5) / march_dims).r;
  }
  march_out_depth = sum * dt;
}
