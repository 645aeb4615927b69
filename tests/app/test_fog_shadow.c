/* The fog's shadow on itself and on the ground (render/fog_sun_shadow.h, fog_light.glsl,
 * docs/light.md), rendered through `fogpipe render`'s frame path for every model:
 * - GL against its CPU twin in double (fog_sun_mean_transmittance over the same sun
 *   volume): in-scatter = (L_amb + a L_sun p(theta) mean) (1 - tau) per pixel, within
 *   FOG_SHADOW_GL_TOLERANCE relative (float shader vs double twin);
 * - the twin's method against the independent reference (tests/reference/
 *   fog_light_reference.h: adaptive quadrature along the view ray, T_s by nested adaptive
 *   quadrature towards the sun): |mean (1 - tau) - S_ref| printed, relative to 1 - tau,
 *   and bounded (height fog: the closed form T_s, so the error is the view-ray sampling's;
 *   the fogmap: the volume's interpolation too);
 * - the shadow darkens: self-shadowed in-scatter <= unshadowed, and somewhere clearly so;
 * - cases: the default fogmap from its camera, and from inside the ground fog (a valley
 *   floor) under a high sun, each by segments and per piece of its walk; the plume volume
 *   lit from the side; height fog; quadric volumes, alone and beside the fogmap;
 * - fog shadows on the ground: with the shadow on, surface pixels under fog lose
 *   tau (1 - T_s(P)) of their sun-lit share, S_sun = S - S(sun dimmed to nothing),
 *   T_s(P) from the twin. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "reference/fog_light_reference.h"
#include "render/render.h"
#include "test_util.h"

enum { W = 64, H = 36 };
static const double pi = 3.14159265358979323846;
#define FOG_SHADOW_GL_TOLERANCE 1e-5
/* The quadrics' pointwise K (alone or beside another model) is Q at a float position (t
 * dir, camera-relative): far from the camera its rounding moves Q by ~1e-5, a sizeable share
 * of K inside a soft edge, and the mean's samples see it (5.7e-5 measured with two nodes a
 * segment, on sky pixels past the hyperboloid; 1.7e-5 beside the fogmap). */
#define FOG_SHADOW_GL_TOLERANCE_QUADRIC 1e-4

#include "frame_util.h"

/* The same scene without fog; sunless: the sun dimmed to nothing (0 would mean default). */
static int render_surface(const scene_config *cfg, frame *f, bool sunless, const char *label) {
  scene_config bare = *cfg;
  bare.fog.model = FOG_MODEL_FOGMAP;
  bare.fog.fogmap[0] = bare.fog.vdb[0] = bare.fog.sequence[0] = '\0';
  bare.fog.quadric_count = 0; /* quadric volumes are fog beside any model */
  if (sunless) bare.light.sun_colour[0] = bare.light.sun_colour[1] = bare.light.sun_colour[2] = 0.0f;
  return render(&bare, f, label);
}

static double phase_hg(double g, double mu) {
  return (1 - g * g) / (4 * pi * pow(1 + g * g - 2 * g * mu, 1.5));
}

/* The scene's light: a low sun from the side of the view, so that lit and shadowed fog
 * are both in sight. */
static void light_up(scene_config *cfg) {
  cfg->fog.albedo = 0.9, cfg->fog.phase_g = 0.3;
  cfg->shadow.fog_self_shadow = 1;
  cfg->shadow.shafts = 0; /* V = 1 here: the shafts are check_shafts' */
}

/* V by an exact ray cast from p towards the sun against the terrain and boxes. */
typedef struct exact_sun {
  const scene_geometry *geo;
} exact_sun;
static double exact_visible(const void *user, const double p[3]) {
  const scene_geometry *geo = ((const exact_sun *)user)->geo;
  double s;
  return scene_geometry_intersect(geo, p, geo->sun_direction, INFINITY, &s, NULL) ? 0.0 : 1.0;
}

