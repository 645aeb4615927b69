/* Terrain heightfield: procedural fBm or image heights, and exact CPU ray intersection. */
#include "render/terrain.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/vec3.h"

/* ---- value noise ---- */

/* Integer hash (the "lowbias32" mixer by C. Wellons): lattice values in [0, 1). */
static uint32_t hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

static double lattice(uint32_t x, uint32_t z, uint32_t seed) {
  uint32_t h = hash32(x * 0x9E3779B1U ^ hash32(z + seed * 0x85EBCA77U));
  return (h >> 8) * (1.0 / 16777216.0);
}

/* The lattice index of a coordinate modulo 2^32, the hash's word (the same bits as an int32
 * index where one fits): a cast to int32 overflowed once frequency x 2^(octaves - 1) passed
 * 2^31 (1e6 and 16 octaves are allowed), undefined behaviour. The coordinate stays below
 * 2^35 there, well inside int64. */
static uint32_t lattice_index(double floored) { return (uint32_t)(int64_t)floored; }

/* Quintic fade (Perlin 2002, "Improving noise"): C2-continuous value noise. */
static double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

static double value_noise(double x, double z, uint32_t seed) {
  double fx = floor(x), fz = floor(z);
  uint32_t ix = lattice_index(fx), iz = lattice_index(fz);
  double u = fade(x - fx), v = fade(z - fz);
  double a = lattice(ix, iz, seed), b = lattice(ix + 1, iz, seed);
  double c = lattice(ix, iz + 1, seed), d = lattice(ix + 1, iz + 1, seed);
  return (a + (b - a) * u) * (1.0 - v) + (c + (d - c) * u) * v;
}

/* ---- creation ---- */

int terrain_create(terrain *t, const terrain_desc *desc, fog_error *err) {
  *t = (terrain){0};
  for (int k = 0; k < 3; k++) t->origin[k] = desc->origin[k];
  t->size[0] = desc->size[0];
  t->size[1] = desc->size[1];
  t->height = desc->height;
  if (!(t->size[0] > 0 && t->size[1] > 0 && t->height >= 0) || !isfinite(t->size[0]) ||
      !isfinite(t->size[1]) || !isfinite(t->height)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "terrain size %g x %g, height %g: expected a finite size > 0 and height >= 0",
             t->size[0], t->size[1], t->height);
    return 1;
  }
  if (desc->heights) {
    if (desc->heights_width < 2 || desc->heights_height < 2) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "terrain heights are %dx%d: expected at least 2x2",
               desc->heights_width, desc->heights_height);
      return 1;
    }
    t->resolution_x = desc->heights_width;
    t->resolution_z = desc->heights_height;
  } else {
    int n = desc->resolution;
    if (n < 2 || n > TERRAIN_MAX_RESOLUTION) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
               "terrain resolution %d: expected 2 to %d vertices per side", n,
               TERRAIN_MAX_RESOLUTION);
      return 1;
    }
    if (desc->octaves < 1 || desc->octaves > 16 || !(desc->frequency > 0) ||
        !isfinite(desc->frequency) || !(desc->persistence > 0 && desc->persistence <= 1)) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
               "terrain fBm: %d octaves, frequency %g, persistence %g: expected 1 to 16 "
               "octaves, a finite frequency > 0 and a persistence in (0, 1]",
               desc->octaves, desc->frequency, desc->persistence);
      return 1;
    }
    t->resolution_x = t->resolution_z = n;
  }
  if ((double)t->resolution_x * t->resolution_z >
      (double)TERRAIN_MAX_RESOLUTION * TERRAIN_MAX_RESOLUTION) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "terrain of %dx%d vertices: at most %d x %d (its mesh must stay under 2 GiB)",
             t->resolution_x, t->resolution_z, TERRAIN_MAX_RESOLUTION, TERRAIN_MAX_RESOLUTION);
    return 1;
  }
  size_t count = (size_t)t->resolution_x * t->resolution_z;
  t->h = malloc(count * sizeof *t->h);
  if (!t->h) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for a %dx%d terrain", t->resolution_x,
             t->resolution_z);
    return 1;
  }
  if (desc->heights) {
    for (size_t k = 0; k < count; k++) {
      float v = desc->heights[k];
      t->h[k] = v != v ? 0.0f : v < 0 ? 0.0f : v > 1 ? 1.0f : v;
    }
  } else {
    const int octaves = desc->octaves;
    const double frequency = desc->frequency, persistence = desc->persistence;
    double total = 0.0, amplitude = 1.0;
    for (int o = 0; o < octaves; o++, amplitude *= persistence) total += amplitude;
    for (int j = 0; j < t->resolution_z; j++)
      for (int i = 0; i < t->resolution_x; i++) {
        double x = (double)i / (t->resolution_x - 1), z = (double)j / (t->resolution_z - 1);
        double sum = 0.0, a = 1.0, f = frequency;
        for (int o = 0; o < octaves; o++, a *= persistence, f *= 2.0)
          sum += a * value_noise(x * f, z * f, desc->seed + 7919u * (unsigned)o);
        double h = sum / total;
        /* Flatten the valleys (where fog pools) and sharpen the peaks. */
        h = h * h * (3.0 - 2.0 * h);
        t->h[(size_t)j * t->resolution_x + i] = (float)h;
      }
  }
  float lo = 1.0f, hi = 0.0f;
  for (size_t k = 0; k < count; k++) {
    if (t->h[k] < lo) lo = t->h[k];
    if (t->h[k] > hi) hi = t->h[k];
  }
  t->min_y = t->origin[1] + t->height * lo;
  t->max_y = t->origin[1] + t->height * hi;
  return 0;
}

