/* One headless frame of a scene config (render_frame.h). */
#include "app/render_frame.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/render_fog.h"
#include "render/render.h"
#include "sim/sim.h"

/* Whether a load by channel name failed for want of the channel (image_exr.c's and
 * image_png.c's "has no channel" message), not for its values. */
static bool channel_missing(const fog_error *e) {
  return e->code == FOG_ERR_NO_SUCH_CHANNEL;
}

/* A heightmap is one channel of heights. A grey image saved with alpha, or as RGB(A) whose
 * colour channels agree (as image editors often write it), is that channel; an RGB image
 * whose channels differ is refused, naming a pixel where they do. A channel that is there
 * but holds a bad height is refused for that (it was "name the one to load", a channel no
 * key names). */
static int load_heights(const char *path, fogmap *map, fog_error *err) {
  fog_error first;
  if (!fogmap_load(path, &(fogmap_load_desc){.values_are = "heights"}, map, &first)) return 0;
  fog_error named;
  if (!fogmap_load(path, &(fogmap_load_desc){.channel = "grey", .values_are = "heights"}, map,
                   &named))
    return 0;
  if (!channel_missing(&named)) return fog_error_pass(err, &named);
  /* an EXR's grey is Y (a Y + A EXR was refused, asking to name a channel no key names) */
  if (!fogmap_load(path, &(fogmap_load_desc){.channel = "Y", .values_are = "heights"}, map,
                   &named))
    return 0;
  if (!channel_missing(&named)) return fog_error_pass(err, &named);
  if (fogmap_load(path, &(fogmap_load_desc){.channel = "R", .values_are = "heights"}, map,
                  &named))
    /* not a colour image: the first reason stands */
    return fog_error_pass(err, channel_missing(&named) ? &first : &named);
  static const char *const others[2] = {"G", "B"};
  for (int k = 0; k < 2; k++) {
    fogmap other;
    if (fogmap_load(path, &(fogmap_load_desc){.channel = others[k], .values_are = "heights"},
                    &other, err)) {
      fogmap_destroy(map);
      return 1;
    }
    size_t n = (size_t)map->width * map->height, i = 0;
    while (i < n && other.density[i] == map->density[i]) i++;
    fogmap_destroy(&other);
    if (i < n) {
      fog_fail(err, FOG_ERR_BAD_FILE,
               "%s: its R and %s channels differ at pixel (%d, %d): expected a grey image "
               "(one channel of heights)", path, others[k], (int)(i % (size_t)map->width),
               (int)(i / (size_t)map->width));
      fogmap_destroy(map);
      return 1;
    }
  }
  return 0;
}

int render_frame_load_heightmap(const scene_config *cfg, float **heights, int *width, int *height,
                                fog_error *err) {
  *heights = NULL;
  *width = *height = 0;
  if (!cfg->terrain.heightmap[0]) return 0;
  fogmap map;
  fog_error serr;
  /* A 16-bit grey PNG reads as value / 65535: heights in [0, 1]. */
  if (load_heights(cfg->terrain.heightmap, &map, &serr)) {
    fog_error_wrap(err, &serr, "%.200s:%d: [terrain] heightmap: ", cfg->path,
                   cfg->terrain.heightmap_line);
    return 1;
  }
  /* the terrain's grid needs two vertices a side, and its mesh stays under 2 GiB (the
   * terrain refused a larger one without the file, line or key) */
  if (map.width < 2 || map.height < 2 ||
      (double)map.width * map.height >
          (double)TERRAIN_MAX_RESOLUTION * TERRAIN_MAX_RESOLUTION) {
    fog_fail(err, FOG_ERR_BAD_FILE,
             "%.200s:%d: [terrain] heightmap: %s is %dx%d pixels: expected at least 2x2 and "
             "at most %d x %d pixels in all", cfg->path, cfg->terrain.heightmap_line,
             cfg->terrain.heightmap, map.width, map.height, TERRAIN_MAX_RESOLUTION,
             TERRAIN_MAX_RESOLUTION);
    fogmap_destroy(&map);
    return 1;
  }
  /* An EXR holds heights in metres as readily as in [0, 1]; the terrain clamps to [0, 1],
   * which flattened every hill above 1 into a plateau without a word. A resampling
   * filter's overshoot of up to 1 % is clamped as before. */
  const float largest = fogmap_max_density(&map);
  if (largest > 1.01f) {
    size_t k = 0;
    while (!(map.density[k] > 1.01f)) k++; /* the first pixel above */
    fog_fail(err, FOG_ERR_BAD_FILE,
             "%.200s:%d: [terrain] heightmap: %s: pixel (%zu, %zu) is %g: expected heights "
             "from 0 to 1, scaled by [terrain] height (the largest here is %g: divide the "
             "map by it)",
             cfg->path, cfg->terrain.heightmap_line, cfg->terrain.heightmap,
             k % (size_t)map.width, k / (size_t)map.width, map.density[k], largest);
    fogmap_destroy(&map);
    return 1;
  }
  *heights = map.density; /* ownership moves to the caller */
  *width = map.width;
  *height = map.height;
  return 0;
}

