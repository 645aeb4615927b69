/* GLSL text generated from the C headers, so that no shader retypes a C constant or the
 * list of models:
 *   fog_constants.glsl    #defines of the model kinds (render/fog_models.def), the profile
 *                         kinds, the grid-slot, level, RBF and profile caps, the series
 *                         switches
 *   fog_model_table.glsl  fog_model_optical_depth(fog_ray): the twin of the variant's
 *                         FOG_MODEL_KIND, exact or marched (FOG_INTEGRATOR), one branch
 *                         per table row
 * gl_util_shader_text's #include expansion takes these names from here before it looks for
 * an embedded file of render/shaders/. */
#ifndef FOGPIPE_RENDER_FOG_SHADER_TEXT_H
#define FOGPIPE_RENDER_FOG_SHADER_TEXT_H

#include <stddef.h>

/* Upper bound of a generated file's length (a test checks it is enough). */
#define FOG_SHADER_GENERATED_MAX 4096

/* Writes generated file `name` into out (cap bytes, NUL-terminated) and returns its length;
 * -1 when name is not one of them, -2 when cap is too small. */
int fog_shader_generated(const char *name, char *out, size_t cap);

#endif