/* Light shafts: the default scene (a low sun ahead, the tower's and the hills' shadows in
 * the glow), GL with the shadow map against the twin with exact ray casts for V. The map's
 * texels (~0.7 units) and PCF blur each shadow's edge, so single pixels whose samples sit
 * on an edge differ by up to a sample's weight: bounded are the share of pixels off by more
 * than 1e-2 of the largest in-scatter and the mean error. */
/* The light shafts of configs/default.ini's scene: its fogmap (homogeneous: false), or a
 * homogeneous fog with the fog's self-shadow off, whose rays to the sky never end (the span
 * stops at an optical depth of FOG_LIGHT_SPAN_DEPTH: without that they had no shafts).
 * Or, with perlin, configs/perlin_fog.ini's hills' shadows in its fog, per piece of the
 * walk (V linear between the span's points). */
static void check_shafts(bool homogeneous, bool perlin) {
  static frame lit, unshafted;
  scene_config cfg;
  fog_error cerr;
  const char *path = perlin ? "configs/perlin_fog.ini" : "configs/default.ini";
  const char *name = perlin ? "perlin, per piece" : homogeneous ? "homogeneous" : "fogmap";
  if (scene_config_load(path, &cfg, &cerr)) {
    CHECK(0, "%s", cerr.message);
    return;
  }
  CHECK(cfg.shadow.shafts == 1, "[light] shafts: expected on by default");
  if (perlin) CHECK(scene_config_light_rule(&cfg).pieces, "perlin: not per piece by default");
  if (homogeneous) {
    cfg.fog.model = FOG_MODEL_HOMOGENEOUS, cfg.fog.density_scale = 0.002;
    cfg.shadow.fog_self_shadow = 0;
    cfg.light.sun_elevation = 4; /* a sun just over the hills: the valley's air in shadow */
  }
  scene_config off = cfg;
  off.shadow.shafts = 0;
  if (render(&cfg, &lit, "shafts") || render(&off, &unshafted, "shafts")) return;
  fog_error ferr = {0};
  render_session *session = render_session_create(&cfg, W, H, &ferr);
  CHECK(session, "%s", ferr.message);
  if (!session) return;
  render_fog *fog = render_session_fog(session);
  fog_model model = render_fog_model(fog);
  const fog_pass_params *params = &fog->params;
  scene_geometry geo;
  fog_error rerr = {0};
  CHECK(!render_scene_geometry_create(&geo, &cfg, &rerr), "%s", rerr.message);
  exact_sun exact = {&geo};
  camera cam;
  scene_config_camera(&cfg, &cam);
  const fog_sun *sun = &params->sun;
  double peak = 0, worst = 0, sum = 0, shafted = 0, shafted_sky = 0;
  int off_pixels = 0;
  static double want[3 * W * H];
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      const int k = py * W + px;
      double o[3], d[3];
      double t_surface = frame_pixel_ray(&lit, &cam, px, py, o, d);
      double mean = fog_sun_mean_light(&model, params->self_shadow, &fog->sun_shadow,
                                       fog_pass_light_rule(params),
                                       fog_pass_depth_limit(params->walk.transmittance_cutoff), o, d,
                                       t_surface, exact_visible, &exact);
      const double mu = d[0] * sun->direction[0] + d[1] * sun->direction[1] +
                        d[2] * sun->direction[2];
      const double p = phase_hg(sun->phase_g, mu), tau = lit.tau[k];
      for (int c = 0; c < 3; c++) {
        want[3 * k + c] =
            (params->fog_colour[c] + sun->albedo * sun->radiance[c] * p * mean) * (1 - tau);
        peak = fmax(peak, want[3 * k + c]);
        shafted = fmax(shafted, unshafted.inscatter[3 * k + c] - lit.inscatter[3 * k + c]);
        if (isinf(t_surface))
          shafted_sky = fmax(shafted_sky, unshafted.inscatter[3 * k + c] - lit.inscatter[3 * k + c]);
      }
    }
  for (int k = 0; k < W * H; k++) {
    double e = 0;
    for (int c = 0; c < 3; c++) e = fmax(e, fabs(lit.inscatter[3 * k + c] - want[3 * k + c]));
    worst = fmax(worst, e / peak);
    sum += e / peak;
    off_pixels += e > 1e-2 * peak;
  }
  printf("shafts (%s): the terrain's shadows take up to %.3f of the in-scatter; GL (shadow "
         "map) vs the twin with exact ray casts: max %.3e, mean %.3e of the largest "
         "in-scatter, %d of %d pixels off by > 1e-2\n", name, shafted, worst, sum / (W * H),
         off_pixels, W * H);
  printf("shafts (%s): towards the sky up to %.3f\n", name, shafted_sky);
  if (homogeneous) CHECK(shafted_sky > 0.01, "no shafts towards the sky (%.3e)", shafted_sky);
  CHECK(shafted > 0.02, "no shafts in view (%.3e)", shafted);
  /* Perlin fog's shafts are thick with the hills' shadow edges (the map's texels against
   * exact casts: measured mean 6.7e-4; with the shader's V at the pieces' nodes against
   * the twin's line, 1.05e-3). The fogmap and homogeneous fog: measured mean 3.6e-5 and
   * 8.9e-6, 2 and 0 pixels off (the bounds were 2e-3 and 46 pixels: 56x slack, room for a
   * shadow map's bias or texel offset along every edge). */
  const double mean_bound = perlin ? 8.5e-4 : 2e-4;
  const int off_bound = perlin ? 20 : 10;
  CHECK(sum / (W * H) < mean_bound, "shafts (%s): mean error %.3e", name, sum / (W * H));
  CHECK(off_pixels <= off_bound, "shafts (%s): %d pixels off by > 1e-2 (at most %d)", name,
        off_pixels, off_bound);
  scene_geometry_destroy(&geo);
  render_session_destroy(session);
}

