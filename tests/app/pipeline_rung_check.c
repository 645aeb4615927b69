/* The demo's model menu (app/live_rung.h, params.live_rung): the simulated fogmap drawn as a
 * cheaper rung fitted to it as it moves.
 *   - each rung's pixels are its fitted model's: the transmittance of every surface pixel
 *     against the CPU twin of the model pipeline_live_rung reports, along the pixel's ray
 *     to its surface (max |dtau| <= 2e-4);
 *   - the fit on fog of known density: a box filled with 0.03 gives homogeneous fog of
 *     0.03, and the height rung, whose layers do not decay, falls back to it;
 *   - the reported error is measured (finite, on 144 rays; a height fog is not the patchy
 *     ground fog: its mean error is above 0.05);
 *   - the bounded rungs (Gaussians, ellipsoids) are lit as themselves: their in-scatter is
 *     (L_amb + a L_sun p(theta) mean T_s)(1 - tau) with T_s from their own sun-shadow volume
 *     (the twin's mean along each pixel's ray, shafts off), not the fogmap's; also paused,
 *     when the sun moves and when the menu goes from one bounded rung to the other;
 *   - back on the fogmap the frame is the fogmap's again, bit for bit with a pipeline that
 *     never left it;
 *   - a [fog] quadric volume beside the fogmap, on the ellipsoids rung: lit with the rung's
 *     volumes, its sun volume of them all. Built by tests/app/pipeline.cmake. */
#include <math.h>
#include <stdio.h>

#include "app/live_rung.h"
#include "pipeline_check_util.h"
#include "render/fog_sun_shadow.h"
#include "test_util.h"

enum { W = 96, H = 54 };

/* The largest |in-scatter - (L_amb + a L_sun p mean T_s)(1 - tau)| over the surface pixels,
 * relative to the largest in-scatter, T_s from a volume computed here for the rung's model. */
static double lit_as_itself(const scene_config *cfg, const camera *cam, const fog_model *rung,
                            const float *tau, const float *depth, const float *inscatter) {
  const fog_sun sun = scene_config_fog_sun(cfg);
  const fog_sun_shadow_kind kind = fog_sun_shadow_kind_of(rung, sun.direction);
  fog_sun_shadow volume = {0};
  fog_error err = {0};
  const int n = cfg->shadow.resolution;
  if (kind != FOG_SUN_SHADOW_VOLUME ||
      fog_sun_shadow_create(&volume, &(fog_sun_shadow_desc){.across = n, .along = n}, &err) ||
      fog_sun_shadow_compute(&volume, rung, sun.direction, 2, &err)) {
    fprintf(stderr, "no sun volume for the rung (kind %d): %s\n", kind, err.message);
    return INFINITY;
  }
  double near, far, worst = 0.0, peak = 0.0;
  camera_depth_range(cam, &near, &far);
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      const int k = py * W + px;
      if (!(depth[k] < far)) continue;
      double o[3], d[3];
      camera_ray(cam, px, py, W, H, o, d);
      const double mean = fog_sun_mean_transmittance(rung, kind, &volume,
                                                     scene_config_light_rule(cfg), HUGE_VAL, o,
                                                     d, depth[k]);
      const double cos_theta = d[0] * sun.direction[0] + d[1] * sun.direction[1] +
                               d[2] * sun.direction[2];
      const double p = fog_phase_hg(sun.phase_g, cos_theta);
      for (int c = 0; c < 3; c++) {
        const double want =
            (cfg->fog.colour[c] + sun.albedo * sun.radiance[c] * p * mean) * (1.0 - tau[k]);
        worst = fmax(worst, fabs(inscatter[3 * k + c] - want));
        peak = fmax(peak, want);
      }
    }
  fog_sun_shadow_destroy(&volume);
  return worst / fmax(peak, 1e-12);
}

