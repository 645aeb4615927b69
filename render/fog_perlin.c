/* Animated Perlin turbulence fog (fog_perlin.h), in double; the GLSL twin is in
 * render/shaders/fog_models.glsl (fog_model_depth_perlin). */
#include "render/fog_perlin.h"

#include "render/fog_models.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

fog_perlin_desc fog_perlin_desc_default(void) {
  return (fog_perlin_desc){
      .seed = 1, .octaves = 3, .size = 32, .feature_size = 48.0,
      .wind = {{3.0, 0.0, 1.0}, {-2.0, 0.3, 3.0}, {4.0, -0.2, -2.5}, {-3.5, 0.0, -3.0},
               {5.0, 0.4, 1.5}, {-1.0, -0.3, 5.0}},
      .lo = {-128.0, 0.0, -128.0}, .hi = {128.0, 24.0, 128.0}};
}

static uint64_t splitmix64(uint64_t *state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/* Perlin 2002's gradient: the 12 cube-edge directions (and 4 repeated) from the hash. */
static double gradient(int hash, double x, double y, double z) {
  int h = hash & 15;
  double u = h < 8 ? x : y, v = h < 4 ? y : (h == 12 || h == 14) ? x : z;
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
static double lerp(double t, double a, double b) { return a + t * (b - a); }

/* Improved noise with lattice coordinates wrapped modulo `period` (periodic in each axis);
 * perm holds a permutation of 0..255. */
static double periodic_noise(const unsigned char perm[256], int period, double x, double y,
                             double z) {
  double fx = floor(x), fy = floor(y), fz = floor(z);
  x -= fx, y -= fy, z -= fz;
  int X = ((int)fx % period + period) % period, Y = ((int)fy % period + period) % period,
      Z = ((int)fz % period + period) % period;
  int X1 = (X + 1) % period, Y1 = (Y + 1) % period, Z1 = (Z + 1) % period;
#define H(a, b, c) perm[(perm[(perm[a] + (b)) & 255] + (c)) & 255]
  double u = fade(x), v = fade(y), w = fade(z);
  return lerp(w,
              lerp(v, lerp(u, gradient(H(X, Y, Z), x, y, z), gradient(H(X1, Y, Z), x - 1, y, z)),
                   lerp(u, gradient(H(X, Y1, Z), x, y - 1, z),
                        gradient(H(X1, Y1, Z), x - 1, y - 1, z))),
              lerp(v,
                   lerp(u, gradient(H(X, Y, Z1), x, y, z - 1),
                        gradient(H(X1, Y, Z1), x - 1, y, z - 1)),
                   lerp(u, gradient(H(X, Y1, Z1), x, y - 1, z - 1),
                        gradient(H(X1, Y1, Z1), x - 1, y - 1, z - 1))));
#undef H
}

static bool finite3(const double v[3]) {
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

int fog_perlin_create(fog_perlin *perlin, const fog_perlin_desc *desc, fog_error *err) {
  memset(perlin, 0, sizeof *perlin);
  const char *bad = NULL;
  int n = desc->size;
  if (desc->octaves < 1 || desc->octaves > FOG_PERLIN_MAX_OCTAVES)
    bad = "octaves: expected 1 to 6";
  else if (n < FOG_PERLIN_MIN_SIZE || n > FOG_PERLIN_MAX_SIZE || (n & (n - 1)))
    bad = "texture size: expected a power of two from 8 to 128";
  else if (!(desc->feature_size > 0) || !isfinite(desc->feature_size))
    bad = "feature size: expected a finite size > 0";
  else if (!finite3(desc->lo) || !finite3(desc->hi) || !(desc->lo[0] < desc->hi[0]) ||
           !(desc->lo[1] < desc->hi[1]) || !(desc->lo[2] < desc->hi[2]))
    bad = "box: expected finite corners with lo < hi";
  for (int i = 0; !bad && i < desc->octaves; i++)
    if (!finite3(desc->wind[i])) bad = "wind: expected finite velocities";
  if (bad) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "Perlin fog: %s", bad);
    return 1;
  }
  size_t per_octave = (size_t)n * n * n;
  perlin->texels = malloc(per_octave * (size_t)desc->octaves * sizeof(float));
  if (!perlin->texels) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "Perlin fog: out of memory for %d^3 x %d texels", n,
             desc->octaves);
    return 1;
  }
  perlin->desc = *desc;
  const int period = n / FOG_PERLIN_TEXELS_PER_LATTICE;
  const double step = 1.0 / FOG_PERLIN_TEXELS_PER_LATTICE;
  for (int i = 0; i < desc->octaves; i++) {
    unsigned char perm[256];
    uint64_t state = desc->seed + (uint64_t)i;
    for (int k = 0; k < 256; k++) perm[k] = (unsigned char)k;
    for (int k = 255; k > 0; k--) { /* Fisher-Yates */
      int j = (int)(splitmix64(&state) % (uint64_t)(k + 1));
      unsigned char t = perm[k];
      perm[k] = perm[j], perm[j] = t;
    }
    float *octave = perlin->texels + per_octave * (size_t)i;
    double sum = 0.0;
    for (int z = 0; z < n; z++)
      for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
          float v = (float)fabs(periodic_noise(perm, period, x * step, y * step, z * step));
          octave[((size_t)z * n + y) * n + x] = v;
          sum += v;
        }
    perlin->mean_turbulence += ldexp(sum / (double)per_octave, -i);
  }
  return 0;
}

