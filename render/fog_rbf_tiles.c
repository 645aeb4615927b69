/* Per-tile lists of Gaussian RBFs (render/fog_rbf_tiles.h). */
#include "render/fog_rbf_tiles.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

double fog_rbf_cull_radius(const fog_rbf *g, int count) {
  /* c r sqrt(pi) exp(-R^2 / r^2) = bound / count */
  double reach = g->density * g->radius * 1.7724538509055160273 * count / FOG_RBF_CULL_BOUND;
  return reach > 1.0 ? g->radius * sqrt(log(reach)) : -1.0;
}

static int grow(fog_rbf_tiles *t, size_t need, fog_error *err) {
  if (need <= t->index_capacity) return 0;
  if (need > UINT32_MAX) { /* a tile's first index is a uint32 */
    fog_fail(err, FOG_ERR_UNSUPPORTED, "RBF tiles: %zu indices, more than 2^32", need);
    return 1;
  }
  size_t capacity = t->index_capacity ? t->index_capacity : 4096;
  while (capacity < need) capacity *= 2;
  uint32_t *more = realloc(t->indices, capacity * sizeof *more);
  if (!more) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "RBF tiles: out of memory (%zu indices)", need);
    return 1;
  }
  t->indices = more;
  t->index_capacity = capacity;
  return 0;
}

int fog_rbf_tiles_build(fog_rbf_tiles *t, const camera *cam, int width, int height,
                        const fog_rbf *rbfs, int count, fog_error *err) {
  const int T = FOG_RBF_TILE_SIZE, tx = (width + T - 1) / T, ty = (height + T - 1) / T;
  if (tx != t->tiles_x || ty != t->tiles_y || !t->ranges) {
    free(t->ranges);
    t->ranges = malloc((size_t)tx * ty * 2 * sizeof *t->ranges);
    if (!t->ranges) {
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "RBF tiles: out of memory (%d x %d)", tx, ty);
      t->tiles_x = t->tiles_y = 0;
      return 1;
    }
    t->tiles_x = tx, t->tiles_y = ty;
  }
  /* Per Gaussian, once: the direction to its centre, and its sphere's angular radius beta
   * as sin and cos (d <= R: the camera inside the sphere, every tile sees it). */
  typedef struct seen_from {
    double dir[3], sin_beta, cos_beta;
    bool around; /* the camera inside its sphere */
    bool culled; /* never reaches the bound */
  } seen_from;
  seen_from *from = malloc((size_t)(count > 0 ? count : 1) * sizeof *from);
  if (!from) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "RBF tiles: out of memory (%d RBFs)", count);
    return 1;
  }
  const double *origin = cam->position; /* every pixel ray starts there (camera_ray) */
  for (int g = 0; g < count; g++) {
    seen_from *f = &from[g];
    double radius = fog_rbf_cull_radius(&rbfs[g], count), v[3];
    for (int a = 0; a < 3; a++) v[a] = rbfs[g].centre[a] - origin[a];
    double d = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    f->culled = !(radius >= 0.0);
    f->around = !f->culled && d <= radius;
    if (f->culled || f->around) continue;
    for (int a = 0; a < 3; a++) f->dir[a] = v[a] / d;
    f->sin_beta = radius / d;
    f->cos_beta = sqrt(1.0 - f->sin_beta * f->sin_beta);
  }
  t->index_count = 0;
  for (int j = 0; j < ty; j++)
    for (int i = 0; i < tx; i++) {
      /* The tile's corner pixels (GL rows: y_gl = height - 1 - image row), their rays, and
       * the cone around them: axis their normalised sum, half-angle theta the widest corner.
       * A sphere at angle phi from the axis meets the cone when phi <= theta + beta, i.e.
       * cos phi >= cos(theta + beta) (always when theta + beta >= pi). The cone holds every
       * ray of the tile while theta < 90 degrees: a cap that small is convex on the sphere,
       * and the tile's rays are the convex hull of its corners'. */
      const int x[2] = {i * T, (i + 1) * T - 1 < width - 1 ? (i + 1) * T - 1 : width - 1};
      const int y[2] = {j * T, (j + 1) * T - 1 < height - 1 ? (j + 1) * T - 1 : height - 1};
      double corner[4][3], axis[3] = {0, 0, 0}, unused[3];
      for (int k = 0; k < 4; k++) {
        camera_ray(cam, x[k & 1], height - 1 - y[k >> 1], width, height, unused, corner[k]);
        for (int a = 0; a < 3; a++) axis[a] += corner[k][a];
      }
      double n = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
      double cos_theta = 1.0;
      for (int a = 0; a < 3; a++) axis[a] /= n;
      for (int k = 0; k < 4; k++)
        cos_theta = fmin(cos_theta, axis[0] * corner[k][0] + axis[1] * corner[k][1] +
                                        axis[2] * corner[k][2]);
      /* rounded down a little: the test stays conservative through the float of the dots */
      cos_theta = fmax(fmin(cos_theta, 1.0) - 1e-12, -1.0);
      const double sin_theta = sqrt(1.0 - cos_theta * cos_theta);
      const size_t first = t->index_count;
      if (grow(t, t->index_count + (size_t)count, err)) {
        free(from);
        return 1;
      }
      for (int g = 0; g < count; g++) {
        const seen_from *f = &from[g];
        if (f->culled) continue;
        /* past 90 degrees the cap round the axis is not convex: rays between two corners
         * leave it (a field of view past ~140 on a small image), so the tile lists all */
        bool seen = f->around || cos_theta < 0.0;
        if (!seen) {
          double cos_sum = cos_theta * f->cos_beta - sin_theta * f->sin_beta; /* cos(theta+beta) */
          bool past_pi = cos_theta * f->sin_beta + sin_theta * f->cos_beta < 0.0 && cos_sum < 0.0;
          double cos_phi = f->dir[0] * axis[0] + f->dir[1] * axis[1] + f->dir[2] * axis[2];
          seen = past_pi || cos_phi >= cos_sum - 1e-12;
        }
        if (seen) t->indices[t->index_count++] = (uint32_t)g;
      }
      uint32_t *range = &t->ranges[2 * ((size_t)j * tx + i)];
      range[0] = (uint32_t)first;
      range[1] = (uint32_t)(t->index_count - first);
    }
  free(from);
  return 0;
}

void fog_rbf_tiles_destroy(fog_rbf_tiles *t) {
  if (!t) return;
  free(t->ranges);
  free(t->indices);
  *t = (fog_rbf_tiles){0};
}
