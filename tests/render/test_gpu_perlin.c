/* Perlin turbulence fog on the GL (fog_models.glsl, fog_model_depth_perlin) against its CPU
 * twin in double (render/fog_perlin.c, itself checked against an independent reference by
 * test_integral_perlin), per pixel of a 96x54 render over a ground plane and sky: the exact
 * integral and the paper's single sample, the camera inside and outside the fog's box, at
 * two times of the animation: max |delta tau| <= 2e-4. And the uniform marcher converges to
 * it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/render.h"
#include "fog_test_gl.h"
#include "test_util.h"

enum { W = 96, H = 54 };

int main(void) {
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_gpu_perlin");
  fog_perlin_desc desc = fog_perlin_desc_default();
  desc.octaves = 4;
  desc.lo[1] = 0.0, desc.hi[1] = 20.0;
  fog_perlin perlin;
  CHECK(fog_perlin_create(&perlin, &desc, &err) == 0, "create: %s", err.message);
  CHECK(fog_pass_upload_perlin(gl.pass, &perlin, &err) == 0, "upload: %s", err.message);
  static float tau[W * H];
  for (int view = 0; view < 2; view++)
    for (int integral = 0; integral < 2; integral++)
      for (int when = 0; when < 2; when++) {
        camera cam = {.position = {view ? -170.0 : 10.0, view ? 45.0 : 6.0, view ? -150.0 : 20.0},
                      .fov_y = 1.0, .near_plane = CAMERA_DEFAULT_NEAR,
                      .far_plane = CAMERA_DEFAULT_FAR};
        camera_look_at(&cam, (double[3]){60.0, 2.0, -40.0});
        fog_test_gl_set_ground(&gl, &cam, -0.5);
        fog_pass_params params = {.model = FOG_MODEL_PERLIN, .model_extinction = 0.06,
                                  .model_y0 = 1.0, .model_scale_height = 8.0,
                                  .model_perlin = &perlin, .model_time = when ? 37.25 : 0.0,
                                  .model_perlin_integral = (fog_perlin_integral)integral};
        CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
              "draw: %s", err.message);
        fog_perlin_medium m = {.extinction = 0.06, .y0 = 1.0, .scale_height = 8.0,
                               .time = params.model_time,
                               .integral = (fog_perlin_integral)integral};
        double worst = 0, min_tau = 1;
        for (int py = 0; py < H; py++)
          for (int px = 0; px < W; px++) {
            double o[3], d[3], t = fog_test_gl_pixel_ray(&gl, &cam, px, py, o, d);
            double want = exp(-fog_perlin_optical_depth(&perlin, &m, o, d, t));
            double e = fabs(want - tau[py * W + px]);
            worst = fmax(worst, e == e ? e : HUGE_VAL);
            min_tau = fmin(min_tau, want);
          }
        printf("view %d, %s, time %g: max |dtau| %.2e (min tau %.3f)\n", view,
               integral ? "paper" : "exact", params.model_time, worst, min_tau);
        CHECK(worst <= 2e-4 && min_tau < 0.7, "view %d integral %d time %g: |dtau| %.3e, min tau %.3f",
              view, integral, params.model_time, worst, min_tau);
        if (integral == 0 && when == 1) { /* the marcher converges to the exact integral */
          float *exact = malloc(sizeof(float) * W * H);
          for (int i = 0; i < W * H; i++) exact[i] = tau[i];
          double errors[2];
          for (int q = 0; q < 2; q++) {
            params.integrator = FOG_INTEGRATOR_MARCH;
            params.march_steps = q ? 1024 : 16;
            CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
                  "march: %s", err.message);
            errors[q] = 0;
            for (int i = 0; i < W * H; i++) errors[q] = fmax(errors[q], fabs(tau[i] - exact[i]));
          }
          printf("  marched: 16 steps %.2e, 1024 steps %.2e\n", errors[0], errors[1]);
          CHECK(errors[1] < 3e-3 && errors[1] < 0.25 * errors[0],
                "the marcher does not converge to the exact integral: %.3e, %.3e", errors[0],
                errors[1]);
          free(exact);
        }
      }
  /* Octaves of another size than those uploaded: refused. */
  {
    fog_perlin other;
    fog_perlin_desc smaller = desc;
    smaller.size = 16;
    CHECK(fog_perlin_create(&other, &smaller, &err) == 0, "create: %s", err.message);
    camera cam = {.position = {0, 5, 0}, .fov_y = 1.0, .near_plane = CAMERA_DEFAULT_NEAR,
                  .far_plane = CAMERA_DEFAULT_FAR};
    fog_pass_params params = {.model = FOG_MODEL_PERLIN, .model_extinction = 0.06,
                              .model_scale_height = 8.0, .model_perlin = &other};
    fog_error e = {0};
    CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &e) != 0,
          "octaves not uploaded: drawn");
    fog_perlin_destroy(&other);
  }
  fog_perlin_destroy(&perlin);
  fog_test_gl_teardown(&gl);
  return test_finish("test_gpu_perlin");
}
