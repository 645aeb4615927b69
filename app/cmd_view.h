/* The window program of `fogpipe view`, which `fogpipe demo` also opens for the models
 * without a simulation: the scene config with a free camera, a volume's VDB sequence
 * played. Part of the executable (app/cmd_view.c). */
#ifndef FOGPIPE_APP_CMD_VIEW_H
#define FOGPIPE_APP_CMD_VIEW_H

#include <stdbool.h>

#include "app/config.h"

typedef struct view_options {
  int width, height;         /* the window; 0: the config's [render] size */
  double render_scale;       /* render at this times the window size, > 0 */
  bool play;                 /* start playing a volume's sequence */
  const char *screenshot;    /* save the last frame as a PNG and return; NULL: run */
  int frames;                /* frames before the screenshot, >= 1 */
  /* `fogpipe fit` before the window opens (app/fit.h): the window then shows the rungs,
   * [ and ] step through them, 0 returns to the config's own fog; the title gives each
   * one's measured error and time beside the window's frame rate. */
  bool fit;
  double fit_tolerance;      /* > 0: the pick the window starts on */
  int rung;                  /* >= 0: start on this rung instead; -1: the pick */
} view_options;

/* Opens the window (title) and runs until it closes or the screenshot is taken; errors
 * printed as `fogpipe view: ...`. The process exit status. */
int view_window_run(const scene_config *cfg, const char *title, const view_options *opts);

#endif