void terrain_destroy(terrain *t) {
  free(t->h);
  *t = (terrain){0};
}

static double spacing_x(const terrain *t) { return t->size[0] / (t->resolution_x - 1); }
static double spacing_z(const terrain *t) { return t->size[1] / (t->resolution_z - 1); }

void terrain_vertex(const terrain *t, int i, int j, double p[3]) {
  p[0] = t->origin[0] + i * spacing_x(t);
  p[1] = t->origin[1] + t->height * t->h[(size_t)j * t->resolution_x + i];
  p[2] = t->origin[2] + j * spacing_z(t);
}

double terrain_height_at(const terrain *t, double x, double z) {
  double u = (x - t->origin[0]) / spacing_x(t), v = (z - t->origin[2]) / spacing_z(t);
  u = u < 0 ? 0 : u > t->resolution_x - 1 ? t->resolution_x - 1 : u;
  v = v < 0 ? 0 : v > t->resolution_z - 1 ? t->resolution_z - 1 : v;
  int i = (int)u, j = (int)v;
  if (i > t->resolution_x - 2) i = t->resolution_x - 2;
  if (j > t->resolution_z - 2) j = t->resolution_z - 2;
  double fu = u - i, fv = v - j;
  const float *row0 = t->h + (size_t)j * t->resolution_x, *row1 = row0 + t->resolution_x;
  double h00 = row0[i], h10 = row0[i + 1], h01 = row1[i], h11 = row1[i + 1];
  /* Linear on the triangle containing (fu, fv): diagonal from (1,0) to (0,1). */
  double h = fu + fv <= 1.0 ? h00 + fu * (h10 - h00) + fv * (h01 - h00)
                            : h11 + (1.0 - fu) * (h01 - h11) + (1.0 - fv) * (h10 - h11);
  return t->origin[1] + t->height * h;
}

/* The surface is linear on each triangle, so its least height over the rectangle lies at a
 * vertex of the rectangle cut by the mesh: a corner, a grid vertex inside, or where an edge
 * crosses a grid line or a cell's diagonal (u + v = k in cell units). Outside the terrain
 * the height is its edge's (clamped), which the clipped rectangle's border covers. */
