/* The lamps' in-scatter (render/fog_lamp.h, fog_lamps.glsl) on the GL pass against its CPU
 * twin (fog_lamps_inscatter, double), pixel by pixel, for every fog model: a point lamp
 * and a spot lamp inside the fog, the sun's radiance and the fog colour 0 and a black
 * surface, so the pass's colour is the lamps' in-scatter alone (Perlin turbulence fog too,
 * its octaves drifted to a time); and with quadric volumes beside the height fog and the
 * volume. Also: albedo 0 draws
 * nothing (the lamps scatter with the fog's albedo), and the spot's cone really cuts; a narrow
 * spot's beam across the view (its pieces cut at the cones, as the twin's). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/render.h"
#include "fog_test_gl.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { W = 64, H = 36 };
static const double ground_y = 0.5;

static double pixel_ray(const camera *cam, const float *dist, int px, int py, double o[3],
                        double d[3]) {
  camera_ray(cam, px, py, W, H, o, d);
  return dist[py * W + px] >= 1e29f ? HUGE_VAL : dist[py * W + px];
}

static fog_lamps two_lamps(const double point[3], const double spot[3]) {
  fog_lamps lamps = {.count = 2,
                     .method = {.angle_pieces = FOG_LAMP_ANGLE_PIECES,
                                .span_pieces = FOG_LAMP_SPAN_PIECES, .depth_steps = FOG_LAMP_DEPTH_STEPS,
                                .shadow_steps = FOG_LAMP_SHADOW_STEPS}};
  lamps.lamp[0] = (fog_lamp){.kind = FOG_LAMP_POINT, .position = {point[0], point[1], point[2]},
                             .intensity = {300, 250, 180}, .radius = 0.5};
  double axis[3] = {0.1, -1.0, 0.25};
  fog_test_unit(axis);
  lamps.lamp[1] = (fog_lamp){.kind = FOG_LAMP_SPOT, .position = {spot[0], spot[1], spot[2]},
                             .intensity = {900, 800, 700}, .radius = 0.5,
                             .axis = {axis[0], axis[1], axis[2]},
                             .cos_inner = cos(20 * 3.14159265358979 / 180), .cos_outer = cos(35 * 3.14159265358979 / 180)};
  return lamps;
}

/* Draws params and compares every pixel's colour with the twin; returns the image's
 * largest in-scatter (for the albedo-0 and cone checks). */
static double compare(fog_test_gl *gl, const camera *cam, const fog_pass_params *params,
                      const fog_model *m, const float *dist,
                      const char *name) {
  static float rgba[4 * W * H], tau[W * H];
  fog_error err = {0};
  CHECK(fog_test_gl_draw_tau(gl, cam, params, tau, &err) == 0 &&
            gl_target_read(&gl->target, 0, 4, rgba, &err) == 0,
        "%s: %s", name, err.message);
  double worst = 0.0, peak = 0.0, worst_rel = 0.0;
  static double want[3 * W * H];
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double o[3], d[3];
      double t_surface = pixel_ray(cam, dist, px, py, o, d);
      fog_lamps_inscatter(m, &params->lamps, params->sun.albedo, params->sun.phase_g, o, d,
                          t_surface, &want[3 * (py * W + px)]);
      for (int c = 0; c < 3; c++) peak = fmax(peak, want[3 * (py * W + px) + c]);
    }
  int outside = 0;
  for (int k = 0; k < W * H; k++)
    for (int c = 0; c < 3; c++) {
      double e = fabs((double)rgba[4 * k + c] - want[3 * k + c]);
      worst = fmax(worst, e);
      if (want[3 * k + c] > 1e-3 * peak) worst_rel = fmax(worst_rel, e / want[3 * k + c]);
      /* float against double: relative 2e-4 of the pixel, and 2e-5 of the image's peak (measured: 4e-5 and 2e-6) */
      if (e > 2e-4 * want[3 * k + c] + 2e-5 * peak) outside++;
    }
  printf("%s: peak in-scatter %.4g, max |GL - twin| %.3e (%.2e of the peak), max relative "
         "%.2e\n", name, peak, worst, worst / fmax(peak, 1e-30), worst_rel);
  CHECK(isfinite(peak) && isfinite(worst), "%s: peak %g, max error %g: not finite", name, peak,
        worst);
  CHECK(outside == 0, "%s: %d pixel values differ from the twin by more than 2e-4 relative + "
        "2e-5 of the peak (max %.3e)", name, outside, worst);
  return peak;
}