void fog_perlin_destroy(fog_perlin *perlin) {
  free(perlin->texels);
  perlin->texels = NULL;
}

double fog_perlin_octave_scale(const fog_perlin *perlin, int octave) {
  return ldexp((double)FOG_PERLIN_TEXELS_PER_LATTICE, octave) / perlin->desc.feature_size;
}

/* Octave i's trilinear N_i inside texel cell c at fraction f in [0, 1]^3 (wrapped). */
static double octave_cell_value(const fog_perlin *perlin, int i, const long c[3],
                                const double f[3]) {
  const int n = perlin->desc.size, mask = n - 1;
  const float *octave = perlin->texels + (size_t)n * n * n * (size_t)i;
  double v = 0.0;
  for (int k = 0; k < 8; k++) {
    int x = (int)((c[0] + (k & 1)) & mask), y = (int)((c[1] + ((k >> 1) & 1)) & mask),
        z = (int)((c[2] + (k >> 2)) & mask);
    double w = ((k & 1) ? f[0] : 1 - f[0]) * (((k >> 1) & 1) ? f[1] : 1 - f[1]) *
               ((k >> 2) ? f[2] : 1 - f[2]);
    v += w * octave[((size_t)z * n + y) * n + x];
  }
  return v;
}

double fog_perlin_turbulence(const fog_perlin *perlin, double time, const double p[3]) {
  double sum = 0.0;
  for (int i = 0; i < perlin->desc.octaves; i++) {
    double s = fog_perlin_octave_scale(perlin, i), f[3];
    long c[3];
    for (int a = 0; a < 3; a++) {
      double u = (p[a] - perlin->desc.wind[i][a] * time) * s;
      double fl = floor(u);
      c[a] = (long)fl, f[a] = u - fl;
    }
    sum += ldexp(octave_cell_value(perlin, i, c, f), -i);
  }
  return sum;
}

static bool inside_box(const fog_perlin *perlin, const double p[3]) {
  for (int a = 0; a < 3; a++)
    if (!(p[a] >= perlin->desc.lo[a] && p[a] <= perlin->desc.hi[a])) return false;
  return true;
}

double fog_perlin_extinction_at(const fog_perlin *perlin, const fog_perlin_medium *m,
                                const double p[3]) {
  if (!inside_box(perlin, p)) return 0.0;
  return m->extinction * exp(-(p[1] - m->y0) / m->scale_height) *
         fog_perlin_turbulence(perlin, m->time, p);
}

static const double gauss4_x[4] = {-0.86113631159405258, -0.33998104358485626,
                                   0.33998104358485626, 0.86113631159405258};
static const double gauss4_w[4] = {0.34785484513745386, 0.65214515486254614,
                                   0.65214515486254614, 0.34785484513745386};

/* int over [ta, tb] (parameters from the entry, position u0 + t du in octave i's texels,
 * height y_entry + t dy) of N_i e^{-(y - y0)/H}: the cell from the piece's middle, cut so
 * that the exponent moves by at most 1/2 per sub-piece, 4 Gauss nodes each. */
