/* The one window program of `fogpipe demo` and `fogpipe view` (part of the executable):
 * a GLFW window with the Dear ImGui panel (app/panel.h), the free camera
 * (app/free_camera.h), the screenshot and one frame loop, over one of two fog sources:
 *
 *   simulated  the config's simulation in the live pipeline (app/pipeline.h), playing or
 *              paused (Space): `demo` on a model with a pyramid (app/window_pipeline.c);
 *   as held    the fog as the config holds it in a render session's fog (app/render_fog.h):
 *              a volume's VDB sequence plays or not (P), RBF emitters and Perlin octaves
 *              drift, the Gaussian brush paints, `--fit` steps through the model ladder:
 *              `view`, and `demo` on the models without a simulation (app/window_session.c).
 *
 * A frame: poll, the panel (the shell's frame rate and the source's sections), the camera,
 * the source's input (keys and mouse the panel does not hold), the source's draw into the
 * back buffer, the panel over it, the screenshot when asked, the swap. */
#ifndef FOGPIPE_APP_WINDOW_PROGRAM_H
#define FOGPIPE_APP_WINDOW_PROGRAM_H

#include <stdbool.h>

#include "app/config.h"
#include "app/fit.h"
#include "app/free_camera.h"
#include "app/panel.h"
#include "render/gl_context.h"
#include "transform/fog_error.h"

typedef struct window_options {
  const char *command;     /* "demo" or "view": messages begin "fogpipe COMMAND: " */
  const char *config_path; /* the window's title; the brush saves NAME.painted.ini beside it */
  int width, height;       /* the window, > 0 */
  /* Render at this times the window size, > 0; 0: the simulated source chooses from the
   * renderer (1 on a GPU, 0.5 on a software renderer with the fog at half of that), the
   * source as held takes 0.5. */
  double render_scale;
  bool simulate;           /* the config's simulation (its model must have a pyramid) */
  bool play;               /* start playing: the simulation, or a volume's VDB sequence */
  int live_rung;           /* simulated: the panel's model (live_rung_kind) to start with */
  bool hide_panel;         /* start with the panel hidden (Tab shows it) */
  /* Save the last frame as a PNG and return (NULL: run). The panel, when shown, is in it
   * from the second frame on (ImGui sizes a window on its first). */
  const char *screenshot;
  int frames;              /* frames before the screenshot, >= 1 */
  /* Without a screenshot: close the window after `frames` frames (`demo --frames N`); false:
   * run until it is closed. */
  bool quit_after_frames;
  /* As held: `fogpipe fit` before the window opens (app/fit.h); the panel's rung menu, or [
   * and ], step through the rungs, 0 returns to the config's own fog. */
  bool fit;
  double fit_tolerance;    /* > 0 */
  int rung;                /* >= 0: start on this rung; -1: fit's pick */
  /* Not NULL: a window that cannot open is not an error printed here; it is put here and
   * window_program_run returns WINDOW_PROGRAM_NO_WINDOW (the demo records instead). */
  fog_error *window_failure;
  const char *note; /* printed as `fogpipe COMMAND: NOTE` once the window is open (or NULL) */
} window_options;

#define WINDOW_PROGRAM_NO_WINDOW (-1)

/* Opens the window and runs until it closes or the screenshot is taken; errors printed as
 * `fogpipe COMMAND: ...` (no display: "cannot open a window: ..."). cfg may be changed (the
 * live terrain LOD and lamp rule on a software renderer). The process exit status, or
 * WINDOW_PROGRAM_NO_WINDOW (see window_failure). */
int window_program_run(scene_config *cfg, const window_options *opts);

/* ---- the fog sources (app/window_pipeline.c, app/window_session.c) ---- */

/* The sun as the panel edits it, for either source: a time of day, its colour as a hue
 * and a strength (the largest channel of [light] sun_colour), [fog] albedo and phase_g,
 * [light] fog_self_shadow and shafts. */
typedef struct window_sunlight {
  float azimuth, elevation; /* degrees */
  float albedo, phase_g;
  float hue[3], strength;
  bool self_shadow, shafts;
} window_sunlight;
/* The panel's "sunlight in the fog" section; true when the user changed a value. */
bool window_panel_sunlight(panel *ui, window_sunlight *sun);
/* [light] sun_colour (or a fog_sun's radiance over SCENE_SUN_IRRADIANCE_PER_COLOUR) as a
 * hue and a strength, and back (app/sun_hue.h): set the hue to the source's last one
 * first, which a colour of strength 0 keeps. */
void window_sunlight_set_colour(window_sunlight *sun, const double colour[3]);
void window_sunlight_colour(const window_sunlight *sun, double colour[3]);

/* The fog's vertical profile as the panel edits it, for either source: fog_profile_kind
 * (the B-spline only offered when the config has one) and the exponential profile's
 * [fog] fog_height and scale_height. */
typedef struct window_profile {
  int kind;
  float fog_height, scale_height;
  bool has_bspline;
} window_profile;
/* The profile's controls (no header of their own); true when the user changed a value.
 * With kind_fixed the kind is not offered (a model whose profile is always exponential). */
bool window_panel_profile(panel *ui, window_profile *profile, bool kind_fixed);

/* The fogmap's wavelet transform and LOD as the panel edits them, for either source:
 * [fog] basis (degree), levels, mu and lod (fog_lod_method). */
typedef struct window_wavelets {
  int degree, levels;
  float mu;
  int lod_method;
} window_wavelets;
/* The basis, levels J, mu and LOD controls (no header of their own); true on a change. */
bool window_panel_wavelets(panel *ui, window_wavelets *wavelets);

/* One frame as the sources see it. */
typedef struct window_frame {
  GLFWwindow *window;
  gl_context *gl;
  int index;             /* 0 for the first frame */
  double now, dt;        /* glfwGetTime(); seconds since the last frame */
  double fps;            /* smoothed frames per second */
  int fb_w, fb_h;        /* the framebuffer, > 0 */
  bool keyboard, mouse;  /* the panel does not hold them */
  const free_camera *fc; /* moved for this frame */
} window_frame;

typedef struct window_source {
  void *self;
  int look_buttons;      /* FREE_CAMERA_LOOK_* the camera looks with */
  /* Optional (NULL: look_buttons always): the mask for this frame, when a tool takes a
   * button (the lamp tool's right click removes a lamp). */
  int (*look_buttons_now)(const void *self);
  double camera_speed;   /* world units per second */
  /* The source's panel sections (inside the shell's window). */
  void (*panel)(void *self, panel *ui, const window_frame *f);
  /* Keys, mouse and time before the draw. */
  int (*input)(void *self, const window_frame *f, fog_error *err);
  /* The frame into the window's back buffer (fb_w x fb_h). */
  int (*draw)(void *self, const window_frame *f, fog_error *err);
  void (*destroy)(void *self);
} window_source;

/* The simulated source of cfg (its model has a pyramid) in the current window context. */
int window_pipeline_source(window_source *src, gl_context *gl, scene_config *cfg,
                           const window_options *opts, fog_error *err);
/* The fog as cfg holds it, in the current window context; fit (NULL: none; taken over, even
 * on failure) is the ladder that --fit made before the window opened. */
int window_session_source(window_source *src, gl_context *gl, const scene_config *cfg,
                          const window_options *opts, fit_result *fit, fog_error *err);

#endif
