/* The demo's time of day: moving the sun through pipeline_set_params (what the panel's sun
 * sliders do) relights the terrain and the fog in the next frame. The fog's in-scatter
 * then equals (L_amb + a L_sun p(theta)) (1 - tau) per pixel with theta from the NEW sun,
 * its direction written here from [light]'s documented convention (azimuth like the
 * camera's yaw: 0 towards -Z, 90 towards +X; elevation above the horizon), and the
 * surfaces differ from an identical pipeline whose sun stayed ([light] fog_self_shadow and
 * shafts off: T_s = V = 1). With the fog's self-shadow on, a sun moved while paused (no new step) re-lights
 * the fog from the step on screen: the frame equals, bit for bit, that of a pipeline
 * created with the new sun. The panel's sun colour (params.sun.radiance = pi x [light]
 * sun_colour) changed while paused gives, bit for bit, the frame of a pipeline created with
 * that sun_colour: the terrain, the sky and the fog all take it. Built by
 * tests/app/pipeline.cmake. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "app/config.h"
#include "app/pipeline.h"
#include "render/gl_context.h"
#include "pipeline_check_util.h"
#include "test_util.h"

enum { W = 80, H = 45 };
static const double pi = 3.14159265358979323846;

static int frame(pipeline *p, const camera *cam, float *rgba, float *tau, float *inscatter) {
  return pipeline_check_frame(
      p, cam, &(frame_pixels){.rgba = rgba, .transmittance = tau, .inscatter = inscatter});
}

/* The sun's colour set through the params, paused, against a config with that colour. */
static void check_sun_colour(const scene_config *cfg, const camera *cam) {
  static const float colour[3] = {0.5f, 1.25f, 2.5f};
  scene_config born_cfg = *cfg;
  for (int c = 0; c < 3; c++) born_cfg.light.sun_colour[c] = colour[c];
  pipeline_error perr = {{0}};
  pipeline *tinted = pipeline_create(&(pipeline_desc){.config = cfg, .width = W, .height = H,
                                                      .synchronous = true}, &perr);
  pipeline *born = pipeline_create(&(pipeline_desc){.config = &born_cfg, .width = W,
                                                    .height = H, .synchronous = true}, &perr);
  CHECK(tinted && born, "pipeline_create: %s", perr.message);
  if (!tinted || !born) return;
  static float a[4 * W * H], b[4 * W * H], before[4 * W * H];
  CHECK(!frame(tinted, cam, before, NULL, NULL), "first frame failed");
  pipeline_params params = pipeline_get_params(tinted);
  params.paused = true;
  for (int c = 0; c < 3; c++) params.sun.radiance[c] = pi * colour[c];
  pipeline_set_params(tinted, &params);
  CHECK(!frame(tinted, cam, a, NULL, NULL) && !frame(born, cam, b, NULL, NULL), "frames failed");
  double changed = 0, differs = 0;
  for (int k = 0; k < 4 * W * H; k++) {
    changed = fmax(changed, fabs(a[k] - before[k]));
    differs = fmax(differs, fabs(a[k] - b[k]));
  }
  printf("sun colour (%g, %g, %g) set while paused: the frame changed by up to %.3f; it differs "
         "from a pipeline born with that colour by %.3g\n", colour[0], colour[1], colour[2],
         changed, differs);
  CHECK(changed > 0.05, "the sun colour changed nothing (%.3e)", changed);
  CHECK(differs == 0, "recoloured frame != a pipeline created with that colour (%.3e)", differs);
  pipeline_destroy(tinted);
  pipeline_destroy(born);
}

/* Self-shadowed: pause after the first step, move the sun, draw again (the relight path),
 * against a pipeline whose config has the new sun from the start. */