void render_scene_destroy(render_scene *s) {
  free(s->distance);
  gl_target_destroy(&s->target);
  scene_pass_destroy(s->pass);
  if (s->have_geo) scene_geometry_destroy(&s->geo);
  *s = (render_scene){0};
}

int render_scene_geometry_create(scene_geometry *geo, const scene_config *cfg, fog_error *err) {
  float *heights = NULL;
  int hw = 0, hh = 0;
  fog_error ferr;
  if (render_frame_load_heightmap(cfg, &heights, &hw, &hh, &ferr)) {
    fog_error_pass(err, &ferr);
    return 1;
  }
  scene_desc desc;
  scene_config_scene_desc(cfg, heights, hw, hh, &desc);
  int status = scene_geometry_create(geo, &desc, err);
  free(heights); /* the geometry has its copy */
  return status;
}

int render_scene_create(render_scene *s, const scene_config *cfg, int width, int height,
                        fog_error *err) {
  *s = (render_scene){.width = width, .height = height};
  scene_config_camera(cfg, &s->cam);
  int status = 1;
  if (render_scene_geometry_create(&s->geo, cfg, err)) goto done;
  s->have_geo = true;
  s->pass = scene_pass_create(&s->geo, err);
  if (!s->pass || scene_target_create(&s->target, width, height, err)) goto done;
  const fog_lamps lamps = scene_config_fog_lamps(cfg);
  if (scene_pass_set_lamp_shadows(s->pass, scene_config_lamp_shadow_size(cfg), err) ||
      scene_pass_set_lamps(s->pass, &lamps, err))
    goto done;
  s->distance = malloc((size_t)width * height * sizeof *s->distance);
  if (!s->distance) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    goto done;
  }
  scene_pass_run(s->pass, &s->cam, &s->target);
  status = gl_target_read(&s->target, 1, 1, s->distance, err);
done:
  if (status) render_scene_destroy(s);
  return status;
}

struct render_session {
  gl_context *ctx;
  render_scene scene;
  gl_target fog_target;
  render_fog fog;
  bool has_fog;
  bool lamps_animated; /* scene_config_lamps_animated */
  scene_config config; /* for the lamps at a time */
  char gl_description[256];
};

void render_session_destroy(render_session *s) {
  if (!s) return;
  render_fog_destroy(&s->fog);
  gl_target_destroy(&s->fog_target);
  render_scene_destroy(&s->scene);
  gl_context_destroy(s->ctx);
  free(s);
}

render_session *render_session_create(const scene_config *cfg, int width, int height,
                                      fog_error *err) {
  render_session *s = calloc(1, sizeof *s);
  if (!s) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    return NULL;
  }
  fog_error rerr = {0};
  s->ctx = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &rerr);
  if (!s->ctx) goto fail;
  snprintf(s->gl_description, sizeof s->gl_description, "%s, %s, %s",
           gl_context_platform(s->ctx), gl_context_version(s->ctx), gl_context_renderer(s->ctx));
  if (render_scene_create(&s->scene, cfg, width, height, &rerr)) goto fail;
  s->has_fog = scene_config_has_fog(cfg);
  /* The fog (fogmap -> wavelet pyramid, or another model of the ladder) over the scene's
   * colour and distance. */
  if (s->has_fog &&
      (render_fog_create(&s->fog, cfg, &rerr) ||
       gl_target_create(&s->fog_target,
                        &(gl_target_desc){.width = width, .height = height,
                                          .color_formats = {GL_RGBA32F, GL_R32F, GL_RGBA32F}},
                        &rerr)))
    goto fail;
  if (s->has_fog) {
    render_fog_set_shafts(&s->fog, cfg, scene_pass_sun_shadow(s->scene.pass));
    render_fog_set_lamp_shadows(&s->fog, scene_pass_lamp_shadows(s->scene.pass));
  }
  s->config = *cfg;
  s->lamps_animated = scene_config_lamps_animated(cfg);
  return s;
