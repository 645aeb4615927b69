/* fogpipe render: the exact extinction integral along view rays, as a double-precision
 * CPU reference and in OpenGL 4.5 core (headless EGL or a GLFW window).
 * The public header of the render library; its parts have their own headers, included
 * here. */
#ifndef FOGPIPE_RENDER_H
#define FOGPIPE_RENDER_H

#include "render/render_error.h"
#include "render/gl_context.h"

#endif
