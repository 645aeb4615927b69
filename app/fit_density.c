/* Least-squares fits on the sampled density (app/fit_density.h). */
#include "app/fit_density.h"

#include <math.h>
#include <stdlib.h>

#include "render/fog_sun_shadow.h"

#define PI 3.14159265358979323846

static size_t sample_count(const fit_samples *s) {
  return (size_t)s->n[0] * s->n[1] * s->n[2];
}

void fit_sample_position(const fit_samples *s, int i, int j, int l, double p[3]) {
  const int index[3] = {i, j, l};
  for (int a = 0; a < 3; a++) p[a] = s->lo[a] + (index[a] + 0.5) * s->cell[a];
}

int fit_samples_create(fit_samples *s, const fog_model *model, const double lo[3],
                       const double hi[3], int max_side, fog_error *err) {
  double longest = 0.0;
  for (int a = 0; a < 3; a++) longest = fmax(longest, hi[a] - lo[a]);
  int n[3];
  for (int a = 0; a < 3; a++) n[a] = (int)ceil(max_side * (hi[a] - lo[a]) / longest);
  return fit_samples_create_grid(s, model, lo, hi, n, err);
}

int fit_samples_create_grid(fit_samples *s, const fog_model *model, const double lo[3],
                            const double hi[3], const int n[3], fog_error *err) {
  *s = (fit_samples){0};
  for (int a = 0; a < 3; a++) {
    s->lo[a] = lo[a], s->hi[a] = hi[a];
    s->n[a] = n[a] < 2 ? 2 : n[a];
    s->cell[a] = (hi[a] - lo[a]) / s->n[a];
  }
  s->k = malloc(sample_count(s) * sizeof *s->k);
  if (!s->k)
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for %dx%dx%d density samples",
                    s->n[0], s->n[1], s->n[2]);
  /* K where the fog is opaque (a classic linear factor past fog_end: infinite) is taken
   * as opaque within one sample cell, depth 40 across it: an infinite sample made every
   * moment-fitted rung infinite, and the fog pass refused it, ending the whole fit. A
   * finite K stays as it is, however dense. */
  const double opaque = 40.0 / fmin(fmin(s->cell[0], s->cell[1]), s->cell[2]);
  size_t at = 0;
  for (int l = 0; l < s->n[2]; l++)
    for (int j = 0; j < s->n[1]; j++)
      for (int i = 0; i < s->n[0]; i++) {
        double p[3];
        fit_sample_position(s, i, j, l, p);
        const double k = fog_light_extinction_at(model, p);
        s->k[at++] = isfinite(k) ? k : opaque;
      }
  return 0;
}

void fit_samples_destroy(fit_samples *s) {
  free(s->k);
  *s = (fit_samples){0};
}

double fit_homogeneous(const fit_samples *s) {
  double sum = 0.0;
  for (size_t i = 0; i < sample_count(s); i++) sum += s->k[i];
  return sum / (double)sample_count(s);
}

bool fit_height(const fit_samples *s, double *k, double *y0, double *scale_height) {
  /* Minimise sum_j w_j (ln m_j - a + b (y_j - y0))^2 with w_j = m_j^2: the weighted
   * normal equations of a straight line in (y_j - y0, ln m_j). */
  const int layer = s->n[0] * s->n[1];
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  *y0 = s->lo[1];
  for (int j = 0; j < s->n[1]; j++) {
    double mean = 0.0;
    for (int l = 0; l < s->n[2]; l++)
      for (int i = 0; i < s->n[0]; i++) mean += s->k[(size_t)l * layer + (size_t)j * s->n[0] + i];
    mean /= (double)s->n[0] * s->n[2];
    if (!(mean > 0.0)) continue;
    double x = s->lo[1] + (j + 0.5) * s->cell[1] - *y0, y = log(mean), w = mean * mean;
    sw += w, sx += w * x, sy += w * y, sxx += w * x * x, sxy += w * x * y;
  }
  double det = sw * sxx - sx * sx;
  if (!(det > 0.0)) return false;
  double slope = (sw * sxy - sx * sy) / det, intercept = (sy - slope * sx) / sw;
  /* A decay slower than e^-1 over 1000 domain heights is no height fog. */
  if (!(-slope * 1000.0 * (s->hi[1] - s->lo[1]) > 1.0)) return false;
  *scale_height = -1.0 / slope;
  *k = exp(intercept);
  return isfinite(*k) && isfinite(*scale_height);
}

/* The cells that hold fog (above 1e-6 of the densest), as points with weights. */
typedef struct fog_points {
  double (*p)[3];
  double *w;
  size_t count;
} fog_points;

