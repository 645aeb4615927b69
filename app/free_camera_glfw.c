/* The free camera's input from GLFW (app/free_camera.h): the window commands' part. */
#include <GLFW/glfw3.h>

#include "app/free_camera.h"
#include "app/window_keys.h"

static int held(GLFWwindow *window, int key) { return window_key_down(key); }

free_camera_input free_camera_read(GLFWwindow *window, int look_buttons, bool keyboard,
                                   bool mouse) {
  free_camera_input in = {0};
  glfwGetCursorPos(window, &in.cursor_x, &in.cursor_y);
  if (mouse)
    in.look = ((look_buttons & FREE_CAMERA_LOOK_MIDDLE) &&
               glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS) ||
              ((look_buttons & FREE_CAMERA_LOOK_RIGHT) &&
               glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS);
  /* Every key is read, whether or not it counts: with sticky keys GLFW latches a press until
   * it is read, and a latched press must not move the camera once the panel lets go. */
  const free_camera_input keys = {
      .forward = held(window, GLFW_KEY_W) - held(window, GLFW_KEY_S),
      .right = held(window, GLFW_KEY_D) - held(window, GLFW_KEY_A),
      .up = held(window, GLFW_KEY_E) - held(window, GLFW_KEY_Q),
      .turn_right = held(window, GLFW_KEY_RIGHT) - held(window, GLFW_KEY_LEFT),
      .turn_up = held(window, GLFW_KEY_UP) - held(window, GLFW_KEY_DOWN),
      .fast = held(window, GLFW_KEY_LEFT_SHIFT) || held(window, GLFW_KEY_RIGHT_SHIFT)};
  /* Ctrl + a key is a command (the brush's Ctrl+S), not a step */
  if (!keyboard || held(window, GLFW_KEY_LEFT_CONTROL) || held(window, GLFW_KEY_RIGHT_CONTROL))
    return in;
  in.forward = keys.forward, in.right = keys.right, in.up = keys.up;
  in.turn_right = keys.turn_right, in.turn_up = keys.turn_up, in.fast = keys.fast;
  return in;
}