double terrain_lowest_in(const terrain *t, double x0, double x1, double z0, double z1) {
  const double dx = spacing_x(t), dz = spacing_z(t);
  const double nu = t->resolution_x - 1, nv = t->resolution_z - 1;
  double u0 = fmin(fmax((x0 - t->origin[0]) / dx, 0.0), nu);
  double u1 = fmin(fmax((x1 - t->origin[0]) / dx, 0.0), nu);
  double v0 = fmin(fmax((z0 - t->origin[2]) / dz, 0.0), nv);
  double v1 = fmin(fmax((z1 - t->origin[2]) / dz, 0.0), nv);
#define AT(u, v) terrain_height_at(t, t->origin[0] + (u) * dx, t->origin[2] + (v) * dz)
  double lowest = fmin(fmin(AT(u0, v0), AT(u1, v0)), fmin(AT(u0, v1), AT(u1, v1)));
  float lowest_h = INFINITY; /* the grid vertices inside, read straight from the heights */
  for (int j = (int)ceil(v0); j <= (int)floor(v1); j++)
    for (int i = (int)ceil(u0); i <= (int)floor(u1); i++)
      lowest_h = fminf(lowest_h, t->h[(size_t)j * t->resolution_x + i]);
  if (lowest_h < INFINITY) lowest = fmin(lowest, t->origin[1] + t->height * lowest_h);
  const double v_edges[2] = {v0, v1}, u_edges[2] = {u0, u1};
  for (int e = 0; e < 2; e++) {
    const double v = v_edges[e], u = u_edges[e];
    for (int i = (int)ceil(u0); i <= (int)floor(u1); i++) lowest = fmin(lowest, AT(i, v));
    for (int k = (int)ceil(u0 + v); k <= (int)floor(u1 + v); k++)
      lowest = fmin(lowest, AT(k - v, v));
    for (int j = (int)ceil(v0); j <= (int)floor(v1); j++) lowest = fmin(lowest, AT(u, j));
    for (int k = (int)ceil(v0 + u); k <= (int)floor(v1 + u); k++)
      lowest = fmin(lowest, AT(u, k - u));
  }
#undef AT
  return lowest;
}

/* ---- intersection ---- */

bool ray_triangle(const double origin[3], const double dir[3], const double a[3],
                  const double b[3], const double c[3], double *s) {
  double e1[3], e2[3], p[3], q[3], tv[3];
  vec3_sub(b, a, e1);
  vec3_sub(c, a, e2);
  vec3_cross(dir, e2, p);
  double det = vec3_dot(e1, p);
  if (fabs(det) < 1e-300) return false;
  double inv = 1.0 / det;
  vec3_sub(origin, a, tv);
  /* Small tolerance so a ray through a shared edge hits one of its two triangles. */
  const double eps = 1e-12;
  double u = vec3_dot(tv, p) * inv;
  if (u < -eps || u > 1.0 + eps) return false;
  vec3_cross(tv, e1, q);
  double v = vec3_dot(dir, q) * inv;
  if (v < -eps || u + v > 1.0 + eps) return false;
  double hit = vec3_dot(e2, q) * inv;
  if (hit <= 0.0) return false;
  *s = hit;
  return true;
}

/* Nearest hit in cell (i, j) below s_best; returns true if it improved *s_best. */
static bool cell_hit(const terrain *t, int i, int j, const double o[3], const double d[3],
                     double *s_best, double normal[3]) {
  double v00[3], v10[3], v01[3], v11[3], s;
  terrain_vertex(t, i, j, v00);
  terrain_vertex(t, i + 1, j, v10);
  terrain_vertex(t, i, j + 1, v01);
  terrain_vertex(t, i + 1, j + 1, v11);
  bool hit = false;
  const double *tri[2][3] = {{v00, v01, v10}, {v10, v01, v11}};
  for (int k = 0; k < 2; k++)
    if (ray_triangle(o, d, tri[k][0], tri[k][1], tri[k][2], &s) && s < *s_best) {
      *s_best = s;
      hit = true;
      if (normal) {
        double e1[3], e2[3];
        vec3_sub(tri[k][1], tri[k][0], e1);
        vec3_sub(tri[k][2], tri[k][0], e2);
        vec3_cross(e1, e2, normal);
        double len = sqrt(vec3_dot(normal, normal));
        if (normal[1] < 0) len = -len; /* point up */
        for (int c = 0; c < 3; c++) normal[c] /= len;
      }
    }
  return hit;
}

