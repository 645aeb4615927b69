/* The demo's model menu (app/live_rung.h, params.live_rung): the simulated fogmap drawn as a
 * cheaper rung fitted to it as it moves.
 *   - each rung's pixels are its fitted model's: the transmittance of every surface pixel
 *     against the CPU twin of the model pipeline_live_rung reports, along the pixel's ray
 *     to its surface (max |dtau| <= 2e-4);
 *   - the fit on fog of known density: a box filled with 0.03 gives homogeneous fog of
 *     0.03, and the height rung, whose layers do not decay, falls back to it;
 *   - the reported error is measured (finite, on 144 rays; a height fog is not the patchy
 *     ground fog: its mean error is above 0.05);
 *   - back on the fogmap the frame is the fogmap's again, bit for bit with a pipeline that
 *     never left it. Built by tests/app/pipeline.cmake. */
#include <math.h>
#include <stdio.h>

#include "app/live_rung.h"
#include "pipeline_check_util.h"
#include "test_util.h"

enum { W = 96, H = 54 };

int main(void) {
  scene_config cfg;
  camera cam;
  gl_context *gl = pipeline_check_begin("configs/default.ini", &cfg, &cam);
  CHECK(gl != NULL, "no GL context");
  if (!gl) return test_finish("pipeline_rung_check");
  fog_error perr = {0};
  pipeline *p = pipeline_create(&(pipeline_desc){.config = &cfg, .width = W, .height = H,
                                                 .synchronous = true}, &perr);
  pipeline *plain = pipeline_create(&(pipeline_desc){.config = &cfg, .width = W, .height = H,
                                                     .synchronous = true}, &perr);
  CHECK(p && plain, "pipeline_create: %s", perr.message);
  static float tau[W * H], depth[W * H], rgba[4 * W * H], plain_rgba[4 * W * H];
  for (int kind = LIVE_RUNG_HOMOGENEOUS; p && plain && kind < LIVE_RUNG_COUNT; kind++) {
    pipeline_params params = pipeline_get_params(p);
    params.live_rung = kind;
    pipeline_set_params(p, &params);
    CHECK(!pipeline_check_frame(p, &cam,
                                &(frame_pixels){.transmittance = tau, .depth = depth}) &&
              !pipeline_check_frame(plain, &cam, &(frame_pixels){.rgba = plain_rgba}),
          "frames failed");
    live_rung r;
    CHECK(pipeline_live_rung(p, &r) && r.fitted, "%s: no rung reported", live_rung_names[kind]);
    double worst = 0.0;
    double near, far;
    camera_depth_range(&cam, &near, &far);
    for (int py = 0; py < H; py++)
      for (int px = 0; px < W; px++) {
        const float t = depth[py * W + px];
        if (!(t < far)) continue; /* the sky: read back at the far plane */
        double o[3], d[3];
        camera_ray(&cam, px, py, W, H, o, d);
        worst = fmax(worst, fabs(exp(-fog_model_optical_depth(&r.model, o, d, t)) -
                                 tau[py * W + px]));
      }
    printf("%s: %s K %.5g y0 %.3g H %.3g; GL vs its twin max |dtau| %.2e; against the fogmap "
           "max %.3f mean %.3f on %d rays\n", live_rung_names[kind],
           fog_model_table[r.model.kind].name, r.model.extinction, r.model.y0,
           r.model.scale_height, worst, r.max_error, r.mean_error, r.rays);
    CHECK(worst <= 2e-4, "%s: the pixels are not the fitted model's (%.3e)", live_rung_names[kind],
          worst);
    CHECK(r.rays == LIVE_RUNG_COLUMNS * LIVE_RUNG_ROWS && isfinite(r.max_error) &&
              r.mean_error > 0.05 && r.max_error <= 1.0,
          "%s: measured error max %g mean %g on %d rays", live_rung_names[kind], r.max_error,
          r.mean_error, r.rays);
    CHECK(r.model.kind == (kind == LIVE_RUNG_HEIGHT ? FOG_MODEL_HEIGHT : FOG_MODEL_HOMOGENEOUS),
          "%s: drew a %s", live_rung_names[kind], fog_model_table[r.model.kind].name);
  }
  /* the fit on fog of known density: a general quadric that fills its box (Q = -1) at
   * 0.03 is homogeneous fog of 0.03 there; its layers do not decay, so the height rung
   * falls back to that same homogeneous fog */
  {
    fog_quadric box = {.q = {0, 0, 0, 0, 0, 0, 0, 0, 0, -1}, .lo = {-50, 0, -30},
                       .hi = {70, 40, 90}, .density = 0.03};
    const fog_model filled = {.kind = FOG_MODEL_QUADRIC, .quadrics = &box, .quadric_count = 1};
    live_rung h, e;
    live_rung_fit(&filled, LIVE_RUNG_HOMOGENEOUS, &h);
    live_rung_fit(&filled, LIVE_RUNG_HEIGHT, &e);
    CHECK(h.fitted && h.model.kind == FOG_MODEL_HOMOGENEOUS &&
              fabs(h.model.extinction - 0.03) < 1e-14,
          "homogeneous fit of a filled box: K %g", h.model.extinction);
    CHECK(e.fitted && e.model.kind == FOG_MODEL_HOMOGENEOUS &&
              fabs(e.model.extinction - 0.03) < 1e-14,
          "height fit of a filled box: %s K %g", fog_model_table[e.model.kind].name,
          e.model.extinction);
  }
  /* back on the fogmap: the fogmap's frame, bit for bit */
  if (p && plain) {
    pipeline_params params = pipeline_get_params(p), plain_params = pipeline_get_params(plain);
    params.live_rung = LIVE_RUNG_FOGMAP;
    params.paused = plain_params.paused = true;
    pipeline_set_params(p, &params);
    pipeline_set_params(plain, &plain_params);
    CHECK(!pipeline_check_frame(p, &cam, &(frame_pixels){.rgba = rgba}) &&
              !pipeline_check_frame(plain, &cam, &(frame_pixels){.rgba = plain_rgba}),
          "frames failed");
    live_rung r;
    CHECK(!pipeline_live_rung(p, &r), "a rung reported on the fogmap");
    double differs = 0.0;
    for (int k = 0; k < 4 * W * H; k++) differs = fmax(differs, fabs(rgba[k] - plain_rgba[k]));
    CHECK(differs == 0.0, "back on the fogmap the frame differs by %g", differs);
  }
  pipeline_destroy(p);
  pipeline_destroy(plain);
  gl_context_destroy(gl);
  return test_finish("pipeline_rung_check");
}