static double octave_piece(const fog_perlin *perlin, int i, const fog_perlin_medium *m,
                           const double u0[3], const double du[3], double y_entry, double dy,
                           double ta, double tb) {
  double mid = 0.5 * (ta + tb);
  long c[3];
  for (int a = 0; a < 3; a++) c[a] = (long)floor(u0[a] + mid * du[a]);
  int cuts = (int)ceil(fabs(dy) * (tb - ta) / m->scale_height / 0.5);
  if (cuts < 1) cuts = 1;
  double sum = 0.0, h = (tb - ta) / cuts;
  for (int k = 0; k < cuts; k++) {
    double half = 0.5 * h, centre = ta + (k + 0.5) * h;
    for (int j = 0; j < 4; j++) {
      double t = centre + half * gauss4_x[j], f[3];
      for (int a = 0; a < 3; a++) f[a] = u0[a] + t * du[a] - (double)c[a];
      sum += half * gauss4_w[j] * octave_cell_value(perlin, i, c, f) *
             exp(-(y_entry + t * dy - m->y0) / m->scale_height);
    }
  }
  return sum;
}

/* Octave i's exact integral over the ray's stretch [t0, t1] in the box: a 3D DDA over its
 * texel cells. */
static double octave_depth(const fog_perlin *perlin, int i, const fog_perlin_medium *m,
                           const double o[3], const double d[3], double t0, double t1) {
  double s = fog_perlin_octave_scale(perlin, i), u0[3], du[3], next[3], delta[3];
  long cell[3];
  int step[3];
  for (int a = 0; a < 3; a++) {
    u0[a] = (o[a] + t0 * d[a] - perlin->desc.wind[i][a] * m->time) * s;
    du[a] = d[a] * s;
    cell[a] = (long)floor(u0[a]);
    if (du[a] > 0) {
      step[a] = 1, delta[a] = 1.0 / du[a], next[a] = ((double)cell[a] + 1 - u0[a]) / du[a];
    } else if (du[a] < 0) {
      step[a] = -1, delta[a] = -1.0 / du[a], next[a] = ((double)cell[a] - u0[a]) / du[a];
    } else {
      step[a] = 0, delta[a] = HUGE_VAL, next[a] = HUGE_VAL;
    }
  }
  double len = t1 - t0, t = 0.0, sum = 0.0, y_entry = o[1] + t0 * d[1];
  while (t < len) {
    double tn = fmin(len, fmin(next[0], fmin(next[1], next[2])));
    if (tn > t) sum += octave_piece(perlin, i, m, u0, du, y_entry, d[1], t, tn);
    for (int a = 0; a < 3; a++)
      if (next[a] <= tn) cell[a] += step[a], next[a] += delta[a];
    t = fmax(t, tn);
  }
  return sum;
}

/* The ray's stretch in the box, clipped to [0, length]; false when empty. */
static bool box_stretch(const fog_perlin *perlin, const double o[3], const double d[3],
                        double length, double *t0, double *t1) {
  double t_in = -HUGE_VAL, t_out = HUGE_VAL;
  for (int a = 0; a < 3; a++) {
    double lo = perlin->desc.lo[a] - o[a], hi = perlin->desc.hi[a] - o[a];
    if (d[a] == 0) {
      if (lo > 0 || hi < 0) return false;
      continue;
    }
    double ta = lo / d[a], tb = hi / d[a];
    t_in = fmax(t_in, fmin(ta, tb));
    t_out = fmin(t_out, fmax(ta, tb));
  }
  *t0 = fmax(t_in, 0.0);
  *t1 = fmin(t_out, length);
  return *t1 > *t0;
}

double fog_perlin_optical_depth(const fog_perlin *perlin, const fog_perlin_medium *m,
                                const double o[3], const double d[3], double length) {
  double t0, t1;
  if (m->extinction == 0.0 || !box_stretch(perlin, o, d, length, &t0, &t1)) return 0.0;
  if (m->integral == FOG_PERLIN_PAPER) {
    /* Zdrojewska: the turbulence once, at the stretch's last point, times the height fog */
    double p[3];
    for (int a = 0; a < 3; a++) p[a] = o[a] + t1 * d[a];
    double y0 = o[1] + t0 * d[1];
    return fog_perlin_turbulence(perlin, m->time, p) *
           fog_height_optical_depth(m->extinction, m->y0, m->scale_height, y0, d[1], t1 - t0);
  }
  double sum = 0.0;
  for (int i = 0; i < perlin->desc.octaves; i++)
    sum += ldexp(octave_depth(perlin, i, m, o, d, t0, t1), -i);
  return m->extinction * sum;
}

