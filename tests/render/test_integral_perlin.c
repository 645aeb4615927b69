/* Animated Perlin turbulence fog (render/fog_perlin.h), the CPU twin in double:
 *   - the noise: |n| is 0 at every lattice point (every 4th texel), the octaves repeat with
 *     the texture's period, and the animation is each octave's drift (one octave: T(p, s) =
 *     T(p - w s, 0));
 *   - the exact optical depth against an independent reference (tests/reference/
 *     perlin_reference.h: the density evaluated from the texels, trilinear and wrapped, its
 *     breaks every crossing of a texel plane of any octave, listed, not walked; the light
 *     reference's adaptive Gauss-Kronrod between them); rays inside and outside the box,
 *     grazing, vertical, at several times: relative error <= 1e-9;
 *   - the light gathered per piece (fog_perlin_light_integral: S = int tau K T_s) with 1, 2
 *     and 3 nodes against the reference's S with the same exact T_s (nested quadrature
 *     towards the sun): the error falls with the nodes, 2 nodes within 1e-5 of S;
 *   - the paper's variant is T at the ray's last point in the box times the height fog there:
 *     checked against the reference's own height integral and turbulence;
 *   - bad descriptors are refused naming the field. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reference/perlin_reference.h"
#include "render/render.h"
#include "test_util.h"

static const double g8_x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                               -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                               0.7966664774136267,  0.9602898564975363};
static const double g8_w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                               0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                               0.2223810344533745, 0.1012285362903763};

/* The box's slab, independently. */
static int ref_stretch(const fog_perlin *p, const double o[3], const double d[3], double length,
                       double *t0, double *t1) {
  double lo = 0, hi = length;
  for (int a = 0; a < 3; a++) {
    if (d[a] == 0) {
      if (o[a] < p->desc.lo[a] || o[a] > p->desc.hi[a]) return 0;
      continue;
    }
    double ta = (p->desc.lo[a] - o[a]) / d[a], tb = (p->desc.hi[a] - o[a]) / d[a];
    lo = fmax(lo, fmin(ta, tb));
    hi = fmin(hi, fmax(ta, tb));
  }
  *t0 = lo, *t1 = hi;
  return hi > lo;
}


