/* The lamps' shadow cubes: their GL-free placement (render/lamp_shadow_map.h). */
#include "render/lamp_shadow_map.h"

#include <math.h>

/* GL's cube-map face selection (the OpenGL 4.5 spec, table 8.19): for direction v and
 * face f, s = sc / ma and t = tc / ma in [-1, 1], each a signed component of v. */
static const struct {
  int sc_axis, tc_axis, ma_axis;
  double sc_sign, tc_sign, ma_sign;
} faces[6] = {
    {2, 1, 0, -1, -1, +1}, /* +X */
    {2, 1, 0, +1, -1, -1}, /* -X */
    {0, 2, 1, +1, +1, +1}, /* +Y */
    {0, 2, 1, +1, -1, -1}, /* -Y */
    {0, 1, 2, +1, -1, +1}, /* +Z */
    {0, 1, 2, -1, -1, -1}, /* -Z */
};

double lamp_shadow_far(const double p[3], const double lo[3], const double hi[3]) {
  double d2 = 0.0;
  for (int c = 0; c < 3; c++) {
    double g = fmax(fabs(lo[c] - p[c]), fabs(hi[c] - p[c]));
    d2 += g * g;
  }
  return 1.01 * sqrt(d2) + 1.0;
}

void lamp_shadow_face_clip(int face, double near_plane, double far_plane, double m[4][4]) {
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) m[r][c] = 0.0;
  m[0][faces[face].sc_axis] = faces[face].sc_sign;
  m[1][faces[face].tc_axis] = faces[face].tc_sign;
  m[3][faces[face].ma_axis] = faces[face].ma_sign;
  /* z: depth from near to far onto [-1, 1] (clipping only: the map's value is written as
   * distance / far by the fragment shader) */
  const double a = (far_plane + near_plane) / (far_plane - near_plane);
  const double b = -2.0 * far_plane * near_plane / (far_plane - near_plane);
  m[2][faces[face].ma_axis] = a * faces[face].ma_sign;
  m[2][3] = b;
}

/* The largest value of the linear function k . v over the box [lo, hi]. */
static double box_max(const double k[3], const double lo[3], const double hi[3]) {
  double s = 0.0;
  for (int c = 0; c < 3; c++) s += fmax(k[c] * lo[c], k[c] * hi[c]);
  return s;
}

bool lamp_shadow_face_culls_box(int face, const double lo[3], const double hi[3]) {
  double sc[3] = {0}, tc[3] = {0}, ma[3] = {0};
  sc[faces[face].sc_axis] = faces[face].sc_sign;
  tc[faces[face].tc_axis] = faces[face].tc_sign;
  ma[faces[face].ma_axis] = faces[face].ma_sign;
  /* the face's pyramid: ma -+ sc >= 0 and ma -+ tc >= 0 */
  for (int side = 0; side < 4; side++) {
    const double *e = side < 2 ? sc : tc;
    const double sign = side & 1 ? -1.0 : 1.0;
    double k[3];
    for (int c = 0; c < 3; c++) k[c] = ma[c] + sign * e[c];
    if (box_max(k, lo, hi) < 0.0) return true;
  }
  return false;
}

bool lamp_shadow_face_needed(const fog_lamp *lamp, int face) {
  if (lamp->kind != FOG_LAMP_SPOT) return true;
  const double corner = atan(sqrt(2.0)); /* 54.7 degrees: a face's centre to its corner */
  double along = faces[face].ma_sign * lamp->axis[faces[face].ma_axis];
  double apart = acos(fmin(fmax(along, -1.0), 1.0));
  return apart <= acos(fmin(fmax(lamp->cos_outer, -1.0), 1.0)) + corner + 1e-9;
}

bool lamp_shadow_same_placement(const fog_lamp *was, const fog_lamp *now) {
  if (was->kind != now->kind) return false;
  for (int c = 0; c < 3; c++)
    if (was->position[c] != now->position[c]) return false;
  if (now->kind != FOG_LAMP_SPOT) return true;
  for (int c = 0; c < 3; c++)
    if (was->axis[c] != now->axis[c]) return false;
  return was->cos_outer == now->cos_outer;
}

lamp_shadow_uniforms lamp_shadow_maps_uniforms(const lamp_shadow_maps *maps) {
  lamp_shadow_uniforms u = {.slack = (float)(LAMP_SHADOW_SLACK_TEXELS * 2.0 / maps->size),
                            .lift = (float)maps->lift_per_distance};
  for (int i = 0; i < maps->count && i < FOG_MAX_LAMPS; i++) u.inv_far[i] = (float)(1.0 / maps->far[i]);
  return u;
}
