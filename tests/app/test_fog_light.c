/* Sunlight in the fog, unshadowed (render/fog_light.h, docs/light.md), for every model:
 * - [fog] albedo = 0 draws Giroud & Biri's eq. 4: rgb = tau S + L_amb (1 - tau), S the
 *   scene drawn without fog, whatever the sun and phase_g (bit for bit between them);
 * - with albedo a > 0 the in-scatter channel is (L_amb + a L_sun p(theta)) (1 - tau) per
 *   pixel (the identity int tau K du = 1 - tau), p Henyey-Greenstein written here from
 *   its definition, theta between the sun and the pixel's ray, within 1e-5 relative; and
 *   rgb = tau S + in-scatter;
 * - energy: with a = 1 and no ambient no pixel gets more than L_sun max p (1 - tau);
 * - p integrates to 1 over the sphere (adaptive Simpson in double);
 * - a sun below the horizon (elevation -5) lights nothing: the frame equals the frame with
 *   a black sun, bit for bit, fog, surfaces and sky; with its centre on the horizon half
 *   its disc shows, and the fog gets (L_amb + a L_sun p / 2)(1 - tau);
 * - `fogpipe render` writes the in-scatter as inscatter.R/G/B and the camera-space depth as Z, and
 *   the camera as the standard worldToCamera and worldToNDC attributes: each pixel's
 *   surface point (the CPU camera ray at the depth) maps to that pixel's centre in NDC and
 *   lies at that depth from the camera; `record` writes the same matrices. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/config.h"
#include "app/render_frame.h"
#include "exr_channel_util.h"
#include "render/render.h"
#include "test_bin.h"
#include "test_util.h"

enum { W = 80, H = 45 };
static const double pi = 3.14159265358979323846;

/* Henyey & Greenstein 1941, per steradian. */
static double hg(double g, double mu) {
  return (1 - g * g) / (4 * pi * pow(1 + g * g - 2 * g * mu, 1.5));
}

static double simpson(double g, double a, double b, double fa, double fm, double fb,
                      double whole, int depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = hg(g, lm), frm = hg(g, rm);
  const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
  if (depth <= 0 || fabs(left + right - whole) < 1e-13) return left + right;
  return simpson(g, a, m, fa, flm, fm, left, depth - 1) +
         simpson(g, m, b, fm, frm, fb, right, depth - 1);
}

static void check_phase_normalised(void) {
  const double gs[] = {-0.9, 0.0, 0.5, 0.7, 0.95};
  for (size_t i = 0; i < sizeof gs / sizeof gs[0]; i++) {
    const double g = gs[i];
    const double fa = hg(g, -1), fm = hg(g, 0), fb = hg(g, 1);
    const double total = 2 * pi * simpson(g, -1, 1, fa, fm, fb, 2.0 / 6 * (fa + 4 * fm + fb), 40);
    CHECK(fabs(total - 1) < 1e-9, "HG g=%g integrates to %.12f over the sphere", g, total);
    for (double mu = -1; mu <= 1; mu += 0.125)
      CHECK(fabs(fog_phase_hg(g, mu) - hg(g, mu)) <= 1e-14 * hg(g, mu),
            "fog_phase_hg(%g, %g) = %.17g, expected %.17g", g, mu, fog_phase_hg(g, mu), hg(g, mu));
  }
}

#include "frame_util.h"

/* p(theta) of pixel (px, py)'s ray and the sun, g given. */
static double pixel_phase(const camera *cam, int px, int py, const fog_sun *sun, double g) {
  double o[3], d[3];
  camera_ray(cam, px, py, W, H, o, d);
  return hg(g, d[0] * sun->direction[0] + d[1] * sun->direction[1] + d[2] * sun->direction[2]);
}

/* S: the same scene and light without fog. */
static int render_surface(const scene_config *cfg, frame *f, const char *label) {
  scene_config bare = *cfg;
  bare.fog.model = FOG_MODEL_FOGMAP;
  bare.fog.fogmap[0] = bare.fog.vdb[0] = bare.fog.sequence[0] = '\0';
  bare.fog.quadric_count = 0; /* quadric volumes are fog beside any model */
  return render(&bare, f, label);
}

