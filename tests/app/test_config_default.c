/* configs/default.ini parses into the values it states, paths resolve against the
 * config's folder, an empty file gives exactly the documented defaults
 * (scene_config_init), and the camera and scene conversions carry the values over. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/config.h"
#include "test_util.h"

/* The live demo's settings on a software renderer (scene_live_*): the lamps' integral is
 * capped at 4 + 4 pieces and a 4-step walk; what is below stays, the other integrals and
 * the depth table are untouched. */
static void check_live_settings(void) {
  const fog_lamp_method product = {.integral = FOG_LAMP_ANGLE, .angle_pieces = 8,
                                   .span_pieces = 8, .depth_steps = 32, .shadow_steps = 8,
                                   .march_steps = 64};
  fog_lamp_method live = scene_live_lamp_method(product);
  CHECK(live.angle_pieces == 4 && live.span_pieces == 4 && live.shadow_steps == 4 &&
            live.depth_steps == 32 && live.march_steps == 64 && live.integral == FOG_LAMP_ANGLE,
        "live lamps %d+%d, walk %d, table %d", live.angle_pieces, live.span_pieces,
        live.shadow_steps, live.depth_steps);
  fog_lamp_method small = product;
  small.angle_pieces = 2, small.span_pieces = 0, small.shadow_steps = 1;
  live = scene_live_lamp_method(small);
  CHECK(live.angle_pieces == 2 && live.span_pieces == 0 && live.shadow_steps == 1,
        "a cheaper method is kept: %d+%d, %d", live.angle_pieces, live.span_pieces,
        live.shadow_steps);
  fog_lamp_method march = product;
  march.integral = FOG_LAMP_MARCH;
  live = scene_live_lamp_method(march);
  CHECK(!memcmp(&live, &march, sizeof live), "the march baseline is not the live rule's");
  CHECK(scene_live_terrain_lod(0.0) == 0.0 && scene_live_terrain_lod(0.5) == 2.0 &&
            scene_live_terrain_lod(3.0) == 6.0,
        "live terrain LOD %g %g %g", scene_live_terrain_lod(0.0), scene_live_terrain_lod(0.5),
        scene_live_terrain_lod(3.0));
}

/* The fogmap's volume (scene_config_fog_volume): [box] places it, the shape gives its
 * extinction and profile, a B-spline takes the config's knots (pointing into it), and one
 * without knots is the slab. */
static void check_fog_volume(void) {
  scene_config cfg;
  scene_config_init(&cfg);
  cfg.box.origin[0] = -300, cfg.box.origin[1] = 120, cfg.box.cell_size = 3.5;
  cfg.box.floor = -4, cfg.box.top = 90;
  cfg.fog.density_scale = 0.031, cfg.fog.profile = SCENE_PROFILE_EXPONENTIAL;
  cfg.fog.fog_height = 12, cfg.fog.scale_height = 40;
  scene_fog_shape shape = scene_config_fog_shape(&cfg);
  fog_volume v = scene_config_fog_volume(&cfg, 200, 150, &shape);
  CHECK(v.map_width == 200 && v.map_height == 150 && v.origin_x == -300 && v.origin_z == 120 &&
            v.cell_size == 3.5 && v.extinction == 0.031 &&
            v.profile.kind == FOG_PROFILE_EXPONENTIAL && v.profile.y_floor == -4 &&
            v.profile.y_top == 90 && v.profile.y0 == 12 && v.profile.scale_height == 40,
        "the config's volume: %dx%d at (%g, %g) cell %g K %g, profile %d [%g, %g] y0 %g H %g",
        v.map_width, v.map_height, v.origin_x, v.origin_z, v.cell_size, v.extinction,
        (int)v.profile.kind, v.profile.y_floor, v.profile.y_top, v.profile.y0,
        v.profile.scale_height);
  /* the live panel's shape: its own values over the config's box */
  const scene_fog_shape live = {.extinction = 0.5, .profile = FOG_PROFILE_SLAB, .y0 = 1,
                                .scale_height = 2};
  v = scene_config_fog_volume(&cfg, 8, 8, &live);
  CHECK(v.extinction == 0.5 && v.profile.kind == FOG_PROFILE_SLAB && v.origin_x == -300,
        "a live shape: K %g, profile %d", v.extinction, (int)v.profile.kind);
  /* a B-spline: the config's knots, in place */
  cfg.fog.profile = SCENE_PROFILE_BSPLINE;
  cfg.fog.profile_count = 3, cfg.fog.profile_degree = 2;
  cfg.fog.profile_coefficients[0] = 1, cfg.fog.profile_coefficients[1] = 0.5;
  cfg.fog.profile_coefficients[2] = 0.25;
  cfg.fog.profile_origin = -2, cfg.fog.profile_spacing = 30;
  shape = scene_config_fog_shape(&cfg);
  v = scene_config_fog_volume(&cfg, 8, 8, &shape);
  CHECK(v.profile.kind == FOG_PROFILE_BSPLINE && v.profile.count == 3 &&
            v.profile.degree == 2 && v.profile.coefficients == cfg.fog.profile_coefficients &&
            v.profile.origin == -2 && v.profile.spacing == 30,
        "the B-spline profile: kind %d, %d knots of degree %d", (int)v.profile.kind,
        v.profile.count, v.profile.degree);
  cfg.fog.profile_count = 0; /* none in the config: the slab */
  v = scene_config_fog_volume(&cfg, 8, 8, &shape);
  CHECK(v.profile.kind == FOG_PROFILE_SLAB && v.profile.count == 0,
        "a B-spline without knots is kind %d", (int)v.profile.kind);
}