fog_perlin_medium fog_model_perlin_medium(const fog_model *m) {
  return (fog_perlin_medium){.extinction = m->extinction, .y0 = m->y0,
                             .scale_height = m->scale_height, .time = m->time,
                             .integral = m->perlin_integral};
}

double fog_model_depth_perlin(const fog_model *m, const double camera[3], const double dir[3],
                              double t_surface) {
  if (!m->perlin) return 0.0;
  fog_perlin_medium medium = fog_model_perlin_medium(m);
  return fog_perlin_optical_depth(m->perlin, &medium, camera, dir, t_surface);
}

void fog_gauss_rule(int n, double x[FOG_PIECE_MAX_NODES], double w[FOG_PIECE_MAX_NODES],
                    double partial[FOG_PIECE_MAX_NODES][FOG_PIECE_MAX_NODES]) {
  static const double nodes[4][4] = {{0.0},
                                     {-0.57735026918962576, 0.57735026918962576},
                                     {-0.77459666924148338, 0.0, 0.77459666924148338},
                                     {-0.86113631159405258, -0.33998104358485626,
                                      0.33998104358485626, 0.86113631159405258}};
  static const double weights[4][4] = {{2.0},
                                       {1.0, 1.0},
                                       {0.55555555555555556, 0.88888888888888889,
                                        0.55555555555555556},
                                       {0.34785484513745386, 0.65214515486254614,
                                        0.65214515486254614, 0.34785484513745386}};
  for (int k = 0; k < n; k++) x[k] = nodes[n - 1][k], w[k] = weights[n - 1][k];
  /* L_k has degree n - 1: the same rule mapped onto [-1, x_j] integrates it exactly */
  for (int j = 0; j < n; j++)
    for (int k = 0; k < n; k++) {
      double half = 0.5 * (x[j] + 1.0), sum = 0.0;
      for (int q = 0; q < n; q++) {
        double s = -1.0 + half * (x[q] + 1.0), l = 1.0;
        for (int m = 0; m < n; m++)
          if (m != k) l *= (s - x[m]) / (x[k] - x[m]);
        sum += w[q] * l;
      }
      partial[j][k] = half * sum;
    }
}

double fog_piece_light(int n, const double w[FOG_PIECE_MAX_NODES],
                       const double partial[FOG_PIECE_MAX_NODES][FOG_PIECE_MAX_NODES], double h,
                       const double K[FOG_PIECE_MAX_NODES], const double f[FOG_PIECE_MAX_NODES],
                       double *depth) {
  /* The piece's share of the ray's light is e^{-D}(1 - e^{-dD}) exactly, dD its Gauss
   * depth, times the mean of f weighted by tau K at its nodes: the shares telescope to
   * 1 - e^{-D}, so a ray lit throughout (f = 1) has a mean of exactly 1 however thick its
   * pieces, as the segments' weights give. Gauss on tau K itself missed once a piece was
   * optically thick (tau falls across it): a dense volume's lit mean was 0.07 to 1.37. A
   * negative K (ringing) weighs nothing in the mean, as in the segments'. */
  double piece = 0.0, weight = 0.0, weighted = 0.0, plain = 0.0, hd[FOG_PIECE_MAX_NODES];
  /* tau within the piece relative to the largest of the nodes that weigh (K > 0): no
   * underflow. Relative to an empty node's, a dense node's e^{least - hd} underflowed (from
   * h K ~ 1290 in double, ~90 in float), every weight was 0 and the mean fell back to the
   * plain average: denser fog drew half-lit. */
  double least = INFINITY;
  for (int j = 0; j < n; j++) {
    double dj = 0.0;
    for (int q = 0; q < n; q++) dj += partial[j][q] * K[q];
    hd[j] = h * dj;
    if (K[j] > 0.0) least = fmin(least, hd[j]);
  }
  for (int j = 0; j < n; j++) {
    /* 0 for an empty node: e^{least - hd} may overflow there, and 0 x inf is NaN */
    const double wk = K[j] > 0.0 ? w[j] * K[j] * exp(least - hd[j]) : 0.0;
    weight += wk;
    weighted += wk * f[j];
    plain += w[j] * f[j];
    piece += h * w[j] * K[j];
  }
  const double mean = weight > 0.0 ? weighted / weight : 0.5 * plain; /* weights sum to 2 */
  const double S = exp(-*depth) * -expm1(-piece) * mean;
  *depth += piece;
  return S;
}

