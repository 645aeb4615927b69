/* The GL fog pass against the double-precision CPU reference with the camera far from the
 * fog: 100 m to 50 km from a 60 x 40 m fog box, a narrow field of view aimed at it, the
 * ground plane under it and sky behind. What float arithmetic of the ray's set-up would
 * lose there (the ray direction rounded to 6e-8 moves the ray 3 mm sideways at 50 km;
 * camera-relative grid coordinates of 2e4 cells keep only 2e-3 of a cell) the pass must
 * not: max |delta tau| <= 1e-5 at every distance, for one grid and for both LOD methods. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/render.h"
#include "fog_test_gl.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { W = 64, H = 36, J = 2 };
static const double ground_y = 0.5;

/* The drawn tau against the CPU's, depth(user, o, d, t_surface) along each pixel's ray to
 * the surface the draw saw: the max |dtau| and (min_tau) the CPU's least tau. */
typedef double (*cpu_depth_fn)(const void *user, const double o[3], const double d[3],
                               double t_surface);
static double max_dtau(const fog_test_gl *gl, const camera *cam, const float *tau,
                       cpu_depth_fn depth, const void *user, double *min_tau) {
  double worst = 0.0;
  *min_tau = 1.0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double o[3], d[3];
      camera_ray(cam, px, py, W, H, o, d);
      const float ts = gl->dist[py * W + px];
      const double want = fog_transmittance(depth(user, o, d, ts >= 1e29f ? HUGE_VAL : ts));
      worst = fmax(worst, fabs(want - tau[py * W + px]));
      *min_tau = fmin(*min_tau, want);
    }
  return worst;
}

typedef struct far_case {
  const fog_volume *v;
  const fog_lod *lod;
  const transform_grid *grid;
  int method; /* -1: one grid */
} far_case;
static double far_depth(const void *user, const double o[3], const double d[3], double t) {
  const far_case *c = user;
  return c->method < 0 ? fog_optical_depth(c->v, c->grid, o, d, 0.0, t)
                       : fog_optical_depth_lod(c->v, c->lod, c->method, o, d, t);
}