typedef struct model_case {
  const char *label;
  scene_config cfg;
  bool reference;          /* compare with the reference (fogmap and height fog) */
  double reference_bound;  /* max |twin - reference| / (1 - tau) allowed */
} model_case;

static void check_case(model_case *mc) {
  static frame lit, flat, surface, sunless;
  scene_config *cfg = &mc->cfg;
  const char *label = mc->label;
  light_up(cfg);
  scene_config unshadowed = *cfg;
  unshadowed.shadow.fog_self_shadow = 0;
  if (render(cfg, &lit, label) || render(&unshadowed, &flat, label) ||
      render_surface(cfg, &surface, false, label) || render_surface(cfg, &sunless, true, label))
    return;

  fog_error ferr = {0};
  render_session *session = render_session_create(cfg, W, H, &ferr);
  CHECK(session, "%s: %s", label, ferr.message);
  if (!session) return;
  render_fog *fog = render_session_fog(session);
  vdb_frame vframe = {0};
  volume_grid_desc grid = {0};
  fog_error rerr = {0};
  if (cfg->fog.model == FOG_MODEL_VOLUME)
    CHECK(!render_fog_load_volume(cfg, &vframe, &grid, &rerr), "%s: %s", label, rerr.message);
  fog->grid3d = &grid;
  fog_model model = render_fog_model(fog);
  const fog_pass_params *params = &fog->params;
  fog_sun_shadow sun_only = {.sun = {params->sun.direction[0], params->sun.direction[1],
                                     params->sun.direction[2]}};
  const fog_sun_shadow *volume =
      params->self_shadow == FOG_SUN_SHADOW_VOLUME ? &fog->sun_shadow : &sun_only;
  CHECK(params->self_shadow != FOG_SUN_SHADOW_NONE, "%s: no self-shadow", label);

  /* The reference's medium: the fogmap the GL draws (mu = 1, switching: A_J, the map
   * itself) or the height fog. */
  light_ref_height height = {.extinction = model.extinction, .y0 = model.y0,
                             .scale_height = model.scale_height};
  light_ref_medium medium =
      model.kind == FOG_MODEL_FOGMAP
          ? light_ref_fogmap(model.volume, &model.lod->approx[model.lod->levels])
          : light_ref_height_medium(&height);
  camera cam;
  scene_config_camera(cfg, &cam);
  const fog_sun *sun = &params->sun;
  double gl_worst = 0, ref_worst = 0, ref_mean = 0, darker = 0, brighter = 0;
  double ground_worst = 0, ground_dimmed = 0;
  int ref_count = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      const int k = py * W + px;
      double o[3], d[3];
      double t_surface = frame_pixel_ray(&lit, &cam, px, py, o, d);
      double mean = fog_sun_mean_transmittance(&model, params->self_shadow, volume,
                                               fog_pass_light_rule(params),
                                               fog_pass_depth_limit(params->walk.transmittance_cutoff), o,
                                               d, t_surface);
      const double mu = d[0] * sun->direction[0] + d[1] * sun->direction[1] +
                        d[2] * sun->direction[2];
      const double p = phase_hg(sun->phase_g, mu), tau = lit.tau[k];
      for (int c = 0; c < 3; c++) {
        const double want =
            (params->fog_colour[c] + sun->albedo * sun->radiance[c] * p * mean) * (1 - tau);
        gl_worst = fmax(gl_worst, fabs(lit.inscatter[3 * k + c] - want) / fmax(want, 1e-3));
        darker = fmax(darker, flat.inscatter[3 * k + c] - lit.inscatter[3 * k + c]);
        brighter = fmax(brighter, lit.inscatter[3 * k + c] - flat.inscatter[3 * k + c]);
      }
      /* the ground: rgb - in-scatter lost tau (1 - T_s(P)) S_sun with the shadow on */
      if (isfinite(t_surface)) {
        double P[3];
        for (int a = 0; a < 3; a++) P[a] = o[a] + t_surface * d[a];
        double ts = exp(-fog_sun_optical_depth(&model, params->self_shadow, volume, P));
        for (int c = 0; c < 3; c++) {
          double lost = (flat.rgba[4 * k + c] - flat.inscatter[3 * k + c]) -
                        (lit.rgba[4 * k + c] - lit.inscatter[3 * k + c]);
          double s_sun = surface.rgba[4 * k + c] - sunless.rgba[4 * k + c];
          double want = tau * (1 - ts) * s_sun;
          ground_worst = fmax(ground_worst, fabs(lost - want));
          ground_dimmed = fmax(ground_dimmed, want);
        }
      }
      /* the reference on every 23rd pixel with fog (nested quadrature is slow) */
      if (mc->reference && k % 23 == 0 && tau < 0.98) {
        double ref_tau;
        double s_ref = light_ref_sun_inscatter(&medium, o, d, t_surface, sun->direction, 1, 1e-9,
                                               &ref_tau);
        double e = fabs(mean * (1 - tau) - s_ref) / (1 - tau);
        ref_worst = fmax(ref_worst, e);
        ref_mean += e;
        ref_count++;
      }
    }
  printf("%s: GL vs its CPU twin: max relative in-scatter error %.2e; the shadow darkens the "
         "in-scatter by up to %.3f (brightens by %.2e)\n", label, gl_worst, darker, brighter);
  const bool quadrics = model.kind == FOG_MODEL_QUADRIC || fog_model_quadrics_beside(&model);
  CHECK(gl_worst <= (quadrics ? FOG_SHADOW_GL_TOLERANCE_QUADRIC : FOG_SHADOW_GL_TOLERANCE),
        "%s: GL vs twin %.3e", label, gl_worst);
  printf("%s: fog shadows on the ground dim the surfaces by up to %.3f; |GL - tau (1 - T_s) "
         "S_sun| <= %.2e\n", label, ground_dimmed, ground_worst);
  CHECK(ground_dimmed > 0.02, "%s: the fog casts no shadow on the ground (%.3e)", label,
        ground_dimmed);
  CHECK(ground_worst <= 1e-5, "%s: ground shadow %.3e off (float surfaces: measured <= 7e-7)",
        label, ground_worst);
  CHECK(darker > 0.02, "%s: the self-shadow does not darken the fog (%.3e)", label, darker);
  CHECK(brighter <= 1e-5, "%s: the self-shadow brightens the fog (%.3e)", label, brighter);
  if (mc->reference && ref_count > 0) {
    printf("%s: the twin's sun in-scatter vs the reference (%d rays): max |error| %.3e, mean "
           "%.3e of (1 - tau)\n", label, ref_count, ref_worst, ref_mean / ref_count);
    CHECK(ref_worst <= mc->reference_bound, "%s: vs the reference %.3e > %.3e", label,
          ref_worst, mc->reference_bound);
  }
  fog->grid3d = NULL;
  vdb_frame_destroy(&vframe);
  render_session_destroy(session);
}