static void check_model(const char *path, const char *label) {
  static frame lit, unlit, moved, surface;
  scene_config cfg;
  fog_error cerr;
  if (scene_config_load(path, &cfg, &cerr)) {
    CHECK(0, "%s: %s", label, cerr.message);
    return;
  }
  cfg.fog.albedo = 0.0;
  if (render_surface(&cfg, &surface, label) || render(&cfg, &unlit, label)) return;
  /* albedo 0: g changes nothing; the sun changes the surfaces but not the fog's light */
  scene_config other = cfg;
  other.fog.phase_g = -0.5;
  if (render(&other, &moved, label)) return;
  CHECK(!memcmp(unlit.rgba, moved.rgba, sizeof unlit.rgba),
        "%s: albedo 0 depends on phase_g", label);
  other.light.sun_azimuth += 120, other.light.sun_elevation = 10;
  if (render(&other, &moved, label)) return;
  CHECK(!memcmp(unlit.inscatter, moved.inscatter, sizeof unlit.inscatter),
        "%s: albedo 0's in-scatter depends on the sun", label);

  double eq4 = 0, min_tau = 1;
  const float *amb = cfg.fog.colour;
  for (int k = 0; k < W * H; k++) {
    const double t = unlit.tau[k];
    min_tau = fmin(min_tau, t);
    for (int c = 0; c < 3; c++) {
      const double want = t * surface.rgba[4 * k + c] + amb[c] * (1 - t);
      eq4 = fmax(eq4, fabs(unlit.rgba[4 * k + c] - want));
      eq4 = fmax(eq4, fabs(unlit.inscatter[3 * k + c] - amb[c] * (1 - t)));
    }
  }
  printf("%s: albedo 0: max |rgb - eq. 4| %.2e (min tau %.3f)\n", label, eq4, min_tau);
  CHECK(eq4 <= 2e-6, "%s: albedo 0 differs from eq. 4 by %.3e", label, eq4);
  CHECK(min_tau < 0.8, "%s: min tau %.3f: too little fog in view to test", label, min_tau);

  /* lit: a = 0.8, g = 0.6, a low sun ahead of the camera (the forward peak in view) */
  camera cam;
  scene_config_camera(&cfg, &cam);
  double o[3], ahead[3];
  camera_ray(&cam, W / 2, H / 2, W, H, o, ahead);
  cfg.fog.albedo = 0.8, cfg.fog.phase_g = 0.6;
  /* The unshadowed identity: T_s = V = 1 ([light] fog_self_shadow = shafts = off; the
   * shadowed in-scatter is test_fog_shadow's). The albedo 0 checks above ran with both on:
   * albedo 0 is eq. 4 whatever the shadow settings. */
  cfg.shadow.fog_self_shadow = 0, cfg.shadow.shafts = 0;
  cfg.light.sun_azimuth = atan2(ahead[0], -ahead[2]) * 180 / pi;
  cfg.light.sun_elevation = 12;
  if (render_surface(&cfg, &surface, label) || render(&cfg, &lit, label)) return;
  const fog_sun sun = scene_config_fog_sun(&cfg);
  double identity = 0, blend = 0, sun_share = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      const int k = py * W + px;
      const double p = pixel_phase(&cam, px, py, &sun, 0.6);
      const double t = lit.tau[k];
      for (int c = 0; c < 3; c++) {
        const double want = (amb[c] + 0.8 * sun.radiance[c] * p) * (1 - t);
        const double got = lit.inscatter[3 * k + c];
        identity = fmax(identity, fabs(got - want) / fmax(want, 1e-3));
        blend = fmax(blend, fabs(lit.rgba[4 * k + c] - (t * surface.rgba[4 * k + c] + got)));
        sun_share = fmax(sun_share, got - amb[c] * (1 - t));
      }
    }
  printf("%s: lit: max relative |in-scatter - (L_amb + a L_sun p)(1 - tau)| %.2e, "
         "|rgb - (tau S + in-scatter)| %.2e, the sun's largest share %.3f\n",
         label, identity, blend, sun_share);
  CHECK(identity <= 1e-5, "%s: the lit identity fails by %.3e relative", label, identity);
  CHECK(blend <= 1e-5, "%s: rgb != tau S + in-scatter by %.3e", label, blend);
  CHECK(sun_share > 0.05, "%s: the sun adds at most %.3f", label, sun_share);

  /* energy: a = 1, no ambient */
  cfg.fog.albedo = 1.0;
  cfg.fog.colour[0] = cfg.fog.colour[1] = cfg.fog.colour[2] = 0.0f;
  if (render(&cfg, &lit, label)) return;
  const double max_p = (1 + 0.6) / (4 * pi * (1 - 0.6) * (1 - 0.6));
  double excess = 0;
  for (int k = 0; k < W * H; k++)
    for (int c = 0; c < 3; c++)
      excess = fmax(excess, lit.inscatter[3 * k + c] -
                                sun.radiance[c] * max_p * (1 - lit.tau[k]) * (1 + 1e-6));
  CHECK(excess <= 0, "%s: a pixel gets %.3e more than the sun can give", label, excess);

  /* below the horizon: the frame of a black sun, bit for bit */
  static frame dark;
  cfg.fog.albedo = 0.8, cfg.fog.colour[0] = amb[0];
  cfg.light.sun_elevation = -5;
  scene_config black = cfg;
  black.light.sun_colour[0] = black.light.sun_colour[1] = black.light.sun_colour[2] = 0.0f;
  if (render(&cfg, &lit, label) || render(&black, &dark, label)) return;
  CHECK(!memcmp(lit.rgba, dark.rgba, sizeof lit.rgba) &&
            !memcmp(lit.inscatter, dark.inscatter, sizeof lit.inscatter),
        "%s: a sun 5 degrees below the horizon still lights the frame", label);
  /* its centre on the horizon: half the disc, half the fog's sunlight */
  cfg.light.sun_elevation = 0;
  cfg.fog.colour[0] = cfg.fog.colour[1] = cfg.fog.colour[2] = 0.0f;
  if (render(&cfg, &lit, label)) return;
  const fog_sun level = scene_config_fog_sun(&cfg);
  double half = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      const int k = py * W + px;
      const double p = pixel_phase(&cam, px, py, &level, 0.6);
      for (int c = 0; c < 3; c++) {
        const double want = 0.8 * level.radiance[c] * p / 2 * (1 - lit.tau[k]);
        half = fmax(half, fabs(lit.inscatter[3 * k + c] - want) / fmax(want, 1e-3));
      }
    }
  printf("%s: the sun on the horizon: max relative |in-scatter - a L_sun p (1 - tau) / 2| "
         "%.2e\n", label, half);
  CHECK(half <= 1e-5, "%s: a sun on the horizon is off half its light by %.3e", label, half);
}

