/* A lamp's shafts in the fog (render/lamp_shadow_map.h, fog_lamps.glsl; docs/light.md,
 * Lamps): a lamp behind a wall with a slit, in homogeneous fog (tau and T in closed form,
 * so V is what is tested), through `fogpipe render`'s frame path.
 * - GL with the shadow cubes against the CPU twin (fog_lamps_inscatter_shadowed) with V by
 *   exact ray casts to the lamp: the cube's texels and PCF blur each shadow's edge, so the
 *   mean error and the share of pixels off by more than 1e-2 of the largest in-scatter are
 *   bounded, not the max;
 * - the wall takes light: without the cubes the in-scatter is far larger beside the shaft
 *   (the wall's shadow);
 * - the twin's integral (Gauss nodes on pieces cut at V's edges, FOG_LAMP_EDGE_BISECTIONS)
 *   against the independent reference with the same V (tests/render/lamp_reference.h: V's
 *   jumps found by its own sampling and made breaks, adaptive quadrature between), on rays
 *   across the shaft: printed and bounded (without the cuts 7.8e-3 of the peak);
 * - the same at half resolution (the live demo's fog: the cubes in the reduced pass, the
 *   halo's core and the shadow edges upsampled), with looser bounds;
 * - a spot and a point lamp on the same wall: cube i serves lamp i. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/config.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "render/lamp_reference.h"
#include "render/render.h"
#include "test_util.h"

enum { W = 96, H = 64 };

static const char *const scene_text =
    "[camera]\nposition = 30 12 45\nlook_at = 0 6 -2\nfov = 55\n"
    "[terrain]\norigin = -200 0 -200\nsize = 400 400\nheight = 0.001\nresolution = 33\n"
    "[objects]\nbox = -9 0 14 20 2\nbox = 9 0 14 20 2\n"
    "[light]\nsun_colour = 0 0 0\nambient = 0 0 0\nshafts = off\nfog_self_shadow = off\n"
    "lamp = 0 8 -12 4000 4000 4000\n%s"
    "[fog]\nmodel = homogeneous\ndensity_scale = 0.02\ncolour = 0 0 0\nalbedo = 0.9\n"
    "phase_g = 0.3\n";

#include "frame_util.h"

static int load(const char *extra, scene_config *cfg) {
  char path[] = "/tmp/fogpipe_lamp_shafts_XXXXXX";
  int fd = mkstemp(path);
  if (fd < 0) return 1;
  FILE *f = fdopen(fd, "w");
  fprintf(f, scene_text, extra);
  fclose(f);
  fog_error cerr;
  int failed = scene_config_load(path, cfg, &cerr);
  CHECK(!failed, "%s", cerr.message);
  unlink(path);
  return failed;
}

/* V by an exact ray cast from x to the lamp against the terrain and boxes. */
typedef struct exact_lamps {
  const scene_geometry *geo;
  const fog_lamps *lamps;
} exact_lamps;

static bool segment_clear(const scene_geometry *geo, const double x[3], const double lamp[3]) {
  double w[3], dist = 0, s;
  for (int a = 0; a < 3; a++) w[a] = lamp[a] - x[a], dist += w[a] * w[a];
  dist = sqrt(dist);
  if (!(dist > 0)) return true;
  for (int a = 0; a < 3; a++) w[a] /= dist;
  return !scene_geometry_intersect(geo, x, w, dist, &s, NULL);
}

static double exact_visible(const void *user, int lamp, const double x[3]) {
  const exact_lamps *e = user;
  return segment_clear(e->geo, x, e->lamps->lamp[lamp].position) ? 1.0 : 0.0;
}

static bool reference_visible(const void *user, const double x[3], const double lamp[3]) {
  return segment_clear(user, x, lamp);
}

static double homogeneous(const void *user, const double p[3]) {
  (void)p;
  return *(const double *)user;
}

/* GL (shadows on) against the twin with exact V; returns the largest in-scatter. */
static double check_against_twin(const scene_config *cfg, const frame *lit, const char *label,
                                 double *twin_out, double mean_bound, int off_share) {
  scene_geometry geo;
  fog_error rerr = {0};
  CHECK(!render_scene_geometry_create(&geo, cfg, &rerr), "%s", rerr.message);
  const fog_lamps lamps = scene_config_fog_lamps(cfg);
  const exact_lamps exact = {&geo, &lamps};
  const fog_model model = {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = cfg->fog.density_scale};
  camera cam;
  scene_config_camera(cfg, &cam);
  double peak = 0, sum = 0, worst = 0;
  int off_pixels = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      const int k = py * W + px;
      double o[3], d[3], want[3];
      double t_surface = frame_pixel_ray(lit, &cam, px, py, o, d);
      fog_lamps_inscatter_shadowed(&model, &lamps, cfg->fog.albedo, cfg->fog.phase_g, o, d,
                                   t_surface, exact_visible, &exact, want);
      for (int c = 0; c < 3; c++) twin_out[3 * k + c] = want[c], peak = fmax(peak, want[c]);
    }
  for (int k = 0; k < W * H; k++) {
    double e = 0;
    for (int c = 0; c < 3; c++) e = fmax(e, fabs(lit->inscatter[3 * k + c] - twin_out[3 * k + c]));
    worst = fmax(worst, e / peak);
    sum += e / peak;
    off_pixels += e > 1e-2 * peak;
  }
  printf("%s: GL (shadow cubes) vs the twin with exact ray casts: max %.3e, mean %.3e of the "
         "largest in-scatter %.3e; %d of %d pixels off by > 1e-2\n", label, worst,
         sum / (W * H), peak, off_pixels, W * H);
  CHECK(sum / (W * H) < mean_bound, "%s: mean error %.3e", label, sum / (W * H));
  CHECK(off_pixels * off_share < W * H, "%s: %d pixels off by > 1e-2", label, off_pixels);
  scene_geometry_destroy(&geo);
  return peak;
}

