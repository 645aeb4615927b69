/* panel: a thin C interface over Dear ImGui (1.86, Debian's libimgui-dev with its GLFW and
 * OpenGL 3 backends), so the window program's panel (demo and view) is written in C. Each widget function
 * is one ImGui call and returns true when the user changed the value this frame.
 *
 * Per frame, on the GL thread, after gl_context_poll_events():
 *   panel_begin_frame(p);
 *   if (panel_window_begin(p, "fog", x, y, w)) { ...widgets... }
 *   panel_window_end(p);
 *   ...render the scene...
 *   panel_end_frame(p);   draws the panel over the current framebuffer
 *   gl_context_swap_buffers(...); */
#ifndef FOGPIPE_APP_PANEL_H
#define FOGPIPE_APP_PANEL_H

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct panel panel;

/* glfw_window is the GLFWwindow* of the current context (gl_context_glfw_window()).
 * ImGui chains the window's existing GLFW callbacks. NULL on failure. */
panel *panel_create(void *glfw_window);
void panel_destroy(panel *p);

void panel_begin_frame(panel *p);
void panel_end_frame(panel *p);

/* True while ImGui uses the mouse or keyboard (the camera and the brush must ignore it). */
bool panel_wants_mouse(const panel *p);
bool panel_wants_keyboard(const panel *p);

/* A window placed at (x, y) with width w on its first use; returns false when collapsed
 * (panel_window_end must be called either way). */
bool panel_window_begin(panel *p, const char *title, float x, float y, float w);
void panel_window_end(panel *p);

bool panel_header(panel *p, const char *label, bool open_by_default);
void panel_text(panel *p, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void panel_separator(panel *p);
void panel_same_line(panel *p);

bool panel_button(panel *p, const char *label);
bool panel_checkbox(panel *p, const char *label, bool *value);
bool panel_slider_float(panel *p, const char *label, float *value, float min, float max,
                        const char *format, bool logarithmic);
bool panel_slider_int(panel *p, const char *label, int *value, int min, int max);
bool panel_combo(panel *p, const char *label, int *current, const char *const *items,
                 int count);
bool panel_color3(panel *p, const char *label, float rgb[3]);
/* A small line plot of values (e.g. a stage's recent timings). */
void panel_plot(panel *p, const char *label, const float *values, int count, float max);

#ifdef __cplusplus
}
#endif

#endif