int main(void) {
  check_live_settings();
  check_fog_volume();
  scene_config cfg;
  fog_error err = {0};
  int status = scene_config_load("configs/default.ini", &cfg, &err);
  CHECK(status == 0, "default.ini: %s", err.message);
  CHECK(!strcmp(cfg.fog.fogmap, "configs/../data/fogmap_sample.png"), "fogmap '%s'",
        cfg.fog.fogmap);
  CHECK(access(cfg.fog.fogmap, R_OK) == 0, "the sample fogmap %s is readable", cfg.fog.fogmap);
  CHECK(cfg.width == 1280 && cfg.height == 720, "size %dx%d", cfg.width, cfg.height);
  CHECK(cfg.fog.degree == 1 && cfg.fog.profile == SCENE_PROFILE_EXPONENTIAL &&
            cfg.fog.lod == SCENE_LOD_SWITCH && cfg.fog.filtering == SCENE_FILTERING_MANUAL,
        "fog enums %d %d %d %d", cfg.fog.degree, cfg.fog.profile, cfg.fog.lod, cfg.fog.filtering);
  /* a box without a colour is light grey (SCENE_BOX_GREY), set when the line is read */
  CHECK(cfg.object_count == 3 && cfg.objects[0].colour[0] == 0.55f &&
            cfg.objects[0].colour[1] == 0.25f && cfg.objects[1].colour[0] == 0.55f &&
            cfg.objects[1].colour[1] == 0.53f && cfg.objects[1].colour[2] == 0.50f,
        "objects: %d", cfg.object_count);
  CHECK(cfg.camera.look_at_set, "look_at");
  CHECK(cfg.terrain.heightmap[0] == '\0' && cfg.terrain.resolution == 257, "terrain");
  CHECK(cfg.box.top > cfg.box.floor && cfg.box.cell_size > 0, "box");

  /* The camera looks at look_at. */
  camera cam;
  scene_config_camera(&cfg, &cam);
  double right[3], up[3], forward[3];
  camera_basis(&cam, 16, 9, right, up, forward);
  double d[3], len = 0;
  for (int k = 0; k < 3; k++) d[k] = cfg.camera.look_at[k] - cfg.camera.position[k], len += d[k] * d[k];
  len = sqrt(len);
  double cosine = (d[0] * forward[0] + d[1] * forward[1] + d[2] * forward[2]) / len;
  CHECK(cosine > 1 - 1e-12, "camera forward . (look_at - position) = %.15f", cosine);
  CHECK(fabs(cam.fov_y - cfg.camera.fov * 3.14159265358979323846 / 180) < 1e-15, "fov");

  scene_desc desc;
  scene_config_scene_desc(&cfg, NULL, 0, 0, &desc);
  CHECK(desc.box_count == 3 && desc.boxes[2].size[0] == 40 && desc.terrain.seed == cfg.terrain.seed,
        "scene desc");

  /* An empty config is the defaults; paths resolve against the config's folder. */
  char dir[] = "/tmp/fogpipe_config_XXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  char path[256], map[256];
  snprintf(path, sizeof path, "%s/empty.ini", dir);
  test_write_text(path, "; nothing\n");
  scene_config empty, defaults;
  scene_config_init(&defaults);
  CHECK(scene_config_load(path, &empty, &err) == 0, "empty: %s", err.message);
  snprintf(defaults.path, sizeof defaults.path, "%s", path);
  CHECK(memcmp(&empty, &defaults, sizeof empty) == 0, "an empty config differs from the defaults");
  CHECK(defaults.fog.fogmap[0] == '\0', "no fog by default");

  snprintf(map, sizeof map, "%s/map.png", dir);
  test_write_text(map, "not really a png; the config only checks that it opens");
  snprintf(path, sizeof path, "%s/rel.ini", dir);
  test_write_text(path,
                  "[fog]\nfogmap = map.png\nbasis = quadratic\n[camera]\nposition = 1, 2, 3\n");
  CHECK(scene_config_load(path, &cfg, &err) == 0, "rel: %s", err.message);
  CHECK(!strcmp(cfg.fog.fogmap, map), "relative fogmap resolved to '%s', expected '%s'",
        cfg.fog.fogmap, map);
  CHECK(cfg.fog.fogmap_line == 2 && cfg.fog.degree == 2, "line %d", cfg.fog.fogmap_line);
  CHECK(cfg.camera.position[0] == 1 && cfg.camera.position[2] == 3, "commas between numbers");
  /* The light's documented defaults (docs/config.md), and a zero meaning zero: a sun on the
   * horizon, a black sun (they used to mean "elevation 35" and "the default colour"). */
  {
    const fog_sun sun = scene_config_fog_sun(&empty);
    const double pi = 3.14159265358979323846, el = 35.0 * pi / 180.0;
    CHECK(empty.light.sun_elevation == 35.0 && empty.light.sun_azimuth == 0.0 &&
              empty.light.sun_colour[0] == 1.9f && empty.light.sun_colour[1] == 1.8f &&
              empty.light.sun_colour[2] == 1.6f && empty.light.ambient[2] == 0.45f &&
              empty.light.sky_horizon[0] == 0.72f && empty.light.sky_zenith[2] == 0.75f,
          "the light's defaults");
    CHECK(fabs(sun.direction[1] - sin(el)) < 1e-15 && fabs(sun.direction[2] + cos(el)) < 1e-15,
          "default sun direction (%g %g %g)", sun.direction[0], sun.direction[1],
          sun.direction[2]);
    snprintf(path, sizeof path, "%s/zero.ini", dir);
    test_write_text(path, "[light]\nsun_elevation = 0\nsun_colour = 0 0 0\nambient = 0 0 0\n"
                     "[objects]\nbox = 0 0 1 1 1 0 0 0\n");
    CHECK(scene_config_load(path, &cfg, &err) == 0, "zero: %s", err.message);
    const fog_sun zero = scene_config_fog_sun(&cfg);
    CHECK(zero.direction[1] == 0.0 && zero.direction[2] == -1.0,
          "sun_elevation = 0: direction (%g %g %g), expected the horizon", zero.direction[0],
          zero.direction[1], zero.direction[2]);
    CHECK(zero.radiance[0] == 0.0 && zero.radiance[1] == 0.0 && zero.radiance[2] == 0.0 &&
              cfg.light.ambient[0] == 0.0f,
          "sun_colour = 0 0 0: radiance (%g %g %g), expected none", zero.radiance[0],
          zero.radiance[1], zero.radiance[2]);
    CHECK(cfg.object_count == 1 && cfg.objects[0].colour[0] == 0.0f &&
              cfg.objects[0].colour[1] == 0.0f && cfg.objects[0].colour[2] == 0.0f,
          "box = ... 0 0 0: a black box (it used to be grey)");
  }
  unlink(map);
  unlink(path);
  snprintf(path, sizeof path, "%s/rel.ini", dir);
  unlink(path);
  snprintf(path, sizeof path, "%s/empty.ini", dir);
  unlink(path);
  rmdir(dir);
  return test_finish("test_config_default");
}
