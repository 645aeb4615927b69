/* How good is the 2.5D model? Transmittance of the original 3D grid (trilinear, fine
 * midpoint march) against K = f(x,z)·g(y) (f a linear B-spline on the fogmap's cell
 * centres, g the fitted profile), on the same parallel rays and the same sample points,
 * for views at several elevations. Both integrals use the same step, so the difference
 * is the 2.5D model's error, not the quadrature's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim/ray_box.h"
#include "sim/vdb_import.h"

typedef struct volume3d {
  const vdb_dense_grid *grid;
  const vdb_world_map *world;
  int world_axis_of[3]; /* fogpipe world axis fed by source axis c */
} volume3d;

/* Trilinear density of the 3D grid at a world point (zero outside the dense box). */
static double density_3d(const volume3d *v, const double p[3]) {
  const vdb_dense_grid *g = v->grid;
  double u[3];
  int i0[3];
  double w[3];
  for (int c = 0; c < 3; c++) {
    const int a = v->world_axis_of[c];
    u[c] = (p[a] - v->world->base[a]) / v->world->step[a] - g->index_min[c];
    const double fl = floor(u[c]);
    i0[c] = (int)fl;
    w[c] = u[c] - fl;
    if (i0[c] < -1 || i0[c] >= g->dim[c]) return 0;
  }
  double sum = 0;
  for (int dz = 0; dz < 2; dz++) {
    const int k = i0[2] + dz;
    if (k < 0 || k >= g->dim[2]) continue;
    const double wz = dz ? w[2] : 1 - w[2];
    for (int dy = 0; dy < 2; dy++) {
      const int j = i0[1] + dy;
      if (j < 0 || j >= g->dim[1]) continue;
      const double wy = dy ? w[1] : 1 - w[1];
      const float *row = g->values + ((size_t)k * g->dim[1] + (size_t)j) * g->dim[0];
      for (int dx = 0; dx < 2; dx++) {
        const int i = i0[0] + dx;
        if (i < 0 || i >= g->dim[0]) continue;
        sum += wz * wy * (dx ? w[0] : 1 - w[0]) * row[i];
      }
    }
  }
  return sum;
}

/* f(x,z): the degree-1 B-spline with the fogmap values on the cell centres. */
static double fogmap_bilinear(const fogmap *map, const vdb_fogmap_place *place, double x,
                              double z) {
  const double u = (x - place->origin_x) / place->cell_size - 0.5;
  const double v = (z - place->origin_z) / place->cell_size - 0.5;
  const int i0 = (int)floor(u), j0 = (int)floor(v);
  const double wu = u - i0, wv = v - j0;
  double sum = 0;
  for (int dj = 0; dj < 2; dj++) {
    const int j = j0 + dj;
    if (j < 0 || j >= map->height) continue;
    for (int di = 0; di < 2; di++) {
      const int i = i0 + di;
      if (i < 0 || i >= map->width) continue;
      sum += (dj ? wv : 1 - wv) * (di ? wu : 1 - wu) * map->density[(size_t)j * map->width + i];
    }
  }
  return sum;
}

int vdb_report_geometry(const vdb_dense_grid *grid, const vdb_world_map *world,
                        const vdb_fogmap_place *place, const vdb_profile *profile,
                        const vdb_report_desc *desc, double lo[3], double hi[3], double *y_mid,
                        double *step, fog_error *err) {
  const double step_fraction = desc && desc->step > 0 ? desc->step : 0.25;
  for (int a = 0; a < 3; a++) {
    const int c = world->index_axis[a];
    const double e1 = world->base[a] + world->step[a] * (grid->index_min[c] - 1.0);
    const double e2 = world->base[a] + world->step[a] * (grid->index_min[c] + grid->dim[c]);
    lo[a] = fmin(e1, e2);
    hi[a] = fmax(e1, e2);
  }
  lo[0] = fmin(lo[0], place->origin_x);
  hi[0] = fmax(hi[0], place->origin_x + place->width * place->cell_size);
  lo[2] = fmin(lo[2], place->origin_z);
  hi[2] = fmax(hi[2], place->origin_z + place->height * place->cell_size);
  lo[1] = fmin(lo[1], profile->y_bottom);
  hi[1] = fmax(hi[1], profile->y_top);
  double cell = fmin(fabs(world->step[0]), fmin(fabs(world->step[1]), fabs(world->step[2])));
  cell = fmin(cell, place->cell_size);
  *step = step_fraction * cell;
  *y_mid = 0.5 * (lo[1] + hi[1]);
  if (!(*step > 0) || !isfinite(*step)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "report: degenerate step %g", *step);
    return 1;
  }
  return 0;
}

