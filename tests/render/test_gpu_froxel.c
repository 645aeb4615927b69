/* The froxel baseline (FOG_INTEGRATOR_FROXEL, render/shaders/fog_froxel.glsl) on the GL:
 *   1. exact where the method is exact: a homogeneous fog lit by the ambient alone has a
 *      constant extinction and source, so each slice's integral is exact and the grid holds
 *      T(z) = e^{-K (z - near)}, L = L_amb (1 - T(z)) at every face z. The lookup of pixel
 *      distance t is then the linear interpolation between the faces around t in the
 *      continuous face index f = slices ln(t / near) / ln(far / near): checked per pixel
 *      against that closed form (sky pixels: the far face exactly);
 *   2. it converges, but slowly: height fog lit by a low sun with its closed-form
 *      self-shadow, each grid against the exact view-ray integral (the fog pass's exact
 *      integrator with 512 segments of the T_s mean): the 2x and 4x grids each err less than
 *      the one before;
 *   3. a grid without a size or depth range is refused, saying what was expected. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "fog_test_gl.h"
#include "test_util.h"

enum { W = 160, H = 90 };
static const double ground_y = 0.0;

/* Max |colour - want| over the pixels and channels, relative to the largest want. */
static double max_rel_error(const float *got, const float *want, int n) {
  double worst = 0, peak = 0;
  for (int i = 0; i < n; i++) peak = fmax(peak, fabs(want[i]));
  for (int i = 0; i < n; i++) {
    double e = fabs((double)got[i] - want[i]);
    worst = fmax(worst, e == e ? e : HUGE_VAL);
  }
  return worst / peak;
}

static int draw(fog_test_gl *gl, const camera *cam, const fog_pass_params *params, float *rgba,
                float *tau, fog_error *err) {
  if (fog_test_gl_draw_tau(gl, cam, params, tau, err)) return 1;
  return gl_target_read(&gl->target, 0, 4, rgba, err);
}

