/* Terrain: a heightfield over the XZ plane (Y up), procedural (fBm value noise with a
 * seed) or from a height image, and its exact CPU ray intersection. The GL scene pass
 * draws exactly the triangles this file intersects, so the CPU distance is a reference
 * for the GL distance texture. (Part of the render library; include "render/render.h".)
 *
 * Grid: vertex (i, j), i < resolution_x, j < resolution_z, sits at world
 *   x = origin[0] + i * size[0] / (resolution_x - 1),  z = origin[2] + j * size[1] / (resolution_z - 1),
 *   y = origin[1] + height * h[j * resolution_x + i],   h in [0, 1].
 * Cell (i, j) is split into two triangles along the diagonal from (i+1, j) to (i, j+1):
 *   {(i,j), (i,j+1), (i+1,j)} and {(i+1,j), (i,j+1), (i+1,j+1)}. */
#ifndef FOGPIPE_RENDER_TERRAIN_H
#define FOGPIPE_RENDER_TERRAIN_H

#include <stdbool.h>

#include "transform/fog_error.h"

/* The largest procedural terrain, vertices per side (and a heightmap's largest pixel count,
 * squared): its mesh, 36 bytes a vertex, must stay under 2 GiB, past which Mesa's GL
 * buffers fail (a terrain of 7750 crashed in the driver). */
#define TERRAIN_MAX_RESOLUTION 7681

/* Every value is taken as given (a scene config supplies its own defaults): a zero is
 * refused where it means nothing, never read as "the default". */
typedef struct terrain_desc {
  double origin[3];  /* world position of vertex (0, 0) at h = 0 (the min corner) */
  double size[2];    /* extent in X and Z, > 0 */
  double height;     /* world height of h = 1, >= 0 (0: flat) */
  /* Heights from an image (e.g. a 16-bit grey PNG loaded by the app), values in [0, 1],
   * row-major, top image row = z index 0. NULL: procedural. */
  const float *heights;
  int heights_width, heights_height;
  /* Procedural terrain (heights == NULL): grid vertices per side (2 to
   * TERRAIN_MAX_RESOLUTION), fBm of value noise: octaves (1 to 16), features across the
   * terrain at the first octave (> 0), amplitude falloff per octave (in (0, 1]), seed.
   * Unread with heights. */
  int resolution;
  int octaves;
  double frequency;
  double persistence;
  unsigned seed;
} terrain_desc;

typedef struct terrain {
  double origin[3];
  double size[2];
  double height;
  int resolution_x, resolution_z;
  float *h;             /* resolution_x * resolution_z, in [0, 1] */
  double min_y, max_y;  /* world height range of the vertices */
} terrain;

int terrain_create(terrain *t, const terrain_desc *desc, fog_error *err);
void terrain_destroy(terrain *t);

/* World position of vertex (i, j) (double). */
void terrain_vertex(const terrain *t, int i, int j, double p[3]);
/* The ground's albedo (linear rgb) at normalised height h (0 to 1) with a normal whose y is
 * normal_y, on a terrain whose h = 1 lies relief world units up: grass, drier up the
 * slopes of hills (from 1 unit of relief, in full from 10), rock where steep, snow on the upper
 * fifth of hills with 10 to 40 units of relief or more (flat ground and a field's bumps
 * stay grass). */
void terrain_albedo(double h, double normal_y, double relief, float out[3]);
/* World height of the triangulated surface at (x, z) (clamped to the terrain's edge). */
double terrain_height_at(const terrain *t, double x, double z);
/* The least height of the surface over [x0, x1] x [z0, z1] (x0 <= x1, z0 <= z1), exact. */
double terrain_lowest_in(const terrain *t, double x0, double x1, double z0, double z1);

/* First hit of the ray origin + s * dir (dir need not be unit length), s in (0, s_max],
 * on the triangle mesh: walks the cells the ray crosses (2D DDA), so it costs O(cells
 * crossed). Returns true and sets *s (and normal, unit, if non-NULL) on a hit. */
bool terrain_intersect(const terrain *t, const double origin[3], const double dir[3],
                       double s_max, double *s, double normal[3]);
/* The same by testing every triangle: an independent oracle for tests (slow). */
bool terrain_intersect_brute(const terrain *t, const double origin[3], const double dir[3],
                             double s_max, double *s);

/* Ray-triangle intersection (Moller & Trumbore 1997) in double: the hit parameter s > 0 if
 * the ray hits triangle (a, b, c), else returns false. */
bool ray_triangle(const double origin[3], const double dir[3], const double a[3],
                  const double b[3], const double c[3], double *s);

#endif