bool terrain_intersect(const terrain *t, const double origin[3], const double dir[3],
                       double s_max, double *s, double normal[3]) {
  /* Clip the ray to the terrain's bounding box (slabs). */
  double lo[3] = {t->origin[0], t->min_y, t->origin[2]};
  double hi[3] = {t->origin[0] + t->size[0], t->max_y, t->origin[2] + t->size[1]};
  double s0 = 0.0, s1 = s_max;
  for (int k = 0; k < 3; k++) {
    if (fabs(dir[k]) < 1e-300) {
      if (origin[k] < lo[k] || origin[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - origin[k]) / dir[k], b = (hi[k] - origin[k]) / dir[k];
    if (a > b) { double tmp = a; a = b; b = tmp; }
    if (a > s0) s0 = a;
    if (b < s1) s1 = b;
  }
  if (s0 > s1) return false;
  /* 2D DDA over cells (Amanatides & Woo 1987) from s0 to s1 in grid units. */
  double dx = spacing_x(t), dz = spacing_z(t);
  double gx = (origin[0] + s0 * dir[0] - t->origin[0]) / dx;
  double gz = (origin[2] + s0 * dir[2] - t->origin[2]) / dz;
  int nx = t->resolution_x - 1, nz = t->resolution_z - 1;
  int i = (int)floor(gx), j = (int)floor(gz);
  if (i < 0) i = 0;
  if (i > nx - 1) i = nx - 1;
  if (j < 0) j = 0;
  if (j > nz - 1) j = nz - 1;
  double ux = dir[0] / dx, uz = dir[2] / dz; /* grid units per unit s */
  int step_i = ux > 0 ? 1 : -1, step_j = uz > 0 ? 1 : -1;
  double next_i = fabs(ux) < 1e-300 ? INFINITY
                  : s0 + ((ux > 0 ? i + 1 : i) - gx) / ux;
  double next_j = fabs(uz) < 1e-300 ? INFINITY
                  : s0 + ((uz > 0 ? j + 1 : j) - gz) / uz;
  double delta_i = fabs(ux) < 1e-300 ? INFINITY : 1.0 / fabs(ux);
  double delta_j = fabs(uz) < 1e-300 ? INFINITY : 1.0 / fabs(uz);
  double best = s_max;
  bool found = false;
  for (;;) {
    /* Test the current cell and, for robustness at cell borders, its next neighbours
     * would be redundant: the triangle test has an edge tolerance. */
    if (cell_hit(t, i, j, origin, dir, &best, normal)) found = true;
    double cell_exit = next_i < next_j ? next_i : next_j;
    /* A hit inside this cell's column precedes every later cell's hits. */
    if (found && best <= cell_exit + 1e-9 * (1.0 + fabs(cell_exit))) break;
    if (cell_exit > s1) break;
    if (next_i < next_j) {
      i += step_i;
      next_i += delta_i;
      if (i < 0 || i >= nx) break;
    } else {
      j += step_j;
      next_j += delta_j;
      if (j < 0 || j >= nz) break;
    }
  }
  if (found) *s = best;
  return found;
}

bool terrain_intersect_brute(const terrain *t, const double origin[3], const double dir[3],
                             double s_max, double *s) {
  double best = s_max;
  bool found = false;
  for (int j = 0; j + 1 < t->resolution_z; j++)
    for (int i = 0; i + 1 < t->resolution_x; i++)
      if (cell_hit(t, i, j, origin, dir, &best, NULL)) found = true;
  if (found) *s = best;
  return found;
}

void terrain_albedo(double h, double normal_y, double relief, float out[3]) {
  const float grass[3] = {0.09f, 0.17f, 0.05f}, dry[3] = {0.22f, 0.22f, 0.10f},
              rock[3] = {0.26f, 0.24f, 0.22f}, snow[3] = {0.85f, 0.87f, 0.90f};
  double rockiness = fmin(fmax((0.88 - normal_y) / 0.12, 0.0), 1.0);
  /* drier up the slopes of hills; none on flat ground or a field's bumps, where h is noise
   * no one can see (a flat plane showed blotches): none below 1 unit of relief, all of it
   * from 10 */
  double dryness = fmin(fmax((h - 0.35) / 0.3, 0.0), 1.0) *
                   fmin(fmax((relief - 1.0) / 9.0, 0.0), 1.0);
  double snowiness = fmin(fmax((h - 0.78) / 0.08, 0.0), 1.0) * (normal_y > 0.75 ? 1.0 : 0.0);
  /* snow caps hills, not the top of a field's centimetre bumps: none below 10 units of
   * relief, all of it from 40 (the default valley's 160 keeps every cap) */
  snowiness *= fmin(fmax((relief - 10.0) / 30.0, 0.0), 1.0);
  for (int c = 0; c < 3; c++) {
    double v = grass[c] + (dry[c] - grass[c]) * dryness;
    v += (rock[c] - v) * rockiness;
    v += (snow[c] - v) * snowiness;
    out[c] = (float)v;
  }
}
