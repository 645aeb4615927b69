/* The classic fog factors as fog models (render/fog_models.h, FOG_MODEL_LINEAR and
 * FOG_MODEL_EXP2): OpenGL's GL_LINEAR and GL_EXP2 fog (Zdrojewska eq. 2 and 4) read as
 * media. The factor f(d) of the distance d from the eye is the view ray's transmittance,
 * so the medium is radial about the eye: K(p) = k(|p - eye|), k(r) = -d ln f / dr. From
 * the eye the closed forms are the factors themselves; from any other point (a lamp's
 * shadow ray, a test's) the integrals below are exact too. */
#include <math.h>

#include "render/fog_models.h"

double fog_linear_extinction(double start, double end, double r) {
  if (r <= start) return 0.0;
  return r < end ? 1.0 / (end - r) : HUGE_VAL;
}

double fog_exp2_extinction(double density, double r) { return 2.0 * density * density * r; }

bool fog_model_about_eye(const fog_model *m) {
  return m->kind == FOG_MODEL_LINEAR || m->kind == FOG_MODEL_EXP2;
}

/* The ray o + t d as seen from the eye: r(t)^2 = h^2 + (t - tc)^2. */
static void radial_frame(const double eye[3], const double o[3], const double d[3], double *tc,
                         double *h) {
  double e[3] = {eye[0] - o[0], eye[1] - o[1], eye[2] - o[2]};
  *tc = e[0] * d[0] + e[1] * d[1] + e[2] * d[2];
  double h2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2] - *tc * *tc;
  *h = h2 > 0.0 ? sqrt(h2) : 0.0;
}

/* int 2 a^2 sqrt(h^2 + s^2) ds = a^2 G(s), G(s) = s sqrt(h^2 + s^2) + h^2 asinh(s / h). */
static double exp2_antiderivative(double h, double s) {
  double g = s * sqrt(h * h + s * s);
  return h > 0.0 ? g + h * h * asinh(s / h) : g;
}

double fog_exp2_optical_depth(double density, const double eye[3], const double o[3],
                              const double d[3], double length) {
  if (density == 0.0) return 0.0;
  if (!(length < HUGE_VAL)) return HUGE_VAL;
  double tc, h;
  radial_frame(eye, o, d, &tc, &h);
  return density * density *
         (exp2_antiderivative(h, length - tc) - exp2_antiderivative(h, -tc));
}

/* An antiderivative of 1 / (end - sqrt(h^2 + s^2)) where sqrt(h^2 + s^2) < end, odd in s,
 * P(0) = 0. With c = sqrt(end^2 - h^2) and R = sqrt(h^2 + s^2) (d/ds checks it):
 *   P(s) = (E/c) artanh(s/c) - asinh(s/h) + (E/c) artanh(E s / (c R)),
 * written with logarithms of factors that do not cancel: c - s = (E - R)(E + R)/(c + s)
 * and 1 - E s/(c R) = h^2 (E - R)(E + R) / (c R (c R + E s)). For h -> 0 (the ray
 * through the eye) it tends to ln E - ln(E - |s|), taken directly below h = 1e-9 E. */
static double linear_antiderivative(double end, double h, double s) {
  const double sign = s < 0.0 ? -1.0 : 1.0, E = end;
  s = fabs(s);
  const double R = sqrt(h * h + s * s);
  if (!(h > 1e-9 * E)) return sign * (log(E) - log(E - s));
  const double c = sqrt((E - h) * (E + h));
  const double logs = log(c + s) + log(c * R + E * s) - log(E - R) - log(E + R);
  /* (E/c)(logs - ln h) - ln(s + R) + ln h, with (1 - E/c) ln h kept apart: it vanishes as
   * h -> 0 while ln h does not */
  return sign * ((E / c) * logs - log(s + R) + (1.0 - E / c) * log(h));
}

double fog_linear_optical_depth(double start, double end, const double eye[3],
                                const double o[3], const double d[3], double length) {
  if (!(length < HUGE_VAL)) return HUGE_VAL; /* every ray reaches the end */
  double tc, h;
  radial_frame(eye, o, d, &tc, &h);
  const double s0 = -tc, s1 = length - tc;
  /* r is largest at an end of the segment: past `end` the fog is opaque */
  if (sqrt(h * h + fmax(s0 * s0, s1 * s1)) >= end) return HUGE_VAL;
  /* no fog where r <= start: |s| <= w */
  const double w = start > h ? sqrt((start - h) * (start + h)) : 0.0;
  double depth = 0.0;
  if (s0 < -w) depth += linear_antiderivative(end, h, fmin(s1, -w)) -
                        linear_antiderivative(end, h, s0);
  if (s1 > w) depth += linear_antiderivative(end, h, s1) -
                       linear_antiderivative(end, h, fmax(s0, w));
  return depth;
}

double fog_model_depth_linear(const fog_model *m, const double camera[3], const double dir[3],
                              double t_surface) {
  return fog_linear_optical_depth(m->fog_start, m->fog_end, m->eye, camera, dir, t_surface);
}

double fog_model_depth_exp2(const fog_model *m, const double camera[3], const double dir[3],
                            double t_surface) {
  return fog_exp2_optical_depth(m->extinction, m->eye, camera, dir, t_surface);
}