int main(void) {
  scene_config cfg;
  camera cam;
  gl_context *gl = pipeline_check_begin("configs/default.ini", &cfg, &cam);
  CHECK(gl != NULL, "no GL context");
  if (!gl) return test_finish("pipeline_rung_check");
  fog_error perr = {0};
  const pipeline_desc desc = {.config = &cfg, .width = W, .height = H,
                              .frame_seconds = 1.0 / 24.0, .synchronous = true};
  pipeline *p = pipeline_create(&desc, &perr), *plain = pipeline_create(&desc, &perr);
  CHECK(p && plain, "pipeline_create: %s", perr.message);
  static float tau[W * H], depth[W * H], rgba[4 * W * H], plain_rgba[4 * W * H];
  static float inscatter[3 * W * H];
  for (int kind = LIVE_RUNG_HOMOGENEOUS; p && plain && kind < LIVE_RUNG_COUNT; kind++) {
    pipeline_params params = pipeline_get_params(p);
    params.live_rung = kind;
    params.shafts = false; /* T_s alone: the twin's mean has no shadow map */
    pipeline_set_params(p, &params);
    CHECK(!pipeline_check_frame(p, &cam,
                                &(frame_pixels){.transmittance = tau, .depth = depth,
                                                .inscatter = inscatter}) &&
              !pipeline_check_frame(plain, &cam, &(frame_pixels){.rgba = plain_rgba}),
          "frames failed");
    live_rung r;
    CHECK(pipeline_live_rung(p, &r) && r.fitted, "%s: no rung reported", live_rung_names[kind]);
    const fog_model drawn = live_rung_model(&r);
    double worst = 0.0;
    double near, far;
    camera_depth_range(&cam, &near, &far);
    for (int py = 0; py < H; py++)
      for (int px = 0; px < W; px++) {
        const float t = depth[py * W + px];
        if (!(t < far)) continue; /* the sky: read back at the far plane */
        double o[3], d[3];
        camera_ray(&cam, px, py, W, H, o, d);
        worst = fmax(worst, fabs(exp(-fog_model_optical_depth(&drawn, o, d, t)) -
                                 tau[py * W + px]));
      }
    printf("%s: %s K %.5g y0 %.3g H %.3g; GL vs its twin max |dtau| %.2e; against the fogmap "
           "max %.3f mean %.3f on %d rays\n", live_rung_names[kind],
           fog_model_table[r.model.kind].name, r.model.extinction, r.model.y0,
           r.model.scale_height, worst, r.max_error, r.mean_error, r.rays);
    CHECK(worst <= 2e-4, "%s: the pixels are not the fitted model's (%.3e)", live_rung_names[kind],
          worst);
    if (live_rung_bounded(kind)) {
      const double lit = lit_as_itself(&cfg, &cam, &drawn, tau, depth, inscatter);
      printf("%s: in-scatter against its own T_s, max error %.2e of the largest\n",
             live_rung_names[kind], lit);
      CHECK(lit <= 2e-3, "%s: not lit as itself (%.3e of the largest in-scatter)",
            live_rung_names[kind], lit);
    }
    CHECK(r.rays == LIVE_RUNG_COLUMNS * LIVE_RUNG_ROWS && isfinite(r.max_error) &&
              r.mean_error > 0.05 && r.max_error <= 1.0,
          "%s: measured error max %g mean %g on %d rays", live_rung_names[kind], r.max_error,
          r.mean_error, r.rays);
    static const fog_model_kind drawn_kind[LIVE_RUNG_COUNT] = {
        [LIVE_RUNG_HOMOGENEOUS] = FOG_MODEL_HOMOGENEOUS, [LIVE_RUNG_HEIGHT] = FOG_MODEL_HEIGHT,
        [LIVE_RUNG_GAUSSIANS] = FOG_MODEL_RBF, [LIVE_RUNG_ELLIPSOIDS] = FOG_MODEL_QUADRIC};
    CHECK(r.model.kind == drawn_kind[kind], "%s: drew a %s", live_rung_names[kind],
          fog_model_table[r.model.kind].name);
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
  /* paused on a bounded rung, with no step between: the sun moves, then the menu changes
   * rung; each frame is lit by the shown rung's own volume for the sun of the moment */
  if (p) {
    pipeline_params params = pipeline_get_params(p);
    params.paused = true, params.shafts = false, params.live_rung = LIVE_RUNG_ELLIPSOIDS;
    pipeline_set_params(p, &params);
    CHECK(!pipeline_check_frame(p, &cam, &(frame_pixels){.transmittance = tau}), "frame");
    scene_config moved = cfg;
    for (int change = 0; change < 2; change++) {
      if (change == 0) params.sun_azimuth += 40, moved.light.sun_azimuth = params.sun_azimuth;
      else params.live_rung = LIVE_RUNG_GAUSSIANS;
      pipeline_set_params(p, &params);
      CHECK(!pipeline_check_frame(p, &cam,
                                  &(frame_pixels){.transmittance = tau, .depth = depth,
                                                  .inscatter = inscatter}),
            "frame");
      live_rung r;
      CHECK(pipeline_live_rung(p, &r), "no rung");
      const fog_model drawn = live_rung_model(&r);
      const double lit = lit_as_itself(&moved, &cam, &drawn, tau, depth, inscatter);
      printf("paused, %s: %s lit as itself within %.2e\n", change ? "the rung changed" : "the sun moved",
             live_rung_names[r.kind], lit);
      CHECK(lit <= 2e-3, "paused, %s: not lit as itself (%.3e)",
            change ? "the rung changed" : "the sun moved", lit);
    }
    params.sun_azimuth -= 40; /* the plain pipeline's sun, for the comparison below */
    pipeline_set_params(p, &params);
  }
  /* paused on the homogeneous rung, the panel's density a tenth: the rung is refitted to
   * the fog of the moment (its K a tenth), not kept from before (its error then measured
   * how stale it was) */
  if (p) {
    pipeline_params params = pipeline_get_params(p);
    params.paused = true, params.live_rung = LIVE_RUNG_HOMOGENEOUS;
    pipeline_set_params(p, &params);
    live_rung before, after;
    CHECK(!pipeline_check_frame(p, &cam, &(frame_pixels){.transmittance = tau}) &&
              pipeline_live_rung(p, &before),
          "frame");
    const float density = params.density;
    params.density = 0.1f * density;
    pipeline_set_params(p, &params);
    CHECK(!pipeline_check_frame(p, &cam, &(frame_pixels){.transmittance = tau}) &&
              pipeline_live_rung(p, &after),
          "frame");
    printf("paused, density a tenth: the homogeneous rung's K %.6g -> %.6g\n",
           before.model.extinction, after.model.extinction);
    CHECK(fabs(after.model.extinction - 0.1 * before.model.extinction) <=
              1e-6 * before.model.extinction,
          "paused, density a tenth: K %g, expected %g", after.model.extinction,
          0.1 * before.model.extinction);
    params.density = density;
    pipeline_set_params(p, &params);
  }
  /* back on the fogmap: the fogmap's frame, bit for bit; the sun moved while a closed-form
   * rung was shown (which leaves the fogmap's volume alone): relit on the way back */
  if (p && plain) {
    pipeline_params params = pipeline_get_params(p), plain_params = pipeline_get_params(plain);
    params.live_rung = LIVE_RUNG_HOMOGENEOUS;
    params.sun_azimuth += 25, plain_params.sun_azimuth = params.sun_azimuth;
    pipeline_set_params(p, &params);
    CHECK(!pipeline_check_frame(p, &cam, &(frame_pixels){.rgba = rgba}), "frame");
    params.live_rung = LIVE_RUNG_FOGMAP;
    params.paused = plain_params.paused = true;
    plain_params.shafts = params.shafts;
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
  /* a [fog] quadric volume beside the fogmap, in view, on the ellipsoids rung: the rung
   * draws it as one of its own volumes, and lights it so, its sun volume made of the
   * fitted ellipsoids and the sphere (it was of the ellipsoids alone: the sphere cast and
   * received no sun shadow on this rung) */
  {
    scene_config beside = cfg;
    double right[3], up[3], forward[3], centre[3];
    camera_basis(&cam, W, H, right, up, forward);
    for (int a = 0; a < 3; a++) centre[a] = cam.position[a] + 120.0 * forward[a];
    beside.fog.quadrics[beside.fog.quadric_count++] =
        fog_quadric_sphere(centre, 25.0, 0.05, 0.0);
    const pipeline_desc beside_desc = {.config = &beside, .width = W, .height = H,
                                       .frame_seconds = 1.0 / 24.0, .synchronous = true};
    pipeline *q = pipeline_create(&beside_desc, &perr);
    CHECK(q != NULL, "pipeline with a quadric beside: %s", perr.message);
    if (q) {
      pipeline_params params = pipeline_get_params(q);
      params.shafts = false, params.live_rung = LIVE_RUNG_ELLIPSOIDS;
      pipeline_set_params(q, &params);
      CHECK(!pipeline_check_frame(q, &cam,
                                  &(frame_pixels){.transmittance = tau, .depth = depth,
                                                  .inscatter = inscatter}),
            "frame with a quadric beside");
      live_rung r;
      CHECK(pipeline_live_rung(q, &r) && r.fitted && r.model.kind == FOG_MODEL_QUADRIC,
            "no ellipsoids rung reported");
      /* what the pass draws: the fitted volumes, then the one beside at the live density */
      fog_quadric all[FOG_MAX_QUADRICS];
      const fog_model fitted = live_rung_model(&r);
      int n = 0;
      for (int i = 0; i < fitted.quadric_count; i++) all[n++] = fitted.quadrics[i];
      all[n] = beside.fog.quadrics[beside.fog.quadric_count - 1];
      all[n++].density *= params.density;
      const fog_model drawn = {.kind = FOG_MODEL_QUADRIC, .quadrics = all, .quadric_count = n};
      const double lit = lit_as_itself(&beside, &cam, &drawn, tau, depth, inscatter);
      printf("ellipsoids beside a quadric volume: lit with it within %.2e\n", lit);
      CHECK(lit <= 2e-3, "ellipsoids with a quadric beside: not lit with it (%.3e)", lit);
      pipeline_destroy(q);
    }
  }
  gl_context_destroy(gl);
  return test_finish("pipeline_rung_check");
}
