/* Perlin fog for the light reference (perlin_reference.h). */
#include "reference/perlin_reference.h"

#include <math.h>

double perlin_ref_turbulence(const fog_perlin *p, double time, const double x[3]) {
  const int n = p->desc.size;
  double sum = 0;
  for (int i = 0; i < p->desc.octaves; i++) {
    double s = pow(2.0, i) * FOG_PERLIN_TEXELS_PER_LATTICE / p->desc.feature_size;
    double u[3], f[3];
    long c[3];
    for (int a = 0; a < 3; a++) {
      u[a] = (x[a] - p->desc.wind[i][a] * time) * s;
      c[a] = (long)floor(u[a]);
      f[a] = u[a] - floor(u[a]);
    }
    double v = 0;
    for (int dz = 0; dz < 2; dz++)
      for (int dy = 0; dy < 2; dy++)
        for (int dx = 0; dx < 2; dx++) {
          long X = ((c[0] + dx) % n + n) % n, Y = ((c[1] + dy) % n + n) % n,
               Z = ((c[2] + dz) % n + n) % n;
          double w = (dx ? f[0] : 1 - f[0]) * (dy ? f[1] : 1 - f[1]) * (dz ? f[2] : 1 - f[2]);
          v += w * p->texels[(((size_t)i * n + Z) * n + Y) * n + X];
        }
    sum += v / pow(2.0, i);
  }
  return sum;
}

static double perlin_density(const light_ref_medium *lm, const double x[3]) {
  const fog_perlin *p = lm->user;
  const fog_perlin_medium *m = lm->user2;
  return m->extinction * exp(-(x[1] - m->y0) / m->scale_height) *
         perlin_ref_turbulence(p, m->time, x);
}

static int perlin_breaks(const light_ref_medium *lm, const double o[3], const double d[3],
                         double t0, double t1, double *out, int capacity) {
  const fog_perlin *p = lm->user;
  const fog_perlin_medium *m = lm->user2;
  int count = 0;
  for (int i = 0; i < p->desc.octaves; i++) {
    double s = pow(2.0, i) * FOG_PERLIN_TEXELS_PER_LATTICE / p->desc.feature_size;
    for (int a = 0; a < 3; a++) {
      if (d[a] == 0) continue;
      double ua = (o[a] + t0 * d[a] - p->desc.wind[i][a] * m->time) * s,
             ub = (o[a] + t1 * d[a] - p->desc.wind[i][a] * m->time) * s;
      for (double k = ceil(fmin(ua, ub)); k <= floor(fmax(ua, ub)); k++) {
        double t = (k / s + p->desc.wind[i][a] * m->time - o[a]) / d[a];
        if (t > t0 && t < t1) {
          if (count < capacity) out[count] = t;
          count++;
        }
      }
    }
  }
  return count;
}

light_ref_medium light_ref_perlin_medium(const fog_perlin *p, const fog_perlin_medium *m) {
  light_ref_medium lm = {.density = perlin_density, .user = p, .user2 = m,
                         .breaks = perlin_breaks};
  for (int a = 0; a < 3; a++) lm.box_min[a] = p->desc.lo[a], lm.box_max[a] = p->desc.hi[a];
  return lm;
}
