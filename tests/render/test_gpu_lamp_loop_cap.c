/* The renderer's loop cap and the fog pass's guard against it (render/gl_util.h,
 * gl_util_loop_cap; render/fog_pass.h, fog_pass_lamp_loop_bound). Mesa's llvmpipe ends all
 * of a shader's loops once they have run 65535 iterations together, and the shader goes on
 * with what it has: a lamp's light over many Gaussians came out wrong without an error.
 *   - the probe finds 65535 on llvmpipe (and no cap where the probe's loop runs whole);
 *   - RBF fog with one lamp and as many Gaussians as a bound of the cap less 1024 allows
 *     (the pass's reserve lifted for it): the pass draws it, equal to the CPU twin (so the
 *     bound is not below what the shader runs by more than that); the same with a spot
 *     across the view (its pieces cut at its cones' crossings, counted);
 *   - with ~1.3x the cap in the bound: the pass refuses, naming the cap; drawn anyway (the
 *     cap lifted), the image is wrong (so the guard protects something real, and the bound
 *     is within 1.3x of what the shader runs);
 *   - the sun's mean along the ray (K at every node loops over the pixel's Gaussians): 8
 *     steps of 2 nodes over 100 Gaussians drawn, 1024 steps refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "fog_test_gl.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { W = 48, H = 27, MAX_GAUSSIANS = 1024 };

static fog_rbf rbfs[MAX_GAUSSIANS];

/* The Gaussians along the view, the lamp among them. */
static void fill_gaussians(void) {
  for (int i = 0; i < MAX_GAUSSIANS; i++)
    rbfs[i] = (fog_rbf){.centre = {fog_test_range(20, 90), fog_test_range(0, 14),
                                   fog_test_range(-60, 10)},
                        .radius = fog_test_range(3, 8), .density = fog_test_range(0.002, 0.01)};
}

static bool with_spot; /* the lamp a spot across the view: its cones cut its pieces */

static fog_pass_params params_with(int n) {
  fog_pass_params p = {.model = FOG_MODEL_RBF, .model_extinction = 0.001, .model_rbfs = rbfs,
                       .model_rbf_count = n,
                       .sun = {.albedo = 0.8, .phase_g = 0.4, .direction = {0, 1, 0}}};
  p.lamps = (fog_lamps){.count = 1,
                        .method = {.angle_pieces = FOG_LAMP_ANGLE_PIECES,
                                   .span_pieces = FOG_LAMP_SPAN_PIECES,
                                   .depth_steps = FOG_LAMP_DEPTH_STEPS,
                                   .shadow_steps = FOG_LAMP_SHADOW_STEPS}};
  p.lamps.lamp[0] = (fog_lamp){.kind = FOG_LAMP_POINT, .position = {50, 6, -25},
                               .intensity = {400, 350, 300}, .radius = 0.5};
  if (with_spot)
    p.lamps.lamp[0] = (fog_lamp){.kind = FOG_LAMP_SPOT, .position = {20, 6, -25},
                                 .intensity = {4000, 3500, 3000}, .radius = 0.5,
                                 .axis = {1, 0, 0}, .cos_inner = cos(0.15), .cos_outer = cos(0.3)};
  return p;
}

/* Pixel values outside 2e-4 relative + 2e-5 of the peak from the CPU twin (test_gpu_lamps'
 * tolerance); the largest difference over the peak in *worst. */
static int count_wrong(const float *rgba, const camera *cam, const fog_pass_params *p,
                       const float *dist, double *worst) {
  static double want[3 * W * H];
  fog_model m = {.kind = FOG_MODEL_RBF, .extinction = p->model_extinction, .rbfs = rbfs,
                 .rbf_count = p->model_rbf_count};
  double peak = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double o[3], d[3];
      camera_ray(cam, px, py, W, H, o, d);
      double ts = dist[py * W + px] >= 1e29f ? HUGE_VAL : dist[py * W + px];
      fog_lamps_inscatter(&m, &p->lamps, p->sun.albedo, p->sun.phase_g, o, d, ts,
                          &want[3 * (py * W + px)]);
      for (int c = 0; c < 3; c++) peak = fmax(peak, want[3 * (py * W + px) + c]);
    }
  int wrong = 0;
  *worst = 0;
  for (int k = 0; k < W * H; k++)
    for (int c = 0; c < 3; c++) {
      double e = fabs((double)rgba[4 * k + c] - want[3 * k + c]);
      if (!(e == e)) e = HUGE_VAL;
      *worst = fmax(*worst, e / fmax(peak, 1e-30));
      if (e > 2e-4 * want[3 * k + c] + 2e-5 * peak) wrong++;
    }
  CHECK(peak > 0.01, "peak in-scatter %g: the lamp does not reach the view", peak);
  return wrong;
}

