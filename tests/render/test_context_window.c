#define _POSIX_C_SOURCE 200809L
/* The window backend without a display fails cleanly: NULL, a one-line message that says
 * there is no display and points at the headless path; no crash, no abort. */
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "test_util.h"

int main(void) {
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  fog_error err = {0};
  gl_context *ctx =
      gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_WINDOW, .width = 64, .height = 48}, &err);
  CHECK(ctx == NULL, "a window context was created without a display");
  if (ctx) gl_context_destroy(ctx);
  CHECK(strstr(err.message, "no display") != NULL, "message: %s", err.message);
  CHECK(strchr(err.message, '\n') == NULL, "message is not one line: %s", err.message);
  printf("message: %s\n", err.message);
  /* The headless backend still works in the same process afterwards. */
  fog_error err2 = {0};
  ctx = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &err2);
  CHECK(ctx != NULL, "headless after failed window: %s", err2.message);
  gl_context_destroy(ctx);
  return test_finish("test_context_window");
}