int main(void) {
  fog_error err = {0};
  fog_perlin_desc desc = fog_perlin_desc_default();
  desc.octaves = 4;
  desc.size = 16;
  desc.feature_size = 20.0;
  desc.lo[0] = -60, desc.lo[1] = 0, desc.lo[2] = -50;
  desc.hi[0] = 70, desc.hi[1] = 18, desc.hi[2] = 40;
  fog_perlin p;
  CHECK(fog_perlin_create(&p, &desc, &err) == 0, "create: %s", err.message);
  if (!p.texels) return test_finish("test_integral_perlin");

  /* The noise: zero at lattice points, texels in [0, 1.1), something in between. */
  const int n = desc.size;
  double worst_lattice = 0, largest = 0;
  for (int i = 0; i < desc.octaves; i++)
    for (int z = 0; z < n; z++)
      for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
          float v = p.texels[(((size_t)i * n + z) * n + y) * n + x];
          if (x % 4 == 0 && y % 4 == 0 && z % 4 == 0) worst_lattice = fmax(worst_lattice, v);
          largest = fmax(largest, v);
          CHECK(v >= 0 && v < 1.1, "octave %d texel (%d %d %d) = %g", i, x, y, z, v);
        }
  CHECK(worst_lattice == 0 && largest > 0.3, "lattice values %g, largest %g", worst_lattice,
        largest);
  /* Periodic: octave 0's world period size * feature / 4 holds for every octave. */
  double period = n * desc.feature_size / FOG_PERLIN_TEXELS_PER_LATTICE, worst_period = 0;
  for (int k = 0; k < 50; k++) {
    double x[3] = {-40 + 1.7 * k, 0.3 * k, 13 - 0.9 * k}, y[3] = {x[0] + period, x[1] - period,
                                                                  x[2] + 2 * period};
    worst_period = fmax(worst_period, fabs(fog_perlin_turbulence(&p, 1.5, x) -
                                           fog_perlin_turbulence(&p, 1.5, y)));
    CHECK(fabs(fog_perlin_turbulence(&p, 0.7, x) - perlin_ref_turbulence(&p, 0.7, x)) < 1e-12,
          "turbulence at sample %d differs from the definition", k);
  }
  CHECK(worst_period < 1e-9, "turbulence not periodic: %g", worst_period);

  /* The animation: one octave drifts with its wind. */
  {
    fog_perlin_desc one = desc;
    one.octaves = 1;
    fog_perlin q;
    CHECK(fog_perlin_create(&q, &one, &err) == 0, "create one octave: %s", err.message);
    double worst = 0;
    for (int k = 0; k < 30; k++) {
      double s = 0.37 * k, x[3] = {5 + k, 3 + 0.2 * k, -7 + 0.5 * k}, y[3];
      for (int a = 0; a < 3; a++) y[a] = x[a] - one.wind[0][a] * s;
      worst = fmax(worst, fabs(fog_perlin_turbulence(&q, s, x) - fog_perlin_turbulence(&q, 0, y)));
    }
    CHECK(worst < 1e-12, "one octave does not drift with its wind: %g", worst);
    fog_perlin_destroy(&q);
  }

  /* The exact optical depth against the reference. */
  const double cams[4][3] = {{5, 6, -3}, {-120, 30, -90}, {10, 40, 10}, {100, 2, 60}};
  const double targets[4][3] = {{60, 2, 30}, {50, 0, 30}, {12, -5, 11}, {-50, 17.9, -40}};
  double worst = 0, worst_paper = 0, mean_gap = 0;
  int rays = 0;
  for (int c = 0; c < 4; c++)
    for (int k = 0; k < 6; k++) {
      double d[3], norm = 0;
      for (int a = 0; a < 3; a++) {
        d[a] = targets[c][a] + (a == 1 ? 0.0 : 9.0 * (k - 2.5)) - cams[c][a];
        norm += d[a] * d[a];
      }
      for (int a = 0; a < 3; a++) d[a] /= sqrt(norm);
      if (c == 2 && k == 0) d[0] = d[2] = 0, d[1] = -1; /* vertical */
      double length = (k % 3 == 0) ? HUGE_VAL : 35.0 + 20 * k;
      fog_perlin_medium m = {.extinction = 0.05, .y0 = 2.0, .scale_height = 6.0,
                             .time = 0.8 * k, .integral = FOG_PERLIN_EXACT};
      double got = fog_perlin_optical_depth(&p, &m, cams[c], d, length);
      light_ref_medium medium = light_ref_perlin_medium(&p, &m);
      double want = light_ref_optical_depth(&medium, cams[c], d, 0.0, length, 1e-13);
      double e = fabs(got - want) / fmax(want, 1e-12);
      worst = fmax(worst, e);
      CHECK(e <= 1e-9, "camera %d ray %d: %.15g vs reference %.15g", c, k, got, want);
      /* the paper's variant: T once at the stretch's end times the height fog over it */
      m.integral = FOG_PERLIN_PAPER;
      double paper = fog_perlin_optical_depth(&p, &m, cams[c], d, length), t0, t1;
      double want_paper = 0;
      if (ref_stretch(&p, cams[c], d, length, &t0, &t1)) {
        double end[3], height = 0;
        for (int a = 0; a < 3; a++) end[a] = cams[c][a] + t1 * d[a];
        fog_perlin_medium flat = m;
        /* the height integral by the same quadrature, with T = 1: a one-octave box of ones */
        for (int q = 0; q < 64; q++) {
          double a = t0 + (t1 - t0) * q / 64, b = t0 + (t1 - t0) * (q + 1) / 64, hh = 0;
          for (int j = 0; j < 8; j++) {
            double t = 0.5 * (a + b) + 0.5 * (b - a) * g8_x[j];
            hh += g8_w[j] * flat.extinction *
                  exp(-(cams[c][1] + t * d[1] - flat.y0) / flat.scale_height);
          }
          height += 0.5 * (b - a) * hh;
        }
        want_paper = perlin_ref_turbulence(&p, m.time, end) * height;
      }
      worst_paper = fmax(worst_paper, fabs(paper - want_paper) / fmax(want_paper, 1e-12));
      if (want > 0) mean_gap += fabs(paper - want) / want, rays++;
    }
  printf("exact vs reference: worst relative error %.2e; paper vs its definition %.2e; the "
         "paper's mean relative distance from the true integral %.1f %%\n",
         worst, worst_paper, 100 * mean_gap / rays);
  CHECK(worst_paper <= 1e-9, "paper variant off its definition by %.3e", worst_paper);
  CHECK(mean_gap / rays > 0.01, "the paper's single sample matches the integral too well (%g): "
        "is it the integral?", mean_gap / rays);

  /* The light gathered per piece against the reference's S, the same exact T_s. */
  {
    fog_perlin_medium m = {.extinction = 0.05, .y0 = 2.0, .scale_height = 6.0, .time = 1.5,
                           .integral = FOG_PERLIN_EXACT};
    light_ref_medium medium = light_ref_perlin_medium(&p, &m);
    light_ref_sun_point user = {.medium = &medium, .tol = 1e-10, .sun = {0.6, 0.35, -0.72}};
    double norm = 0;
    for (int a = 0; a < 3; a++) norm += user.sun[a] * user.sun[a];
    for (int a = 0; a < 3; a++) user.sun[a] /= sqrt(norm);
    double worst[3] = {0, 0, 0}, worst_depth = 0;
    for (int r = 0; r < 3; r++) {
      const double o[3] = {-20.0 + 15 * r, 4.0 + 3 * r, 10.0 - 12 * r};
      double d[3] = {cos(1.1 * r + 0.3), -0.08, sin(1.1 * r + 0.3)}, n = 0;
      for (int a = 0; a < 3; a++) n += d[a] * d[a];
      for (int a = 0; a < 3; a++) d[a] /= sqrt(n);
      double ref_tau, s_ref = light_ref_sun_inscatter(&medium, o, d, 45.0, user.sun, 1, 1e-10,
                                                      &ref_tau);
      CHECK(s_ref == s_ref && s_ref > 1e-3, "light ray %d: reference S %g", r, s_ref);
      for (int nodes = 1; nodes <= 3; nodes++) {
        double D, S = fog_perlin_light_integral(&p, &m, o, d, 45.0, nodes, HUGE_VAL,
                                                light_ref_sun_point_light, &user, &D);
        worst[nodes - 1] = fmax(worst[nodes - 1], fabs(S - s_ref) / s_ref);
        if (nodes == 3) worst_depth = fmax(worst_depth, fabs(exp(-D) - ref_tau));
      }
    }
    printf("light per piece vs the reference's S: 1 node %.2e, 2 nodes %.2e, 3 nodes %.2e "
           "(relative); the walk's tau %.2e off\n", worst[0], worst[1], worst[2], worst_depth);
    CHECK(worst[1] < worst[0] && worst[2] < worst[1], "no convergence with the nodes: %.3e "
          "%.3e %.3e", worst[0], worst[1], worst[2]);
    CHECK(worst[1] <= 1e-5 && worst[2] <= 1e-6 && worst_depth <= 1e-9,
          "per-piece light off: 2 nodes %.3e, 3 nodes %.3e, tau %.3e", worst[1], worst[2],
          worst_depth);
  }

  /* Bad descriptors. */
  const char *said[4] = {"octaves", "texture size", "feature size", "box"};
  for (int k = 0; k < 4; k++) {
    fog_perlin_desc bad = fog_perlin_desc_default();
    if (k == 0) bad.octaves = 7;
    if (k == 1) bad.size = 24;
    if (k == 2) bad.feature_size = 0;
    if (k == 3) bad.hi[1] = bad.lo[1];
    fog_perlin q;
    fog_error e = {0};
    CHECK(fog_perlin_create(&q, &bad, &e) != 0 && strstr(e.message, said[k]) && !q.texels,
          "bad descriptor %d: '%s'", k, e.message);
  }
  fog_perlin_destroy(&p);
  return test_finish("test_integral_perlin");
}