static int fog_points_gather(const fit_samples *s, fog_points *pts) {
  *pts = (fog_points){0};
  double peak = 0.0;
  for (size_t i = 0; i < sample_count(s); i++) peak = fmax(peak, s->k[i]);
  if (!(peak > 0.0)) return 0;
  pts->p = malloc(sample_count(s) * sizeof *pts->p);
  pts->w = malloc(sample_count(s) * sizeof *pts->w);
  if (!pts->p || !pts->w) {
    free(pts->p), free(pts->w);
    return 1;
  }
  size_t at = 0;
  for (int l = 0; l < s->n[2]; l++)
    for (int j = 0; j < s->n[1]; j++)
      for (int i = 0; i < s->n[0]; i++, at++) {
        if (!(s->k[at] > 1e-6 * peak)) continue;
        fit_sample_position(s, i, j, l, pts->p[pts->count]);
        pts->w[pts->count++] = s->k[at];
      }
  return 0;
}

static double distance2(const double a[3], const double b[3]) {
  double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

/* A cluster's weight, centroid and per-axis variances; false where it is empty. */
static bool cluster_moments(const fog_points *pts, const int *label, int cluster, double *w,
                            double m[3], double var[3]) {
  *w = 0.0;
  for (int a = 0; a < 3; a++) m[a] = var[a] = 0.0;
  for (size_t i = 0; i < pts->count; i++)
    if (label[i] == cluster) {
      *w += pts->w[i];
      for (int a = 0; a < 3; a++) m[a] += pts->w[i] * pts->p[i][a];
    }
  if (!(*w > 0.0)) return false;
  for (int a = 0; a < 3; a++) m[a] /= *w;
  for (size_t i = 0; i < pts->count; i++)
    if (label[i] == cluster)
      for (int a = 0; a < 3; a++) var[a] += pts->w[i] * (pts->p[i][a] - m[a]) * (pts->p[i][a] - m[a]);
  for (int a = 0; a < 3; a++) var[a] /= *w;
  return true;
}

/* One cluster's moments as a Gaussian c e^{-|x - m|^2 / r^2}: mass M = c pi^{3/2} r^3 and
 * per-axis variance r^2 / 2 (the points' own: the cells are points at their centres). */
static bool cluster_gaussian(const fog_points *pts, const int *label, int cluster,
                             const double cell[3], void *item) {
  double w, m[3], var3[3];
  if (!cluster_moments(pts, label, cluster, &w, m, var3)) return false;
  double var = (var3[0] + var3[1] + var3[2]) / 3.0;
  double r = sqrt(2.0 * var);
  double mass = w * cell[0] * cell[1] * cell[2];
  double floor_r = 0.5 * fmin(cell[0], fmin(cell[1], cell[2]));
  if (!(r > floor_r)) r = floor_r; /* a single cell: no narrower than the sampling */
  *(fog_rbf *)item = (fog_rbf){.centre = {m[0], m[1], m[2]}, .radius = r,
                               .density = mass / (pow(PI, 1.5) * r * r * r)};
  return true;
}

/* Weighted k-means of the fog's cells into `count` clusters (fewer where fewer cells hold
 * fog): the points and each one's cluster label, for the banks below. Returns the cluster
 * count (0: no fog), -1 out of memory (nothing stays allocated then, nor with 0). */
static int fit_clusters(const fit_samples *s, int count, fog_points *pts, int **labels) {
  *labels = NULL;
  if (fog_points_gather(s, pts)) return -1;
  if (pts->count == 0 || count < 1) {
    free(pts->p), free(pts->w);
    return 0;
  }
  if ((size_t)count > pts->count) count = (int)pts->count;
  double(*centre)[3] = malloc((size_t)count * sizeof *centre);
  int *label = malloc(pts->count * sizeof *label);
  double *near2 = malloc(pts->count * sizeof *near2);
  if (!centre || !label || !near2) {
    free(centre), free(label), free(near2), free(pts->p), free(pts->w);
    return -1;
  }
  /* Seeds: the densest cell, then each time the cell of most weight x squared distance
   * to its nearest seed (k-means++ made deterministic). */
  size_t first = 0;
  for (size_t i = 1; i < pts->count; i++)
    if (pts->w[i] > pts->w[first]) first = i;
  for (int a = 0; a < 3; a++) centre[0][a] = pts->p[first][a];
  for (size_t i = 0; i < pts->count; i++) near2[i] = distance2(pts->p[i], centre[0]);
  for (int c = 1; c < count; c++) {
    size_t best = 0;
    for (size_t i = 1; i < pts->count; i++)
      if (pts->w[i] * near2[i] > pts->w[best] * near2[best]) best = i;
    for (int a = 0; a < 3; a++) centre[c][a] = pts->p[best][a];
    for (size_t i = 0; i < pts->count; i++)
      near2[i] = fmin(near2[i], distance2(pts->p[i], centre[c]));
  }
  /* Lloyd's iterations on the weighted points. */
  for (int iteration = 0; iteration < 25; iteration++) {
    bool moved = false;
    for (size_t i = 0; i < pts->count; i++) {
      int best = 0;
      double best_d = distance2(pts->p[i], centre[0]);
      for (int c = 1; c < count; c++) {
        double d = distance2(pts->p[i], centre[c]);
        if (d < best_d) best_d = d, best = c;
      }
      if (iteration == 0 || label[i] != best) moved = true;
      label[i] = best;
    }
    if (!moved) break;
    for (int c = 0; c < count; c++) {
      double w = 0, m[3] = {0, 0, 0};
      for (size_t i = 0; i < pts->count; i++)
        if (label[i] == c) {
          w += pts->w[i];
          for (int a = 0; a < 3; a++) m[a] += pts->w[i] * pts->p[i][a];
        }
      if (w > 0.0)
        for (int a = 0; a < 3; a++) centre[c][a] = m[a] / w;
    }
  }
  free(centre), free(near2);
  *labels = label;
  return count;
}

/* One cluster's moments as an axis-aligned uniform ellipsoid: the same mass, centroid and
 * per-axis variances (a uniform ellipsoid's is a^2/5; each cell's own size added as a
 * uniform box's, cell^2/12). */
static bool cluster_ellipsoid(const fog_points *pts, const int *label, int cluster,
                              const double cell[3], void *item) {
  double w, m[3], var[3], r[3];
  if (!cluster_moments(pts, label, cluster, &w, m, var)) return false;
  for (int a = 0; a < 3; a++)
    r[a] = fmax(sqrt(5.0 * (var[a] + cell[a] * cell[a] / 12.0)), 0.5 * cell[a]);
  const double mass = w * cell[0] * cell[1] * cell[2];
  *(fog_quadric *)item = fog_quadric_ellipsoid(m, r, mass / (4.0 / 3.0 * PI * r[0] * r[1] * r[2]), 0.0);
  return true;
}

/* One cluster's moments as an upright uniform cylinder: the same mass, centroid, mean
 * horizontal variance (a uniform disc's is R^2/4 per axis) and vertical variance (a uniform
 * height's is h^2/12); each cell's own size added as a uniform box's. A plume or a column is
 * a cylinder more than an ellipsoid. */
static bool cluster_cylinder(const fog_points *pts, const int *label, int cluster,
                             const double cell[3], void *item) {
  double w, m[3], var[3];
  if (!cluster_moments(pts, label, cluster, &w, m, var)) return false;
  const double across = 0.5 * (var[0] + cell[0] * cell[0] / 12.0 + var[2] + cell[2] * cell[2] / 12.0);
  const double r = fmax(2.0 * sqrt(across), 0.5 * fmin(cell[0], cell[2]));
  const double h = fmax(sqrt(12.0 * var[1] + cell[1] * cell[1]), cell[1]);
  const double base[3] = {m[0], m[1] - 0.5 * h, m[2]};
  const double mass = w * cell[0] * cell[1] * cell[2];
  *(fog_quadric *)item = fog_quadric_cylinder(base, r, h, mass / (PI * r * r * h), 0.0);
  return true;
}

/* One cluster's weighted covariance (its centroid m), each cell's own size added on the
 * diagonal as a uniform box's. */
static bool cluster_covariance(const fog_points *pts, const int *label, int cluster,
                               const double cell[3], double *w, double m[3], double cov[3][3]) {
  double var[3];
  if (!cluster_moments(pts, label, cluster, w, m, var)) return false;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) cov[a][b] = 0.0;
  for (size_t i = 0; i < pts->count; i++)
    if (label[i] == cluster)
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
          cov[a][b] += pts->w[i] * (pts->p[i][a] - m[a]) * (pts->p[i][b] - m[b]);
  for (int a = 0; a < 3; a++) {
    for (int b = 0; b < 3; b++) cov[a][b] /= *w;
    cov[a][a] += cell[a] * cell[a] / 12.0;
  }
  return true;
}