double fog_perlin_light_integral(const fog_perlin *perlin, const fog_perlin_medium *m,
                                 const double o[3], const double d[3], double length,
                                 int nodes, double depth_limit, fog_point_light_fn light,
                                 const void *user, double *depth) {
  *depth = 0.0;
  double t0, t1;
  if (m->extinction == 0.0 || nodes < 1 || nodes > FOG_PIECE_MAX_NODES ||
      !box_stretch(perlin, o, d, length, &t0, &t1))
    return 0.0;
  double gx[FOG_PIECE_MAX_NODES], gw[FOG_PIECE_MAX_NODES],
      partial[FOG_PIECE_MAX_NODES][FOG_PIECE_MAX_NODES];
  fog_gauss_rule(nodes, gx, gw, partial);
  const int octaves = perlin->desc.octaves;
  double u0[FOG_PERLIN_MAX_OCTAVES][3], du[FOG_PERLIN_MAX_OCTAVES][3];
  double next[FOG_PERLIN_MAX_OCTAVES][3], delta[FOG_PERLIN_MAX_OCTAVES][3];
  for (int i = 0; i < octaves; i++) {
    double s = fog_perlin_octave_scale(perlin, i);
    for (int a = 0; a < 3; a++) {
      u0[i][a] = (o[a] + t0 * d[a] - perlin->desc.wind[i][a] * m->time) * s;
      du[i][a] = d[a] * s;
      double cell = floor(u0[i][a]);
      if (du[i][a] > 0) {
        delta[i][a] = 1.0 / du[i][a], next[i][a] = (cell + 1 - u0[i][a]) / du[i][a];
      } else if (du[i][a] < 0) {
        delta[i][a] = -1.0 / du[i][a], next[i][a] = (cell - u0[i][a]) / du[i][a];
      } else {
        delta[i][a] = HUGE_VAL, next[i][a] = HUGE_VAL;
      }
    }
  }
  const double len = t1 - t0, y_entry = o[1] + t0 * d[1];
  double t = 0.0, D = 0.0, S = 0.0;
  while (t < len && D < depth_limit) {
    double tn = len;
    for (int i = 0; i < octaves; i++)
      for (int a = 0; a < 3; a++) tn = fmin(tn, next[i][a]);
    if (tn > t) {
      long c[FOG_PERLIN_MAX_OCTAVES][3];
      double mid = 0.5 * (t + tn);
      for (int i = 0; i < octaves; i++)
        for (int a = 0; a < 3; a++) c[i][a] = (long)floor(u0[i][a] + mid * du[i][a]);
      int cuts = (int)ceil(fabs(d[1]) * (tn - t) / m->scale_height / 0.5);
      if (cuts < 1) cuts = 1;
      double h = 0.5 * (tn - t) / cuts;
      for (int k = 0; k < cuts; k++) {
        double centre = t + (2 * k + 1) * h, K[FOG_PIECE_MAX_NODES], tj[FOG_PIECE_MAX_NODES];
        for (int j = 0; j < nodes; j++) {
          tj[j] = centre + h * gx[j];
          double turbulence = 0.0;
          for (int i = 0; i < octaves; i++) {
            double f[3];
            for (int a = 0; a < 3; a++) f[a] = u0[i][a] + tj[j] * du[i][a] - (double)c[i][a];
            turbulence += ldexp(octave_cell_value(perlin, i, c[i], f), -i);
          }
          K[j] = m->extinction * exp(-(y_entry + tj[j] * d[1] - m->y0) / m->scale_height) *
                 turbulence;
        }
        double f[FOG_PIECE_MAX_NODES];
        for (int j = 0; j < nodes; j++) {
          double x[3];
          for (int a = 0; a < 3; a++) x[a] = o[a] + (t0 + tj[j]) * d[a];
          f[j] = light(user, x);
        }
        S += fog_piece_light(nodes, gw, partial, h, K, f, &D);
      }
    }
    for (int i = 0; i < octaves; i++)
      for (int a = 0; a < 3; a++)
        if (next[i][a] <= tn) next[i][a] += delta[i][a];
    t = fmax(t, tn);
  }
  *depth = D;
  return S;
}
