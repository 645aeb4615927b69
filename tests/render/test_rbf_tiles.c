/* Gaussian fog banks at Fogshop's scale (render/fog_rbf_tiles.h): 3000 Gaussians spread over
 * a valley, seen from inside and above it.
 *   - the bound: for every pixel ray (to the ground and to infinity) the Gaussians its tile
 *     lists give the optical depth of all of them within FOG_RBF_CULL_BOUND (1e-6), summed
 *     in double with the closed form of fog_models.h per Gaussian;
 *   - the culling culls: a tile lists a small share of the Gaussians (else the bound is
 *     met by listing everything);
 *   - the GL pass (buffer texture, per-tile lists) against the CPU integral of ALL the
 *     Gaussians, per pixel: max |delta tau| within float rounding plus the bound; and with
 *     a dozen Gaussians (the config's scale) the same.
 * Seen to fail: with the tile's cone narrowed to its axis (half-angle 0) the bound breaks. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/fog_rbf_tiles.h"
#include "fog_test_gl.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { W = 160, H = 90, N = 3000 };
static const double ground_y = 0.0;

static double surface_distance(const double o[3], const double d[3]) {
  return d[1] < 0.0 ? (ground_y - o[1]) / d[1] : HUGE_VAL;
}

/* The optical depth of the Gaussians listed[0..n) (all when listed is NULL). */
static double depth_of(const fog_rbf *g, const uint32_t *listed, int n, const double o[3],
                       const double d[3], double length) {
  double sum = 0.0;
  for (int k = 0; k < n; k++)
    sum += fog_rbf_optical_depth(0.0, &g[listed ? (int)listed[k] : k], 1, o, d, length);
  return sum;
}

static void check_view(const fog_rbf *g, int count, const camera *cam, const char *label,
                       fog_test_gl *gl) {
  fog_rbf_tiles tiles = {0};
  fog_error err = {0};
  if (fog_rbf_tiles_build(&tiles, cam, W, H, g, count, &err)) {
    CHECK(0, "%s: %s", label, err.message);
    return;
  }
  double worst = 0.0, listed_share = 0.0;
  static double full_depth[W * H];
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double o[3], d[3];
      camera_ray(cam, px, py, W, H, o, d);
      int y_gl = H - 1 - py;
      const uint32_t *range =
          &tiles.ranges[2 * ((size_t)(y_gl / FOG_RBF_TILE_SIZE) * tiles.tiles_x +
                             px / FOG_RBF_TILE_SIZE)];
      for (int sky = 0; sky < 2; sky++) {
        double length = sky ? HUGE_VAL : surface_distance(o, d);
        double all = depth_of(g, NULL, count, o, d, length);
        double listed = depth_of(g, tiles.indices + range[0], (int)range[1], o, d, length);
        worst = fmax(worst, fabs(all - listed));
        if (!sky) full_depth[py * W + px] = all;
      }
      listed_share += range[1] / ((double)count * W * H);
    }
  printf("%s: %d Gaussians, a pixel's tile lists %.1f %% of them; |all - listed| <= %.2e "
         "(bound %.0e)\n", label, count, 100.0 * listed_share, worst, FOG_RBF_CULL_BOUND);
  CHECK(worst <= FOG_RBF_CULL_BOUND, "%s: the culled Gaussians add %.3e", label, worst);
  if (count > 100)
    CHECK(listed_share < 0.25, "%s: tiles list %.1f %% of the Gaussians", label,
          100.0 * listed_share);

  /* The GL pass against the CPU integral of all of them. */
  static float dist[W * H], tau[W * H];
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double o[3], d[3];
      camera_ray(cam, px, py, W, H, o, d);
      double t = surface_distance(o, d);
      dist[py * W + px] = t < 1e29 ? (float)t : 1e30f;
    }
  fog_test_gl_upload_flipped(gl, gl->dist_tex, GL_RED, 1, dist);
  fog_pass_params params = {.model = FOG_MODEL_RBF, .model_rbfs = g, .model_rbf_count = count};
  if (fog_test_gl_draw_tau(gl, cam, &params, tau, &err)) {
    CHECK(0, "%s: draw: %s", label, err.message);
  } else {
    double gl_worst = 0.0, min_tau = 1.0, max_tau = 0.0;
    for (int k = 0; k < W * H; k++) {
      /* the GL target's rows are flipped back by gl_target_read: top first, as here */
      double want = exp(-full_depth[k]);
      gl_worst = fmax(gl_worst, fabs(want - tau[k]));
      min_tau = fmin(min_tau, want), max_tau = fmax(max_tau, want);
    }
    printf("%s: GL vs the CPU integral of all %d: max |dtau| %.2e (tau %.3f .. %.3f)\n", label,
           count, gl_worst, min_tau, max_tau);
    CHECK(gl_worst <= 2e-5 + FOG_RBF_CULL_BOUND, "%s: GL vs CPU %.3e", label, gl_worst);
    CHECK(max_tau - min_tau > 0.3, "%s: tau %.3f .. %.3f: too little variation to test", label,
          min_tau, max_tau);
  }
  fog_rbf_tiles_destroy(&tiles);
}

