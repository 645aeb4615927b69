/* The analytic fog models (fog_models.h); twins in render/shaders/fog_models.glsl. */
#include <math.h>

#include "render/fog_models.h"

double fog_exprel(double x) {
  if (fabs(x) < FOG_EXPREL_SWITCH)  /* sum_{n<=10} (-x)^n/(n+1)!: error < x^11/12! ~ 2e-20 */
    return 1.0 + x * (-1.0 / 2.0 + x * (1.0 / 6.0 + x * (-1.0 / 24.0 + x * (1.0 / 120.0 +
           x * (-1.0 / 720.0 + x * (1.0 / 5040.0 + x * (-1.0 / 40320.0 +
           x * (1.0 / 362880.0 + x * (-1.0 / 3628800.0 + x * (1.0 / 39916800.0))))))))));
  return (1.0 - exp(-x)) / x;
}

double fog_homogeneous_optical_depth(double extinction, double length) {
  if (extinction == 0.0) return 0.0; /* no fog, even to infinity */
  return extinction * length; /* OpenGL GL_EXP fog: tau = exp(-density * distance) */
}

double fog_height_optical_depth(double extinction, double y0, double scale_height,
                                double camera_y, double dir_y, double length) {
  if (extinction == 0.0) return 0.0;
  double k = extinction * exp(-(camera_y - y0) / scale_height);
  double a = dir_y / scale_height;
  if (isinf(length)) return a > 0.0 ? k / a : HUGE_VAL;
  return k * length * fog_exprel(a * length);
}

static const double half_sqrt_pi = 0.88622692545275801365; /* int_0^inf e^{-u^2} du */

double fog_erf_difference(double u0, double u1) {
  if (u0 >= 0.0) return erfc(u0) - erfc(u1);
  if (u1 <= 0.0) return erfc(-u1) - erfc(-u0);
  return erf(u1) - erf(u0); /* opposite signs: the two add up, no cancellation */
}

double fog_rbf_optical_depth(double base, const fog_rbf *rbfs, int count, const double camera[3],
                             const double dir[3], double length) {
  double sum = fog_homogeneous_optical_depth(base, length);
  for (int i = 0; i < count; i++) {
    const fog_rbf *g = &rbfs[i];
    double v[3], w[3];
    for (int a = 0; a < 3; a++) v[a] = g->centre[a] - camera[a];
    double tc = v[0] * dir[0] + v[1] * dir[1] + v[2] * dir[2];
    for (int a = 0; a < 3; a++) w[a] = v[a] - tc * dir[a]; /* from the line to the centre */
    double h2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    double inv_r = 1.0 / g->radius;
    double u0 = -tc * inv_r, u1 = isinf(length) ? HUGE_VAL : (length - tc) * inv_r;
    sum += g->density * exp(-h2 * inv_r * inv_r) * g->radius * half_sqrt_pi *
           fog_erf_difference(u0, u1);
  }
  return sum;
}

/* Trilinear at index position u, zero outside the grid (GL_CLAMP_TO_BORDER with 0). */
static double grid3d_sample(const volume_grid_desc *g, const double u[3]) {
  int base[3];
  double f[3];
  for (int c = 0; c < 3; c++) {
    double fl = floor(u[c]);
    base[c] = (int)fl;
    f[c] = u[c] - fl;
  }
  double sum = 0.0;
  for (int corner = 0; corner < 8; corner++) {
    int idx[3];
    double w = 1.0;
    for (int c = 0; c < 3; c++) {
      int o = (corner >> c) & 1;
      idx[c] = base[c] + o;
      w *= o ? f[c] : 1.0 - f[c];
    }
    if (idx[0] < 0 || idx[1] < 0 || idx[2] < 0 || idx[0] >= g->dim[0] || idx[1] >= g->dim[1] ||
        idx[2] >= g->dim[2])
      continue;
    sum += w * g->values[((size_t)idx[2] * g->dim[1] + idx[1]) * g->dim[0] + idx[0]];
  }
  return sum;
}

/* The ray's stretch [t0, t1] inside the grid's support and [0, length], with the index
 * position u0 + t du; 0 when empty. */
