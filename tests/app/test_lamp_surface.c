/* Lamp light on the surfaces crosses the fog between the lamp and the surface (Fogshop §4;
 * render/shaders/fog_lamps.glsl, fog_lamps_surface): a flat ground lit by one lamp alone
 * (no sun, no sky light, black fog colour, albedo 0), in homogeneous fog of K = 0.02. Each
 * ground pixel is then tau(P) x T(lamp, P) x its unfogged colour, so against the same scene
 * without fog (K = 0) the ratio is exp(-K (t + |P - lamp|)), t the pixel's surface distance:
 * an analytic reference. Then two lamps of different colours, whose per-channel weights the
 * fog pass recovers from the scene pass's packed normal: each channel's ratio lies between
 * the two lamps' own transmittances (it is their weighted mean); two white lamps, each
 * channel the weighted mean itself, the weights cos / (d^2 + r^2). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/config.h"
#include "app/render_frame.h"
#include "test_util.h"

enum { W = 64, H = 48 };

static const char *const scene =
    "[camera]\nposition = 0 30 40\nlook_at = 0 0 0\nfov = 60\n"
    "[terrain]\norigin = -200 0 -200\nsize = 400 400\nheight = 0.001\nresolution = 33\n"
    "[light]\nsun_colour = 0 0 0\nambient = 0 0 0\nshafts = off\n%s"
    "[fog]\nmodel = homogeneous\ndensity_scale = %g\ncolour = 0 0 0\n";

/* Renders the scene with `lamps` lines and fog K: colour and depth. */
static int render(const char *dir, const char *lamps, double k, float *rgba, float *depth) {
  char path[256], text[1024];
  snprintf(path, sizeof path, "%s/lamp_surface.ini", dir);
  snprintf(text, sizeof text, scene, lamps, k);
  FILE *f = fopen(path, "w");
  if (!f) return 1;
  fputs(text, f);
  fclose(f);
  scene_config cfg;
  fog_error cerr;
  if (scene_config_load(path, &cfg, &cerr)) {
    CHECK(0, "%s", cerr.message);
    return 1;
  }
  render_frame_info info;
  fog_error err;
  int status = render_frame(&cfg, W, H, &(frame_pixels){.rgba = rgba, .depth = depth}, &info,
                            &err);
  CHECK(status == 0, "%s", err.message);
  unlink(path);
  return status;
}

