/* Early termination at opacity (fog_pass_params.walk.transmittance_cutoff) against the
 * same draw over whole rays, in fog thick enough that most pixels pass the cut-off:
 * - every pixel's tau moves by at most the cut-off c (the walk stops once tau_partial <= c
 *   and the whole ray only lowers it), and its colour L = tau L(P) + (1 - tau) S by at most
 *   c |L(P) - S| per channel (S the in-scatter source: L_fog, or with the sun and no
 *   shadow L_amb + a L_sun p(theta));
 * - tested at the bound: the largest |delta tau| is above c/4 (the walks really stop, and
 *   the bound is not loose by orders);
 * for c = 1e-4 (the product's default) and 1e-2, on the fogmap's single grid and LOD
 * switching (both fetches), the volume's DDA, and lit fog. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/render.h"
#include "fog_test_gl.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { W = 80, H = 45, LEVELS = 2 };
static const double ground_y = 0.5;

static double phase_hg(double g, double mu) {
  return (1 - g * g) / (4 * 3.14159265358979323846 * pow(1 + g * g - 2 * g * mu, 1.5));
}

typedef struct drawn {
  float rgba[4 * W * H], tau[W * H];
} drawn;

static int draw(fog_test_gl *gl, const camera *cam, const fog_pass_params *params, drawn *out,
                fog_error *err) {
  if (fog_test_gl_draw_tau(gl, cam, params, out->tau, err)) return 1;
  return gl_target_read(&gl->target, 0, 4, out->rgba, err);
}

int main(void) {
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_gpu_early_stop");
  static float surface[4 * W * H];
  static drawn whole, cut;
  for (int i = 0; i < W * H; i++)
    for (int c = 0; c < 4; c++) surface[4 * i + c] = c < 3 ? (float)fog_test_range(0, 2) : 1.0f;
  fog_test_gl_upload_flipped(&gl, gl.surface_tex, GL_RGBA, 4, surface);

  fog_volume v = fog_test_volume(FOG_PROFILE_EXPONENTIAL);
  v.extinction = 1.5; /* thick: tau 1e-4 within ~ten world units */
  transform_grid grids[LEVELS + 1], grid_details[LEVELS];
  fog_test_pyramid(1, LEVELS, grids, grid_details);
  double lo[3], hi[3];
  fog_volume_box(&v, lo, hi);
  /* A volume over the same box: 2-unit voxels, random density around 1.5 per unit. */
  enum { GX = 30, GZ = 20, GY = 10 };
  static float voxels[GX * GZ * GY];
  for (int i = 0; i < GX * GZ * GY; i++) voxels[i] = (float)fog_test_range(0.5, 2.5);
  volume_grid_desc grid3d = {.dim = {GX, GY, GZ}, .values = voxels,
                             .index_from_world = {{0.5, 0, 0}, {0, 0.5, 0}, {0, 0, 0.5}},
                             .index_offset = {-0.5 * lo[0], -0.5 * 0.0, -0.5 * lo[2]}};
  CHECK(fog_pass_upload_grid3d(gl.pass, &grid3d, &err) == 0, "volume: %s", err.message);

  camera cam = {.fov_y = 1.0, .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
  cam.position[0] = lo[0] + 3.0;
  cam.position[1] = 2.5;
  cam.position[2] = 0.5 * (lo[2] + hi[2]);
  camera_look_at(&cam, (double[3]){hi[0], 1.5, 0.5 * (lo[2] + hi[2]) + 8.0});
  fog_test_gl_set_ground(&gl, &cam, ground_y);

  const double cutoffs[2] = {FOG_PASS_TRANSMITTANCE_CUTOFF, 1e-2};
  const char *names[5] = {"one grid", "one grid (hardware)", "LOD switching", "volume",
                          "lit one grid"};
  const float fog_colour[3] = {0.7f, 0.75f, 0.8f};
  for (int mode = 0; mode < 5; mode++) {
    if (mode == 0 || mode == 4)
      CHECK(fog_pass_upload_grid(gl.pass, 0, &grids[LEVELS], &err) == 0, "%s", err.message);
    if (mode == 2) {
      transform_grid detail[LEVELS];
      transform_grid approx[LEVELS + 1];
      fog_test_pyramid(1, LEVELS, approx, detail);
      fog_lod lod = {.levels = LEVELS, .approx = approx, .detail = detail, .mu = 0.5};
      CHECK(fog_pass_upload_lod(gl.pass, &lod, &err) == 0, "%s", err.message);
      for (int l = 0; l <= LEVELS; l++) transform_grid_destroy(&approx[l]);
      for (int l = 0; l < LEVELS; l++) transform_grid_destroy(&detail[l]);
    }
    fog_pass_params params = {
        .model = mode == 3 ? FOG_MODEL_VOLUME : FOG_MODEL_FOGMAP,
        .volume = &v,
        .levels = mode == 2 ? LEVELS : 0,
        .lod_method = FOG_LOD_SWITCH,
        .mu = 0.5,
        .fog_colour = {fog_colour[0], fog_colour[1], fog_colour[2]},
        .fetch = mode == 1 ? FOG_FETCH_HARDWARE : FOG_FETCH_MANUAL,
    };
    double sun_dir[3] = {0.3, 0.8, -0.52};
    fog_test_unit(sun_dir);
    if (mode == 4)
      params.sun = (fog_sun){.albedo = 0.8, .phase_g = 0.5,
                             .radiance = {3.0f, 2.8f, 2.4f},
                             .direction = {sun_dir[0], sun_dir[1], sun_dir[2]}};
    CHECK(draw(&gl, &cam, &params, &whole, &err) == 0, "%s: %s",
          names[mode], err.message);
    int past = 0;
    for (int k = 0; k < W * H; k++) past += whole.tau[k] < 1e-5f;
    CHECK(past > W * H / 3, "%s: only %d of %d pixels are past tau 1e-5: fog too thin",
          names[mode], past, W * H);
    for (int ci = 0; ci < 2; ci++) {
      const double c = cutoffs[ci];
      params.walk.transmittance_cutoff = c;
      CHECK(draw(&gl, &cam, &params, &cut, &err) == 0, "%s: %s",
            names[mode], err.message);
      double worst_tau = 0.0, worst_ratio = 0.0;
      int outside = 0;
      for (int py = 0; py < H; py++)
        for (int px = 0; px < W; px++) {
          const int k = py * W + px; /* all images rows top first */
          const double dtau = fabs((double)cut.tau[k] - whole.tau[k]);
          worst_tau = fmax(worst_tau, dtau);
          if (dtau > c + 2e-6) outside++;
          double o[3], d[3];
          camera_ray(&cam, px, py, W, H, o, d);
          double p = phase_hg(params.sun.phase_g, d[0] * sun_dir[0] + d[1] * sun_dir[1] +
                                                      d[2] * sun_dir[2]);
          for (int ch = 0; ch < 3; ch++) {
            double source = fog_colour[ch] + params.sun.albedo * params.sun.radiance[ch] * p;
            double lp = surface[4 * k + ch]; /* the sky's colour too: the texture's */
            double bound = c * fabs(lp - source);
            double dl = fabs((double)cut.rgba[4 * k + ch] - whole.rgba[4 * k + ch]);
            if (dl > bound + 2e-5 * (1 + source)) outside++;
            if (bound > 1e-7) worst_ratio = fmax(worst_ratio, dl / bound);
          }
        }
      printf("%s, cut-off %g: max |dtau| %.3e (%.2f of the cut-off), colour up to %.2f of "
             "its bound\n", names[mode], c, worst_tau, worst_tau / c, worst_ratio);
      CHECK(outside == 0, "%s, cut-off %g: %d pixel values outside the bounds", names[mode], c,
            outside);
      CHECK(worst_tau > 0.25 * c, "%s, cut-off %g: max |dtau| %.3e: did the walk stop?",
            names[mode], c, worst_tau);
    }
  }
  for (int l = 0; l <= LEVELS; l++) transform_grid_destroy(&grids[l]);
  for (int l = 0; l < LEVELS; l++) transform_grid_destroy(&grid_details[l]);
  fog_test_gl_teardown(&gl);
  return test_finish("test_gpu_early_stop");
}
