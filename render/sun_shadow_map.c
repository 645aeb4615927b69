/* The sun shadow map's light space (render/sun_shadow_map.h). */
#include "render/sun_shadow_map.h"

#include <math.h>

void sun_shadow_map_fit(sun_shadow_map *map, const double sun[3], const double box_min[3],
                        const double box_max[3]) {
  double *e0 = map->axis[0], *e1 = map->axis[1], *s = map->axis[2];
  for (int c = 0; c < 3; c++) s[c] = map->sun[c] = sun[c];
  /* e0 = up x sun (horizontal), e1 = sun x e0; a sun at the zenith takes x as reference */
  double ref[3] = {0, 1, 0};
  if (fabs(sun[1]) > 0.99) ref[0] = 1, ref[1] = 0;
  e0[0] = ref[1] * s[2] - ref[2] * s[1];
  e0[1] = ref[2] * s[0] - ref[0] * s[2];
  e0[2] = ref[0] * s[1] - ref[1] * s[0];
  double n = sqrt(e0[0] * e0[0] + e0[1] * e0[1] + e0[2] * e0[2]);
  for (int c = 0; c < 3; c++) e0[c] /= n;
  e1[0] = s[1] * e0[2] - s[2] * e0[1];
  e1[1] = s[2] * e0[0] - s[0] * e0[2];
  e1[2] = s[0] * e0[1] - s[1] * e0[0];
  for (int c = 0; c < 3; c++) map->centre[c] = 0.5 * (box_min[c] + box_max[c]);
  for (int a = 0; a < 3; a++) map->lo[a] = HUGE_VAL, map->hi[a] = -HUGE_VAL;
  for (int corner = 0; corner < 8; corner++) {
    double p[3];
    for (int c = 0; c < 3; c++)
      p[c] = (((corner >> c) & 1) ? box_max[c] : box_min[c]) - map->centre[c];
    for (int a = 0; a < 3; a++) {
      double d = p[0] * map->axis[a][0] + p[1] * map->axis[a][1] + p[2] * map->axis[a][2];
      map->lo[a] = fmin(map->lo[a], d), map->hi[a] = fmax(map->hi[a], d);
    }
  }
  /* a margin of a few texels around, and depth room on both ends */
  for (int a = 0; a < 3; a++) {
    double pad = 0.01 * (map->hi[a] - map->lo[a]) + 1e-6;
    map->lo[a] -= pad, map->hi[a] += pad;
  }
}

void sun_shadow_map_matrix(const sun_shadow_map *map, const double origin[3], double m[4][4]) {
  double rel[3]; /* origin - centre: a point r from the origin is at r + rel from the centre */
  for (int c = 0; c < 3; c++) rel[c] = origin[c] - map->centre[c];
  for (int a = 0; a < 3; a++) {
    const double *e = map->axis[a];
    double along = e[0] * rel[0] + e[1] * rel[1] + e[2] * rel[2];
    double span = map->hi[a] - map->lo[a];
    /* u, v = (x - lo) / span; depth = (hi - z) / span */
    double k = a < 2 ? 1.0 / span : -1.0 / span;
    double base = a < 2 ? -map->lo[a] / span : map->hi[a] / span;
    for (int c = 0; c < 3; c++) m[a][c] = k * e[c];
    m[a][3] = k * along + base;
  }
  m[3][0] = m[3][1] = m[3][2] = 0.0, m[3][3] = 1.0;
}

double sun_shadow_map_texel(const sun_shadow_map *map) {
  return fmax(map->hi[0] - map->lo[0], map->hi[1] - map->lo[1]) / map->size;
}
