/* Double-precision 3-vector helpers for the CPU geometry (terrain hits, frustum planes). */
#ifndef FOGPIPE_RENDER_VEC3_H
#define FOGPIPE_RENDER_VEC3_H

static inline void vec3_sub(const double a[3], const double b[3], double r[3]) {
  r[0] = a[0] - b[0], r[1] = a[1] - b[1], r[2] = a[2] - b[2];
}

static inline void vec3_cross(const double a[3], const double b[3], double r[3]) {
  r[0] = a[1] * b[2] - a[2] * b[1];
  r[1] = a[2] * b[0] - a[0] * b[2];
  r[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double vec3_dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

#endif