int main(void) {
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_gpu_lamps");
  static float surface[4 * W * H];
  for (int i = 0; i < W * H; i++) surface[4 * i + 3] = 1.0f; /* black, opaque */
  fog_test_gl_upload_flipped(&gl, gl.surface_tex, GL_RGBA, 4, surface);
  const fog_sun sun = {.albedo = 0.8, .phase_g = 0.4, .direction = {0, 1, 0}};

  /* The fogmap: the test box (x 100..160, z -50..-10), exponential profile. */
  {
    fog_volume v = fog_test_volume(FOG_PROFILE_EXPONENTIAL);
    transform_grid grid = fog_test_grid(1, 1.0, 0.0);
    CHECK(fog_pass_upload_grid(gl.pass, 0, &grid, &err) == 0, "%s", err.message);
    fog_lod lod = {.levels = 0, .approx = &grid};
    fog_model m = {.kind = FOG_MODEL_FOGMAP, .volume = &v, .lod = &lod,
                   .lod_method = FOG_LOD_SWITCH};
    camera cam = {.position = {96.0, 4.0, -30.0}, .fov_y = 1.1,
        .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    camera_look_at(&cam, (double[3]){160.0, 3.0, -24.0});
    fog_test_gl_set_ground(&gl, &cam, ground_y);
    fog_pass_params params = {.model = FOG_MODEL_FOGMAP, .volume = &v, .sun = sun,
                              .lamps = two_lamps((double[3]){122, 3, -28},
                                                 (double[3]){140, 10, -33})};
    double peak = compare(&gl, &cam, &params, &m, gl.dist, "fogmap");
    CHECK(peak > 0.05, "fogmap: peak in-scatter %g: the lamps do not reach the view", peak);
    /* uniform marching (the bench's baseline) */
    params.lamps.method.integral = FOG_LAMP_MARCH;
    params.lamps.method.march_steps = 48;
    compare(&gl, &cam, &params, &m, gl.dist, "fogmap, marched");
    params.lamps.method.integral = FOG_LAMP_ANGLE;
    /* albedo 0: the lamps scatter nothing */
    params.sun.albedo = 0.0;
    double none = compare(&gl, &cam, &params, &m, gl.dist, "fogmap, albedo 0");
    CHECK(none == 0.0, "albedo 0: in-scatter %g", none);
    /* the spot turned away from the view, the point lamp gone: nothing but what the cone's
     * outside leaks (smoothstep: exactly 0) */
    params.sun.albedo = sun.albedo;
    params.lamps.count = 1;
    params.lamps.lamp[0] = params.lamps.lamp[1];
    params.lamps.lamp[0].axis[0] = 0, params.lamps.lamp[0].axis[1] = 1,
    params.lamps.lamp[0].axis[2] = 0;
    params.lamps.lamp[0].position[1] = 60.0; /* above the box, shining up */
    double away = compare(&gl, &cam, &params, &m, gl.dist, "fogmap, spot away");
    CHECK(away == 0.0, "a spot shining away from all fog: in-scatter %g", away);
    /* a narrow spot (inner 2, outer 4 degrees) across the view: the pieces cut at the
     * ray's crossings of its cones (fog_lamp_cone_cuts), as in the twin */
    params.lamps.lamp[0].position[0] = 130, params.lamps.lamp[0].position[1] = 3,
    params.lamps.lamp[0].position[2] = -48;
    params.lamps.lamp[0].axis[0] = 0, params.lamps.lamp[0].axis[1] = 0,
    params.lamps.lamp[0].axis[2] = 1;
    params.lamps.lamp[0].cos_inner = cos(2 * 3.14159265358979 / 180);
    params.lamps.lamp[0].cos_outer = cos(4 * 3.14159265358979 / 180);
    double beam = compare(&gl, &cam, &params, &m, gl.dist, "fogmap, a narrow spot across");
    CHECK(beam > 1e-3, "the narrow spot's beam is not in view: peak %g", beam);
    transform_grid_destroy(&grid);
  }

  /* The analytic models and the volume (the scene of test_gpu_fog_vs_cpu). */
  fog_test_models scene;
  fog_test_scene_models(&scene);
  CHECK(fog_pass_upload_grid3d(gl.pass, &scene.grid3d, &err) == 0, "volume upload: %s",
        err.message);
  /* quadric volumes near the lamps: a soft sphere around the first, a hard cylinder, and a
   * soft cone the second's light crosses */
  const fog_quadric quadrics[3] = {
      fog_quadric_sphere((double[3]){42, 5, -18}, 10, 0.08, 0.4),
      fog_quadric_cylinder((double[3]){60, 0, -40}, 5, 18, 0.1, 0.0),
      fog_quadric_cone((double[3]){30, 0, -35}, 12, 16, 0.06, 0.5)};
  static const char *names[] = {"", "homogeneous", "height", "rbf", "volume", "quadric",
                                "linear", "exp2"};
  for (int model = FOG_MODEL_HOMOGENEOUS; model <= FOG_MODEL_EXP2; model++) {
    camera cam = {.position = {10.0, 3.0, 20.0}, .fov_y = 1.1,
        .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    camera_look_at(&cam, (double[3]){80.0, 6.0, -60.0});
    fog_test_gl_set_ground(&gl, &cam, ground_y);
    fog_model m = fog_test_scene_model(&scene, model, 0.002);
    if (model == FOG_MODEL_QUADRIC)
      m = (fog_model){.kind = model, .quadrics = quadrics, .quadric_count = 3};
    /* the classic factors: radial about the camera, the lamps' light marched through them */
    if (model == FOG_MODEL_LINEAR)
      m = (fog_model){.kind = model, .fog_start = 20, .fog_end = 160,
                      .eye = {cam.position[0], cam.position[1], cam.position[2]}};
    if (model == FOG_MODEL_EXP2)
      m = (fog_model){.kind = model, .extinction = 0.012,
                      .eye = {cam.position[0], cam.position[1], cam.position[2]}};
    fog_pass_params params = {.model = model, .model_extinction = m.extinction,
                              .model_fog_start = m.fog_start, .model_fog_end = m.fog_end,
                              .model_y0 = m.y0, .model_scale_height = m.scale_height,
                              .model_rbfs = m.rbfs, .model_rbf_count = m.rbf_count,
                              .model_quadrics = m.quadrics,
                              .model_quadric_count = m.quadric_count, .sun = sun,
                              .lamps = two_lamps((double[3]){40, 4, -15},
                                                 (double[3]){55, 12, -30})};
    double peak = compare(&gl, &cam, &params, &m, gl.dist, names[model]);
    CHECK(peak > 0.05, "%s: peak in-scatter %g: the lamps do not reach the view", names[model],
          peak);
    if (model == FOG_MODEL_RBF) { /* Fogshop's approximation, the bench's comparison */
      params.lamps.method.integral = FOG_LAMP_FOGSHOP;
      compare(&gl, &cam, &params, &m, gl.dist, "rbf, Fogshop's approximation");
      params.lamps.method.integral = FOG_LAMP_MARCH;
      params.lamps.method.march_steps = 48;
      compare(&gl, &cam, &params, &m, gl.dist, "rbf, marched");
    }
  }
  /* the quadrics beside the height fog (closed-form depths) and the volume (marched T) */
  for (int k = 0; k < 2; k++) {
    const int model = k ? FOG_MODEL_VOLUME : FOG_MODEL_HEIGHT;
    camera cam = {.position = {10.0, 3.0, 20.0}, .fov_y = 1.1,
        .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    camera_look_at(&cam, (double[3]){80.0, 6.0, -60.0});
    fog_test_gl_set_ground(&gl, &cam, ground_y);
    fog_model m = {.kind = model, .extinction = 0.01, .y0 = 4.0, .scale_height = 6.0,
                   .grid3d = k ? &scene.grid3d : NULL, .quadrics = quadrics, .quadric_count = 3};
    fog_pass_params params = {.model = model, .model_extinction = m.extinction,
                              .model_y0 = m.y0, .model_scale_height = m.scale_height,
                              .model_quadrics = quadrics, .model_quadric_count = 3, .sun = sun,
                              .lamps = two_lamps((double[3]){40, 4, -15},
                                                 (double[3]){55, 12, -30})};
    const char *name = k ? "volume, quadrics beside" : "height, quadrics beside";
    double peak = compare(&gl, &cam, &params, &m, gl.dist, name);
    CHECK(peak > 0.05, "%s: peak in-scatter %g", name, peak);
  }
  /* Perlin turbulence fog (the model table's last row), its octaves drifted to a time */
  {
    fog_perlin_desc pd = fog_perlin_desc_default();
    pd.octaves = 3;
    pd.lo[0] = -20.0, pd.hi[0] = 140.0, pd.lo[1] = 0.0, pd.hi[1] = 30.0;
    pd.lo[2] = -120.0, pd.hi[2] = 40.0;
    fog_perlin perlin = {0};
    CHECK(fog_perlin_create(&perlin, &pd, &err) == 0 &&
              fog_pass_upload_perlin(gl.pass, &perlin, &err) == 0,
          "perlin: %s", err.message);
    if (!perlin.texels) return test_finish("test_gpu_lamps");
    camera cam = {.position = {10.0, 3.0, 20.0}, .fov_y = 1.1,
        .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    camera_look_at(&cam, (double[3]){80.0, 6.0, -60.0});
    fog_test_gl_set_ground(&gl, &cam, ground_y);
    fog_model m = {.kind = FOG_MODEL_PERLIN, .extinction = 0.03, .y0 = 4.0,
                   .scale_height = 6.0, .perlin = &perlin, .time = 12.5};
    fog_pass_params params = {.model = FOG_MODEL_PERLIN, .model_extinction = m.extinction,
                              .model_y0 = m.y0, .model_scale_height = m.scale_height,
                              .model_perlin = &perlin, .model_time = m.time, .sun = sun,
                              .lamps = two_lamps((double[3]){40, 4, -15},
                                                 (double[3]){55, 12, -30})};
    double peak = compare(&gl, &cam, &params, &m, gl.dist, "perlin");
    CHECK(peak > 0.05, "perlin: peak in-scatter %g", peak);
    fog_perlin_destroy(&perlin);
  }
  free(scene.grid_values);
  fog_test_gl_teardown(&gl);
  return test_finish("test_gpu_lamps");
}
