/* The lamps' shadow maps of the terrain and boxes: V_i(x) in docs/light.md (Lamps), lamp i's
 * visibility past the scene's surfaces: the shafts a lamp throws through the gaps between
 * boxes and hills, and the shadows it casts on the ground.
 *
 * One depth cube per lamp, the layers 6 i .. 6 i + 5 of a cube-map array, faces in GL's
 * order +X, -X, +Y, -Y, +Z, -Z. A texel holds the distance from the lamp to the first
 * surface in its direction, over the lamp's `far` (every scene surface is nearer than far):
 * linear, so the comparison's slack is one number per lamp. A point lamp renders all six
 * faces; a spot only the faces its outer cone reaches (the others hold 1: nothing there, and
 * its cone is 0 there anyway). The scene pass renders a lamp's cube again when the lamp moves
 * or its cone turns (not when its intensity flickers).
 *
 * The lookup (lamp_shadow.glsl, the surfaces' and the fog's): a point x at distance d from
 * lamp i is lit when d (1 - slack) <= the cube's distance in the direction of x, 2 x 2
 * filtered (PCF); slack = LAMP_SHADOW_SLACK_TEXELS texels' angle, since a texel's distance
 * spans about d times its angle along a surface seen face on. The surfaces look up from
 * a point moved the same distance along their normal (no acne where the lamp grazes them).
 *
 * This header's functions are GL-free (the faces' projection and culling, tested on the
 * CPU); the GL objects are the scene pass's (render/scene_lamp_shadow.c). */
#ifndef FOGPIPE_RENDER_LAMP_SHADOW_MAP_H
#define FOGPIPE_RENDER_LAMP_SHADOW_MAP_H

#include <stdbool.h>

#include "render/fog_lamp.h"

/* [light] lamp_shadow_size's default and bounds: texels per cube face side. At 512 one
 * texel spans 1/256 rad at a face's centre: 0.2 units at 50 units from the lamp. */
#define LAMP_SHADOW_SIZE 512
#define LAMP_SHADOW_SIZE_MIN 16
#define LAMP_SHADOW_SIZE_MAX 2048
/* The comparison's slack and the surfaces' normal offset, in texels (see above). */
#define LAMP_SHADOW_SLACK_TEXELS 1.5

typedef struct lamp_shadow_maps {
  int size;          /* texels per face side */
  int count;         /* lamps rendered: the cubes 0 .. count-1 match fog_lamps' order */
  int capacity;      /* cubes the texture holds (>= 1) */
  unsigned texture;  /* GL_TEXTURE_CUBE_MAP_ARRAY, DEPTH_COMPONENT32F, compare mode on */
  double far[FOG_MAX_LAMPS]; /* per lamp: depth = distance / far */
  fog_lamp rendered[FOG_MAX_LAMPS]; /* what each cube was rendered for */
  /* Terrain LOD (the scene pass's last run): the drawn surface may lie below the full mesh
   * the cubes hold by up to this much per unit of distance from the camera, so a surface's
   * lookup rises by that (as the sun's does); 0 without LOD. */
  double lift_per_distance;
} lamp_shadow_maps;

/* The world distance past every point of the box [lo, hi] from lamp position p (a margin
 * of 1 % and one unit): the cube's depth scale. */
double lamp_shadow_far(const double p[3], const double lo[3], const double hi[3]);

/* Face f's projection (row-major 4 x 4) from a point v relative to the lamp to clip space,
 * a 90 degree frustum from near to far whose window (x, y) in [-1, 1]^2 is GL's cube-map
 * (s, t) of direction v scaled to [-1, 1] (the spec's table of major axes): so a face
 * rendered with it and sampled with direction v meet at the same texel. */
void lamp_shadow_face_clip(int face, double near_plane, double far_plane, double m[4][4]);

/* Whether face f's frustum (from the lamp, out to infinity) misses the box [lo, hi] given
 * relative to the lamp: the box lies wholly outside one of the face's four side planes. */
bool lamp_shadow_face_culls_box(int face, const double lo[3], const double hi[3]);

/* Whether lamp's light reaches face f: always for a point lamp; for a spot, whether its
 * outer cone meets the face's pyramid (conservatively: the cone's axis within the outer
 * half-angle plus 54.7 degrees, the face's centre-to-corner angle, of the face's axis). */
bool lamp_shadow_face_needed(const fog_lamp *lamp, int face);

/* lamp_shadow.glsl's uniforms for maps, as floats: each cube's 1/far (count of them, the
 * rest 0), the comparison's slack (LAMP_SHADOW_SLACK_TEXELS texels' angle) and the terrain
 * LOD lift. The surfaces' program and the fog pass both set them from here. */
typedef struct lamp_shadow_uniforms {
  float inv_far[FOG_MAX_LAMPS];
  float slack, lift;
} lamp_shadow_uniforms;
lamp_shadow_uniforms lamp_shadow_maps_uniforms(const lamp_shadow_maps *maps);

/* Whether the cube rendered for `was` serves `now`: the same kind, position and cone. */
bool lamp_shadow_same_placement(const fog_lamp *was, const fog_lamp *now);

#endif
