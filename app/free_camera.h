/* The free camera of the window commands (`demo` and `view`): one set of controls.
 *
 *   W A S D     move along the view and across it; Q / E down / up; Shift 4x faster
 *   look        drag with a look button (middle; over the fog as held, `view`'s, the right
 *               button too, which the simulated fog keeps for erasing), or the arrow keys
 *   Ctrl + key  a command (the brush's Ctrl+S), not a step
 *
 * free_camera_step is the motion, pure (tested without a window); free_camera_read samples
 * GLFW for it (app/free_camera_glfw.c, in the executable). */
#ifndef FOGPIPE_APP_FREE_CAMERA_H
#define FOGPIPE_APP_FREE_CAMERA_H

#include <stdbool.h>

#include "render/camera.h"

#define FREE_CAMERA_LOOK_RATE 0.004 /* radians of yaw or pitch per pixel dragged */
#define FREE_CAMERA_TURN_RATE 1.2   /* radians per second with an arrow key */
/* straight up or down at most: the camera's basis holds there (right is horizontal, from
 * the yaw alone), so a config's pitch of -90 opens as `render` draws it (1.55 turned it to
 * -88.8 degrees) */
#define FREE_CAMERA_PITCH_LIMIT 1.5707963267948966
#define FREE_CAMERA_FAST 4.0        /* Shift */

/* One frame's input: the cursor, whether a look button is held, and the keys as -1/0/1. */
typedef struct free_camera_input {
  double cursor_x, cursor_y;
  bool look;
  int forward, right, up; /* W - S, D - A, E - Q */
  int turn_right, turn_up; /* Right - Left, Up - Down */
  bool fast;
} free_camera_input;

typedef struct free_camera {
  camera cam;
  double speed; /* world units per second */
  double last_x, last_y;
  bool looking; /* a drag is under way: the next look turns by the cursor's motion */
} free_camera;

/* Moves and turns fc for one frame of dt seconds (camera.h's yaw and pitch: yaw = pitch = 0
 * looks along -Z, positive yaw toward +X; forward follows the pitch, right stays level). */
void free_camera_step(free_camera *fc, const free_camera_input *in, double dt);

/* Which buttons look around (free_camera_read). */
enum { FREE_CAMERA_LOOK_MIDDLE = 1, FREE_CAMERA_LOOK_RIGHT = 2 };

typedef struct GLFWwindow GLFWwindow;
/* The window's input now: keys only when `keyboard` (no UI has them), buttons only when
 * `mouse`; look_buttons a mask of FREE_CAMERA_LOOK_*. */
free_camera_input free_camera_read(GLFWwindow *window, int look_buttons, bool keyboard,
                                   bool mouse);

#endif
