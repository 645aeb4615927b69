/* The GL fog pass against the double-precision CPU reference, per pixel, on a 128x72
 * render: transmittance max |delta tau| <= 2e-4 for every basis (degree 0, 1, 2) x LOD
 * method (sum of details, approximation switching) x camera inside / outside the fog x
 * vertical profile (slab, exponential, B-spline), and the analytic models (homogeneous,
 * height, Gaussian RBFs), over
 * an analytic ground plane (distance texture computed on the CPU) and sky; both LOD methods
 * agree on the GPU at the same mu; the composited colour is eq. 4 of Giroud & Biri. The
 * hardware-filtered fetch is measured too (its weights are quantised: looser bound). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "fog_test_gl.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { W = 128, H = 72, J = 2 };
static const double ground_y = 0.5;

/* Pixel (px, py)'s ray (rows top first) and its surface distance: HUGE_VAL for sky. */
static double pixel_ray(const camera *cam, const float *dist, int px, int py, double o[3],
                        double d[3]) {
  camera_ray(cam, px, py, W, H, o, d);
  return dist[py * W + px] >= 1e29f ? HUGE_VAL : dist[py * W + px];
}

/* The CPU reference of a LOD draw, per pixel: the double-precision transmittance from the
 * camera to the surface. */
static void reference_lod_tau(const camera *cam, const float *dist, const fog_volume *v,
                              const fog_lod *lod, fog_lod_method method, double *want) {
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double o[3], d[3];
      double t_surface = pixel_ray(cam, dist, px, py, o, d);
      want[py * W + px] = fog_transmittance(fog_optical_depth_lod(v, lod, method, o, d, t_surface));
    }
}

/* max |want - tau| over the image, and where (wx, wy may be NULL). */
static double max_tau_error(const double *want, const float *tau, int *wx, int *wy) {
  double worst = 0.0;
  for (int k = 0; k < W * H; k++) {
    double e = fabs(want[k] - tau[k]);
    if (e > worst) {
      worst = e;
      if (wx) *wx = k % W;
      if (wy) *wy = k / W;
    }
  }
  return worst;
}

