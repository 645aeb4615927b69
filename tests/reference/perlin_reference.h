/* Perlin turbulence fog (render/fog_perlin.h) as a medium of the light reference
 * (tests/reference/fog_light_reference.h): its density evaluated here from the octaves'
 * texels as the header defines it (trilinear between texels, wrapped; the height factor; 0
 * outside the box), and its breaks every crossing of an integer texel plane of any octave
 * (listed, not walked). Written apart from fog_perlin.c's walks; it shares the texels.
 * p and m are referenced: they must outlive the medium. */
#ifndef FOGPIPE_TESTS_REFERENCE_PERLIN_REFERENCE_H
#define FOGPIPE_TESTS_REFERENCE_PERLIN_REFERENCE_H

#include "reference/fog_light_reference.h"
#include "render/fog_perlin.h"

light_ref_medium light_ref_perlin_medium(const fog_perlin *p, const fog_perlin_medium *m);
/* T(x, time) from the texels, the height factor left out. */
double perlin_ref_turbulence(const fog_perlin *p, double time, const double x[3]);

#endif
