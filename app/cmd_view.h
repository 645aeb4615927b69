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
} view_options;

/* Opens the window (title) and runs until it closes or the screenshot is taken; errors
 * printed as `fogpipe view: ...`. The process exit status. */
int view_window_run(const scene_config *cfg, const char *title, const view_options *opts);

#endif
