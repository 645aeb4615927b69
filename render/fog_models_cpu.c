/* The fog models besides the fogmap (fog_models.h), in double, and the model table;
 * twins in render/shaders/fog_models.glsl. The volume's integrals are in fog_grid3d_cpu.c,
 * the fogmap's in fog_integral_cpu.c. */
#include <math.h>
#include <string.h>

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
  double a = dir_y / scale_height;
  if (isinf(length)) return a > 0.0 ? extinction * exp(-(camera_y - y0) / scale_height) / a
                                    : HUGE_VAL;
  /* downwards from the lower end, as the GLSL (no 0 * inf far above the fog) */
  if (a < 0.0)
    return extinction * exp(-(camera_y + dir_y * length - y0) / scale_height) * length *
           fog_exprel(-a * length);
  return extinction * exp(-(camera_y - y0) / scale_height) * length * fog_exprel(a * length);
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

/* The CPU twins of the table's rows (the volume's lives in fog_grid3d_cpu.c). */
double fog_model_depth_fogmap(const fog_model *m, const double camera[3], const double dir[3],
                              double t_surface) {
  if (!m->lod) return 0.0;
  return fog_optical_depth_lod(m->volume, m->lod, m->lod_method, camera, dir, t_surface);
}

double fog_model_depth_homogeneous(const fog_model *m, const double camera[3],
                                   const double dir[3], double t_surface) {
  (void)camera, (void)dir;
  return fog_homogeneous_optical_depth(m->extinction, t_surface);
}

double fog_model_depth_height(const fog_model *m, const double camera[3], const double dir[3],
                              double t_surface) {
  return fog_height_optical_depth(m->extinction, m->y0, m->scale_height, camera[1], dir[1],
                                  t_surface);
}

double fog_model_depth_rbf(const fog_model *m, const double camera[3], const double dir[3],
                           double t_surface) {
  return fog_rbf_optical_depth(m->extinction, m->rbfs, m->rbf_count, camera, dir, t_surface);
}

const fog_model_info fog_model_table[FOG_MODEL_COUNT] = {
#define FOG_MODEL_ROW(KIND, id, label_, keys_, pyramid_)                                      \
  [FOG_MODEL_##KIND] = {.kind = FOG_MODEL_##KIND, .name = #id, .label = label_, .keys = keys_, \
                        .pyramid = pyramid_, .optical_depth = fog_model_depth_##id},
#include "render/fog_models.def"
#undef FOG_MODEL_ROW
};

const fog_model_info *fog_model_find(const char *name) {
  for (int k = 0; k < FOG_MODEL_COUNT; k++)
    if (!strcmp(fog_model_table[k].name, name)) return &fog_model_table[k];
  return NULL;
}

bool fog_model_quadrics_beside(const fog_model *m) {
  return m->kind != FOG_MODEL_QUADRIC && m->quadric_count > 0 && m->quadrics;
}

fog_model fog_model_alone(const fog_model *m) {
  fog_model alone = *m;
  if (fog_model_quadrics_beside(m)) alone.quadrics = NULL, alone.quadric_count = 0;
  return alone;
}

double fog_model_optical_depth(const fog_model *m, const double camera[3], const double dir[3],
                               double t_surface) {
  if ((unsigned)m->kind >= FOG_MODEL_COUNT) return NAN;
  double depth = fog_model_table[m->kind].optical_depth(m, camera, dir, t_surface);
  if (fog_model_quadrics_beside(m)) {
    const fog_quadric_noise noise = fog_model_quadric_noise(m);
    depth += fog_quadric_optical_depth(m->quadrics, m->quadric_count, &noise, camera, dir,
                                       t_surface);
  }
  return depth;
}
