/* The free camera's motion (app/free_camera.h). */
#include "app/free_camera.h"

#include <math.h>

void free_camera_step(free_camera *fc, const free_camera_input *in, double dt) {
  camera *cam = &fc->cam;
  if (in->look && fc->looking) {
    cam->yaw += FREE_CAMERA_LOOK_RATE * (in->cursor_x - fc->last_x);
    cam->pitch -= FREE_CAMERA_LOOK_RATE * (in->cursor_y - fc->last_y);
  }
  fc->looking = in->look;
  fc->last_x = in->cursor_x, fc->last_y = in->cursor_y;
  cam->yaw += FREE_CAMERA_TURN_RATE * dt * in->turn_right;
  cam->pitch += FREE_CAMERA_TURN_RATE * dt * in->turn_up;
  cam->pitch = fmax(-FREE_CAMERA_PITCH_LIMIT, fmin(FREE_CAMERA_PITCH_LIMIT, cam->pitch));
  const double forward[3] = {sin(cam->yaw) * cos(cam->pitch), sin(cam->pitch),
                             -cos(cam->yaw) * cos(cam->pitch)};
  const double right[3] = {cos(cam->yaw), 0.0, sin(cam->yaw)};
  const double step = fc->speed * dt * (in->fast ? FREE_CAMERA_FAST : 1.0);
  for (int i = 0; i < 3; i++)
    cam->position[i] += step * (in->forward * forward[i] + in->right * right[i]);
  cam->position[1] += step * in->up;
}