static int load(const char *path, scene_config *cfg);

/* The sum of details at mu = 1 draws A_0 + D_1..D_J = A_J, the fog switching at mu = 1
 * draws: the sun's and the lamps' in-scatter must be the same, within float rounding of
 * the two walks' tau (until the fifteenth session the lights of the sum read A_0: the
 * default scene's sun 0.8 %, night_lamps' lamps 3.6 % of the peak off). */
static void check_sum_lit_as_switch(const char *path) {
  static frame sum, sw;
  scene_config cfg;
  if (load(path, &cfg)) return;
  CHECK(cfg.fog.levels > 0, "%s: no LOD levels", path);
  cfg.fog.mu = 1.0;
  cfg.fog.lod = SCENE_LOD_SWITCH;
  if (render(&cfg, &sw, path)) return;
  cfg.fog.lod = SCENE_LOD_SUM;
  if (render(&cfg, &sum, path)) return;
  double peak = 0, worst = 0;
  for (int k = 0; k < 3 * W * H; k++) {
    peak = fmax(peak, sw.inscatter[k]);
    worst = fmax(worst, fabs(sum.inscatter[k] - sw.inscatter[k]));
  }
  printf("%s: sum of details vs switching at mu = 1: in-scatter max |difference| %.2e of the "
         "peak %.3f\n", path, worst / peak, peak);
  CHECK(peak > 0 && worst <= 1e-4 * peak, "%s: the sum of details lit another fog: %.3e of the "
        "peak", path, worst / peak);
}

