/* The sun's shadow map of the terrain and boxes: V(u) in docs/light.md, the sun's
 * visibility past the scene's surfaces. An orthographic depth map looking along the
 * sunlight, fitted around the terrain's and boxes' bounds; the scene pass renders it
 * (scene_pass_run, again whenever the sun moves) and shadows the surfaces with it, the fog
 * pass reads it for light shafts (fog_pass_params.shafts).
 *
 * Light space: axes e0, e1 across the sunlight and the unit vector towards the sun, centred
 * on the bounds' centre; a point's map coordinates are u, v in [0, 1] across and its depth
 * (hi - z)/(hi - lo) along (0: nearest the sun). This header is GL-free for the map's
 * placement (its CPU twin); the GL objects live in scene.c. */
#ifndef FOGPIPE_RENDER_SUN_SHADOW_MAP_H
#define FOGPIPE_RENDER_SUN_SHADOW_MAP_H

#include <stdbool.h>

typedef struct sun_shadow_map {
  int size;            /* texels per side */
  unsigned texture;    /* GL depth texture (DEPTH_COMPONENT32F), compare mode on */
  double centre[3];    /* world origin of light space */
  double axis[3][3];   /* e0, e1, and the unit vector towards the sun */
  double lo[3], hi[3]; /* light-space bounds of the scene */
  double sun[3];       /* the direction it was fitted (and rendered) for */
} sun_shadow_map;

/* Fits light space for the unit direction sun towards the sun around the world box
 * [box_min, box_max] (the scene's surfaces). */
void sun_shadow_map_fit(sun_shadow_map *map, const double sun[3], const double box_min[3],
                        const double box_max[3]);

/* The affine map from a point relative to `origin` (the camera) to (u, v, depth) in the
 * map, as a row-major 4x4 (last row 0 0 0 1), computed in double: what the shaders take. */
void sun_shadow_map_matrix(const sun_shadow_map *map, const double origin[3], double m[4][4]);

/* World size of one texel across the sunlight (the larger of the two axes). */
double sun_shadow_map_texel(const sun_shadow_map *map);

#endif