int main(void) {
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_gpu_froxel");
  static float rgba[4 * W * H], tau[W * H], want[4 * W * H], exact[4 * W * H];
  camera cam = {.position = {0.0, 3.0, 0.0}, .fov_y = 1.0, .near_plane = CAMERA_DEFAULT_NEAR,
                .far_plane = CAMERA_DEFAULT_FAR};
  camera_look_at(&cam, (double[3]){100.0, 1.0, 30.0});
  fog_test_gl_set_ground(&gl, &cam, ground_y);

  /* 1. Homogeneous fog, ambient light only: the closed form of the grid and its lookup. */
  {
    const double K = 0.02, near = 0.5, far = 300.0;
    const int slices = 48;
    const float ambient[3] = {0.6f, 0.7f, 0.8f};
    fog_pass_params params = {.model = FOG_MODEL_HOMOGENEOUS, .model_extinction = K,
                              .fog_colour = {ambient[0], ambient[1], ambient[2]},
                              .integrator = FOG_INTEGRATOR_FROXEL,
                              .froxel = {.columns = 40, .rows = 24, .slices = slices,
                                         .near_distance = near, .far_distance = far}};
    CHECK(draw(&gl, &cam, &params, rgba, tau, &err) == 0, "froxel draw: %s",
          err.message);
    for (int i = 0; i < W * H; i++) {
      double t = fmin(gl.dist[i] >= 1e29f ? HUGE_VAL : gl.dist[i], far);
      double f = slices * log(t / near) / log(far / near), T;
      if (f >= 1) {
        int k = (int)floor(f);
        double a = near * pow(far / near, (double)k / slices),
               b = near * pow(far / near, (double)(k + 1) / slices);
        T = k >= slices ? exp(-K * (far - near))
                        : (1 - (f - k)) * exp(-K * (a - near)) + (f - k) * exp(-K * (b - near));
      } else {
        T = 1 - f + f * exp(-K * (near * pow(far / near, 1.0 / slices) - near));
      }
      for (int c = 0; c < 3; c++) want[4 * i + c] = (float)(ambient[c] * (1 - T));
      want[4 * i + 3] = (float)T; /* compared with the tau attachment */
    }
    double worst_tau = 0;
    for (int i = 0; i < W * H; i++) worst_tau = fmax(worst_tau, fabs(tau[i] - want[4 * i + 3]));
    for (int i = 0; i < W * H; i++) rgba[4 * i + 3] = want[4 * i + 3];
    double worst = max_rel_error(rgba, want, 4 * W * H);
    printf("homogeneous, ambient: max |dtau| %.2e, max in-scatter error %.2e of the largest\n",
           worst_tau, worst);
    CHECK(worst_tau <= 2e-5 && worst <= 2e-5,
          "the froxel grid misses its closed form: |dtau| %.3e, in-scatter %.3e", worst_tau,
          worst);
  }

  /* 2. Height fog under a low sun, self-shadowed by its closed form: convergence. */
  {
    fog_pass_params params = {
        .model = FOG_MODEL_HEIGHT, .model_extinction = 0.03, .model_y0 = 1.0,
        .model_scale_height = 4.0, .fog_colour = {0.05f, 0.06f, 0.08f},
        .sun = {.albedo = 0.9, .phase_g = 0.6, .direction = {0.93, 0.25, 0.27},
                .radiance = {3.0, 2.7, 2.2}},
        .self_shadow = FOG_SUN_SHADOW_HEIGHT, .shadow_steps = 512, .shadow_nodes = 2};
    double norm = sqrt(0.93 * 0.93 + 0.25 * 0.25 + 0.27 * 0.27);
    for (int a = 0; a < 3; a++) params.sun.direction[a] /= norm;
    CHECK(draw(&gl, &cam, &params, exact, tau, &err) == 0,
          "exact draw: %s", err.message);
    double errors[3];
    for (int level = 0; level < 3; level++) {
      int s = 1 << level;
      params.integrator = FOG_INTEGRATOR_FROXEL;
      params.froxel = (fog_froxel_grid){.columns = 40 * s, .rows = 24 * s, .slices = 32 * s,
                                        .near_distance = 0.5, .far_distance = 400.0};
      CHECK(draw(&gl, &cam, &params, rgba, tau, &err) == 0,
            "froxel draw %dx: %s", s, err.message);
      errors[level] = max_rel_error(rgba, exact, 4 * W * H);
      printf("height fog, low sun: froxels %dx%dx%d: max error %.2e of the largest in-scatter\n",
             params.froxel.columns, params.froxel.rows, params.froxel.slices, errors[level]);
    }
    CHECK(errors[1] < errors[0] && errors[2] < errors[1],
          "the froxel grid does not converge: %.3e, %.3e, %.3e", errors[0], errors[1], errors[2]);
    CHECK(errors[0] > 1e-3, "the 1x grid is suspiciously exact (%.3e): is the exact draw "
          "the froxels' too?", errors[0]);
  }

  /* 3. Bad grids are refused. */
  {
    const fog_froxel_grid bad[3] = {
        {.columns = 0, .rows = 9, .slices = 8, .near_distance = 1, .far_distance = 10},
        {.columns = 16, .rows = 9, .slices = 8, .near_distance = 0, .far_distance = 10},
        {.columns = 16, .rows = 9, .slices = 8, .near_distance = 5, .far_distance = 5}};
    for (int k = 0; k < 3; k++) {
      fog_pass_params params = {.model = FOG_MODEL_HOMOGENEOUS, .model_extinction = 0.01,
                                .integrator = FOG_INTEGRATOR_FROXEL, .froxel = bad[k]};
      fog_error e = {0};
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &e) != 0 &&
                strstr(e.message, "0 < near < far"),
            "bad froxel grid %d: '%s'", k, e.message);
    }
  }
  fog_test_gl_teardown(&gl);
  return test_finish("test_gpu_froxel");
}
