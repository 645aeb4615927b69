/* `fogpipe record` as a function: the recording `fogpipe demo` also runs without a
 * display. Part of the executable (app/cmd_record.c), not of fogpipe_app. */
#ifndef FOGPIPE_APP_CMD_RECORD_H
#define FOGPIPE_APP_CMD_RECORD_H

#include <stdbool.h>

/* A whole recording: what `fogpipe record` runs, and `fogpipe demo` without a display. Returns the process exit status (0; 130 when
 * interrupted by SIGINT/SIGTERM after finishing the current frame; 1 on errors, printed as
 * `fogpipe <command>: ...`). */
typedef struct record_job {
  const char *command;     /* "record" or "demo", for messages */
  const char *config_path;
  int first_frame;         /* the range first_frame..frames (farm jobs); 0: 1 */
  int frames;              /* the last frame (with first_frame 1: the frame count) */
  const char *out;
  double fps;              /* frames per second of simulated time (> 0; --fps, 24) */
  bool fps_given;          /* --fps was on the command line (the resume hint repeats it) */
  int width, height;       /* 0: the config's size */
  bool resume;
  const char *preview;     /* video path or NULL */
  bool quiet;              /* no per-frame progress */
  bool synchronous;        /* sim + transform on the GL thread (same frames, slower) */
  /* demo: the folder's frames of an earlier run are removed, once the scene has loaded and
   * before the first frame is written (a scene that fails to load leaves them), and said */
  bool replace_earlier;
} record_job;

int record_run(const record_job *job);

#endif
