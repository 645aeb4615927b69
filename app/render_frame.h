/* Headless frames of a scene config: an EGL context, the scene and its fog made once
 * (render_session), rendered and read back per frame. `fogpipe render` takes one frame
 * (render_frame); `fogpipe record` of a VDB volume sequence moves the volume's time
 * between them (render_fog_set_volume_time). */
#ifndef FOGPIPE_APP_RENDER_FRAME_H
#define FOGPIPE_APP_RENDER_FRAME_H

#include "transform/fog_error.h"
#include "app/frame_pixels.h"
#include <stdbool.h>

#include "app/config.h"
#include "render/render.h"

typedef struct render_frame_info {
  bool has_fog;              /* false: the fog pass is not part of this build yet */
  char gl_description[256];  /* "egl-surfaceless, 4.5 (Core Profile) Mesa ..., llvmpipe" */
} render_frame_info;

/* A config's terrain and boxes drawn once from its camera, with the GL context current:
 * the scene target (colour 0, distance 1) and the distances read back (rows as
 * gl_target_read gives them; SCENE_SKY_DISTANCE for the sky). */
typedef struct render_scene {
  int width, height;
  camera cam;
  scene_geometry geo;
  bool have_geo;
  scene_pass *pass;
  gl_target target;
  float *distance;
} render_scene;

/* The config's terrain (its heightmap loaded) and boxes as geometry. Errors name the
 * heightmap's file:line. */
int render_scene_geometry_create(scene_geometry *geo, const scene_config *cfg, fog_error *err);
/* Loads the config's heightmap, builds the geometry and draws it. Errors name the
 * heightmap's file:line. */
int render_scene_create(render_scene *scene, const scene_config *cfg, int width, int height,
                        fog_error *err);
void render_scene_destroy(render_scene *scene);

typedef struct render_session render_session;

/* Makes the context, the scene and the fog of cfg (copied) for width x height frames. */
render_session *render_session_create(const scene_config *cfg, int width, int height,
                                      fog_error *err);
void render_session_destroy(render_session *session);
/* "egl-surfaceless, 4.5 (Core Profile) Mesa ..., llvmpipe" */
const char *render_session_gl_description(const render_session *session);
/* The session's fog (NULL when the config has none), to change between frames. */
struct render_fog *render_session_fog(render_session *session);
/* The scene time of the next frames, seconds: lamps that move or flicker ([light] lamp_path,
 * lamp_flicker) are set for it (the surfaces they light drawn again), and so are the puffs
 * of [fog] rbf_emitter lines (render_fog_set_time); nothing else moves. */
int render_session_set_time(render_session *session, double time, fog_error *err);
/* One frame, outputs as render_frame's. */
int render_session_frame(render_session *session, const frame_pixels *out, fog_error *err);

/* Renders cfg at width x height (a session of one frame) into out (app/frame_pixels.h). */
int render_frame(const scene_config *cfg, int width, int height, const frame_pixels *out,
                 render_frame_info *info, fog_error *err);

/* The heightmap of cfg (if any) as heights in [0, 1]: *heights is malloc'd (NULL and
 * sizes 0 for a procedural terrain). A grey image may come with alpha or as RGB(A) whose
 * colour channels agree; one whose colour channels differ is refused. */
int render_frame_load_heightmap(const scene_config *cfg, float **heights, int *width, int *height,
                                fog_error *err);

#endif