/* A field of view past 140 degrees on a small image: a tile's rays then spread more than
 * 90 degrees from its axis, where a cone through the corners no longer holds the rays
 * between them (a unit Gaussian on pixel (15, 5)'s ray at fov 160, 24x11, was left off
 * its tile: tau 1.000 for 0.170). One Gaussian on every pixel's ray, CPU lists only. */
static void check_wide_field(void) {
  enum { w = 24, h = 11 };
  camera wide = {.position = {0, 1000, 0}, .fov_y = 160.0 * 3.14159265358979323846 / 180.0,
                 .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
  camera_look_at(&wide, (double[3]){0, 1000, -1});
  static fog_rbf on_rays[w * h];
  for (int py = 0; py < h; py++)
    for (int px = 0; px < w; px++) {
      double o[3], d[3];
      camera_ray(&wide, px, py, w, h, o, d);
      fog_rbf *g = &on_rays[py * w + px];
      *g = (fog_rbf){.radius = 1.0, .density = 1.0};
      for (int a = 0; a < 3; a++) g->centre[a] = o[a] + 50.0 * d[a];
    }
  fog_rbf_tiles tiles = {0};
  fog_error err = {0};
  if (fog_rbf_tiles_build(&tiles, &wide, w, h, on_rays, w * h, &err)) {
    CHECK(0, "wide field: %s", err.message);
    return;
  }
  double worst = 0.0;
  int worst_x = 0, worst_y = 0;
  for (int py = 0; py < h; py++)
    for (int px = 0; px < w; px++) {
      double o[3], d[3];
      camera_ray(&wide, px, py, w, h, o, d);
      const int y_gl = h - 1 - py;
      const uint32_t *range = &tiles.ranges[2 * ((size_t)(y_gl / FOG_RBF_TILE_SIZE) *
                                                     tiles.tiles_x + px / FOG_RBF_TILE_SIZE)];
      const double all = depth_of(on_rays, NULL, w * h, o, d, HUGE_VAL);
      const double listed = depth_of(on_rays, tiles.indices + range[0], (int)range[1], o, d,
                                     HUGE_VAL);
      if (fabs(all - listed) > worst) worst = fabs(all - listed), worst_x = px, worst_y = py;
    }
  printf("fov 160 at %dx%d: |all - listed| <= %.2e (pixel %d, %d)\n", w, h, worst, worst_x,
         worst_y);
  CHECK(worst <= FOG_RBF_CULL_BOUND, "fov 160 at %dx%d: pixel (%d, %d) misses %.3e of depth",
        w, h, worst_x, worst_y, worst);
  fog_rbf_tiles_destroy(&tiles);
}

int main(void) {
  check_wide_field();
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_rbf_tiles");
  /* Banks of small Gaussians over a 1000 x 1000 valley, 0..60 high (Fogshop's scenes are
   * thousands of Gaussians of a few units). */
  static fog_rbf g[N];
  for (int i = 0; i < N; i++)
    g[i] = (fog_rbf){.centre = {fog_test_range(-500, 500), fog_test_range(0, 60),
                                fog_test_range(-500, 500)},
                     .radius = fog_test_range(6, 20), .density = fog_test_range(0.001, 0.008)};
  camera inside = {.position = {0, 20, 480}, .fov_y = 1.0,
      .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
  camera_look_at(&inside, (double[3]){0, 10, 0});
  camera above = {.position = {-300, 260, 400}, .fov_y = 0.9,
      .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
  camera_look_at(&above, (double[3]){50, 0, -100});
  check_view(g, N, &inside, "3000 Gaussians, camera inside the banks", &gl);
  check_view(g, N, &above, "3000 Gaussians, from above", &gl);
  /* A config's scale: a dozen large banks ahead of the camera. */
  fog_rbf banks[12];
  for (int i = 0; i < 12; i++)
    banks[i] = (fog_rbf){.centre = {fog_test_range(-250, 250), fog_test_range(0, 40),
                                    fog_test_range(-300, 200)},
                         .radius = fog_test_range(40, 90), .density = fog_test_range(0.01, 0.03)};
  check_view(banks, 12, &inside, "12 Gaussians", &gl);
  fog_test_gl_teardown(&gl);
  return test_finish("test_rbf_tiles");
}
