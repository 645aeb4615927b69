/* The keyboard as one frame sees it (the window commands). GLFW's sticky keys latch a press
 * until glfwGetKey reads it, and the first read of a frame takes it: the camera read S and
 * Ctrl before the brush did, so a quick Ctrl+S tap never saved. Every key is read once a
 * frame into this snapshot, and every reader of that frame asks the snapshot. One window a
 * process (the window program's). Debian's Dear ImGui 1.86 backend reads no key with
 * glfwGetKey; later ones read the modifiers in their key callback, which would take a
 * latched Ctrl before the snapshot (app/window_ctrl_s_tap would say so). */
#ifndef FOGPIPE_APP_WINDOW_KEYS_H
#define FOGPIPE_APP_WINDOW_KEYS_H

#include <stdbool.h>

typedef struct GLFWwindow GLFWwindow;

/* Reads every key of window (GLFW_KEY_SPACE .. GLFW_KEY_LAST) into the snapshot. */
void window_keys_read(GLFWwindow *window);
/* Whether key was down (or pressed since the last read: sticky) at the last read. */
bool window_key_down(int key);

#endif