fail:
  fog_error_pass(err, &rerr);
  render_session_destroy(s);
  return NULL;
}

const char *render_session_gl_description(const render_session *s) { return s->gl_description; }

int render_session_set_time(render_session *s, double time, fog_error *err) {
  if (s->has_fog && render_fog_animated(&s->config)) {
    fog_error ferr = {0};
    if (render_fog_set_time(&s->fog, &s->config, time, &ferr)) {
      fog_error_pass(err, &ferr);
      return 1;
    }
  }
  if (!s->lamps_animated) return 0;
  const fog_lamps lamps = scene_config_fog_lamps_at(&s->config, time);
  if (s->has_fog) s->fog.params.lamps = lamps;
  fog_error rerr = {0};
  if (scene_pass_set_lamps(s->scene.pass, &lamps, &rerr)) {
    fog_error_pass(err, &rerr);
    return 1;
  }
  scene_pass_run(s->scene.pass, &s->scene.cam, &s->scene.target);
  if (gl_util_check("render: lamps", &rerr)) {
    fog_error_pass(err, &rerr);
    return 1;
  }
  return 0;
}

render_fog *render_session_fog(render_session *s) { return s->has_fog ? &s->fog : NULL; }

/* The scene was drawn once (render_scene_create: the camera does not move in a session);
 * a frame is the fog over it. */
int render_session_frame(render_session *s, const frame_pixels *out, fog_error *err) {
  fog_error rerr = {0};
  const render_scene *sc = &s->scene;
  size_t pixels = (size_t)sc->width * sc->height;
  if (s->has_fog) {
    if (render_fog_draw(&s->fog, &sc->cam, &sc->target, &s->fog_target, &rerr)) {
      /* the scene's settings refused (the loop cap names the keys to change): say whose */
      if (rerr.code == FOG_ERR_UNSUPPORTED)
        fog_error_wrap(&rerr, &rerr, "%.300s: ", s->config.path);
      goto fail;
    }
    if (out->rgba && gl_target_read(&s->fog_target, 0, 4, out->rgba, &rerr)) goto fail;
    if (out->transmittance && gl_target_read(&s->fog_target, 1, 1, out->transmittance, &rerr))
      goto fail;
    if (out->inscatter && gl_target_read(&s->fog_target, 2, 3, out->inscatter, &rerr))
      goto fail;
  } else {
    if (out->rgba && gl_target_read(&sc->target, 0, 4, out->rgba, &rerr)) goto fail;
    if (out->transmittance)
      for (size_t k = 0; k < pixels; k++) out->transmittance[k] = 1.0f;
    if (out->inscatter) memset(out->inscatter, 0, 3 * pixels * sizeof *out->inscatter);
  }
  if (gl_util_check("render", &rerr)) goto fail;
  if (out->depth)
    for (size_t k = 0; k < pixels; k++)
      out->depth[k] =
          sc->distance[k] >= SCENE_SKY_DISTANCE ? (float)sc->cam.far_plane : sc->distance[k];
  return 0;
fail:
  fog_error_pass(err, &rerr);
  return 1;
}

int render_frame(const scene_config *cfg, int width, int height, const frame_pixels *out,
                 render_frame_info *info, fog_error *err) {
  *info = (render_frame_info){0};
  render_session *s = render_session_create(cfg, width, height, err);
  if (!s) return 1;
  snprintf(info->gl_description, sizeof info->gl_description, "%s", s->gl_description);
  info->has_fog = s->has_fog;
  int status = render_session_frame(s, out, err);
  render_session_destroy(s);
  return status;
}
