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

static void write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  fputs(text, f);
  fclose(f);
}

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

int main(void) {
  check_live_settings();
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
  write_file(path, "; nothing\n");
  scene_config empty, defaults;
  scene_config_init(&defaults);
  CHECK(scene_config_load(path, &empty, &err) == 0, "empty: %s", err.message);
  snprintf(defaults.path, sizeof defaults.path, "%s", path);
  CHECK(memcmp(&empty, &defaults, sizeof empty) == 0, "an empty config differs from the defaults");
  CHECK(defaults.fog.fogmap[0] == '\0', "no fog by default");

  snprintf(map, sizeof map, "%s/map.png", dir);
  write_file(map, "not really a png; the config only checks that it opens");
  snprintf(path, sizeof path, "%s/rel.ini", dir);
  write_file(path, "[fog]\nfogmap = map.png\nbasis = quadratic\n[camera]\nposition = 1, 2, 3\n");
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
    write_file(path, "[light]\nsun_elevation = 0\nsun_colour = 0 0 0\nambient = 0 0 0\n"
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
