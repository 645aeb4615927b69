/* FOG_MODEL_VOLUME's CPU integrals (fog_models.h): a dense grid, trilinear between voxel
 * centres and zero beyond the outer ones, integrated exactly by a 3D DDA over index
 * space's lattice cells or marched; the GLSL twins are in render/shaders/fog_models.glsl. */
#include <math.h>

#include "render/fog_field.h"
#include "render/fog_models.h"

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
  double lo[3], hi[3]; /* the support, index coordinates in [-1, dim], relative to u0 */
  volume_grid_index_of(g, camera, u0);
  for (int c = 0; c < 3; c++) {
    du[c] = 0.0; /* a direction: the matrix alone */
    for (int a = 0; a < 3; a++) du[c] += g->index_from_world[c][a] * dir[a];
    lo[c] = -1.0 - u0[c], hi[c] = g->dim[c] - u0[c];
  }
  if (!fog_slab_entry_exit(lo, hi, du, t0, t1)) return 0;
  *t0 = fmax(*t0, 0.0);
  *t1 = fmin(*t1, length);
  return *t0 < *t1;
}

/* The 3D DDA over index space's lattice cells from the ray's entry ue (parameter 0):
 * cell[c] = floor(u), the next lattice plane along axis c at t_next[c]. */
typedef struct grid3d_dda {
  double ue[3], du[3], t_next[3];
  int cell[3];
} grid3d_dda;

static grid3d_dda grid3d_dda_start(const double u0[3], const double du[3], double t0) {
  grid3d_dda w;
  for (int c = 0; c < 3; c++) {
    w.du[c] = du[c];
    w.ue[c] = u0[c] + t0 * du[c];
    w.cell[c] = (int)floor(w.ue[c]);
    w.t_next[c] = du[c] == 0.0 ? HUGE_VAL : (w.cell[c] + (du[c] > 0.0) - w.ue[c]) / du[c];
  }
  return w;
}

/* The end of the piece from t (capped at len). */
static double grid3d_dda_piece_end(const grid3d_dda *w, double len) {
  return fmin(len, fmin(w->t_next[0], fmin(w->t_next[1], w->t_next[2])));
}

/* Past the piece that ends at tn: every axis whose plane it reached steps on. */
static void grid3d_dda_step(grid3d_dda *w, double tn) {
  for (int c = 0; c < 3; c++)
    if (w->t_next[c] <= tn) {
      w->cell[c] += w->du[c] > 0.0 ? 1 : -1;
      w->t_next[c] = (w->cell[c] + (w->du[c] > 0.0) - w->ue[c]) / w->du[c];
    }
}

double fog_grid3d_optical_depth(const volume_grid_desc *g, const double camera[3],
                                const double dir[3], double length) {
  double u0[3], du[3], t0, t1;
  if (!grid3d_stretch(g, camera, dir, length, u0, du, &t0, &t1)) return 0.0;
  grid3d_dda w = grid3d_dda_start(u0, du, t0);
  const double node = 0.57735026918962576; /* 1/sqrt(3): two-point Gauss-Legendre */
  double len = t1 - t0, t = 0.0, sum = 0.0;
  while (t < len) {
    double tn = grid3d_dda_piece_end(&w, len);
    if (tn > t) {
      double half = 0.5 * (tn - t), mid = 0.5 * (tn + t);
      for (int s = -1; s <= 1; s += 2) {
        double u[3];
        for (int c = 0; c < 3; c++) u[c] = w.ue[c] + (mid + s * node * half) * du[c];
        sum += half * grid3d_sample(g, u);
      }
    }
    grid3d_dda_step(&w, tn);
    t = fmax(t, tn);
  }
  return sum;
}

double fog_grid3d_light_integral(const volume_grid_desc *g, const double camera[3],
                                 const double dir[3], double length, int nodes,
                                 double depth_limit, fog_point_light_fn light,
                                 const void *user, double *depth) {
  *depth = 0.0;
  double u0[3], du[3], t0, t1;
  if (nodes < 1 || nodes > FOG_PIECE_MAX_NODES ||
      !grid3d_stretch(g, camera, dir, length, u0, du, &t0, &t1))
    return 0.0;
  double gx[FOG_PIECE_MAX_NODES], gw[FOG_PIECE_MAX_NODES],
      partial[FOG_PIECE_MAX_NODES][FOG_PIECE_MAX_NODES];
  fog_gauss_rule(nodes, gx, gw, partial);
  grid3d_dda w = grid3d_dda_start(u0, du, t0);
  double len = t1 - t0, t = 0.0, D = 0.0, S = 0.0;
  while (t < len && D < depth_limit) {
    double tn = grid3d_dda_piece_end(&w, len);
    if (tn > t) {
      double h = 0.5 * (tn - t), mid = 0.5 * (tn + t), K[FOG_PIECE_MAX_NODES];
      for (int j = 0; j < nodes; j++) {
        double u[3];
        for (int c = 0; c < 3; c++) u[c] = w.ue[c] + (mid + h * gx[j]) * du[c];
        K[j] = grid3d_sample(g, u);
      }
      double f[FOG_PIECE_MAX_NODES];
      for (int j = 0; j < nodes; j++) {
        double x[3];
        for (int a = 0; a < 3; a++) x[a] = camera[a] + (t0 + mid + h * gx[j]) * dir[a];
        f[j] = light(user, x);
      }
      S += fog_piece_light(nodes, gw, partial, h, K, f, &D);
    }
    grid3d_dda_step(&w, tn);
    t = fmax(t, tn);
  }
  *depth = D;
  return S;
}

double fog_grid3d_optical_depth_march(const volume_grid_desc *g, double step,
                                      const double camera[3], const double dir[3],
                                      double length) {
  double u0[3], du[3], t0, t1;
  if (!grid3d_stretch(g, camera, dir, length, u0, du, &t0, &t1)) return 0.0;
  /* at most 16384 samples, as the GLSL twin (fog_models.glsl): clamped in double, since a
   * fine step's count overflowed int (INT_MIN: no samples, no fog) */
  int n = (int)fmin(fmax(ceil((t1 - t0) / step), 1.0), 16384.0);
  double dt = (t1 - t0) / n, sum = 0.0;
  for (int s = 0; s < n; s++) {
    double t = t0 + (s + 0.5) * dt, u[3];
    for (int c = 0; c < 3; c++) u[c] = u0[c] + t * du[c];
    sum += grid3d_sample(g, u);
  }
  return sum * dt;
}

/* The table's CPU twin of FOG_MODEL_VOLUME (fog_models.def). */
double fog_model_depth_volume(const fog_model *m, const double camera[3], const double dir[3],
                              double t_surface) {
  return fog_grid3d_optical_depth(m->grid3d, camera, dir, t_surface);
}

double fog_grid3d_extinction_at(const volume_grid_desc *g, const double p[3]) {
  double u[3];
  volume_grid_index_of(g, p, u);
  return grid3d_sample(g, u);
}
