/* The sun's optical-depth volume (render/fog_sun_shadow.h). */
#include "render/fog_sun_shadow.h"

#include "render/fog_light.h"
#include "render/fog_rbf_tiles.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

fog_sun_shadow_kind fog_sun_shadow_kind_of(const fog_model *m, const double sun_dir[3]) {
  double lo[3], hi[3];
  /* a sun wholly below the horizon lights nothing: its T_s would be multiplied by 0 */
  if (!(fog_sun_above_horizon(sun_dir) > 0)) return FOG_SUN_SHADOW_NONE;
  switch (m->kind) {
    case FOG_MODEL_HOMOGENEOUS:
      return m->extinction > 0 ? FOG_SUN_SHADOW_OPAQUE : FOG_SUN_SHADOW_NONE;
    case FOG_MODEL_HEIGHT:
      if (!(m->extinction > 0)) return FOG_SUN_SHADOW_NONE;
      return sun_dir[1] > 0 ? FOG_SUN_SHADOW_HEIGHT : FOG_SUN_SHADOW_OPAQUE;
    default:
      if (m->kind == FOG_MODEL_RBF && m->extinction > 0) return FOG_SUN_SHADOW_OPAQUE;
      return fog_model_bounds(m, lo, hi) ? FOG_SUN_SHADOW_VOLUME : FOG_SUN_SHADOW_NONE;
  }
}

/* The world box of index coordinates [-1, dim] (the trilinear support): its 8 corners
 * through the inverse of index_from_world. */
static bool grid3d_bounds(const volume_grid_desc *g, double lo[3], double hi[3]) {
  const double(*a)[3] = g->index_from_world;
  double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
               a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  if (!(fabs(det) > 0) || !isfinite(det)) return false;
  double inv[3][3]; /* adjugate / det */
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) {
      int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      inv[r][c] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det;
    }
  for (int c = 0; c < 3; c++) lo[c] = HUGE_VAL, hi[c] = -HUGE_VAL;
  for (int corner = 0; corner < 8; corner++) {
    double u[3];
    for (int c = 0; c < 3; c++)
      u[c] = (((corner >> c) & 1) ? g->dim[c] : -1.0) - g->index_offset[c];
    for (int r = 0; r < 3; r++) {
      double p = inv[r][0] * u[0] + inv[r][1] * u[1] + inv[r][2] * u[2];
      lo[r] = fmin(lo[r], p), hi[r] = fmax(hi[r], p);
    }
  }
  return true;
}

bool fog_model_bounds(const fog_model *m, double lo[3], double hi[3]) {
  switch (m->kind) {
    case FOG_MODEL_FOGMAP:
      if (!m->volume || !m->lod) return false;
      fog_volume_box(m->volume, lo, hi);
      return lo[0] < hi[0] && lo[1] < hi[1] && lo[2] < hi[2];
    case FOG_MODEL_VOLUME:
      return m->grid3d && grid3d_bounds(m->grid3d, lo, hi);
    case FOG_MODEL_RBF:
      if (m->extinction > 0 || m->rbf_count < 1) return false;
      for (int c = 0; c < 3; c++) lo[c] = HUGE_VAL, hi[c] = -HUGE_VAL;
      for (int i = 0; i < m->rbf_count; i++)
        for (int c = 0; c < 3; c++) {
          lo[c] = fmin(lo[c], m->rbfs[i].centre[c] - 6.0 * m->rbfs[i].radius);
          hi[c] = fmax(hi[c], m->rbfs[i].centre[c] + 6.0 * m->rbfs[i].radius);
        }
      return true;
    case FOG_MODEL_QUADRIC:
      return fog_quadric_bounds(m->quadrics, m->quadric_count, lo, hi);
    case FOG_MODEL_PERLIN:
      if (!m->perlin || !(m->extinction > 0)) return false;
      for (int c = 0; c < 3; c++) lo[c] = m->perlin->desc.lo[c], hi[c] = m->perlin->desc.hi[c];
      return true;
    default:
      return false;
  }
}