static int grid3d_stretch(const volume_grid_desc *g, const double camera[3], const double dir[3],
                          double length, double u0[3], double du[3], double *t0, double *t1) {
  *t0 = 0.0;
  *t1 = length;
  for (int c = 0; c < 3; c++) {
    u0[c] = g->index_offset[c];
    du[c] = 0.0;
    for (int a = 0; a < 3; a++) {
      u0[c] += g->index_from_world[c][a] * camera[a];
      du[c] += g->index_from_world[c][a] * dir[a];
    }
    double lo = -1.0, hi = g->dim[c]; /* the support, in index units */
    if (du[c] == 0.0) {
      if (u0[c] < lo || u0[c] > hi) return 0;
      continue;
    }
    double ta = (lo - u0[c]) / du[c], tb = (hi - u0[c]) / du[c];
    *t0 = fmax(*t0, fmin(ta, tb));
    *t1 = fmin(*t1, fmax(ta, tb));
  }
  return *t0 < *t1;
}

double fog_grid3d_optical_depth(const volume_grid_desc *g, const double camera[3],
                                const double dir[3], double length) {
  double u0[3], du[3], t0, t1;
  if (!grid3d_stretch(g, camera, dir, length, u0, du, &t0, &t1)) return 0.0;
  /* DDA from the entry: cell[c] = floor(u), the next lattice plane at t_next[c]. */
  double ue[3], t_next[3];
  int cell[3];
  for (int c = 0; c < 3; c++) {
    ue[c] = u0[c] + t0 * du[c];
    cell[c] = (int)floor(ue[c]);
    t_next[c] = du[c] == 0.0 ? HUGE_VAL : (cell[c] + (du[c] > 0.0) - ue[c]) / du[c];
  }
  const double node = 0.57735026918962576; /* 1/sqrt(3): two-point Gauss-Legendre */
  double len = t1 - t0, t = 0.0, sum = 0.0;
  while (t < len) {
    double tn = fmin(len, fmin(t_next[0], fmin(t_next[1], t_next[2])));
    if (tn > t) {
      double half = 0.5 * (tn - t), mid = 0.5 * (tn + t);
      for (int s = -1; s <= 1; s += 2) {
        double u[3];
        for (int c = 0; c < 3; c++) u[c] = ue[c] + (mid + s * node * half) * du[c];
        sum += half * grid3d_sample(g, u);
      }
    }
    for (int c = 0; c < 3; c++)
      if (t_next[c] <= tn) {
        cell[c] += du[c] > 0.0 ? 1 : -1;
        t_next[c] = (cell[c] + (du[c] > 0.0) - ue[c]) / du[c];
      }
    t = fmax(t, tn);
  }
  return sum;
}

double fog_grid3d_optical_depth_march(const volume_grid_desc *g, double step,
                                      const double camera[3], const double dir[3],
                                      double length) {
  double u0[3], du[3], t0, t1;
  if (!grid3d_stretch(g, camera, dir, length, u0, du, &t0, &t1)) return 0.0;
  int n = (int)ceil((t1 - t0) / step);
  double dt = (t1 - t0) / n, sum = 0.0;
  for (int s = 0; s < n; s++) {
    double t = t0 + (s + 0.5) * dt, u[3];
    for (int c = 0; c < 3; c++) u[c] = u0[c] + t * du[c];
    sum += grid3d_sample(g, u);
  }
  return sum * dt;
}

double fog_model_optical_depth(const fog_model *m, const double camera[3], const double dir[3],
                               double t_surface) {
  switch (m->kind) {
    case FOG_MODEL_HOMOGENEOUS:
      return fog_homogeneous_optical_depth(m->extinction, t_surface);
    case FOG_MODEL_HEIGHT:
      return fog_height_optical_depth(m->extinction, m->y0, m->scale_height, camera[1], dir[1],
                                      t_surface);
    case FOG_MODEL_RBF:
      return fog_rbf_optical_depth(m->extinction, m->rbfs, m->rbf_count, camera, dir, t_surface);
    case FOG_MODEL_VOLUME:
      return fog_grid3d_optical_depth(m->grid3d, camera, dir, t_surface);
    default: {
      if (!m->lod) return 0.0;
      return fog_optical_depth_lod(m->volume, m->lod, m->lod_method, camera, dir, t_surface);
    }
  }
}
