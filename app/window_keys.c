/* The frame's keyboard snapshot (app/window_keys.h). */
#include "app/window_keys.h"

#include <GLFW/glfw3.h>

static bool down[GLFW_KEY_LAST + 1];

void window_keys_read(GLFWwindow *window) {
  for (int key = GLFW_KEY_SPACE; key <= GLFW_KEY_LAST; key++)
    down[key] = glfwGetKey(window, key) == GLFW_PRESS; /* codes GLFW names no key: up */
}

bool window_key_down(int key) { return key >= 0 && key <= GLFW_KEY_LAST && down[key]; }
