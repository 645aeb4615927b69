/* player: the one frame path of the headless commands (docs/architecture.md). A scene
 * config, resolved once, becomes a fog source, and frame n of it is rendered and read
 * back. The source is chosen by the config (the model table's row) and desc.play:
 *
 *   simulated  model = fogmap, play: the per-frame pipeline (app/pipeline.h), one
 *              simulation step per frame (a `[fog] vdb` sequence plays as fogmaps),
 *              then the transform, the upload and the scene + fog passes
 *   static     not simulated: without play, the fogmap or volume as the file holds it (a
 *              VDB sequence: frame vdb_frame), or an analytic model, played or not: a
 *              render session (app/render_frame.h) whose fog is made once; each frame
 *              sets its time, start_time + (n - 1) / fps (render_session_set_time),
 *              which moves Perlin fog, RBF emitters' puffs, noisy quadric volumes and
 *              lamps on a lamp_path or flickering (the scene pass drawn again for them)
 *   played     model = volume, play: a render session whose 3D grid moves through the VDB
 *              sequence, frame n at that same time, blended between VDB frames
 *
 * `fogpipe record` and `fogpipe render` draw every frame through this; the window program
 * (demo, view: app/window_program.h) uses the same pipeline, or render_fog with a scene
 * pass of its own for the fog as held.
 *
 * Lifecycle: player_create (makes its own headless GL context) → player_skip (for --resume
 * or a range; in parts if need be: the frames add up) → player_frame per frame →
 * player_destroy. */
#ifndef FOGPIPE_APP_PLAYER_H
#define FOGPIPE_APP_PLAYER_H

#include "app/frame_pixels.h"
#include <stdbool.h>

#include "app/config.h"
#include "transform/fog_error.h"

typedef struct player player;

enum { PLAYER_MAX_SIDE = 16384 }; /* pixels a side the sources draw, supersampled */

typedef struct player_desc {
  const scene_config *config; /* copied */
  int width, height;          /* > 0 */
  double fps;                 /* output frames per second of scene time, > 0 */
  /* The scene time of frame 1, seconds (>= 0), for a source that is not simulated: frame n
   * shows start_time + (n - 1) / fps (`render --time`). A simulation starts at 0. */
  double start_time;
  bool play;                  /* the scene's time passes: a fogmap simulates, a volume plays */
  bool synchronous;           /* the pipeline's CPU stages on the GL thread */
} player_desc;

player *player_create(const player_desc *desc, fog_error *err);
void player_destroy(player *player);
/* The GL the frames are drawn with: "egl-surfaceless, 4.5 (Core Profile) Mesa ..., llvmpipe". */
const char *player_gl_description(const player *player);
/* Whether the fog of a frame depends on the frames before it (a simulation, whose skip
 * costs the simulation of the frames skipped). Frame n after no frames drawn needs
 * player_skip(n - 1) first, whatever the source. */
bool player_is_sequential(const player *player);
/* Moves the source on by `frames` frames without drawing them (only before the first
 * player_frame): a simulation runs them, a played bake only counts them; a render session
 * draws any frame directly and ignores it. */
int player_skip(player *player, long frames, fog_error *err);
/* Draws frame n (1-based; a sequential source: the one after the last drawn or skipped) and
 * reads it back, rows top first, [render] supersample^2 samples a pixel (app/supersample.h),
 * any output may be NULL: rgba (4 linear floats a pixel),
 * the transmittance (1 where no fog) and the depth (distance along the view ray to the first
 * surface; the camera's far plane for the sky). */
int player_frame(player *player, int n, const frame_pixels *out, fog_error *err);
/* The camera the frames are drawn with. */
const camera *player_camera(const player *player);

#endif