int main(void) {
  char dir[] = "/tmp/fogpipe_lamp_surface_XXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  static float clear[4 * W * H], fogged[4 * W * H], depth[W * H];
  const double k = 0.02, lamp[3] = {5, 8, -3};
  camera cam = {.position = {0, 30, 40}, .fov_y = 60 * 3.14159265358979323846 / 180,
                .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
  camera_look_at(&cam, (double[3]){0, 0, 0});

  /* One white lamp. */
  if (render(dir, "lamp = 5 8 -3 4000 4000 4000 0.5\n", 0.0, clear, depth) ||
      render(dir, "lamp = 5 8 -3 4000 4000 4000 0.5\n", k, fogged, depth))
    return test_finish("test_lamp_surface");
  double worst = 0.0, dimmest = 1.0;
  int pixels = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      int i = py * W + px;
      if (!(clear[4 * i] > 0.02f) || depth[i] >= 1e5f) continue; /* lit ground only */
      double o[3], d[3], p[3];
      camera_ray(&cam, px, py, W, H, o, d);
      for (int a = 0; a < 3; a++) p[a] = o[a] + depth[i] * d[a];
      double to_lamp = sqrt(pow(lamp[0] - p[0], 2) + pow(lamp[1] - p[1], 2) +
                            pow(lamp[2] - p[2], 2));
      double want = exp(-k * (depth[i] + to_lamp)), got = fogged[4 * i] / clear[4 * i];
      /* the fog pass subtracts the lamps' share (1 - T) from the float colour: relative to
       * T x share its rounding grows as 1/T */
      worst = fmax(worst, fabs(got / want - 1.0) * exp(-k * to_lamp));
      dimmest = fmin(dimmest, exp(-k * to_lamp));
      pixels++;
    }
  printf("one lamp: %d lit ground pixels, fogged / clear against exp(-K (t + |P - lamp|)): "
         "worst relative error x T %.2e (the lamp's own T down to %.3f)\n", pixels, worst,
         dimmest);
  CHECK(pixels > 200, "only %d lit ground pixels", pixels);
  CHECK(worst < 1e-5, "relative error x T %.3e (float colours: measured 4e-7)", worst);

  /* The surface colour is linear in the lamp's intensity past half float's 65504 (the
   * scene pass's colour target once clipped a lamp-lit ground there): 1e5 x the lamp, 1e5 x
   * every lit pixel, to float precision. */
  static float bright[4 * W * H];
  if (render(dir, "lamp = 5 8 -3 4000 4000 4000 0.5\n", 0.0, clear, depth) ||
      render(dir, "lamp = 5 8 -3 4e8 4e8 4e8 0.5\n", 0.0, bright, depth))
    return test_finish("test_lamp_surface");
  double worst_scale = 0.0, brightest = 0.0;
  for (int i = 0; i < W * H; i++) {
    if (!(clear[4 * i] > 0.02f) || depth[i] >= 1e5f) continue;
    worst_scale = fmax(worst_scale, fabs(bright[4 * i] / (1e5 * clear[4 * i]) - 1.0));
    brightest = fmax(brightest, bright[4 * i]);
  }
  printf("a lamp 1e5 x brighter: every lit pixel 1e5 x brighter within %.2e (brightest %.3g)\n",
         worst_scale, brightest);
  CHECK(brightest > 65504.0 && worst_scale < 1e-5,
        "1e5 x the lamp: a lit pixel off 1e5 x by %.3e relative (brightest %.6g)", worst_scale,
        brightest);

  /* Two lamps, red near and blue far: per channel the weighted mean of their T. */
  const char *two = "lamp = 5 8 -3 4000 0 0 0.5\nlamp = -30 6 -20 0 0 40000 0.5\n";
  const double lamps[2][3] = {{5, 8, -3}, {-30, 6, -20}};
  if (render(dir, two, 0.0, clear, depth) || render(dir, two, k, fogged, depth))
    return test_finish("test_lamp_surface");
  int outside = 0, checked = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      int i = py * W + px;
      if (depth[i] >= 1e5f) continue;
      double o[3], d[3], p[3], t[2];
      camera_ray(&cam, px, py, W, H, o, d);
      for (int a = 0; a < 3; a++) p[a] = o[a] + depth[i] * d[a];
      for (int l = 0; l < 2; l++)
        t[l] = exp(-k * sqrt(pow(lamps[l][0] - p[0], 2) + pow(lamps[l][1] - p[1], 2) +
                             pow(lamps[l][2] - p[2], 2)));
      double tau = exp(-k * depth[i]);
      for (int c = 0; c < 3; c += 2) { /* red: lamp 0 alone; blue: lamp 1 alone */
        if (!(clear[4 * i + c] > 0.02f)) continue;
        double got = fogged[4 * i + c] / (tau * clear[4 * i + c]), want = t[c == 0 ? 0 : 1];
        checked++;
        if (fabs(got / want - 1.0) > 1e-5 + 1e-5 / want) outside++;
      }
    }
  printf("two coloured lamps: %d channel values, %d off their own lamp's T by more than "
         "1e-5 (1 + 1/T)\n",
         checked, outside);
  CHECK(checked > 200 && outside == 0, "%d of %d channel values off", outside, checked);

  /* Two white lamps, 10 x apart in intensity: every channel the weighted mean
   * sum I g T / sum I g, g = cos / (d^2 + r^2) on the flat ground (the coloured pair above
   * gives each channel one lamp, where any weights pass) */
  const char *white = "lamp = 5 8 -3 4000 4000 4000 0.5\nlamp = -30 6 -20 40000 40000 40000 0.5\n";
  const double intensity[2] = {4000.0, 40000.0}, r2 = 0.25;
  if (render(dir, white, 0.0, clear, depth) || render(dir, white, k, fogged, depth))
    return test_finish("test_lamp_surface");
  double worst_mean = 0.0, spread = 0.0;
  int means = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      int i = py * W + px;
      if (depth[i] >= 1e5f || !(clear[4 * i] > 0.02f)) continue;
      double o[3], d[3], p[3], weight = 0.0, weighted = 0.0, t[2];
      camera_ray(&cam, px, py, W, H, o, d);
      for (int a = 0; a < 3; a++) p[a] = o[a] + depth[i] * d[a];
      for (int l = 0; l < 2; l++) {
        const double to[3] = {lamps[l][0] - p[0], lamps[l][1] - p[1], lamps[l][2] - p[2]};
        const double d2 = to[0] * to[0] + to[1] * to[1] + to[2] * to[2];
        const double g = fmax(to[1] / sqrt(d2), 0.0) / (d2 + r2); /* the ground's normal: up */
        t[l] = exp(-k * sqrt(d2));
        weight += intensity[l] * g, weighted += intensity[l] * g * t[l];
      }
      const double want = weighted / weight, tau = exp(-k * depth[i]);
      spread = fmax(spread, fabs(t[0] - t[1]) / want);
      for (int c = 0; c < 3; c++) {
        const double got = fogged[4 * i + c] / (tau * clear[4 * i + c]);
        worst_mean = fmax(worst_mean, fabs(got / want - 1.0) / (1.0 + 1.0 / want));
        means++;
      }
    }
  printf("two white lamps: %d channel values, worst |T / (sum I g T / sum I g) - 1| / (1 + 1/T) "
         "%.2e (the lamps' T differ by up to %.2f of it)\n", means, worst_mean, spread);
  /* measured 4.5e-5: the ground is the terrain of height 0.001, whose bumps tilt its normal
   * ~1e-4 from up; a weight without its cosine or falloff is off by 10 % and more */
  CHECK(means > 600 && spread > 0.3 && worst_mean < 2e-4,
        "two white lamps: a channel off the weighted mean by %.3e (of %d; spread %.2f)",
        worst_mean, means, spread);
  rmdir(dir);
  return test_finish("test_lamp_surface");
}