/* p' = p M for the row vector p = (x, y, z, 1), M row-major (EXR's convention). */
static void row_times(const double p[3], const float m[16], double out[4]) {
  for (int j = 0; j < 4; j++)
    out[j] = p[0] * m[j] + p[1] * m[4 + j] + p[2] * m[8 + j] + m[12 + j];
}

static void check_camera_matrices(const char *exr, const scene_config *cfg, const float *depth,
                                  const float *z) {
  float to_camera[16], to_ndc[16];
  fog_error err;
  if (image_read_exr_matrix(exr, "worldToCamera", to_camera, &err) ||
      image_read_exr_matrix(exr, "worldToNDC", to_ndc, &err)) {
    CHECK(0, "%s", err.message);
    return;
  }
  camera cam;
  scene_config_camera(cfg, &cam);
  double worst_ndc = 0, worst_distance = 0, worst_z = 0;
  int checked = 0;
  for (int py = 0; py < H; py += 3)
    for (int px = 0; px < W; px += 3) {
      const double d = depth[py * W + px];
      if (d >= cam.far_plane) continue;  /* the sky */
      double o[3], dir[3], p[3], c[4], n[4];
      camera_ray(&cam, px, py, W, H, o, dir);
      for (int a = 0; a < 3; a++) p[a] = o[a] + d * dir[a];
      row_times(p, to_camera, c);
      row_times(p, to_ndc, n);
      /* OpenEXR's NDC (ImfStandardAttributes): (0, 0) the upper left corner of the image,
       * (1, 1) the lower right, y down */
      const double nx = (px + 0.5) / W, ny = (py + 0.5) / H;
      worst_ndc = fmax(worst_ndc, fmax(fabs(n[0] / n[3] - nx), fabs(n[1] / n[3] - ny)));
      worst_distance = fmax(worst_distance,
                            fabs(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) - d) / d);
      /* its camera space is RenderMan's: left-handed, in front at z > 0; Z is that z */
      CHECK(c[2] > 0, "pixel (%d, %d): camera-space z %.3f, not in front (+Z)", px, py, c[2]);
      worst_z = fmax(worst_z, fabs(z[py * W + px] - c[2]) / c[2]);
      checked++;
    }
  for (int k = 0; k < W * H; k++)
    if (depth[k] >= cam.far_plane)
      CHECK(z[k] == (float)cam.far_plane, "the sky's Z %g: expected the far plane %g",
            (double)z[k], cam.far_plane);
  printf("camera matrices: %d surface points: max |NDC - pixel centre| %.2e, max relative "
         "|distance - depth| %.2e, |Z - camera z| %.2e\n", checked, worst_ndc, worst_distance,
         worst_z);
  CHECK(checked > 100, "only %d surface pixels", checked);
  CHECK(worst_ndc < 1e-4 && worst_distance < 1e-5 && worst_z < 1e-5,
        "camera matrices off: %.3e NDC, %.3e depth, %.3e Z", worst_ndc, worst_distance, worst_z);
}

