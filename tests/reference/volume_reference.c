/* The volume for the light reference (volume_reference.h). */
#include "reference/volume_reference.h"

#include <math.h>

static void index_of(const volume_grid_desc *g, const double x[3], double u[3]) {
  for (int c = 0; c < 3; c++) u[c] = g->index_from_world[c][c] * x[c] + g->index_offset[c];
}

static double voxel(const volume_grid_desc *g, long i, long j, long k) {
  if (i < 0 || j < 0 || k < 0 || i >= g->dim[0] || j >= g->dim[1] || k >= g->dim[2]) return 0;
  return g->values[((size_t)k * g->dim[1] + j) * g->dim[0] + i];
}

static double volume_density(const light_ref_medium *m, const double x[3]) {
  const volume_grid_desc *g = m->user;
  double u[3];
  index_of(g, x, u);
  long i = (long)floor(u[0]), j = (long)floor(u[1]), k = (long)floor(u[2]);
  double fx = u[0] - i, fy = u[1] - j, fz = u[2] - k, sum = 0;
  for (int dz = 0; dz < 2; dz++)
    for (int dy = 0; dy < 2; dy++)
      for (int dx = 0; dx < 2; dx++)
        sum += (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz) *
               voxel(g, i + dx, j + dy, k + dz);
  return sum;
}

static int volume_breaks(const light_ref_medium *m, const double o[3], const double d[3],
                         double t0, double t1, double *out, int capacity) {
  const volume_grid_desc *g = m->user;
  int count = 0;
  for (int c = 0; c < 3; c++) {
    double s = g->index_from_world[c][c];
    if (d[c] == 0 || s == 0) continue;
    double ua = s * (o[c] + t0 * d[c]) + g->index_offset[c],
           ub = s * (o[c] + t1 * d[c]) + g->index_offset[c];
    for (double k = ceil(fmin(ua, ub)); k <= floor(fmax(ua, ub)); k++) {
      double t = ((k - g->index_offset[c]) / s - o[c]) / d[c];
      if (t > t0 && t < t1) {
        if (count < capacity) out[count] = t;
        count++;
      }
    }
  }
  return count;
}

light_ref_medium light_ref_volume_medium(const volume_grid_desc *g) {
  light_ref_medium m = {.density = volume_density, .user = g, .breaks = volume_breaks};
  for (int c = 0; c < 3; c++) { /* the support u in [-1, dim] */
    double s = g->index_from_world[c][c];
    double a = (-1.0 - g->index_offset[c]) / s, b = (g->dim[c] - g->index_offset[c]) / s;
    m.box_min[c] = fmin(a, b), m.box_max[c] = fmax(a, b);
  }
  return m;
}
