/* The classic fog factors as media (fog_models.h, FOG_MODEL_LINEAR and FOG_MODEL_EXP2,
 * render/fog_classic_cpu.c):
 *   - from the eye the optical depth is the factor itself: -ln((end - L)/(end - start))
 *     past start, 0 before, +inf from end on; (a L)^2;
 *   - from any other point (a lamp's shadow ray) the closed forms match adaptive Simpson
 *     quadrature of k(|o + t d - eye|) in double, split where the ray crosses the start
 *     sphere (k jumps there), to 1e-9 relative; rays passing within 1e-8 of the eye too;
 *   - the model's pointwise K (fog_light_extinction_at) is the derivative of its depth. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/fog_models.h"
#include "render/fog_sun_shadow.h"
#include "test_util.h"

typedef struct medium {
  int linear;
  double start, end, a;
  double eye[3], o[3], d[3];
} medium;

static double k_at(const medium *m, double t) {
  double r2 = 0.0;
  for (int i = 0; i < 3; i++) {
    double x = m->o[i] + t * m->d[i] - m->eye[i];
    r2 += x * x;
  }
  double r = sqrt(r2);
  if (!m->linear) return 2.0 * m->a * m->a * r;
  return r <= m->start ? 0.0 : 1.0 / (m->end - r);
}

static double simpson(const medium *m, double a, double b, double fa, double fm, double fb,
                      double whole, double tol, int depth) {
  double c = 0.5 * (a + b), l = 0.5 * (a + c), r = 0.5 * (c + b);
  double fl = k_at(m, l), fr = k_at(m, r);
  double left = (c - a) / 6.0 * (fa + 4.0 * fl + fm), right = (b - c) / 6.0 * (fm + 4.0 * fr + fb);
  if (depth <= 0 || fabs(left + right - whole) <= 15.0 * tol)
    return left + right + (left + right - whole) / 15.0;
  return simpson(m, a, c, fa, fl, fm, left, 0.5 * tol, depth - 1) +
         simpson(m, c, b, fm, fr, fb, right, 0.5 * tol, depth - 1);
}

static double quad(const medium *m, double a, double b) {
  if (!(b > a)) return 0.0;
  double fa = k_at(m, a), fb = k_at(m, b), fm = k_at(m, 0.5 * (a + b));
  return simpson(m, a, b, fa, fm, fb, (b - a) / 6.0 * (fa + 4.0 * fm + fb), 1e-14, 48);
}

/* The reference: quadrature over [0, L] cut where |o + t d - eye| = start. */
static double reference(const medium *m, double length) {
  double e[3], tc = 0.0, e2 = 0.0;
  for (int i = 0; i < 3; i++) e[i] = m->o[i] - m->eye[i], tc -= e[i] * m->d[i], e2 += e[i] * e[i];
  double cuts[4] = {0.0, length, length, length};
  int n = 1;
  double disc = tc * tc - (e2 - m->start * m->start);
  if (m->linear && disc > 0.0) {
    double roots[2] = {tc - sqrt(disc), tc + sqrt(disc)};
    for (int i = 0; i < 2; i++)
      if (roots[i] > 0.0 && roots[i] < length) cuts[n++] = roots[i];
  }
  cuts[n] = length;
  double sum = 0.0;
  for (int i = 0; i < n; i++) sum += quad(m, cuts[i], cuts[i + 1]);
  return sum;
}

static double uniform(double lo, double hi) { return lo + (hi - lo) * (rand() / (double)RAND_MAX); }

static void random_unit(double d[3]) {
  double n;
  do {
    for (int i = 0; i < 3; i++) d[i] = uniform(-1, 1);
    n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  } while (n < 0.1 || n > 1.0);
  for (int i = 0; i < 3; i++) d[i] /= n;
}

static double depth_of(const medium *m, double length) {
  return m->linear ? fog_linear_optical_depth(m->start, m->end, m->eye, m->o, m->d, length)
                   : fog_exp2_optical_depth(m->a, m->eye, m->o, m->d, length);
}