int fog_sun_shadow_create(fog_sun_shadow *s, const fog_sun_shadow_desc *desc, fog_error *err) {
  memset(s, 0, sizeof *s);
  if (desc->across < 2 || desc->along < 2 || desc->across > FOG_SUN_SHADOW_MAX_SIZE ||
      desc->along > FOG_SUN_SHADOW_MAX_SIZE) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "sun shadow volume %d x %d x %d: expected 2..%d samples along each axis", desc->across,
             desc->across, desc->along, FOG_SUN_SHADOW_MAX_SIZE);
    return 1;
  }
  s->size[0] = s->size[1] = desc->across;
  s->size[2] = desc->along;
  s->optical_depth = calloc((size_t)desc->across * desc->across * desc->along, sizeof(float));
  if (!s->optical_depth) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "sun shadow volume: out of memory");
    return 1;
  }
  return 0;
}

void fog_sun_shadow_destroy(fog_sun_shadow *s) {
  if (!s) return;
  free(s->optical_depth);
  s->optical_depth = NULL;
}

/* e2 = -sun; e0, e1 any orthonormal pair across it (e0 horizontal unless the sun is at the
 * zenith). */
static void sun_frame(const double sun[3], double axis[3][3]) {
  double *e0 = axis[0], *e1 = axis[1], *e2 = axis[2];
  for (int c = 0; c < 3; c++) e2[c] = -sun[c];
  double ref[3] = {0, 1, 0};
  if (fabs(e2[1]) > 0.99) ref[0] = 1, ref[1] = 0;
  e0[0] = ref[1] * e2[2] - ref[2] * e2[1]; /* ref x e2 */
  e0[1] = ref[2] * e2[0] - ref[0] * e2[2];
  e0[2] = ref[0] * e2[1] - ref[1] * e2[0];
  double n = sqrt(e0[0] * e0[0] + e0[1] * e0[1] + e0[2] * e0[2]);
  for (int c = 0; c < 3; c++) e0[c] /= n;
  e1[0] = e2[1] * e0[2] - e2[2] * e0[1]; /* e2 x e0 */
  e1[1] = e2[2] * e0[0] - e2[0] * e0[2];
  e1[2] = e2[0] * e0[1] - e2[1] * e0[0];
}

typedef struct shadow_job {
  fog_sun_shadow *s;
  const fog_model *model;
  int first_row, row_step; /* rows j of columns this thread fills */
  /* FOG_MODEL_RBF: each Gaussian's cull radius (render/fog_rbf_tiles.h) and room for a
   * column's own list: a column is a line, so the Gaussians farther from it than their
   * radius change its optical depth by < FOG_RBF_CULL_BOUND in all */
  const double *cull_radius;
  fog_rbf *column_rbfs;
} shadow_job;

/* The model for the column through start along e2: for RBFs only the Gaussians near it. */
static fog_model column_model(const shadow_job *job, const double start[3], const double e2[3]) {
  fog_model m = *job->model;
  if (m.kind != FOG_MODEL_RBF || !job->column_rbfs) return m;
  int n = 0;
  for (int i = 0; i < job->model->rbf_count; i++) {
    const fog_rbf *g = &job->model->rbfs[i];
    if (!(job->cull_radius[i] >= 0.0)) continue;
    double v[3], along = 0.0, h2 = 0.0;
    for (int a = 0; a < 3; a++) v[a] = g->centre[a] - start[a], along += v[a] * e2[a];
    for (int a = 0; a < 3; a++) h2 += (v[a] - along * e2[a]) * (v[a] - along * e2[a]);
    if (h2 <= job->cull_radius[i] * job->cull_radius[i]) job->column_rbfs[n++] = *g;
  }
  m.rbfs = job->column_rbfs, m.rbf_count = n;
  return m;
}

/* Column (i, j): its entry point on the sun-side face, then sample k's optical depth as
 * the sum of the exact depths of the segments before it (one walk's work per column). */
static void *shadow_rows(void *arg) {
  shadow_job *job = arg;
  fog_sun_shadow *s = job->s;
  const int n0 = s->size[0], n1 = s->size[1], n2 = s->size[2];
  const double step = s->extent[2] / (n2 - 1);
  const double *e2 = s->axis[2];
  for (int j = job->first_row; j < n1; j += job->row_step)
    for (int i = 0; i < n0; i++) {
      double a = s->extent[0] * i / (n0 - 1), b = s->extent[1] * j / (n1 - 1);
      float *column = s->optical_depth + (size_t)j * n0 + i;
      double start[3], running[FOG_SUN_SHADOW_MAX_SIZE];
      for (int c = 0; c < 3; c++) start[c] = s->origin[c] + a * s->axis[0][c] + b * s->axis[1][c];
      if (job->model->kind == FOG_MODEL_FOGMAP) {
        /* one walk down the column, its running sum read at each sample */
        fog_optical_depth_samples(job->model->volume, job->model->lod->approx, start, e2, step,
                                  n2, running);
      } else {
        const fog_model column = column_model(job, start, e2);
        running[0] = 0.0;
        for (int k = 1; k < n2; k++) {
          double p[3];
          for (int c = 0; c < 3; c++) p[c] = start[c] + (k - 1) * step * e2[c];
          running[k] = running[k - 1] + fog_model_optical_depth(&column, p, e2, step);
        }
      }
      for (int k = 0; k < n2; k++) column[(size_t)k * n0 * n1] = (float)running[k];
    }
  return NULL;
}