static int load(const char *path, scene_config *cfg) {
  fog_error cerr;
  if (scene_config_load(path, cfg, &cerr)) {
    CHECK(0, "%s: %s", path, cerr.message);
    return 1;
  }
  return 0;
}

int main(void) {
  static model_case cases[16];
  int n = 0;
  model_case *c = &cases[n];
  if (!load("configs/default.ini", &c->cfg)) {
    c->label = "fogmap (configs/default.ini)";
    c->reference = true, c->reference_bound = 0.02; /* 8 steps, 48^3: measured 7.5e-3 */
    n++;
  }
  c = &cases[n];
  if (!load("configs/default.ini", &c->cfg)) {
    /* the camera 10 units above the lowest valley floor (inside the ground fog, below its
     * y0), looking across the valley; a high sun */
    c->label = "fogmap, camera inside the fog, sun 60 deg up";
    scene_geometry geo;
    fog_error gerr = {0};
    if (render_scene_geometry_create(&geo, &c->cfg, &gerr)) {
      CHECK(0, "%s", gerr.message);
    } else {
      double best[3] = {0, HUGE_VAL, 0};
      for (int i = 0; i <= 12; i++)
        for (int j = 0; j <= 12; j++) {
          double x = -300 + 50 * i, z = -300 + 50 * j, y = terrain_height_at(&geo.terrain, x, z);
          if (y < best[1]) best[0] = x, best[1] = y, best[2] = z;
        }
      double *pos = c->cfg.camera.position, *at = c->cfg.camera.look_at;
      pos[0] = best[0], pos[1] = best[1] + 10, pos[2] = best[2];
      at[0] = 0, at[1] = best[1] + 10, at[2] = 0;
      if (best[0] == 0 && best[2] == 0) at[2] = -100;
      c->cfg.camera.look_at_set = true;
      printf("camera inside the fog at (%.0f, %.1f, %.0f), fog y0 %.0f\n", pos[0], pos[1], pos[2],
             c->cfg.fog.fog_height);
      CHECK(pos[1] < c->cfg.fog.fog_height, "the valley floor is above the fog");
      scene_geometry_destroy(&geo);
      c->cfg.light.sun_elevation = 60;
      c->reference = true, c->reference_bound = 0.02;
      n++;
    }
  }
  /* the two fogmap cases again with the mean per piece of the exact walk */
  for (int k = 0, fogmaps = n; k < fogmaps; k++) {
    c = &cases[n++];
    *c = cases[k];
    c->label = k == 0 ? "fogmap (configs/default.ini), per piece"
                      : "fogmap, camera inside the fog, per piece";
    c->cfg.shadow.pieces = 1;
  }
  /* the sum of details: at mu = 1 it draws A_0 + D_1..D_J = A_J, the fog the light must
   * see (the reference's medium); at mu = 0.6 the GL against its twin. Both lit A_0, 8x
   * coarser, until the fifteenth session (the reference check: 0.19 off) */
  for (int k = 0; k < 2; k++) {
    c = &cases[n];
    if (!load("configs/default.ini", &c->cfg)) {
      c->label = k ? "fogmap, sum of details at mu = 0.6" : "fogmap, sum of details at mu = 1";
      c->cfg.fog.lod = SCENE_LOD_SUM;
      c->cfg.fog.mu = k ? 0.6 : 1.0;
      c->reference = k == 0, c->reference_bound = 0.02;
      n++;
    }
  }
  c = &cases[n];
  if (!load("configs/vdb_plume_volume.ini", &c->cfg)) {
    c->label = "volume (configs/vdb_plume_volume.ini)";
    c->cfg.light.sun_azimuth = 75, c->cfg.light.sun_elevation = 20;
    n++;
  }
  c = &cases[n];
  if (!load("configs/vdb_plume_volume.ini", &c->cfg)) {
    c->label = "volume (configs/vdb_plume_volume.ini), per piece";
    c->cfg.light.sun_azimuth = 75, c->cfg.light.sun_elevation = 20;
    c->cfg.shadow.pieces = 1;
    n++;
  }
  c = &cases[n];
  if (!load("configs/default.ini", &c->cfg)) {
    c->label = "height";
    c->reference = true, c->reference_bound = 0.02; /* measured 5.3e-4 */
    c->cfg.fog.model = FOG_MODEL_HEIGHT;
    c->cfg.fog.density_scale = 0.01, c->cfg.fog.fog_height = 40, c->cfg.fog.scale_height = 30;
    n++;
  }
  c = &cases[n];
  if (!load("configs/quadric_volumes.ini", &c->cfg)) {
    c->label = "quadric (configs/quadric_volumes.ini)";
    n++;
  }
  c = &cases[n];
  if (!load("configs/quadrics_in_fog.ini", &c->cfg)) {
    c->label = "fogmap, quadrics beside it (configs/quadrics_in_fog.ini), box top at 80";
    c->cfg.box.top = 80; /* the plume rises out of the fogmap's box: K there is theirs alone */
    n++;
  }
  /* Perlin fog: its mean per piece of the exact walk (the default), and by segments */
  for (int pieces = 1; pieces >= 0; pieces--) {
    c = &cases[n];
    if (!load("configs/perlin_fog.ini", &c->cfg)) {
      c->label = pieces ? "perlin (configs/perlin_fog.ini), per piece"
                        : "perlin (configs/perlin_fog.ini), 8 segments";
      c->cfg.shadow.pieces = pieces;
      n++;
    }
  }
  for (int i = 0; i < n; i++) check_case(&cases[i]);
  check_sum_lit_as_switch("configs/default.ini");
  check_sum_lit_as_switch("configs/night_lamps.ini");
  check_shafts(false, false);
  check_shafts(true, false);
  check_shafts(false, true);
  return test_finish("test_fog_shadow");
}