int main(void) {
  srand(17);
  /* From the eye: the factors. */
  {
    medium m = {.linear = 1, .start = 100, .end = 900, .eye = {3, 40, -7}, .o = {3, 40, -7}};
    random_unit(m.d);
    const double lengths[] = {50, 100, 100.5, 400, 899, 899.999};
    for (int i = 0; i < 6; i++) {
      double L = lengths[i], want = L <= 100 ? 0.0 : -log((900 - L) / 800.0);
      double got = depth_of(&m, L);
      CHECK(fabs(got - want) <= 1e-12 * fmax(1.0, want), "linear from the eye, L %g: %.17g, want %.17g",
            L, got, want);
    }
    CHECK(depth_of(&m, 900) == HUGE_VAL && depth_of(&m, 5000) == HUGE_VAL &&
              depth_of(&m, HUGE_VAL) == HUGE_VAL, "linear: opaque from end on");
    m.linear = 0, m.a = 0.0021;
    for (int i = 0; i < 6; i++) {
      double L = lengths[i], want = (0.0021 * L) * (0.0021 * L), got = depth_of(&m, L);
      CHECK(fabs(got - want) <= 1e-13 * fmax(1e-3, want), "exp2 from the eye, L %g: %.17g, want %.17g",
            L, got, want);
    }
  }
  /* From anywhere: against quadrature. */
  double worst[2] = {0, 0};
  int cases[2] = {0, 0};
  for (int trial = 0; trial < 400; trial++) {
    medium m = {.linear = trial % 2, .end = uniform(200, 1000), .a = uniform(1e-4, 5e-3)};
    m.start = uniform(0, 0.6) * m.end;
    for (int i = 0; i < 3; i++) m.eye[i] = uniform(-100, 100);
    random_unit(m.d);
    double off[3];
    random_unit(off);
    /* the start point: inside the end sphere; every 5th ray passes within 1e-8 of the eye */
    double r0 = uniform(0.0, 0.9) * m.end;
    for (int i = 0; i < 3; i++) m.o[i] = m.eye[i] + r0 * off[i];
    if (trial % 5 == 0) {
      double along = 0.0;
      for (int i = 0; i < 3; i++) along += (m.eye[i] - m.o[i]) * m.d[i];
      for (int i = 0; i < 3; i++) m.o[i] = m.eye[i] - along * m.d[i] + 1e-8 * off[i];
    }
    /* a length that stays inside the end sphere (the linear fog is finite there) */
    double length = uniform(1, 2 * m.end), far = 0.0;
    for (int shrink = 0; shrink < 60; shrink++, length *= 0.8) {
      far = 0.0;
      for (int i = 0; i < 3; i++) {
        double x = m.o[i] + length * m.d[i] - m.eye[i];
        far += x * x;
      }
      if (sqrt(far) < 0.99 * m.end) break;
    }
    if (!(sqrt(far) < 0.99 * m.end)) continue;
    double want = reference(&m, length), got = depth_of(&m, length);
    double rel = fabs(got - want) / fmax(want, 1e-6);
    worst[m.linear] = fmax(worst[m.linear], rel);
    cases[m.linear]++;
    CHECK(rel <= 1e-9, "%s trial %d: %.17g, quadrature %.17g (rel %.2e)",
          m.linear ? "linear" : "exp2", trial, got, want, rel);
  }
  printf("from anywhere: linear %d rays, worst rel %.2e; exp2 %d rays, worst rel %.2e\n",
         cases[1], worst[1], cases[0], worst[0]);
  CHECK(cases[0] > 100 && cases[1] > 100, "too few rays: %d, %d", cases[0], cases[1]);
  /* K at a point is the depth's derivative, as the light's samples read it. */
  {
    fog_model lin = {.kind = FOG_MODEL_LINEAR, .fog_start = 50, .fog_end = 700,
                     .eye = {10, 20, 30}};
    fog_model e2 = {.kind = FOG_MODEL_EXP2, .extinction = 0.003, .eye = {10, 20, 30}};
    double d[3] = {0.6, 0.0, 0.8}, p[3];
    for (int k = 0; k < 2; k++) {
      const fog_model *m = k ? &e2 : &lin;
      for (double t = 60; t < 690; t += 90) {
        for (int i = 0; i < 3; i++) p[i] = m->eye[i] + t * d[i];
        double h = 1e-3;
        double slope = (fog_model_optical_depth(m, m->eye, d, t + h) -
                        fog_model_optical_depth(m, m->eye, d, t - h)) / (2 * h);
        double k_p = fog_light_extinction_at(m, p);
        CHECK(fabs(slope - k_p) <= 1e-6 * k_p, "%s at t %g: K %.12g, slope %.12g",
              k ? "exp2" : "linear", t, k_p, slope);
      }
    }
  }
  return test_finish("test_integral_classic");
}