/* The draw's bound as the pass counts it, every Gaussian in the pixel's tile. */
static double bound_of(const fog_pass_params *p) {
  return fog_pass_loop_bound(p, p->model_rbf_count);
}

/* The most Gaussians whose bound is at most `loops`. */
static int gaussians_within(double loops) {
  int n = 1;
  while (n < MAX_GAUSSIANS) {
    fog_pass_params p = params_with(n + 1);
    if (bound_of(&p) > loops) break;
    n++;
  }
  return n;
}

int main(void) {
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_gpu_lamp_loop_cap");
  const char *renderer = (const char *)glGetString(GL_RENDERER);
  const long cap = fog_pass_loop_cap(gl.pass);
  printf("renderer %s: loop cap %ld\n", renderer, cap == GL_UTIL_NO_LOOP_CAP ? -1 : cap);
  if (strstr(renderer, "llvmpipe"))
    CHECK(cap == 65535, "llvmpipe: the probe found a cap of %ld, expected 65535 (Mesa's "
          "LP_MAX_TGSI_LOOP_ITERATIONS)", cap);
  if (cap == GL_UTIL_NO_LOOP_CAP) { /* a GPU: nothing to guard */
    fog_test_gl_teardown(&gl);
    return test_finish("test_gpu_lamp_loop_cap");
  }

  fill_gaussians();
  static float surface[4 * W * H], rgba[4 * W * H], tau[W * H];
  for (int i = 0; i < W * H; i++) surface[4 * i + 3] = 1.0f; /* black, opaque */
  fog_test_gl_upload_flipped(&gl, gl.surface_tex, GL_RGBA, 4, surface);
  camera cam = {.position = {5.0, 4.0, 25.0}, .fov_y = 1.1, .near_plane = CAMERA_DEFAULT_NEAR,
                .far_plane = CAMERA_DEFAULT_FAR};
  camera_look_at(&cam, (double[3]){60.0, 5.0, -40.0});
  fog_test_gl_set_ground(&gl, &cam, 0.5);

  /* as many Gaussians as a bound of the cap less VIEW_SLACK allows (the pass's reserve
   * lifted to that for the draw): drawn, and right, so the bound is not below what the
   * shader runs by more than that slack (this view ray's own walk is a few hundred) */
  enum { VIEW_SLACK = 1024 };
  const int allowed = gaussians_within((double)cap - FOG_PASS_LOOP_RESERVE);
  const int under = gaussians_within((double)cap - VIEW_SLACK);
  fog_pass_set_loop_cap(gl.pass, cap + FOG_PASS_LOOP_RESERVE - VIEW_SLACK);
  fog_pass_params p = params_with(under);
  double worst;
  CHECK(fog_test_gl_draw_tau(&gl, &cam, &p, tau, &err) == 0 &&
            gl_target_read(&gl.target, 0, 4, rgba, &err) == 0,
        "%d Gaussians (bound %.0f): %s", under, bound_of(&p), err.message);
  int wrong = count_wrong(rgba, &cam, &p, gl.dist, &worst);
  printf("%d Gaussians, bound %.0f loop iterations: %d values off the twin (max %.2e of the "
         "peak)\n", under, bound_of(&p), wrong, worst);
  /* the same with a spot across the view: its 4 cuts at the cones' crossings counted (the
   * bound above the point lamp's; the draw right near the cap) */
  {
    const fog_pass_params point_lamp = params_with(under);
    with_spot = true;
    const fog_pass_params spot_lamp = params_with(under);
    CHECK(bound_of(&spot_lamp) > bound_of(&point_lamp), "a spot's bound %.0f, a point lamp's "
          "%.0f: its cone cuts not counted", bound_of(&spot_lamp), bound_of(&point_lamp));
  }
  const int under_spot = gaussians_within((double)cap - VIEW_SLACK);
  fog_pass_params ps = params_with(under_spot);
  CHECK(fog_test_gl_draw_tau(&gl, &cam, &ps, tau, &err) == 0 &&
            gl_target_read(&gl.target, 0, 4, rgba, &err) == 0,
        "a spot, %d Gaussians (bound %.0f): %s", under_spot, bound_of(&ps), err.message);
  double worst_spot;
  const int wrong_spot = count_wrong(rgba, &cam, &ps, gl.dist, &worst_spot);
  printf("a spot, %d Gaussians, bound %.0f loop iterations: %d values off the twin (max %.2e "
         "of the peak)\n", under_spot, bound_of(&ps), wrong_spot, worst_spot);
  CHECK(wrong_spot == 0, "a spot, %d Gaussians within the guard's bound: %d values wrong (max "
        "%.2e of the peak): the bound is below what the shader runs", under_spot, wrong_spot,
        worst_spot);
  with_spot = false;
  fog_pass_set_loop_cap(gl.pass, cap);
  printf("the guard allows %d Gaussians with one lamp\n", allowed);
  CHECK(allowed >= 200, "the guard allows only %d Gaussians with one lamp", allowed);
  CHECK(wrong == 0, "%d Gaussians within the guard's bound: %d values wrong (max %.2e of the "
        "peak): the bound is below what the shader runs", under, wrong, worst);

  /* ~1.3x the cap: refused, naming the cap; drawn anyway, wrong */
  const int over = gaussians_within(1.3 * (double)cap);
  p = params_with(over);
  err = (fog_error){0};
  CHECK(fog_test_gl_draw_tau(&gl, &cam, &p, tau, &err) != 0,
        "%d Gaussians (bound %.0f) were drawn past the cap %ld", over,
        bound_of(&p), cap);
  char cap_text[32];
  snprintf(cap_text, sizeof cap_text, "after %ld", cap);
  CHECK(err.code == FOG_ERR_UNSUPPORTED && strstr(err.message, "loop iterations") &&
            strstr(err.message, cap_text) && strstr(err.message, "Gaussians"),
        "the refusal does not name the loops, the cap and the Gaussians: %s", err.message);
  printf("refused: %s\n", err.message);
  fog_pass_set_loop_cap(gl.pass, GL_UTIL_NO_LOOP_CAP);
  CHECK(fog_test_gl_draw_tau(&gl, &cam, &p, tau, &err) == 0 &&
            gl_target_read(&gl.target, 0, 4, rgba, &err) == 0,
        "%d Gaussians, the cap lifted: %s", over, err.message);
  wrong = count_wrong(rgba, &cam, &p, gl.dist, &worst);
  printf("%d Gaussians, bound %.0f, drawn past the cap: %d values off the twin (max %.2e of "
         "the peak)\n", over, bound_of(&p), wrong, worst);
  CHECK(wrong > 0 && worst > 1e-3, "%d Gaussians past the cap drew right (%d values off, max "
        "%.2e): the bound is more than 1.3x what the shader runs", over, wrong, worst);
  fog_pass_set_loop_cap(gl.pass, cap);

  /* the sun's mean along the ray over 100 Gaussians: K at each of its steps' nodes loops
   * over the pixel's tile; 8 steps of 2 nodes are drawn, 1024 refused (no lamps) */
  p = params_with(100);
  p.lamps.count = 0;
  p.self_shadow = FOG_SUN_SHADOW_HEIGHT, p.shadow_steps = 8, p.shadow_nodes = 2;
  CHECK(fog_test_gl_draw_tau(&gl, &cam, &p, tau, &err) == 0,
        "the sun's mean, 8 steps over 100 Gaussians: %s", err.message);
  p.shadow_steps = 1024;
  err = (fog_error){0};
  CHECK(fog_test_gl_draw_tau(&gl, &cam, &p, tau, &err) != 0 &&
            strstr(err.message, "the sun's mean over 1024 shadow steps of 2 nodes"),
        "the sun's mean, 1024 steps of 2 nodes over 100 Gaussians (bound %.0f): %s",
        bound_of(&p), err.message[0] ? err.message : "drawn");
  printf("refused: %s\n", err.message);

  fog_test_gl_teardown(&gl);
  return test_finish("test_gpu_lamp_loop_cap");
}