static void check_exr_channels(void) {
  char dir[] = "/tmp/fogpipe_light_XXXXXX";
  const char *bin = test_bin_and_folder(dir);
  if (!bin) return;
  char ini[256], exr[256], cmd[1024];
  snprintf(ini, sizeof ini, "%s/lit.ini", dir);
  snprintf(exr, sizeof exr, "%s/lit.exr", dir);
  FILE *f = fopen(ini, "w");
  fputs("[camera]\nposition = 0 60 300\nlook_at = 0 20 -100\n"
        "[terrain]\nresolution = 65\n[light]\nsun_elevation = 15\n"
        "[fog]\nmodel = homogeneous\ndensity_scale = 0.004\nalbedo = 0.9\nphase_g = 0.5\n", f);
  fclose(f);
  snprintf(cmd, sizeof cmd, "%s render %s --size %dx%d --out %s > /dev/null", bin, ini, W,
           H, exr);
  CHECK(system(cmd) == 0, "%s failed", cmd);
  scene_config cfg;
  fog_error cerr;
  static frame want;
  if (scene_config_load(ini, &cfg, &cerr) == 0 && render(&cfg, &want, "exr") == 0) {
    const char *names[3] = {"inscatter.R", "inscatter.G", "inscatter.B"};
    for (int c = 0; c < 3; c++) {
      float *v = load_exr_channel(exr, names[c], W, H);
      double worst = 0;
      for (int k = 0; v && k < W * H; k++)
        worst = fmax(worst, fabs(v[k] - want.inscatter[3 * k + c]));
      CHECK(v && worst == 0, "%s: %s differs from render_frame by %.3e", exr, names[c], worst);
      free(v);
    }
    float *z = load_exr_channel(exr, "Z", W, H), *depth = load_exr_channel(exr, "depth", W, H);
    CHECK(z && depth && !memcmp(depth, want.depth, sizeof(float) * W * H),
          "%s: depth differs from render_frame's", exr);
    if (z) check_camera_matrices(exr, &cfg, want.depth, z);
    free(z), free(depth);
  }
  /* record writes the same camera */
  char seq[300], frame1[400];
  snprintf(seq, sizeof seq, "%s/seq", dir);
  snprintf(frame1, sizeof frame1, "%s/frame.0001.exr", seq);
  snprintf(cmd, sizeof cmd, "%s record %s --frames 1 --size %dx%d --out %s > /dev/null", bin, ini,
           W, H, seq);
  CHECK(system(cmd) == 0, "%s failed", cmd);
  float a[16], b[16];
  fog_error err;
  for (int k = 0; k < 2; k++) {
    const char *name = k ? "worldToNDC" : "worldToCamera";
    CHECK(image_read_exr_matrix(exr, name, a, &err) == 0 &&
              image_read_exr_matrix(frame1, name, b, &err) == 0 && !memcmp(a, b, sizeof a),
          "record's %s differs from render's", name);
  }
  unlink(frame1), rmdir(seq);
  unlink(exr), unlink(ini), rmdir(dir);
}

int main(void) {
  check_phase_normalised();
  check_model("configs/default.ini", "fogmap (configs/default.ini)");
  check_model("configs/rbf_fog_banks.ini", "rbf (configs/rbf_fog_banks.ini)");
  check_model("configs/vdb_plume_volume.ini", "volume (configs/vdb_plume_volume.ini)");
  check_model("configs/quadric_volumes.ini", "quadric (configs/quadric_volumes.ini)");
  char dir[] = "/tmp/fogpipe_light_models_XXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  static const char *const fogs[2][2] = {
      {"homogeneous", "[fog]\nmodel = homogeneous\ndensity_scale = 0.003\n"},
      {"height", "[fog]\nmodel = height\ndensity_scale = 0.02\nfog_height = 30\nscale_height = 25\n"}};
  for (int m = 0; m < 2; m++) {
    char path[256];
    snprintf(path, sizeof path, "%s/%s.ini", dir, fogs[m][0]);
    FILE *f = fopen(path, "w");
    fprintf(f, "[camera]\nposition = 0 120 400\nlook_at = 0 20 -100\n[terrain]\nresolution = 65\n%s",
            fogs[m][1]);
    fclose(f);
    check_model(path, fogs[m][0]);
    unlink(path);
  }
  rmdir(dir);
  check_exr_channels();
  return test_finish("test_fog_light");
}