int main(void) {
  static frame lit, unshadowed;
  static double twin[3 * W * H];
  scene_config cfg, off;
  if (load("", &cfg) || load("lamp_shadows = off\n", &off)) return test_finish("test_lamp_shafts");
  CHECK(cfg.shadow.lamp_shadows == 1 && off.shadow.lamp_shadows == 0,
        "[light] lamp_shadows: expected on by default");
  if (render(&cfg, &lit, "lamp shadows on") || render(&off, &unshadowed, "lamp shadows off"))
    return test_finish("test_lamp_shafts");
  const double peak = check_against_twin(&cfg, &lit, "point lamp behind a slit", twin, 5e-4, 200);

  /* the wall's shadow: light the cubes take away */
  double taken = 0;
  for (int k = 0; k < W * H; k++) taken = fmax(taken, unshadowed.inscatter[3 * k] - lit.inscatter[3 * k]);
  printf("the wall takes up to %.3f of the largest in-scatter\n", taken / peak);
  CHECK(taken > 0.3 * peak, "no shadow of the wall in the fog (%.3e)", taken / peak);

  /* the twin's integral against the reference with the same V, across the shaft */
  {
    scene_geometry geo;
    fog_error rerr = {0};
    CHECK(!render_scene_geometry_create(&geo, &cfg, &rerr), "%s", rerr.message);
    const fog_lamps lamps = scene_config_fog_lamps(&cfg);
    const fog_lamp *l = &lamps.lamp[0];
    const double k = cfg.fog.density_scale;
    const lamp_ref_medium medium = {
        .extinction = homogeneous, .user = &k, .albedo = cfg.fog.albedo,
        .phase_g = cfg.fog.phase_g, .tolerance = 1e-9, .visible = reference_visible,
        .visible_user = &geo};
    const lamp_ref_lamp rl = {.position = {l->position[0], l->position[1], l->position[2]},
                              .intensity = l->intensity[0], .radius = l->radius};
    camera cam;
    scene_config_camera(&cfg, &cam);
    lamp_ref_medium unshadowed_medium = medium;
    unshadowed_medium.visible = NULL;
    double worst = 0, shadowed = 0;
    int rays = 0;
    const int py = H / 2;
    for (int px = 0; px < W; px += 3) {
      const int idx = py * W + px;
      double o[3], d[3];
      camera_ray(&cam, px, py, W, H, o, d);
      double t_end = lit.depth[idx] >= 0.999 * cam.far_plane ? 400.0 : lit.depth[idx];
      lamp_ref_info info;
      double ref = lamp_ref_inscatter_ex(&medium, &rl, o, d, t_end, &info);
      CHECK(info.converged, "reference did not converge at pixel %d", px);
      worst = fmax(worst, fabs(twin[3 * idx] - ref) / peak);
      shadowed = fmax(shadowed, lamp_ref_inscatter(&unshadowed_medium, &rl, o, d, t_end) - ref);
      rays++;
    }
    printf("the twin's integral vs the reference with the same V on %d rays across the shaft: "
           "max %.3e of the largest in-scatter (V takes up to %.3f there)\n", rays, worst,
           shadowed / peak);
    CHECK(shadowed > 0.2 * peak, "the reference's V takes only %.3e", shadowed / peak);
    CHECK(worst < 1e-4, "the twin's shafted integral is off the reference by %.3e", worst);
    scene_geometry_destroy(&geo);
  }

  /* the live demo's setting: the fog at half resolution, the cubes in its reduced pass */
  {
    fog_error ferr = {0};
    render_session *session = render_session_create(&cfg, W, H, &ferr);
    CHECK(session != NULL, "session: %s", ferr.message);
    if (session) {
      render_session_fog(session)->params.resolution_divisor = 2;
      const frame_pixels out = {.rgba = lit.rgba, .transmittance = lit.tau, .depth = lit.depth,
                                .inscatter = lit.inscatter};
      CHECK(render_session_frame(session, &out, &ferr) == 0, "half resolution: %s", ferr.message);
      check_against_twin(&cfg, &lit, "at half resolution (the live setting)", twin, 1.5e-3, 100);
      render_session_destroy(session);
    }
  }

  /* a spot and a point lamp: each reads its own cube */
  scene_config two;
  if (!load("spot = 6 14 -20 20000 20000 20000 -0.3 -0.4 1 12 20\n", &two) &&
      !render(&two, &lit, "a spot and a point lamp"))
    check_against_twin(&two, &lit, "a spot and a point lamp", twin, 5e-4, 200);
  return test_finish("test_lamp_shafts");
}
