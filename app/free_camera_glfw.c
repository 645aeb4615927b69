/* The free camera's input from GLFW (app/free_camera.h): the window commands' part. */
#include <GLFW/glfw3.h>

#include "app/free_camera.h"

static int held(GLFWwindow *window, int key) { return glfwGetKey(window, key) == GLFW_PRESS; }

free_camera_input free_camera_read(GLFWwindow *window, int look_buttons, bool keyboard,
                                   bool mouse) {
  free_camera_input in = {0};
  glfwGetCursorPos(window, &in.cursor_x, &in.cursor_y);
  if (mouse)
    in.look = ((look_buttons & FREE_CAMERA_LOOK_MIDDLE) &&
               glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS) ||
              ((look_buttons & FREE_CAMERA_LOOK_RIGHT) &&
               glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS);
  /* Ctrl + a key is a command (the brush's Ctrl+S), not a step */
  if (!keyboard || held(window, GLFW_KEY_LEFT_CONTROL) || held(window, GLFW_KEY_RIGHT_CONTROL))
    return in;
  in.forward = held(window, GLFW_KEY_W) - held(window, GLFW_KEY_S);
  in.right = held(window, GLFW_KEY_D) - held(window, GLFW_KEY_A);
  in.up = held(window, GLFW_KEY_E) - held(window, GLFW_KEY_Q);
  in.turn_right = held(window, GLFW_KEY_RIGHT) - held(window, GLFW_KEY_LEFT);
  in.turn_up = held(window, GLFW_KEY_UP) - held(window, GLFW_KEY_DOWN);
  in.fast = held(window, GLFW_KEY_LEFT_SHIFT) || held(window, GLFW_KEY_RIGHT_SHIFT);
  return in;
}
