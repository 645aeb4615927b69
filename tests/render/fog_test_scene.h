/* Shared set-up for the integrator tests: a seeded RNG, random coefficient grids with
 * ghost margins, the three vertical profiles, a fog volume and random rays. */
#ifndef FOGPIPE_TESTS_RENDER_FOG_TEST_SCENE_H
#define FOGPIPE_TESTS_RENDER_FOG_TEST_SCENE_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "render/fog_field.h"
#include "render/fog_models.h"
#include "render/volume_march.h"
#include "transform/transform.h"

static uint64_t fog_test_rng = 0x9E3779B97F4A7C15ull;
static inline double fog_test_uniform(void) { /* xorshift64*, [0, 1) */
  fog_test_rng ^= fog_test_rng >> 12;
  fog_test_rng ^= fog_test_rng << 25;
  fog_test_rng ^= fog_test_rng >> 27;
  return (double)((fog_test_rng * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}
static inline double fog_test_range(double a, double b) { return a + (b - a) * fog_test_uniform(); }

/* A W x H fogmap box: 24 x 16 fine samples of 2.5 world units at (100, -50). */
enum { FOG_TEST_W = 24, FOG_TEST_H = 16 };

/* A zero degree-d grid at the given spacing covering a box of width x height fine samples
 * with a ghost margin of d+1 coarse cells, its origin moved by (du, dv). */
static inline transform_grid fog_test_margin_grid(int degree, double spacing, int width,
                                                  int height, double du, double dv) {
  transform_grid g;
  fog_error err;
  int margin = degree + 1;
  int w = (int)ceil(width / spacing) + 2 * margin + 1;
  int h = (int)ceil(height / spacing) + 2 * margin + 1;
  transform_grid_create(&g, w, h, &err);
  g.degree = degree;
  g.spacing = spacing;
  g.origin_u = -0.5 - margin * spacing + du;
  g.origin_v = -0.5 - margin * spacing + dv;
  return g;
}

/* A random degree-d grid at the given spacing covering the box with a ghost margin of
 * d+1 coarse cells (and an arbitrary sub-cell origin offset). */
static inline transform_grid fog_test_grid(int degree, double spacing, double offset) {
  transform_grid g =
      fog_test_margin_grid(degree, spacing, FOG_TEST_W, FOG_TEST_H, offset, -0.37 * offset);
  for (int i = 0; i < g.width * g.height; i++) g.coefficients[i] = (float)fog_test_uniform();
  return g;
}

/* The exact refinement of a coarse grid onto the grid of half its spacing (two-scale
 * relation of the centred B-spline: phi_d(x) = sum_k 2^-d C(d+1,k) phi_d(2x - k + (d+1)/2)),
 * so fine coefficient 2i+k sits at origin - spacing_fine (d+1)/2 + spacing_fine (2i+k). */
static inline transform_grid fog_test_refine(const transform_grid *c) {
  static const double mask[3][4] = {{1, 1}, {0.5, 1, 0.5}, {0.25, 0.75, 0.75, 0.25}};
  int d = c->degree;
  transform_grid f;
  fog_error err;
  transform_grid_create(&f, 2 * c->width + d, 2 * c->height + d, &err);
  f.degree = d;
  f.spacing = 0.5 * c->spacing;
  f.origin_u = c->origin_u - f.spacing * 0.5 * (d + 1);
  f.origin_v = c->origin_v - f.spacing * 0.5 * (d + 1);
  for (int j = 0; j < c->height; j++)
    for (int i = 0; i < c->width; i++)
      for (int l = 0; l <= d + 1; l++)
        for (int k = 0; k <= d + 1; k++)
          f.coefficients[(size_t)(2 * j + l) * f.width + 2 * i + k] +=
              (float)(mask[d][k] * mask[d][l] * c->coefficients[(size_t)j * c->width + i]);
  return f;
}

/* A consistent LOD pyramid of `levels` levels: A_0 random at spacing 2^J, D_l random
 * (signed, smaller) on the refined grid of A_{l-1}, A_l = refine(A_{l-1}) + D_l exactly as
 * functions (float sums of small dyadic-weighted values; tests allow float rounding). */
static inline void fog_test_pyramid(int degree, int levels, transform_grid *approx,
                                    transform_grid *detail) {
  approx[0] = fog_test_grid(degree, (double)(1 << levels), 0.0);
  for (int l = 1; l <= levels; l++) {
    transform_grid up = fog_test_refine(&approx[l - 1]);
    transform_grid dl = fog_test_refine(&approx[l - 1]);
    for (int i = 0; i < dl.width * dl.height; i++) {
      dl.coefficients[i] = (float)fog_test_range(-0.25, 0.25);
      up.coefficients[i] += dl.coefficients[i];
    }
    approx[l] = up;
    detail[l - 1] = dl;
  }
}

static double fog_test_profile_coefficients[8];

static inline fog_profile fog_test_profile(fog_profile_kind kind) {
  switch (kind) {
    case FOG_PROFILE_SLAB:
      return (fog_profile){.kind = kind, .y_floor = 2.0, .y_top = 12.0};
    case FOG_PROFILE_EXPONENTIAL:
      return (fog_profile){.kind = kind, .y_floor = 0.0, .y0 = 3.0, .scale_height = 4.0,
                           .y_top = 40.0};
    default:
      for (int k = 0; k < 8; k++) fog_test_profile_coefficients[k] = fog_test_range(0.2, 1.5);
      return (fog_profile){.kind = FOG_PROFILE_BSPLINE, .count = 8, .degree = 2,
                           .coefficients = fog_test_profile_coefficients, .origin = 1.0,
                           .spacing = 2.0};
  }
}

static inline fog_volume fog_test_volume(fog_profile_kind kind) {
  return (fog_volume){.map_width = FOG_TEST_W, .map_height = FOG_TEST_H, .origin_x = 100.0,
                      .origin_z = -50.0, .cell_size = 2.5, .extinction = 0.05,
                      .profile = fog_test_profile(kind)};
}

/* Fog in patches (the empty-space skipping tests): a FOG_TEST_PATCH_W x _H box of the
 * volume above, a grid of `background` (0, or values in [background/2, background]) with 7
 * rectangular patches of random fog in [0.2, 1.2]. */
enum { FOG_TEST_PATCH_W = 180, FOG_TEST_PATCH_H = 120 };

static inline transform_grid fog_test_patch_grid(int degree, double spacing, float background) {
  transform_grid g =
      fog_test_margin_grid(degree, spacing, FOG_TEST_PATCH_W, FOG_TEST_PATCH_H, 0.3, -0.11);
  const int w = g.width, h = g.height;
  for (int i = 0; i < w * h; i++)
    g.coefficients[i] =
        background > 0 ? (float)(background * (0.5 + 0.5 * fog_test_uniform())) : 0.0f;
  for (int p = 0; p < 7; p++) {
    int pw = 2 + (int)(fog_test_uniform() * 14), ph = 2 + (int)(fog_test_uniform() * 14);
    int x0 = (int)(fog_test_uniform() * (w - pw)), z0 = (int)(fog_test_uniform() * (h - ph));
    for (int j = z0; j < z0 + ph; j++)
      for (int i = x0; i < x0 + pw; i++)
        g.coefficients[(size_t)j * w + i] = (float)fog_test_range(0.2, 1.2);
  }
  return g;
}

static inline fog_volume fog_test_patch_volume(fog_profile_kind kind) {
  fog_volume v = fog_test_volume(kind);
  v.map_width = FOG_TEST_PATCH_W;
  v.map_height = FOG_TEST_PATCH_H;
  return v;
}

static inline void fog_test_unit(double d[3]) {
  double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int i = 0; i < 3; i++) d[i] /= n;
}

/* A random ray: camera inside the (slightly enlarged) box with probability 1/2, else
 * around it, aimed at a random point of the box. */
static inline void fog_test_ray(const fog_volume *v, double camera[3], double dir[3]) {
  double lo[3], hi[3], target[3];
  fog_volume_box(v, lo, hi);
  int inside = fog_test_uniform() < 0.5;
  for (int a = 0; a < 3; a++) {
    double ext = hi[a] - lo[a];
    camera[a] = inside ? fog_test_range(lo[a], hi[a]) : fog_test_range(lo[a] - ext, hi[a] + ext);
    target[a] = fog_test_range(lo[a], hi[a]);
    dir[a] = target[a] - camera[a];
  }
  fog_test_unit(dir);
}

/* The analytic models' scene of test_gpu_fog_vs_cpu and test_gpu_lamps: a dozen Gaussians
 * between the camera and the view's far side, drawn from the generator in this order. */
enum { FOG_TEST_RBF_COUNT = 12 };
static inline void fog_test_scene_rbfs(fog_rbf rbfs[FOG_TEST_RBF_COUNT]) {
  for (int i = 0; i < FOG_TEST_RBF_COUNT; i++) {
    double s_i = fog_test_range(0.15, 1.0);
    rbfs[i] = (fog_rbf){.centre = {10.0 + 70.0 * s_i + fog_test_range(-15, 15),
                                   fog_test_range(0.0, 14.0),
                                   20.0 - 80.0 * s_i + fog_test_range(-15, 15)},
                        .radius = fog_test_range(3.0, 15.0), .density = fog_test_range(0.04, 0.15)};
  }
}

/* And its volume: 2-unit voxels over x 30..78, z -50..-10, y 0..20, index axes (z, x, y): a
 * permutation that is not its own transpose (the matrix's layout matters), random density.
 * The values are malloc'ed into *values (the caller frees them). */
static inline volume_grid_desc fog_test_scene_volume(float **values) {
  enum { GX = 24, GZ = 20, GY = 10 };
  *values = malloc(sizeof(float) * GX * GZ * GY);
  for (int i = 0; i < GX * GZ * GY; i++) (*values)[i] = (float)fog_test_range(0.0, 0.12);
  return (volume_grid_desc){.dim = {GZ, GX, GY}, .values = *values,
                            .index_from_world = {{0, 0, 0.5}, {0.5, 0, 0}, {0, 0.5, 0}},
                            .index_offset = {25.0, -15.0, 0.0}};
}

/* The scene's Gaussians and volume together (drawn in that order; grid_values malloc'ed:
 * free it), and its models: homogeneous and height fog at K 0.02 (height: y0 4, scale
 * height 6), the Gaussians over a base of rbf_base, the volume. */
typedef struct fog_test_models {
  fog_rbf rbfs[FOG_TEST_RBF_COUNT];
  float *grid_values;
  volume_grid_desc grid3d;
} fog_test_models;
static inline void fog_test_scene_models(fog_test_models *s) {
  fog_test_scene_rbfs(s->rbfs);
  s->grid3d = fog_test_scene_volume(&s->grid_values);
}
static inline fog_model fog_test_scene_model(const fog_test_models *s, fog_model_kind kind,
                                             double rbf_base) {
  if (kind == FOG_MODEL_RBF)
    return (fog_model){.kind = kind, .extinction = rbf_base, .rbfs = s->rbfs,
                       .rbf_count = FOG_TEST_RBF_COUNT};
  if (kind == FOG_MODEL_VOLUME) return (fog_model){.kind = kind, .grid3d = &s->grid3d};
  return (fog_model){.kind = kind, .extinction = 0.02, .y0 = 4.0, .scale_height = 6.0};
}

#endif