void vdb_report_direction(double elevation_deg, int azimuth, int azimuths, double dir[3]) {
  const double pi = 3.14159265358979323846;
  const double el = elevation_deg * pi / 180, phi = (azimuth + 0.5) * 2 * pi / azimuths;
  dir[0] = cos(el) * cos(phi);
  dir[1] = -sin(el);
  dir[2] = cos(el) * sin(phi);
}

int vdb_report_run(const vdb_dense_grid *grid, const vdb_world_map *world, const fogmap *map,
                   const vdb_fogmap_place *place, const vdb_profile *profile,
                   const vdb_report_desc *desc, vdb_report_row *rows, int row_count,
                   fog_error *err) {
  const int side = desc && desc->rays_per_side > 0 ? desc->rays_per_side : 48;
  const int azimuths = desc && desc->azimuths > 0 ? desc->azimuths : 4;
  double *reference = desc ? desc->reference_depth : NULL;
  volume3d v = {.grid = grid, .world = world};
  for (int a = 0; a < 3; a++) v.world_axis_of[world->index_axis[a]] = a;
  double lo[3], hi[3], y_mid, step;
  if (vdb_report_geometry(grid, world, place, profile, desc, lo, hi, &y_mid, &step, err))
    return 1;
  for (int r = 0; r < row_count; r++) {
    double sum_err = 0, max_err = 0, sum_t = 0;
    int rays = 0;
    for (int az = 0; az < azimuths; az++) {
      double d[3];
      vdb_report_direction(rows[r].elevation_deg, az, azimuths, d);
      for (int iz = 0; iz < side; iz++)
        for (int ix = 0; ix < side; ix++) {
          double *ref = reference ? reference + (((size_t)r * azimuths + az) * side + iz) * side + ix
                                  : NULL;
          if (ref) *ref = -1;
          /* the ray through a point of the mid-height plane over the footprint */
          const double o[3] = {lo[0] + (ix + 0.5) * (hi[0] - lo[0]) / side, y_mid,
                               lo[2] + (iz + 0.5) * (hi[2] - lo[2]) / side};
          double t0, t1;
          if (!ray_box_clip(o, d, lo, hi, &t0, &t1)) continue;
          int n = (int)ceil((t1 - t0) / step);
          if (n < 1) n = 1;
          const double dt = (t1 - t0) / n;
          double tau3 = 0, tau25 = 0;
          for (int s = 0; s < n; s++) {
            const double t = t0 + (s + 0.5) * dt;
            const double p[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
            tau3 += density_3d(&v, p);
            tau25 += fogmap_bilinear(map, place, p[0], p[2]) * vdb_profile_eval(profile, p[1]);
          }
          tau3 *= dt;
          tau25 *= dt;
          if (ref) *ref = tau3;
          if (tau3 < 1e-4) continue;
          const double e = fabs(exp(-tau25) - exp(-tau3));
          sum_err += e;
          max_err = fmax(max_err, e);
          sum_t += exp(-tau3);
          rays++;
        }
    }
    rows[r].rays = rays;
    rows[r].mean_abs_error = rays ? sum_err / rays : 0;
    rows[r].max_abs_error = max_err;
    rows[r].mean_transmittance = rays ? sum_t / rays : 1;
  }
  return 0;
}
