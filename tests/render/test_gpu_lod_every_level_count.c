/* The GL fog pass against the double-precision CPU reference for every pyramid depth the
 * pass takes, J = 1 .. 7: the shader is compiled per J (FOG_LEVELS) and walks the levels
 * as straight-line code guarded by l <= J (fog_pass_fs.glsl), so each J is its own program.
 * Linear basis, exponential profile, both LOD methods, a camera inside the fog (every
 * segment starts at the camera) and one outside (the nearest segments end before the box:
 * empty walks); max |delta tau| <= 2e-4 against the CPU, and the two methods agree to 2e-5. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/render.h"
#include "fog_test_gl.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { W = 64, H = 36, MAX_J = 7 };
static const double ground_y = 0.5;

int main(void) {
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_gpu_lod_every_level_count");
  static float tau[W * H], tau_sum[W * H];
  fog_volume v = fog_test_volume(FOG_PROFILE_EXPONENTIAL);
  double lo[3], hi[3];
  fog_volume_box(&v, lo, hi);
  double worst_cpu = 0.0, worst_methods = 0.0;
  for (int J = 1; J <= MAX_J; J++) {
    transform_grid approx[MAX_J + 1], detail[MAX_J];
    fog_test_pyramid(1, J, approx, detail);
    fog_lod lod = {.levels = J, .approx = approx, .detail = detail, .mu = 0.7};
    CHECK(fog_pass_upload_lod(gl.pass, &lod, &err) == 0, "J = %d upload: %s", J, err.message);
    for (int inside = 0; inside <= 1; inside++) {
      camera cam = {.fov_y = 1.0,
          .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
      double target[3] = {hi[0], ground_y, lo[2]};
      if (inside) {
        cam.position[0] = lo[0] + 0.1 * (hi[0] - lo[0]);
        cam.position[1] = 5.0;
        cam.position[2] = lo[2] + 0.9 * (hi[2] - lo[2]);
      } else {
        cam.position[0] = lo[0] - 12.0;
        cam.position[1] = 9.0;
        cam.position[2] = hi[2] + 12.0;
      }
      camera_look_at(&cam, target);
      fog_test_gl_set_ground(&gl, &cam, ground_y);
      for (int method = 0; method <= 1; method++) {
        fog_pass_params params = {.volume = &v, .levels = J, .lod_method = method,
                                  .mu = lod.mu};
        CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, method ? tau : tau_sum, &err) == 0,
              "J = %d draw: %s", J, err.message);
        const float *got = method ? tau : tau_sum;
        double worst = 0.0, min_tau = 1.0;
        for (int py = 0; py < H; py++)
          for (int px = 0; px < W; px++) {
            double o[3], d[3];
            double t_surface = fog_test_gl_pixel_ray(&gl, &cam, px, py, o, d);
            double want = fog_transmittance(
                fog_optical_depth_lod(&v, &lod, (fog_lod_method)method, o, d, t_surface));
            worst = fmax(worst, fabs(want - got[py * W + px]));
            min_tau = fmin(min_tau, want);
          }
        printf("J = %d camera %s method %d: max |dtau| %.2e, min tau %.3f\n", J,
               inside ? "inside " : "outside", method, worst, min_tau);
        CHECK(worst <= 2e-4, "J = %d inside %d method %d: max |dtau| %.3e", J, inside, method,
              worst);
        CHECK(min_tau < 0.7, "J = %d inside %d: min tau %.3f: no fog in view", J, inside,
              min_tau);
        worst_cpu = fmax(worst_cpu, worst);
      }
      double e = 0.0;
      for (int k = 0; k < W * H; k++) e = fmax(e, fabs(tau[k] - tau_sum[k]));
      CHECK(e <= 2e-5, "J = %d inside %d: the GPU's LOD methods differ by %.3e", J, inside, e);
      worst_methods = fmax(worst_methods, e);
    }
    for (int l = 0; l <= J; l++) transform_grid_destroy(&approx[l]);
    for (int l = 0; l < J; l++) transform_grid_destroy(&detail[l]);
  }
  printf("J = 1..%d: max |dtau| vs CPU %.2e, sum vs switching %.2e\n", MAX_J, worst_cpu,
         worst_methods);
  fog_test_gl_teardown(&gl);
  return test_finish("test_gpu_lod_every_level_count");
}
