/* fogpipe render: the exact extinction integral along view rays, as a double-precision
 * CPU reference and in OpenGL 4.5 core (headless EGL or a GLFW window).
 * The public header of the render library; its parts have their own headers, included
 * here. */
#ifndef FOGPIPE_RENDER_H
#define FOGPIPE_RENDER_H

#include "transform/fog_error.h"
#include "render/gl_context.h"
#include "render/gl_util.h"
#include "render/display.h"
#include "render/gl_present.h"
#include "render/terrain.h"
#include "render/terrain_lod.h"
#include "render/scene.h"
#include "render/camera.h"
#include "render/fog_field.h"
#include "render/fog_occupancy.h"
#include "render/fog_light.h"
#include "render/fog_sun_shadow.h"
#include "render/fog_models.h"
#include "render/fog_pass.h"
#include "render/volume_march.h"

#endif
