/* Window output: a linear-colour texture drawn over the whole default framebuffer with the
 * display transform (render/display.h), the sRGB transfer function (IEC 61966-2-1) and its
 * 8-bit dither, as `fogpipe render` encodes its PNGs, and the window read back for
 * screenshots. The app draws windows through this and never calls GL
 * itself.
 *
 *   gl_presenter_create()   compiles the program (a current GL context)
 *   gl_presenter_draw()     per frame, before the swap
 *   gl_read_window()        the window's back buffer, for --screenshot
 *   gl_presenter_destroy() */
#ifndef FOGPIPE_RENDER_GL_PRESENT_H
#define FOGPIPE_RENDER_GL_PRESENT_H

#include <stdbool.h>

#include "render/display.h"
#include "render/gl_util.h"

typedef struct gl_presenter gl_presenter;

typedef enum gl_present_scaling {
  GL_PRESENT_NEAREST = 0, /* every window pixel shows one texel (a crisp view) */
  GL_PRESENT_BILINEAR,    /* the texture's own filter (the simulated demo's reduced scale) */
} gl_present_scaling;

gl_presenter *gl_presenter_create(fog_error *err);
void gl_presenter_destroy(gl_presenter *presenter);
/* Draws colour attachment 0 of source scaled to the window's width x height, through the
 * display transform (render/display.h). */
void gl_presenter_draw(gl_presenter *presenter, const gl_target *source, int width, int height,
                       gl_present_scaling scaling, const display_transform *display);
/* The default framebuffer's back buffer as RGB floats, rows top first. */
int gl_read_window(int width, int height, float *rgb, fog_error *err);
/* One texel of colour attachment `attachment` of target at image pixel (x, y), row 0 at the
 * top; NAN on a GL error. */
float gl_target_read_texel(const gl_target *target, int attachment, int x, int y);
/* Waits for the GL to finish every command (for timing). */
void gl_finish(void);

#endif