static void check_relight(const scene_config *cfg, const camera *cam) {
  CHECK(cfg->shadow.fog_self_shadow == 1 && cfg->fog.albedo > 0,
        "configs/default.ini: expected the fog's self-shadow on by default");
  scene_config moved_cfg = *cfg;
  moved_cfg.light.sun_azimuth = -70, moved_cfg.light.sun_elevation = 25;
  pipeline_error perr = {{0}};
  pipeline *moved = pipeline_create(&(pipeline_desc){.config = cfg, .width = W, .height = H,
                                                     .synchronous = true}, &perr);
  pipeline *born = pipeline_create(&(pipeline_desc){.config = &moved_cfg, .width = W,
                                                    .height = H, .synchronous = true}, &perr);
  CHECK(moved && born, "pipeline_create: %s", perr.message);
  if (!moved || !born) return;
  static float a[4 * W * H], b[4 * W * H], before[4 * W * H];
  CHECK(!frame(moved, cam, before, NULL, NULL), "first frame failed");
  pipeline_params params = pipeline_get_params(moved);
  params.paused = true;
  params.sun_azimuth = -70, params.sun_elevation = 25;
  pipeline_set_params(moved, &params);
  CHECK(!frame(moved, cam, a, NULL, NULL) && !frame(born, cam, b, NULL, NULL), "frames failed");
  double changed = 0, differs = 0;
  for (int k = 0; k < 4 * W * H; k++) {
    changed = fmax(changed, fabs(a[k] - before[k]));
    differs = fmax(differs, fabs(a[k] - b[k]));
  }
  printf("self-shadowed: the sun moved while paused changed the frame by up to %.3f; it "
         "differs from a pipeline born with that sun by %.3g\n", changed, differs);
  CHECK(changed > 0.05, "the paused frame was not relit (%.3e)", changed);
  CHECK(differs == 0, "relit frame != a pipeline created with the new sun (%.3e)", differs);
  pipeline_destroy(moved);
  pipeline_destroy(born);
}

int main(void) {
  scene_config cfg;
  camera cam;
  gl_context *gl = pipeline_check_begin("configs/default.ini", &cfg, &cam);
  if (!gl) return 1;
  const scene_config shadowed = cfg;
  cfg.shadow.fog_self_shadow = 0, cfg.shadow.shafts = 0;
  pipeline_error perr = {{0}};
  const pipeline_desc desc = {.config = &cfg, .width = W, .height = H, .synchronous = true};
  pipeline *moved = pipeline_create(&desc, &perr), *still = pipeline_create(&desc, &perr);
  CHECK(moved && still, "pipeline_create: %s", perr.message);
  if (!moved || !still) return test_finish("pipeline_sun_check");
  static float rgba_moved[4 * W * H], rgba_still[4 * W * H], tau[W * H], inscatter[3 * W * H];
  CHECK(!frame(moved, &cam, rgba_moved, tau, inscatter) &&
            !frame(still, &cam, rgba_still, tau, inscatter),
        "first frame failed");
  CHECK(!memcmp(rgba_moved, rgba_still, sizeof rgba_moved), "identical pipelines differ");

  pipeline_params params = pipeline_get_params(moved);
  const double azimuth = -70, elevation = 25;
  params.sun_azimuth = (float)azimuth, params.sun_elevation = (float)elevation;
  pipeline_set_params(moved, &params);
  CHECK(!frame(moved, &cam, rgba_moved, tau, inscatter) &&
            !frame(still, &cam, rgba_still, NULL, NULL),
        "second frame failed");
  const double az = azimuth * pi / 180, el = elevation * pi / 180;
  const double sun[3] = {cos(el) * sin(az), sin(el), -cos(el) * cos(az)};
  const double g = params.sun.phase_g, a = params.sun.albedo;
  double worst = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double o[3], d[3];
      camera_ray(&cam, px, py, W, H, o, d);
      const double mu = d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2];
      const double p = (1 - g * g) / (4 * pi * pow(1 + g * g - 2 * g * mu, 1.5));
      const int k = py * W + px;
      for (int c = 0; c < 3; c++) {
        const double want = (params.fog_colour[c] + a * params.sun.radiance[c] * p) * (1 - tau[k]);
        worst = fmax(worst, fabs(inscatter[3 * k + c] - want) / fmax(want, 1e-3));
      }
    }
  double relit = 0;
  for (int k = 0; k < 4 * W * H; k++) relit = fmax(relit, fabs(rgba_moved[k] - rgba_still[k]));
  printf("sun moved to azimuth %g, elevation %g: in-scatter vs the new sun, max relative "
         "error %.2e; surfaces changed by up to %.3f\n", azimuth, elevation, worst, relit);
  CHECK(a > 0, "configs/default.ini's fog is not lit (albedo %g)", a);
  CHECK(worst <= 1e-5, "the fog is not lit by the moved sun (%.3e)", worst);
  CHECK(relit > 0.05, "the terrain was not relit (%.3e)", relit);
  pipeline_destroy(moved);
  pipeline_destroy(still);
  check_relight(&shadowed, &cam);
  check_sun_colour(&shadowed, &cam);
  gl_context_destroy(gl);
  return test_finish("pipeline_sun_check");
}