/* RBFs: each Gaussian's sphere of its cull radius (fog_rbf_cull_radius: past it a Gaussian
 * adds less than 1e-6 / count to any line's optical depth), projected on the sun's frame.
 * A sun ray from a point outside them misses every sphere, so the volume's zero there errs
 * by less than 1e-6 in all. The 6-radius box of fog_model_bounds, projected through its
 * corners on a slanted sun's axes, made the volume wider and its samples coarser (its error
 * goes as their spacing squared). Leaves mn > mx when every Gaussian is too faint to matter
 * (the caller then fits the bounds). */
static void rbf_sun_extent(const fog_model *m, const double axis[3][3], double mn[3],
                           double mx[3]) {
  for (int i = 0; i < m->rbf_count; i++) {
    const fog_rbf *g = &m->rbfs[i];
    const double reach = fog_rbf_cull_radius(g, m->rbf_count);
    if (!(reach > 0)) continue;
    for (int a = 0; a < 3; a++) {
      double d = g->centre[0] * axis[a][0] + g->centre[1] * axis[a][1] + g->centre[2] * axis[a][2];
      mn[a] = fmin(mn[a], d - reach), mx[a] = fmax(mx[a], d + reach);
    }
  }
}

int fog_sun_shadow_compute(fog_sun_shadow *s, const fog_model *beside, const double sun_dir[3],
                           int threads, fog_error *err) {
  /* the model alone: the quadrics beside it add their exact depth at each lookup */
  const fog_model alone = fog_model_alone(beside), *model = &alone;
  double lo[3], hi[3];
  if (!s->optical_depth || !fog_model_bounds(model, lo, hi)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "sun shadow volume: %s",
             !s->optical_depth ? "not created" : "the fog model has no bounds");
    return 1;
  }
  double len = sqrt(sun_dir[0] * sun_dir[0] + sun_dir[1] * sun_dir[1] + sun_dir[2] * sun_dir[2]);
  if (!(fabs(len - 1.0) < 1e-6)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "sun shadow volume: sun direction of length %g: expected a unit vector", len);
    return 1;
  }
  for (int c = 0; c < 3; c++) s->sun[c] = sun_dir[c];
  sun_frame(sun_dir, s->axis);
  /* The box's extent in the sun's frame: RBFs from their spheres, the others from their
   * bounds' 8 corners. */
  double mn[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, mx[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  if (model->kind == FOG_MODEL_RBF) rbf_sun_extent(model, s->axis, mn, mx);
  const bool fitted = mn[0] <= mx[0];
  for (int corner = 0; corner < 8 && !fitted; corner++) {
    double p[3];
    for (int c = 0; c < 3; c++) p[c] = ((corner >> c) & 1) ? hi[c] : lo[c];
    for (int a = 0; a < 3; a++) {
      double d = p[0] * s->axis[a][0] + p[1] * s->axis[a][1] + p[2] * s->axis[a][2];
      mn[a] = fmin(mn[a], d), mx[a] = fmax(mx[a], d);
    }
  }
  for (int c = 0; c < 3; c++) {
    s->origin[c] = mn[0] * s->axis[0][c] + mn[1] * s->axis[1][c] + mn[2] * s->axis[2][c];
  }
  for (int a = 0; a < 3; a++) s->extent[a] = fmax(mx[a] - mn[a], 1e-9);
  /* The fogmap's sunlight walks one level of its pyramid: the coarsest whose knot spacing
   * is at most half the volume's sample spacing across the sunlight (detail finer than
   * that falls between the columns anyway), A_J when none is. A
   * level coarser by one halves the knot cells a column crosses, and the walk's time. */
  fog_lod walked_lod;
  fog_model walked = *model;
  if (model->kind == FOG_MODEL_FOGMAP) {
    const int J = model->lod->levels;
    const double across = fmin(s->extent[0] / (s->size[0] - 1), s->extent[1] / (s->size[1] - 1));
    int level = J;
    while (level > 0 &&
           model->volume->cell_size * model->lod->approx[level - 1].spacing <= 0.5 * across)
      level--;
    s->level = level;
    walked_lod = (fog_lod){.levels = 0, .approx = model->lod->approx + level, .mu = 1.0};
    walked.lod = &walked_lod;
  }
  if (threads < 1) threads = 1;
  if (threads > 16) threads = 16;
  shadow_job jobs[16];
  pthread_t ids[16];
  int started = 0;
  /* RBFs: per column only those near it (their lists take 1 + threads arrays of them) */
  double *cull_radius = NULL;
  fog_rbf *column_rbfs = NULL;
  if (model->kind == FOG_MODEL_RBF && model->rbf_count > 0) {
    cull_radius = malloc(sizeof *cull_radius * (size_t)model->rbf_count);
    column_rbfs = malloc(sizeof *column_rbfs * (size_t)model->rbf_count * threads);
    if (!cull_radius || !column_rbfs) {
      free(cull_radius), free(column_rbfs);
      cull_radius = NULL, column_rbfs = NULL; /* every Gaussian in every column, then */
    } else {
      for (int i = 0; i < model->rbf_count; i++)
        cull_radius[i] = fog_rbf_cull_radius(&model->rbfs[i], model->rbf_count);
    }
  }
  for (int t = 0; t < threads; t++)
    jobs[t] = (shadow_job){.s = s, .model = &walked, .first_row = t, .row_step = threads,
                           .cull_radius = cull_radius,
                           .column_rbfs = column_rbfs ? column_rbfs + (size_t)t * model->rbf_count
                                                      : NULL};
  for (int t = 1; t < threads; t++)
    if (pthread_create(&ids[t], NULL, shadow_rows, &jobs[t]) == 0) started = t;
    else break;
  shadow_rows(&jobs[0]);
  for (int t = 1; t <= started; t++) pthread_join(ids[t], NULL);
  for (int t = started + 1; t < threads; t++) shadow_rows(&jobs[t]); /* threads that failed */
  free(cull_radius);
  free(column_rbfs);
  return 0;
}

void fog_sun_shadow_tex_map(const fog_sun_shadow *s, double m[3][3], double offset[3]) {
  for (int a = 0; a < 3; a++) {
    double scale = (s->size[a] - 1) / (s->size[a] * s->extent[a]);
    for (int c = 0; c < 3; c++) m[a][c] = s->axis[a][c] * scale;
    offset[a] = 0.5 / s->size[a];
  }
}

/* One sample, with GL's wrap modes: across (axes 0, 1) a zero border, along (axis 2) the
 * edge. */
static double shadow_sample(const fog_sun_shadow *s, int i, int j, int k) {
  if (i < 0 || j < 0 || i >= s->size[0] || j >= s->size[1]) return 0.0;
  k = k < 0 ? 0 : (k >= s->size[2] ? s->size[2] - 1 : k);
  return s->optical_depth[((size_t)k * s->size[1] + j) * s->size[0] + i];
}

double fog_sun_shadow_depth_at(const fog_sun_shadow *s, const double p[3]) {
  double m[3][3], offset[3], x[3];
  int base[3];
  double f[3];
  fog_sun_shadow_tex_map(s, m, offset);
  for (int a = 0; a < 3; a++) {
    double tex = offset[a];
    for (int c = 0; c < 3; c++) tex += m[a][c] * (p[c] - s->origin[c]);
    x[a] = tex * s->size[a] - 0.5; /* GL_LINEAR: texel space, centres at integers */
    x[a] = fmin(fmax(x[a], -2.0), s->size[a] + 1.0); /* beyond: the border or the edge */
    base[a] = (int)floor(x[a]);
    f[a] = x[a] - base[a];
  }
  double sum = 0.0;
  for (int corner = 0; corner < 8; corner++) {
    double w = 1.0;
    int idx[3];
    for (int a = 0; a < 3; a++) {
      int o = (corner >> a) & 1;
      idx[a] = base[a] + o;
      w *= o ? f[a] : 1.0 - f[a];
    }
    if (w != 0.0) sum += w * shadow_sample(s, idx[0], idx[1], idx[2]);
  }
  return sum;
}
