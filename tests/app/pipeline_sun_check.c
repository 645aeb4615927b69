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
 * that sun_colour: the terrain, the sky and the fog all take it; and so does a lamp placed
 * through the params (the demo's lamp tool), on the surfaces and in the fog. Built by
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

/* A change made through the params while paused (what the panel does) against a pipeline
 * created with a config that has it from the start: the paused frame changes, and equals
 * that pipeline's bit for bit. */
static void check_paused_change(const scene_config *cfg, const scene_config *born_cfg,
                                const camera *cam,
                                void (*change)(pipeline_params *), const char *what) {
  fog_error perr = {0};
  pipeline_desc desc = {.config = cfg, .width = W, .height = H, .frame_seconds = 1.0 / 24.0,
                        .synchronous = true};
  pipeline *changed_p = pipeline_create(&desc, &perr);
  desc.config = born_cfg;
  pipeline *born = pipeline_create(&desc, &perr);
  CHECK(changed_p && born, "pipeline_create: %s", perr.message);
  if (changed_p && born) {
    static float a[4 * W * H], b[4 * W * H], before[4 * W * H];
    CHECK(!frame(changed_p, cam, before, NULL, NULL), "first frame failed");
    pipeline_params params = pipeline_get_params(changed_p);
    params.paused = true;
    change(&params);
    pipeline_set_params(changed_p, &params);
    CHECK(!frame(changed_p, cam, a, NULL, NULL) && !frame(born, cam, b, NULL, NULL),
          "frames failed");
    double changed = 0, differs = 0;
    for (int k = 0; k < 4 * W * H; k++) {
      changed = fmax(changed, fabs(a[k] - before[k]));
      differs = fmax(differs, fabs(a[k] - b[k]));
    }
    printf("%s while paused: the frame changed by up to %.3f; it differs from a pipeline born "
           "with it by %.3g\n", what, changed, differs);
    CHECK(changed > 0.05, "%s: the paused frame did not change (%.3e)", what, changed);
    CHECK(differs == 0, "%s: the frame != a pipeline created with it (%.3e)", what, differs);
  }
  if (changed_p) pipeline_destroy(changed_p);
  if (born) pipeline_destroy(born);
}

static const float new_colour[3] = {0.5f, 1.25f, 2.5f};
static void set_colour(pipeline_params *p) {
  for (int c = 0; c < 3; c++) p->sun.radiance[c] = pi * new_colour[c];
}
static void move_sun(pipeline_params *p) { p->sun_azimuth = -70, p->sun_elevation = 25; }
/* a lamp placed (what the demo's lamp tool does): in the fog and on the surfaces */
static const double lamp_at[3] = {20.0, 60.0, -40.0}, lamp_colour[3] = {900, 700, 500};
static void place_lamp(pipeline_params *p) {
  p->lamps.count = 1;
  p->lamps.lamp[0] = (fog_lamp){.kind = FOG_LAMP_POINT, .radius = 0.5,
                                .position = {lamp_at[0], lamp_at[1], lamp_at[2]},
                                .intensity = {lamp_colour[0], lamp_colour[1], lamp_colour[2]}};
}

/* The sun's colour (the panel's hue and strength) and, self-shadowed, the sun moved (the
 * relight path): each against a pipeline whose config has it from the start. */
static void check_paused_changes(const scene_config *cfg, const camera *cam) {
  CHECK(cfg->shadow.fog_self_shadow == 1 && cfg->fog.albedo > 0,
        "configs/default.ini: expected the fog's self-shadow on by default");
  scene_config moved_cfg = *cfg, tinted_cfg = *cfg, lamp_cfg = *cfg;
  lamp_cfg.lamp_count = 1;
  lamp_cfg.lamps[0] = (scene_lamp_config){.radius = 0.5};
  for (int a = 0; a < 3; a++)
    lamp_cfg.lamps[0].position[a] = lamp_at[a], lamp_cfg.lamps[0].colour[a] = lamp_colour[a];
  moved_cfg.light.sun_azimuth = -70, moved_cfg.light.sun_elevation = 25;
  for (int c = 0; c < 3; c++) tinted_cfg.light.sun_colour[c] = new_colour[c];
  check_paused_change(cfg, &moved_cfg, cam, move_sun, "self-shadowed: the sun moved");
  check_paused_change(cfg, &tinted_cfg, cam, set_colour,
                      "the sun colour set to (0.5, 1.25, 2.5)");
  check_paused_change(cfg, &lamp_cfg, cam, place_lamp, "a lamp placed");
}

int main(void) {
  scene_config cfg;
  camera cam;
  gl_context *gl = pipeline_check_begin("configs/default.ini", &cfg, &cam);
  if (!gl) return 1;
  const scene_config shadowed = cfg;
  cfg.shadow.fog_self_shadow = 0, cfg.shadow.shafts = 0;
  fog_error perr = {0};
  const pipeline_desc desc = {.config = &cfg, .width = W, .height = H,
                              .frame_seconds = 1.0 / 24.0, .synchronous = true};
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
  check_paused_changes(&shadowed, &cam);
  gl_context_destroy(gl);
  return test_finish("pipeline_sun_check");
}