int main(void) {
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_gpu_fog_vs_cpu");
  static float tau[W * H], tau_other[W * H], tau_hw[W * H], colour[4 * W * H],
      surface[4 * W * H];
  /* a GPU's texture filter weighs with 8 bits; llvmpipe's in full float, as exact */
  const bool float_filter = strstr((const char *)glGetString(GL_RENDERER), "llvmpipe") != NULL;
  const double hardware_bound = float_filter ? 2e-4 : 2e-2;
  static double want[W * H];
  for (int i = 0; i < W * H; i++) {
    surface[4 * i + 0] = 0.2f + 0.6f * (float)((i % W) / (double)W);
    surface[4 * i + 1] = 0.3f;
    surface[4 * i + 2] = 0.9f - 0.5f * (float)((i / W) / (double)H);
    surface[4 * i + 3] = 1.0f;
  }
  fog_test_gl_upload_flipped(&gl, gl.surface_tex, GL_RGBA, 4, surface);

  /* Profiles: slab, exponential, and B-splines of degree 2, 1 and 0 (degrees 0 and 1, what
   * `fogpipe import` fits, take their own closed form in the walk). */
  const fog_profile_kind kinds[5] = {FOG_PROFILE_SLAB, FOG_PROFILE_EXPONENTIAL,
                                     FOG_PROFILE_BSPLINE, FOG_PROFILE_BSPLINE,
                                     FOG_PROFILE_BSPLINE};
  const int profile_degrees[5] = {0, 0, 2, 1, 0};
  double worst_exact = 0.0, worst_methods = 0.0, worst_colour = 0.0, worst_hw[3] = {0, 0, 0};
  for (int degree = 0; degree <= 2; degree++) {
    transform_grid approx[J + 1], detail[J];
    fog_test_pyramid(degree, J, approx, detail);
    fog_lod lod = {.levels = J, .approx = approx, .detail = detail, .mu = 0.6};
    CHECK(fog_pass_upload_lod(gl.pass, &lod, &err) == 0, "upload: %s", err.message);
    for (int inside = 0; inside <= 1; inside++)
    for (int kind = 0; kind < 5; kind++) {
      fog_volume v = fog_test_volume(kinds[kind]);
      if (kinds[kind] == FOG_PROFILE_BSPLINE) v.profile.degree = profile_degrees[kind];
      double lo[3], hi[3];
      fog_volume_box(&v, lo, hi);
      camera cam = {.fov_y = 1.0,
          .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
      double target_pos[3] = {0.5 * (lo[0] + hi[0]) + 7.0, ground_y, 0.5 * (lo[2] + hi[2])};
      if (inside) {
        cam.position[0] = lo[0] + 0.3 * (hi[0] - lo[0]);
        cam.position[1] = lo[1] + 0.4 * (hi[1] - lo[1]);
        cam.position[2] = lo[2] + 0.8 * (hi[2] - lo[2]);
        target_pos[1] = cam.position[1] - 1.0;
      } else {
        cam.position[0] = lo[0] - 25.0;
        cam.position[1] = hi[1] + 6.0;
        cam.position[2] = hi[2] + 30.0;
      }
      camera_look_at(&cam, target_pos);
      fog_test_gl_set_ground(&gl, &cam, ground_y);
      for (int method = 0; method <= 1; method++) {
        fog_pass_params params = {.volume = &v, .levels = J, .lod_method = method, .mu = lod.mu,
                                  .fog_colour = {0.7f, 0.75f, 0.8f}};
        CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
              "draw: %s", err.message);
        CHECK(gl_target_read(&gl.target, 0, 4, colour, &err) == 0, "read: %s", err.message);
        double min_tau = 1.0;
        int wx = 0, wy = 0;
        for (int i = 0; i < W * H; i++) min_tau = fmin(min_tau, tau[i]);
        /* The view must actually see fog (and some clear pixels) for the comparison to mean
         * anything. */
        CHECK(min_tau < 0.7, "degree %d inside %d: min tau %.3f: no fog in view", degree, inside,
              min_tau);
        reference_lod_tau(&cam, gl.dist, &v, &lod, method, want);
        double worst = max_tau_error(want, tau, &wx, &wy);
        for (int py = 0; py < H; py++)
          for (int px = 0; px < W; px++) {
            double s[3] = {surface[4 * (py * W + px)], surface[4 * (py * W + px) + 1],
                           surface[4 * (py * W + px) + 2]};
            double fogc[3] = {0.7f, 0.75f, 0.8f}, blended[3];
            fog_blend(tau[py * W + px], s, fogc, blended);
            for (int ch = 0; ch < 3; ch++) {
              double ec = fabs(blended[ch] - colour[4 * (py * W + px) + ch]);
              if (ec > worst_colour) worst_colour = ec;
            }
          }
        printf("degree %d camera %s profile %d method %d: max |dtau| %.2e at (%d, %d), min tau %.3f\n",
               degree, inside ? "inside " : "outside", v.profile.kind, method, worst, wx, wy,
               min_tau);
        CHECK(worst <= 2e-4, "degree %d inside %d method %d: max |dtau| %.3e at pixel (%d, %d)",
              degree, inside, method, worst, wx, wy);
        if (worst > worst_exact) worst_exact = worst;
        if (method == 0) {
          for (int i = 0; i < W * H; i++) tau_other[i] = tau[i];
        } else {
          double e = 0.0;
          for (int i = 0; i < W * H; i++) e = fmax(e, fabs(tau_other[i] - tau[i]));
          if (e > worst_methods) worst_methods = e;
          CHECK(e <= 2e-5, "GPU LOD methods differ by %.3e (degree %d inside %d)", e, degree, inside);
        }
        /* Hardware-filtered fetch (degree 0 uses texelFetch in both variants), into a
         * buffer of its own: it overwrote method 0's image, so the methods' comparison
         * above read the hardware image */
        params.fetch = FOG_FETCH_HARDWARE;
        CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau_hw, &err) == 0,
              "draw (hardware): %s", err.message);
        /* want still holds this view's reference of this method */
        double e_hw = max_tau_error(want, tau_hw, NULL, NULL);
        if (e_hw > worst_hw[degree]) worst_hw[degree] = e_hw;
        CHECK(e_hw <= hardware_bound, "hardware fetch degree %d method %d: max |dtau| %.3e "
              "(bound %g)", degree, method, e_hw, hardware_bound);
      }
    }
    /* Streaming: new coefficients of the same size go through glTexSubImage2D into the
     * same textures; the image must follow them. */
    for (int l = 0; l <= J; l++)
      for (int i = 0; i < approx[l].width * approx[l].height; i++) approx[l].coefficients[i] *= 1.5f;
    for (int l = 0; l < J; l++)
      for (int i = 0; i < detail[l].width * detail[l].height; i++) detail[l].coefficients[i] *= 1.5f;
    CHECK(fog_pass_upload_lod(gl.pass, &lod, &err) == 0, "re-upload: %s", err.message);
    {
      fog_volume v = fog_test_volume(FOG_PROFILE_SLAB);
      camera cam = {.position = {60.0, 20.0, 30.0}, .fov_y = 1.0,
          .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
      camera_look_at(&cam, (double[3]){130.0, ground_y, -30.0});
      fog_test_gl_set_ground(&gl, &cam, ground_y);
      fog_pass_params params = {.volume = &v, .levels = J, .lod_method = FOG_LOD_SWITCH,
                                .mu = lod.mu};
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
            "draw after re-upload: %s", err.message);
      reference_lod_tau(&cam, gl.dist, &v, &lod, FOG_LOD_SWITCH, want);
      double worst = max_tau_error(want, tau, NULL, NULL);
      printf("degree %d after re-upload (same size): max |dtau| %.2e\n", degree, worst);
      CHECK(worst <= 2e-4, "degree %d after re-upload: max |dtau| %.3e", degree, worst);
    }
    for (int l = 0; l <= J; l++) transform_grid_destroy(&approx[l]);
    for (int l = 0; l < J; l++) transform_grid_destroy(&detail[l]);
  }
  /* Long rays: a 1024 x 64 fogmap of spacing-1 cells seen along its long axis from inside,
   * every degree, exponential fog (the heaviest piece). Each ray crosses up to ~1000 knot
   * cells: this guards the shader against llvmpipe's per-invocation loop budget (65535
   * iterations; fog_integral.glsl), which silently cut such walks short once. */
  for (int degree = 0; degree <= 2; degree++) {
    transform_grid g;
    fog_error terr;
    transform_grid_create(&g, 1024 + 6, 64 + 6, &terr);
    g.degree = degree;
    g.origin_u = g.origin_v = -3.0;
    for (int i = 0; i < g.width * g.height; i++) g.coefficients[i] = (float)fog_test_uniform();
    CHECK(fog_pass_upload_grid(gl.pass, 0, &g, &err) == 0, "upload long grid: %s", err.message);
    fog_volume v = {.map_width = 1024, .map_height = 64, .cell_size = 1.0, .extinction = 0.004,
                    .profile = {.kind = FOG_PROFILE_EXPONENTIAL, .y_floor = 0.0, .y0 = 0.5,
                                .scale_height = 3.0, .y_top = 30.0}};
    camera cam = {.position = {2.0, 1.5, 20.0}, .fov_y = 0.6,
        .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    camera_look_at(&cam, (double[3]){1024.0, 0.5, 44.0});
    fog_test_gl_set_ground(&gl, &cam, ground_y);
    fog_pass_params params = {.volume = &v};
    /* Only the middle 32 x 12 pixels (around the horizon, the longest rays): llvmpipe needs
     * ~2 s per full frame of such rays. The scissor limits the helper's clear too. */
    enum { X0 = W / 2 - 16, Y0 = H / 2 - 6 };
    glEnable(GL_SCISSOR_TEST);
    glScissor(X0, H - Y0 - 12, 32, 12);
    CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
          "draw long rays: %s", err.message);
    glDisable(GL_SCISSOR_TEST);
    double worst = 0.0, min_tau = 1.0;
    for (int py = Y0; py < Y0 + 12; py++)
      for (int px = X0; px < X0 + 32; px++) {
        double o[3], d[3];
        double t_surface = pixel_ray(&cam, gl.dist, px, py, o, d);
        double want_k = fog_transmittance(fog_optical_depth(&v, &g, o, d, 0.0, t_surface));
        worst = fmax(worst, fabs(want_k - tau[py * W + px]));
        min_tau = fmin(min_tau, want_k);
      }
    printf("long rays (1024 cells), degree %d: max |dtau| %.2e, min tau %.3f\n", degree, worst,
           min_tau);
    CHECK(worst <= 2e-4 && min_tau < 0.5, "long rays degree %d: max |dtau| %.3e (min tau %.3f)",
          degree, worst, min_tau);
    transform_grid_destroy(&g);
  }
  /* Gaussians far wider than the view (radius 1e4 .. 1e6 over rays of ~100 units): their
   * erf difference is taken near 0, where erfc's values near 1 left float's absolute 1e-7
   * (7.5e-4 in tau at 1e6 before the series; the closed form in double is the reference). */
  for (int k = 4; k <= 6; k++) {
    const fog_rbf wide = {.centre = {30, 0, -40}, .radius = pow(10.0, k), .density = 0.01};
    camera cam = {.position = {10.0, 3.0, 20.0}, .fov_y = 1.1, .near_plane = CAMERA_DEFAULT_NEAR,
                  .far_plane = CAMERA_DEFAULT_FAR};
    camera_look_at(&cam, (double[3]){80.0, 6.0, -60.0});
    fog_test_gl_set_ground(&gl, &cam, ground_y);
    const fog_model m = {.kind = FOG_MODEL_RBF, .rbfs = &wide, .rbf_count = 1};
    fog_pass_params params = {.model = FOG_MODEL_RBF, .model_rbfs = &wide, .model_rbf_count = 1};
    CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0, "draw a wide Gaussian: %s",
          err.message);
    double min_tau = 1.0;
    for (int py = 0; py < H; py++)
      for (int px = 0; px < W; px++) {
        double o[3], d[3];
        double t_surface = pixel_ray(&cam, gl.dist, px, py, o, d);
        /* the sky: the Gaussian's whole line, a depth ~ c r sqrt(pi) past float; the
         * ground's rays are the finite stretches */
        const bool ground = t_surface < 1e29;
        want[py * W + px] = ground
                                ? fog_transmittance(fog_model_optical_depth(&m, o, d, t_surface))
                                : tau[py * W + px];
        if (ground) min_tau = fmin(min_tau, want[py * W + px]);
      }
    double worst = max_tau_error(want, tau, NULL, NULL);
    printf("a Gaussian of radius 1e%d: max |dtau| %.2e, min tau on the ground %.3f\n", k, worst,
           min_tau);
    CHECK(worst <= 1e-5 && min_tau < 0.7, "radius 1e%d: max |dtau| %.3e (min tau %.3f)", k,
          worst, min_tau);
  }
  /* The analytic models of the ladder (fog_models.h) through the same pass; the RBFs are
   * a dozen Gaussians between the camera and the view's far side, over no base (view 0:
   * the sky stays finite) and over a thin one (view 1). */
  fog_test_models scene;
  fog_test_scene_models(&scene);
  CHECK(fog_pass_upload_grid3d(gl.pass, &scene.grid3d, &err) == 0, "volume upload: %s",
        err.message);
  for (int model = FOG_MODEL_HOMOGENEOUS; model <= FOG_MODEL_VOLUME; model++)
    for (int view = 0; view < 2; view++) {
      camera cam = {.position = {10.0, view ? 40.0 : 3.0, 20.0}, .fov_y = 1.1,
          .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
      camera_look_at(&cam, (double[3]){80.0, view ? 0.0 : 6.0, -60.0});
      fog_test_gl_set_ground(&gl, &cam, ground_y);
      fog_model m = fog_test_scene_model(&scene, model, view ? 0.002 : 0.0);
      fog_pass_params params = {.model = model, .model_extinction = m.extinction,
                                .model_y0 = m.y0, .model_scale_height = m.scale_height,
                                .model_rbfs = m.rbfs, .model_rbf_count = m.rbf_count};
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
            "draw model %d: %s", model, err.message);
      double min_tau = 1.0;
      for (int py = 0; py < H; py++)
        for (int px = 0; px < W; px++) {
          double o[3], d[3];
          double t_surface = pixel_ray(&cam, gl.dist, px, py, o, d);
          want[py * W + px] = fog_transmittance(fog_model_optical_depth(&m, o, d, t_surface));
          min_tau = fmin(min_tau, tau[py * W + px]);
        }
      double worst = max_tau_error(want, tau, NULL, NULL);
      printf("model %d view %d: max |dtau| %.2e, min tau %.3f\n", model, view, worst, min_tau);
      /* (The volume's samples are the hardware's trilinear filter: on llvmpipe its R32F
       * 3D weights are full float, 5e-7 here; a GPU's 8-bit weights would need ~1e-3.) */
      CHECK(worst <= 2e-4 && min_tau < 0.5, "model %d view %d: max |dtau| %.3e, min tau %.3f",
            model, view, worst, min_tau);
      if (model == FOG_MODEL_VOLUME) {
        /* The exact walk sampling with the hardware's filter instead of the corners (float
         * weights on llvmpipe: as exact; a GPU's 8-bit weights would need ~1e-3). */
        params.fetch = FOG_FETCH_HARDWARE;
        CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
              "draw volume, hardware filtering: %s", err.message);
        double eh = max_tau_error(want, tau, NULL, NULL);
        printf("model %d view %d exact with hardware filtering: max |dtau| %.2e\n", model, view,
               eh);
        CHECK(eh <= 2e-4, "volume exact, hardware filtering, view %d: max |dtau| %.3e", view, eh);
        params.fetch = FOG_FETCH_MANUAL;
        /* The volume's march against its CPU twin (the same samples, in double). */
        params.integrator = FOG_INTEGRATOR_MARCH;
        params.model_grid3d_step = 0.7;
        CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
              "draw volume marched: %s", err.message);
        for (int py = 0; py < H; py++)
          for (int px = 0; px < W; px++) {
            double o[3], d[3];
            double t_surface = pixel_ray(&cam, gl.dist, px, py, o, d);
            want[py * W + px] = fog_transmittance(
                fog_grid3d_optical_depth_march(&scene.grid3d, 0.7, o, d, t_surface));
          }
        double e = max_tau_error(want, tau, NULL, NULL);
        printf("model %d view %d marched at 0.7: max |dtau| vs its CPU twin %.2e\n", model,
               view, e);
        CHECK(e <= 2e-4, "volume march view %d: max |dtau| %.3e", view, e);
        if (view == 0) {
          /* a step so fine that both twins take their cap of 16384 samples a ray (the C
           * twin's count overflowed int there: no samples, tau 1) */
          params.model_grid3d_step = 1e-12;
          CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
                "draw volume marched finely: %s", err.message);
          for (int py = 0; py < H; py++)
            for (int px = 0; px < W; px++) {
              double o[3], d[3];
              double t_surface = pixel_ray(&cam, gl.dist, px, py, o, d);
              want[py * W + px] = fog_transmittance(
                  fog_grid3d_optical_depth_march(&scene.grid3d, 1e-12, o, d, t_surface));
            }
          e = max_tau_error(want, tau, NULL, NULL);
          printf("volume marched at 1e-12 (capped): max |dtau| vs its CPU twin %.2e\n", e);
          CHECK(e <= 2e-4, "volume march at the cap: max |dtau| %.3e", e);
        }
        continue;
      }
      /* The same model ray-marched (the bench's alternative): it converges to the exact
       * integral as the steps grow, sky included (marched to where the fog ends). */
      double march_error[2];
      for (int k = 0; k < 2; k++) {
        params.integrator = FOG_INTEGRATOR_MARCH;
        params.march_steps = k ? 1024 : 16;
        CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
              "draw model %d marched: %s", model, err.message);
        march_error[k] = max_tau_error(want, tau, NULL, NULL);
      }
      printf("model %d view %d marched: 16 steps %.2e, 1024 steps %.2e\n", model, view,
             march_error[0], march_error[1]);
      CHECK(march_error[1] <= 1e-3, "model %d view %d: 1024 marching steps off by %.3e", model,
            view, march_error[1]);
      CHECK(model == FOG_MODEL_HOMOGENEOUS || march_error[1] < 0.5 * march_error[0],
            "model %d view %d: marching does not converge (%.3e, %.3e)", model, view,
            march_error[0], march_error[1]);
    }
  /* Fog of extinction 0 marched is no fog, the sky too (the marcher's infinite reach once
   * made the sky opaque there while the exact integral said clear). */
  {
    camera cam = {.position = {10.0, 3.0, 20.0}, .fov_y = 1.1,
        .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    camera_look_at(&cam, (double[3]){80.0, 6.0, -60.0});
    fog_test_gl_set_ground(&gl, &cam, ground_y);
    const fog_model_kind clear[3] = {FOG_MODEL_HOMOGENEOUS, FOG_MODEL_HEIGHT, FOG_MODEL_EXP2};
    for (int k = 0; k < 3; k++) {
      const fog_pass_params params = {.model = clear[k], .model_extinction = 0.0,
                                      .model_scale_height = 10.0,
                                      .integrator = FOG_INTEGRATOR_MARCH, .march_steps = 16};
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0, "clear model %d: %s",
            clear[k], err.message);
      double lowest = 1.0;
      for (int i = 0; i < W * H; i++) lowest = fmin(lowest, tau[i]);
      CHECK(lowest == 1.0, "model %d of extinction 0, marched: tau down to %g", clear[k], lowest);
    }
  }
  /* Bad model parameters are refused before anything is drawn, saying what was expected. */
  {
    camera cam = {.position = {10.0, 3.0, 20.0}, .fov_y = 1.1,
        .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    fog_rbf flat = {.centre = {0, 0, 0}, .radius = 0.0, .density = 1.0};
    const fog_pass_params bad[3] = {
        {.model = FOG_MODEL_RBF, .model_rbfs = &flat, .model_rbf_count = 1},
        {.model = FOG_MODEL_RBF, .model_rbfs = scene.rbfs, .model_rbf_count = FOG_MAX_RBFS + 1},
        {.model = FOG_MODEL_VOLUME, .integrator = FOG_INTEGRATOR_MARCH}};
    const char *const said[3] = {"expected radius > 0", "expected 0..4096",
                                 "expected a march step > 0"};
    for (int k = 0; k < 3; k++) {
      fog_error e = {0};
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &bad[k], tau, &e) != 0 &&
                strstr(e.message, said[k]),
            "bad model parameters %d: '%s' lacks '%s'", k, e.message, said[k]);
    }
    /* and a camera without a field of view or depth range: no "0 means default" */
    const camera unset = {.position = {10.0, 3.0, 20.0}};
    const fog_pass_params fine = {.model = FOG_MODEL_HOMOGENEOUS, .model_extinction = 0.01};
    fog_error e = {0};
    CHECK(fog_test_gl_draw_tau(&gl, &unset, &fine, tau, &e) != 0 &&
              strstr(e.message, "expected 0 < fov < pi and 0 < near < far"),
          "a camera of fov 0: '%s'", e.message);
  }
  printf("manual fetch: max |dtau| %.2e; GPU sum vs switching %.2e; colour vs eq. 4 %.2e\n",
         worst_exact, worst_methods, worst_colour);
  printf("hardware fetch: max |dtau| degree 0 %.2e, 1 %.2e, 2 %.2e\n", worst_hw[0], worst_hw[1],
         worst_hw[2]);
  CHECK(worst_colour <= 1e-5, "composited colour differs from eq. 4 by %.3e", worst_colour);
  free(scene.grid_values);
  fog_test_gl_teardown(&gl);
  return test_finish("test_gpu_fog_vs_cpu");
}