/* One cluster's moments as a uniform ellipsoid in any orientation (a general quadric): the
 * same mass, centroid and full covariance. A uniform ellipsoid {(x-m)^T S^-1 (x-m) <= 1}
 * has covariance S/5, so S = 5 cov, its volume 4/3 pi sqrt(det S), its box m -+ sqrt(S_aa)
 * per axis, and Q = (x-m)^T S^-1 (x-m) - 1 (-1 at the centre, 0 on the surface, as the
 * shape constructors scale it) expands into the ten coefficients A..J. */
static bool cluster_oriented(const fog_points *pts, const int *label, int cluster,
                             const double cell[3], void *item) {
  double w, m[3], cov[3][3], S[3][3];
  if (!cluster_covariance(pts, label, cluster, cell, &w, m, cov)) return false;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) S[a][b] = 5.0 * cov[a][b];
  /* S^-1 by the adjugate: S is symmetric positive definite (the cells' boxes make it so) */
  double P[3][3];
  P[0][0] = S[1][1] * S[2][2] - S[1][2] * S[2][1];
  P[0][1] = S[0][2] * S[2][1] - S[0][1] * S[2][2];
  P[0][2] = S[0][1] * S[1][2] - S[0][2] * S[1][1];
  P[1][1] = S[0][0] * S[2][2] - S[0][2] * S[2][0];
  P[1][2] = S[0][2] * S[1][0] - S[0][0] * S[1][2];
  P[2][2] = S[0][0] * S[1][1] - S[0][1] * S[1][0];
  const double det = S[0][0] * P[0][0] + S[1][0] * P[0][1] + S[2][0] * P[0][2];
  if (!(det > 0.0)) return false;
  P[1][0] = P[0][1], P[2][0] = P[0][2], P[2][1] = P[1][2];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) P[a][b] /= det;
  double Pm[3];
  for (int a = 0; a < 3; a++) Pm[a] = P[a][0] * m[0] + P[a][1] * m[1] + P[a][2] * m[2];
  fog_quadric v = {
      .q = {P[0][0], P[1][1], P[2][2], 2.0 * P[0][1], 2.0 * P[1][2], 2.0 * P[0][2],
            -2.0 * Pm[0], -2.0 * Pm[1], -2.0 * Pm[2],
            m[0] * Pm[0] + m[1] * Pm[1] + m[2] * Pm[2] - 1.0},
      .density = w * cell[0] * cell[1] * cell[2] / (4.0 / 3.0 * PI * sqrt(det))};
  for (int a = 0; a < 3; a++) {
    const double half = sqrt(S[a][a]);
    v.lo[a] = m[a] - half, v.hi[a] = m[a] + half;
  }
  *(fog_quadric *)item = v;
  return true;
}

