/* The fog pass's performance options keep its results:
 * - resolution_divisor 0 and 1 draw the same image, bit for bit (full resolution);
 * - resolution_divisor 2 (the reduced walk + joint bilateral upsampling) on a smooth fog
 *   (a linear grid of sines, exponential profile) over a ground plane with a near occluder
 *   (sharp depth edges) stays within a stated distance of the full-resolution transmittance:
 *   max |dtau| <= 0.02 (edges: no fog bleeds across them, unmatched pixels walk their own
 *   ray), mean |dtau| <= 1e-3; divisor 4 within 0.05 / 3e-3;
 * - early termination (walk.transmittance_cutoff = the product's 1e-4) in thick fog agrees
 *   with the CPU (double, whole rays) within the cut-off, the walk without it within 2e-6;
 * - LOD draws that reduce to one grid (switching at mu = 1: A_J alone; mu = 0: A_0 alone;
 *   the sum of details at mu = 0), which the pass draws as that grid's one-grid variant,
 *   agree with the CPU's LOD integral within 2e-4, as does mu = 0.6 for both methods;
 * - height fog, Perlin fog and lamps at divisor 2 and 4 against their full resolution. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "fog_test_gl.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { W = 128, H = 72 };

static double cmp_max(const float *a, const float *b, double *mean) {
  double worst = 0.0, sum = 0.0;
  for (int k = 0; k < W * H; k++) {
    double e = fabs((double)a[k] - (double)b[k]);
    if (!(e == e)) e = INFINITY;
    worst = fmax(worst, e);
    sum += e;
  }
  if (mean) *mean = sum / (W * H);
  return worst;
}

int main(void) {
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_gpu_fog_resolution");

  /* A smooth linear grid over the test box. */
  transform_grid grid = fog_test_grid(1, 1.0, 0.0);
  for (int j = 0; j < grid.height; j++)
    for (int i = 0; i < grid.width; i++)
      grid.coefficients[(size_t)j * grid.width + i] =
          (float)(0.6 + 0.4 * sin(0.3 * i) * cos(0.25 * j));
  CHECK(fog_pass_upload_grid(gl.pass, 0, &grid, &err) == 0, "upload: %s", err.message);
  fog_volume v = fog_test_volume(FOG_PROFILE_EXPONENTIAL);
  double lo[3], hi[3];
  fog_volume_box(&v, lo, hi);
  camera cam = {.position = {0.5 * (lo[0] + hi[0]), 14.0, hi[2] + 25.0}, .fov_y = 0.9,
      .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
  camera_look_at(&cam, (double[3]){0.5 * (lo[0] + hi[0]), 0.0, lo[2]});

  /* Surface distances (rows top first): the ground y = 0.5, the sky above the horizon, and
   * a near occluder (distance 20) over a screen rectangle: depth edges in both directions. */
  float *colour = calloc((size_t)W * H * 4, sizeof(float));
  float *distance = malloc(sizeof(float) * W * H);
  double *dirs = malloc(sizeof(double) * 3 * W * H);
  fog_test_gl_ground_distance(&gl, &cam, 0.5, distance);
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double o[3];
      camera_ray(&cam, px, py, W, H, o, &dirs[3 * (py * W + px)]);
      if (px >= 37 && px < 71 && py >= 21 && py < 45) distance[py * W + px] = 20.0f;
    }
  for (int k = 0; k < W * H; k++) colour[4 * k + 0] = colour[4 * k + 1] = colour[4 * k + 2] = 0.5f;
  fog_test_gl_upload_flipped(&gl, gl.surface_tex, GL_RGBA, 4, colour);
  fog_test_gl_upload_flipped(&gl, gl.dist_tex, GL_RED, 1, distance);

  float *tau[4], *rgba[2];
  for (int k = 0; k < 4; k++) tau[k] = malloc(sizeof(float) * W * H);
  for (int k = 0; k < 2; k++) rgba[k] = malloc(sizeof(float) * 4 * W * H);
  static const int divisors[4] = {0, 1, 2, 4};
  for (int k = 0; k < 4; k++) {
    fog_pass_params params = {.volume = &v, .fog_colour = {0.8f, 0.8f, 0.9f},
                              .resolution_divisor = divisors[k]};
    CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau[k], &err) == 0,
          "draw divisor %d: %s", divisors[k], err.message);
    if (k < 2) CHECK(gl_target_read(&gl.target, 0, 4, rgba[k], &err) == 0, "read: %s", err.message);
  }
  /* Full resolution against the CPU (double), as test_gpu_fog_vs_cpu. */
  double worst_cpu = 0.0, min_tau = 1.0;
  for (int k = 0; k < W * H; k++) {
    double o[3] = {cam.position[0], cam.position[1], cam.position[2]};
    double t = distance[k] >= 1e29f ? HUGE_VAL : distance[k];
    double want = fog_transmittance(fog_optical_depth(&v, &grid, o, &dirs[3 * k], 0.0, t));
    worst_cpu = fmax(worst_cpu, fabs(want - tau[1][k]));
    min_tau = fmin(min_tau, want);
  }
  CHECK(worst_cpu <= 2e-4, "full resolution vs CPU: %.3e", worst_cpu);
  CHECK(min_tau < 0.7, "the scene has too little fog to test anything (min tau %.3f)", min_tau);
  CHECK(memcmp(tau[0], tau[1], sizeof(float) * W * H) == 0 &&
            memcmp(rgba[0], rgba[1], sizeof(float) * 4 * W * H) == 0,
        "divisor 0 and 1 differ");
  double mean2, mean4;
  double max2 = cmp_max(tau[2], tau[1], &mean2), max4 = cmp_max(tau[3], tau[1], &mean4);
  printf("full vs CPU %.2e (min tau %.3f); divisor 2: max |dtau| %.3e mean %.2e; divisor 4: "
         "max %.3e mean %.2e\n", worst_cpu, min_tau, max2, mean2, max4, mean4);
  CHECK(max2 <= 0.02 && mean2 <= 1e-3, "divisor 2 vs full: max %.3e mean %.3e", max2, mean2);
  CHECK(max4 <= 0.05 && mean4 <= 3e-3, "divisor 4 vs full: max %.3e mean %.3e", max4, mean4);
  /* The upsampling must not be a no-op copy of the full pass: it interpolates. */
  CHECK(mean2 > 0.0, "divisor 2 is bit-identical to full resolution: not reduced?");

  /* The other models take the reduced pass too: height fog and Perlin turbulence (whose
   * exact walk is the costliest per pixel) at divisor 2 and 4, against their own full
   * resolution. Where it breaks: the endless height fog's optical depth grows without bound
   * towards the horizon, and the upsampling interpolates depth between rows of very
   * different depths there (measured max |dtau| 0.11 at divisor 2, 0.27 at 4, on the rows
   * at the horizon; the boxed Perlin fog 0.042 and 0.083). Bounds: those, with margin. */
  static const double bound_max[2][2] = {{0.15, 0.35}, {0.06, 0.12}};
  static const double bound_mean[2][2] = {{4e-3, 1.5e-2}, {1.5e-3, 4.5e-3}};
  fog_perlin perlin;
  fog_perlin_desc pd = fog_perlin_desc_default();
  for (int a = 0; a < 3; a++) pd.lo[a] = lo[a] - 20.0, pd.hi[a] = hi[a] + 20.0;
  pd.feature_size = 30.0;
  CHECK(fog_perlin_create(&perlin, &pd, &err) == 0 && fog_pass_upload_perlin(gl.pass, &perlin, &err) == 0,
        "perlin: %s", err.message);
  for (int m = 0; m < 2; m++) {
    for (int k = 1; k < 4; k++) {
      fog_pass_params params = {.model = m ? FOG_MODEL_PERLIN : FOG_MODEL_HEIGHT,
                                .model_extinction = m ? 0.2 : 0.05, .model_y0 = 2.0,
                                .model_scale_height = 6.0, .model_perlin = &perlin,
                                .model_time = 3.0, .fog_colour = {0.8f, 0.8f, 0.9f},
                                .resolution_divisor = divisors[k]};
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau[k], &err) == 0,
            "model %d divisor %d: %s", m, divisors[k], err.message);
    }
    double model_mean2, model_mean4, full_min = 1.0;
    for (int k = 0; k < W * H; k++) full_min = fmin(full_min, tau[1][k]);
    double model_max2 = cmp_max(tau[2], tau[1], &model_mean2),
           model_max4 = cmp_max(tau[3], tau[1], &model_mean4);
    printf("%s: divisor 2 max |dtau| %.3e mean %.2e; divisor 4 max %.3e mean %.2e (min tau "
           "%.3f)\n", m ? "perlin" : "height", model_max2, model_mean2, model_max4, model_mean4,
           full_min);
    CHECK(full_min < 0.7, "model %d: too little fog (min tau %.3f)", m, full_min);
    CHECK(model_max2 <= bound_max[m][0] && model_mean2 <= bound_mean[m][0] && model_mean2 > 0.0,
          "model %d divisor 2 vs full: max %.3e mean %.3e", m, model_max2, model_mean2);
    CHECK(model_max4 <= bound_max[m][1] && model_mean4 <= bound_mean[m][1],
          "model %d divisor 4 vs full: max %.3e mean %.3e", m, model_max4, model_mean4);
  }
  fog_perlin_destroy(&perlin);

  /* Lamps take the reduced pass too: each sample's ray integrates them, the upsampling
   * blends their in-scatter with the depth's weights. A point lamp in the fog beside the
   * occluder and a spot over the ground; the lamps' share of the colour (a draw with lamps
   * minus one without, the same tau) at divisor 2 and 4 against full resolution, relative to
   * its peak. Where it breaks: the halo's 1/d^2 core, which samples a reduced pixel apart
   * miss: the pixels whose samples' lamp light differs by more than 25 % walk their own ray
   * (without that: max 0.49 at divisor 2, 0.98 at 4; with it 0.046 and 0.21, the core
   * between samples 4 pixels apart that agree). */
  {
    const double mid_x = 0.5 * (lo[0] + hi[0]), mid_z = 0.5 * (lo[2] + hi[2]);
    fog_lamps lamps = {.count = 2,
                       .method = {.integral = FOG_LAMP_ANGLE, .angle_pieces = FOG_LAMP_ANGLE_PIECES,
                                  .span_pieces = FOG_LAMP_SPAN_PIECES,
                                  .depth_steps = FOG_LAMP_DEPTH_STEPS,
                                  .shadow_steps = FOG_LAMP_SHADOW_STEPS}};
    lamps.lamp[0] = (fog_lamp){.kind = FOG_LAMP_POINT, .position = {mid_x - 6.0, 4.0, mid_z},
                               .intensity = {300, 260, 200}, .radius = 0.5};
    lamps.lamp[1] = (fog_lamp){.kind = FOG_LAMP_SPOT, .position = {mid_x + 8.0, 12.0, mid_z + 10.0},
                               .intensity = {2000, 2000, 2400}, .radius = 0.5,
                               .axis = {0.0, -1.0, 0.0}, .cos_inner = cos(0.35),
                               .cos_outer = cos(0.6)};
    float *lit[3], *dark = malloc(sizeof(float) * 4 * W * H);
    double peak = 0, lamp_max[3] = {0}, lamp_mean[3] = {0};
    for (int k = 0; k < 3; k++) {
      lit[k] = malloc(sizeof(float) * 4 * W * H);
      for (int with = 0; with < 2; with++) {
        fog_pass_params params = {.volume = &v, .resolution_divisor = divisors[k + 1],
                                  .sun = {.albedo = 0.9, .phase_g = 0.3}};
        if (with) params.lamps = lamps;
        CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau[0], &err) == 0 &&
                  gl_target_read(&gl.target, 0, 4, with ? lit[k] : dark, &err) == 0,
              "lamps divisor %d: %s", divisors[k + 1], err.message);
      }
      for (int q = 0; q < 4 * W * H; q++) lit[k][q] -= dark[q]; /* the lamps' share */
    }
    for (int q = 0; q < 4 * W * H; q++)
      if (q % 4 < 3) peak = fmax(peak, lit[0][q]);
    for (int k = 1; k < 3; k++) {
      for (int q = 0; q < 4 * W * H; q++) {
        if (q % 4 == 3) continue;
        double e = fabs((double)lit[k][q] - lit[0][q]) / peak;
        lamp_max[k] = fmax(lamp_max[k], e);
        lamp_mean[k] += e / (3.0 * W * H);
      }
    }
    printf("lamps (peak in-scatter %.3f): divisor 2 max %.3e mean %.2e, divisor 4 max %.3e "
           "mean %.2e of the peak\n", peak, lamp_max[1], lamp_mean[1], lamp_max[2],
           lamp_mean[2]);
    CHECK(peak > 0.05, "the lamps light too little fog to test (%.3e)", peak);
    CHECK(lamp_max[1] <= 0.1 && lamp_mean[1] <= 3e-3 && lamp_mean[1] > 0.0,
          "lamps divisor 2 vs full: max %.3e mean %.3e", lamp_max[1], lamp_mean[1]);
    CHECK(lamp_max[2] <= 0.3 && lamp_mean[2] <= 8e-3,
          "lamps divisor 4 vs full: max %.3e mean %.3e", lamp_max[2], lamp_mean[2]);
    for (int k = 0; k < 3; k++) free(lit[k]);
    free(dark);
  }

  /* Thick fog: most rays pass the cut-off. */
  v.extinction = 10.0;
  double worst_cut[2] = {0, 0};
  int opaque = 0;
  for (int c = 0; c < 2; c++) {
    fog_pass_params params = {
        .volume = &v, .walk = {.transmittance_cutoff = c ? 0.0 : FOG_PASS_TRANSMITTANCE_CUTOFF}};
    CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau[0], &err) == 0,
          "draw: %s", err.message);
    for (int k = 0; k < W * H; k++) {
      double o[3] = {cam.position[0], cam.position[1], cam.position[2]};
      double t = distance[k] >= 1e29f ? HUGE_VAL : distance[k];
      double depth = fog_optical_depth(&v, &grid, o, &dirs[3 * k], 0.0, t);
      worst_cut[c] = fmax(worst_cut[c], fabs(fog_transmittance(depth) - tau[0][k]));
      if (c == 0) opaque += depth > fog_pass_depth_limit(FOG_PASS_TRANSMITTANCE_CUTOFF);
    }
  }
  printf("thick fog: %d of %d pixels past the cut-off; vs CPU with cut-off %.2e, without %.2e\n",
         opaque, W * H, worst_cut[0], worst_cut[1]);
  CHECK(opaque > W * H / 4, "thick fog: only %d pixels past the cut-off", opaque);
  CHECK(worst_cut[0] <= FOG_PASS_TRANSMITTANCE_CUTOFF + 2e-6 && worst_cut[1] <= 2e-6,
        "cut-off %.3e, none %.3e", worst_cut[0], worst_cut[1]);

  /* LOD: a random 2-level linear pyramid, thin fog again. */
  enum { J = 2 };
  transform_grid approx[J + 1], detail[J];
  fog_test_pyramid(1, J, approx, detail);
  v.extinction = 0.05;
  fog_lod lod = {.levels = J, .approx = approx, .detail = detail};
  CHECK(fog_pass_upload_lod(gl.pass, &lod, &err) == 0, "upload: %s", err.message);
  static const double mus[3] = {1.0, 0.0, 0.6};
  for (int m = 0; m < 3; m++)
    for (int method = 0; method <= 1; method++) {
      fog_lod_method lm = method ? FOG_LOD_SWITCH : FOG_LOD_SUM_OF_DETAILS;
      lod.mu = mus[m];
      fog_pass_params params = {.volume = &v, .levels = J, .lod_method = lm, .mu = mus[m]};
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau[0], &err) == 0,
            "draw: %s", err.message);
      double worst = 0.0;
      for (int k = 0; k < W * H; k++) {
        double o[3] = {cam.position[0], cam.position[1], cam.position[2]};
        double t = distance[k] >= 1e29f ? HUGE_VAL : distance[k];
        double want = fog_transmittance(fog_optical_depth_lod(&v, &lod, lm, o, &dirs[3 * k], t));
        worst = fmax(worst, fabs(want - tau[0][k]));
      }
      printf("LOD %s mu %.1f: GPU vs CPU %.2e\n", method ? "switch" : "sum", mus[m], worst);
      CHECK(worst <= 2e-4, "LOD method %d mu %.1f: GPU vs CPU %.3e", method, mus[m], worst);
      /* at divisor 2 against this full draw */
      params.resolution_divisor = 2;
      CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, tau[1], &err) == 0, "draw: %s",
            err.message);
      double lod_mean, lod_max = cmp_max(tau[1], tau[0], &lod_mean);
      printf("LOD %s mu %.1f: divisor 2 vs full max |dtau| %.3e mean %.2e\n",
             method ? "switch" : "sum", mus[m], lod_max, lod_mean);
      /* at mu = 1 both methods draw A_J: the same fog, so the same upsampling, whose
       * first-order term is the depth's rate at the surface (the sum's read A_0 alone) */
      if (m == 0 && method == 0) memcpy(tau[2], tau[1], sizeof(float) * W * H);
      if (m == 0 && method == 1) {
        const double same = cmp_max(tau[1], tau[2], NULL);
        printf("LOD at mu 1, divisor 2: sum vs switch max |dtau| %.2e\n", same);
        CHECK(same <= 1e-5, "LOD at mu 1, divisor 2: the sum of details upsampled another fog "
              "(%.3e from switching)", same);
      }
    }
  for (int l = 0; l <= J; l++) transform_grid_destroy(&approx[l]);
  for (int l = 0; l < J; l++) transform_grid_destroy(&detail[l]);

  transform_grid_destroy(&grid);
  fog_test_gl_teardown(&gl);
  for (int k = 0; k < 4; k++) free(tau[k]);
  for (int k = 0; k < 2; k++) free(rgba[k]);
  free(colour);
  free(distance);
  free(dirs);
  return test_finish("test_gpu_fog_resolution");
}