int main(void) {
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_gpu_far_camera");
  static float tau[W * H];

  transform_grid approx[J + 1], detail[J];
  fog_test_pyramid(1, J, approx, detail);
  fog_lod lod = {.levels = J, .approx = approx, .detail = detail, .mu = 0.6};
  fog_volume v = fog_test_volume(FOG_PROFILE_EXPONENTIAL);
  double lo[3], hi[3];
  fog_volume_box(&v, lo, hi);
  const double distances[4] = {100.0, 1e3, 1e4, 5e4};
  for (int k = 0; k < 4; k++) {
    double D = distances[k];
    /* From the south-west and a little above, the box filling about half the view. */
    camera cam = {.fov_y = 2.0 * atan(45.0 / D),
        .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    double centre[3] = {0.5 * (lo[0] + hi[0]), 4.0, 0.5 * (lo[2] + hi[2])};
    cam.position[0] = centre[0] - 0.6 * D;
    cam.position[1] = centre[1] + 0.02 * D;
    cam.position[2] = centre[2] + 0.8 * D;
    camera_look_at(&cam, centre);
    fog_test_gl_set_ground(&gl, &cam, ground_y);
    for (int method = -1; method <= 1; method++) { /* -1: the finest grid alone */
      /* the one-grid draw reads slot 0, which the pyramid's A_0 occupies: upload each
       * before the draws that read it */
      if (method < 0)
        CHECK(fog_pass_upload_grid(gl.pass, 0, &approx[J], &err) == 0, "upload: %s",
              err.message);
      else if (method == 0)
        CHECK(fog_pass_upload_lod(gl.pass, &lod, &err) == 0, "upload: %s", err.message);
      fog_pass_params params = {.volume = &v, .levels = method < 0 ? 0 : J,
                                .lod_method = method < 0 ? 0 : method, .mu = lod.mu};
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0,
            "draw: %s", err.message);
      double min_tau;
      const far_case fc = {.v = &v, .lod = &lod, .grid = &approx[J], .method = method};
      const double worst = max_dtau(&gl, &cam, tau, far_depth, &fc, &min_tau);
      const char *name = method < 0 ? "one grid" : method == 0 ? "LOD sum" : "LOD switch";
      printf("camera %6.0f m away, %-10s: max |dtau| %.2e (min tau %.3f)\n", D, name, worst,
             min_tau);
      CHECK(min_tau < 0.8, "%.0f m, %s: min tau %.3f: no fog in view", D, name, min_tau);
      CHECK(worst <= 1e-5, "%.0f m, %s: max |dtau| %.3e", D, name, worst);
    }
  }
  /* High above the fog, looking down: the camera-relative heights are large, and the
   * profile's height above y0 (a steep one, H = 0.5 with y0 at 3.3) came from the float
   * difference of two of them (100 km up: 3.6e-3 in tau). Both profiles, one grid. */
  CHECK(fog_pass_upload_grid(gl.pass, 0, &approx[J], &err) == 0, "upload: %s", err.message);
  const double altitudes[2] = {1e4, 1e5};
  for (int k = 0; k < 2; k++)
    for (int kind = 0; kind < 2; kind++) {
      fog_volume steep = fog_test_volume(kind ? FOG_PROFILE_BSPLINE : FOG_PROFILE_EXPONENTIAL);
      if (!kind) steep.profile.y0 = 3.3, steep.profile.scale_height = 0.5, steep.extinction = 0.15;
      else steep.profile.spacing = 1.7; /* 1/spacing not a float: the set-up's in double */
      steep.profile.y_top = 40.17;
      double slo[3], shi[3];
      fog_volume_box(&steep, slo, shi);
      const double A = altitudes[k];
      camera cam = {.fov_y = 2.0 * atan(25.0 / A), .near_plane = CAMERA_DEFAULT_NEAR,
                    .far_plane = 4.0 * A};
      cam.position[0] = 0.5 * (slo[0] + shi[0]) + 0.013 * A;
      cam.position[1] = A + 0.3;
      cam.position[2] = 0.5 * (slo[2] + shi[2]) - 0.011 * A;
      camera_look_at(&cam, (double[3]){0.5 * (slo[0] + shi[0]), 0.0, 0.5 * (slo[2] + shi[2])});
      fog_test_gl_set_ground(&gl, &cam, ground_y);
      fog_pass_params params = {.volume = &steep};
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0, "draw: %s", err.message);
      double min_tau;
      const far_case fc = {.v = &steep, .grid = &approx[J], .method = -1};
      const double worst = max_dtau(&gl, &cam, tau, far_depth, &fc, &min_tau);
      printf("camera %6.0f m up, %s profile: max |dtau| %.2e (min tau %.3f)\n", A,
             kind ? "B-spline" : "exponential (H 0.5)", worst, min_tau);
      CHECK(min_tau < 0.8, "%.0f m up: min tau %.3f: no fog in view", A, min_tau);
      CHECK(worst <= 1e-5, "%.0f m up, %s profile: max |dtau| %.3e", A,
            kind ? "B-spline" : "exponential", worst);
    }
  /* The volume and the quadric volumes, 100 m to 100 km away. Their rays' stretch and
   * entry are set up in float (the camera's index position and the slab's t0), which loses
   * about 1e-8 of tau per unit of distance here: measured 8.4e-7 at 100 m, 1.5e-5 at 2 km,
   * 2.0e-4 at 20 km, 9.5e-4 at 100 km. A double set-up held 5.2e-7 at every distance but
   * cost the near exact walks 15-25 % on llvmpipe (bench models, side by side; also as a
   * shader variant of its own), so the bound here is the float's: max(1e-5, 1.2e-8 D). */
  fog_test_models scene;
  fog_test_scene_models(&scene);
  CHECK(fog_pass_upload_grid3d(gl.pass, &scene.grid3d, &err) == 0, "volume upload: %s",
        err.message);
  const fog_quadric quadrics[2] = {
      fog_quadric_sphere((double[3]){42, 8, -18}, 10, 0.08, 0.4),
      fog_quadric_cylinder((double[3]){60, 0, -40}, 5, 18, 0.1, 0.0)};
  const double far_distances[4] = {100.0, 2e3, 2e4, 1e5};
  for (int k = 0; k < 4; k++)
    for (int quadric = 0; quadric < 2; quadric++) {
      const double D = far_distances[k];
      const double centre[3] = {54.0, 8.0, -30.0};
      camera cam = {.fov_y = 2.0 * atan(30.0 / D), .near_plane = CAMERA_DEFAULT_NEAR,
                    .far_plane = 4.0 * D};
      cam.position[0] = centre[0] - 0.6 * D;
      cam.position[1] = centre[1] + 0.02 * D;
      cam.position[2] = centre[2] + 0.8 * D;
      camera_look_at(&cam, centre);
      fog_test_gl_set_ground(&gl, &cam, ground_y);
      const fog_model m =
          quadric ? (fog_model){.kind = FOG_MODEL_QUADRIC, .quadrics = quadrics, .quadric_count = 2}
                  : fog_test_scene_model(&scene, FOG_MODEL_VOLUME, 0.0);
      fog_pass_params params = {.model = m.kind, .model_quadrics = quadrics,
                                .model_quadric_count = quadric ? 2 : 0};
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau, &err) == 0, "draw: %s", err.message);
      double worst = 0.0, min_tau = 1.0;
      for (int py = 0; py < H; py++)
        for (int px = 0; px < W; px++) {
          double o[3], d[3];
          camera_ray(&cam, px, py, W, H, o, d);
          const float ts = gl.dist[py * W + px];
          const double want = fog_transmittance(
              fog_model_optical_depth(&m, o, d, ts >= 1e29f ? HUGE_VAL : ts));
          worst = fmax(worst, fabs(want - tau[py * W + px]));
          min_tau = fmin(min_tau, want);
        }
      const char *name = quadric ? "quadrics" : "volume";
      printf("camera %6.0f m away, %-8s: max |dtau| %.2e (min tau %.3f)\n", D, name, worst,
             min_tau);
      CHECK(min_tau < 0.8, "%.0f m, %s: min tau %.3f: no fog in view", D, name, min_tau);
      const double bound = fmax(1e-5, 1.2e-8 * D);
      CHECK(worst <= bound, "%.0f m, %s: max |dtau| %.3e (bound %.1e)", D, name, worst, bound);
    }
  free(scene.grid_values);
  for (int l = 0; l <= J; l++) transform_grid_destroy(&approx[l]);
  for (int l = 0; l < J; l++) transform_grid_destroy(&detail[l]);
  fog_test_gl_teardown(&gl);
  return test_finish("test_gpu_far_camera");
}