/* A bank of up to `count` items, one per cluster, made by `make` into out (items of `size`
 * bytes); how many (0: no fog, -1 out of memory). */
static int fit_bank(const fit_samples *s, int count, void *out, size_t size,
                    bool (*make)(const fog_points *, const int *, int, const double *, void *)) {
  fog_points pts;
  int *label;
  int clusters = fit_clusters(s, count, &pts, &label);
  if (clusters <= 0) return clusters;
  int made = 0;
  for (int c = 0; c < clusters; c++)
    if (make(&pts, label, c, s->cell, (char *)out + (size_t)made * size)) made++;
  free(label), free(pts.p), free(pts.w);
  return made;
}

int fit_rbfs(const fit_samples *s, int count, fog_rbf *out) {
  return fit_bank(s, count, out, sizeof *out, cluster_gaussian);
}

int fit_ellipsoids(const fit_samples *s, int count, fog_quadric *out) {
  return fit_bank(s, count, out, sizeof *out, cluster_ellipsoid);
}

int fit_cylinders(const fit_samples *s, int count, fog_quadric *out) {
  return fit_bank(s, count, out, sizeof *out, cluster_cylinder);
}

int fit_oriented_ellipsoids(const fit_samples *s, int count, fog_quadric *out) {
  return fit_bank(s, count, out, sizeof *out, cluster_oriented);
}

bool fit_ellipsoid(const fit_samples *s, double centre[3], double radii[3], double *density) {
  double w = 0, m[3] = {0, 0, 0}, var[3] = {0, 0, 0};
  size_t at = 0;
  for (int l = 0; l < s->n[2]; l++)
    for (int j = 0; j < s->n[1]; j++)
      for (int i = 0; i < s->n[0]; i++, at++) {
        double p[3];
        fit_sample_position(s, i, j, l, p);
        w += s->k[at];
        for (int a = 0; a < 3; a++) m[a] += s->k[at] * p[a];
      }
  if (!(w > 0.0)) return false;
  for (int a = 0; a < 3; a++) m[a] /= w;
  at = 0;
  for (int l = 0; l < s->n[2]; l++)
    for (int j = 0; j < s->n[1]; j++)
      for (int i = 0; i < s->n[0]; i++, at++) {
        double p[3];
        fit_sample_position(s, i, j, l, p);
        for (int a = 0; a < 3; a++) var[a] += s->k[at] * (p[a] - m[a]) * (p[a] - m[a]);
      }
  for (int a = 0; a < 3; a++) {
    centre[a] = m[a];
    radii[a] = fmax(sqrt(5.0 * var[a] / w), 0.5 * s->cell[a]);
  }
  double mass = w * s->cell[0] * s->cell[1] * s->cell[2];
  *density = mass / (4.0 / 3.0 * PI * radii[0] * radii[1] * radii[2]);
  return true;
}
