/* The scene the fog sits in: a terrain heightfield, a few boxes standing on it, a sun and
 * a sky. Two halves (part of the render library; include "render/render.h"):
 *   - scene_geometry (CPU, double): the terrain and the boxes, and the exact first-hit
 *     distance along any ray: the reference the GL distance texture is tested against and
 *     what CPU fog references clip their rays with;
 *   - scene_pass (GL): rasterises that geometry into a render target holding
 *       attachment 0: surface colour, RGBA32F (linear, lit; sky where nothing is hit;
 *                     float: a lamp-lit surface may pass half's 65504),
 *       attachment 1: surface DISTANCE, R32F: Euclidean distance from the camera to the
 *                     first surface along the pixel's ray (SCENE_SKY_DISTANCE for sky),
 *       attachment 2: the sun-lit share of the colour, RGBA32F (0 for the sky): what the
 *                     fog's shadow on the surfaces dims (fog_pass_params.surface_sun),
 *       a depth buffer (DEPTH32F).
 *     The fog pass (render/fog_pass.h) reads the colour and distance textures.
 * Coordinates are camera-relative on the GPU (camera.h): vertices are stored relative to
 * the terrain origin and shifted by (origin - camera position), computed in double. */
#ifndef FOGPIPE_RENDER_SCENE_H
#define FOGPIPE_RENDER_SCENE_H

#include <stdbool.h>

#include "render/camera.h"
#include "render/fog_lamp.h"
#include "render/gl_util.h"
#include "render/lamp_shadow_map.h"
#include "transform/fog_error.h"
#include "render/sun_shadow_map.h"
#include "render/terrain.h"

/* What the distance texture holds where a ray hits nothing (sky). */
#define SCENE_SKY_DISTANCE 1e30f
#define SCENE_MAX_BOXES 16

/* A light grey albedo: a box's colour when a config gives none. */
#define SCENE_BOX_GREY {0.55f, 0.53f, 0.50f}

/* A box standing on the terrain: centred at (x, z) in world, size width (X) x height (Y)
 * x depth (Z); its bottom is placed at the lowest terrain height under its footprint, so
 * it never floats. colour is linear albedo, as given (0 is black; configs default to
 * SCENE_BOX_GREY). */
typedef struct scene_box_desc {
  double center[2]; /* x, z */
  double size[3];
  float colour[3];
} scene_box_desc;

/* The sun and the sky. Every field means what it says, zero included (an elevation of 0 is
 * the horizon, a colour of 0 black): start from scene_light_default(). */
typedef struct scene_light {
  double sun_azimuth;    /* degrees, like camera yaw: 0 toward -Z, 90 toward +X */
  double sun_elevation;  /* degrees above the horizon */
  float sun_colour[3];   /* linear radiance multiplier */
  float ambient[3];      /* sky-light on upward surfaces */
  float sky_horizon[3];
  float sky_zenith[3];
} scene_light;

/* Azimuth 0, elevation 35, sun (1.9, 1.8, 1.6), ambient (0.30, 0.36, 0.45), sky from
 * (0.72, 0.78, 0.85) at the horizon to (0.28, 0.45, 0.75) at the zenith. */
scene_light scene_light_default(void);

typedef struct scene_desc {
  terrain_desc terrain;
  scene_box_desc boxes[SCENE_MAX_BOXES];
  int box_count;
  scene_light light;
} scene_desc;

typedef struct scene_box {
  double min[3], max[3];
  float colour[3];
} scene_box;

typedef struct scene_geometry {
  terrain terrain;
  scene_box boxes[SCENE_MAX_BOXES];
  int box_count;
  scene_light light;        /* the desc's (the window panel's time of day moves it) */
  double sun_direction[3];  /* unit vector toward the sun, from azimuth and elevation */
} scene_geometry;

int scene_geometry_create(scene_geometry *geo, const scene_desc *desc, fog_error *err);
void scene_geometry_destroy(scene_geometry *geo);
/* The world box around the terrain and the boxes (what the shadow maps must cover). */
void scene_geometry_bounds(const scene_geometry *geo, double lo[3], double hi[3]);
/* The unit direction towards the light's sun (what the surfaces and the fog are lit by). */
void scene_light_sun_direction(const scene_light *light, double sun_direction[3]);

/* First hit along origin + s * dir (dir unit length: s is the Euclidean distance) for
 * s in (0, s_max], on the terrain mesh or a box (whose bottom is open, as the GL draws
 * it). Returns true and sets *s (and if non-NULL the unit normal of the side the ray sees,
 * facing against dir). */
bool scene_geometry_intersect(const scene_geometry *geo, const double origin[3],
                              const double dir[3], double s_max, double *s, double normal[3]);
/* The value the distance texture should hold at pixel (px, py) (row 0 at the top): the
 * first-hit distance along camera_ray, or SCENE_SKY_DISTANCE. */
double scene_geometry_pixel_distance(const scene_geometry *geo, const camera *cam, int px,
                                     int py, int width, int height);

/* The GL half. */
typedef struct scene_pass scene_pass;

/* Uploads geo's meshes and builds the shaders; geo must outlive the pass. */
scene_pass *scene_pass_create(const scene_geometry *geo, fog_error *err);
void scene_pass_destroy(scene_pass *pass);
/* Draws sky, terrain and boxes into target (made by scene_target_create, or any target
 * with colour 0 and R32F colour 1 and a depth buffer; colour 2 optional), at the target's size. Does not
 * allocate. */
void scene_pass_run(scene_pass *pass, const camera *cam, const gl_target *target);
/* The lamps that light the surfaces (render/fog_lamp.h; copied; none until set): Lambertian,
 * irradiance I cos / (d^2 + r^2) times the spot's cone and V, the lamp's visibility past
 * the terrain and boxes (its shadow cube, rendered here for each lamp that moved since its
 * last), not dimmed by the fog. Fails only when GL does (the cubes' memory). */
int scene_pass_set_lamps(scene_pass *pass, const fog_lamps *lamps, fog_error *err);
/* The lamps' shadow cubes (render/lamp_shadow_map.h): `size` texels per face side, in
 * LAMP_SHADOW_SIZE_MIN..MAX, or 0: no lamp shadows (V = 1). LAMP_SHADOW_SIZE at creation. */
int scene_pass_set_lamp_shadows(scene_pass *pass, int size, fog_error *err);
/* The cubes of the lamps set, for the fog's shafts (fog_pass_params.lamp_shadows); NULL when
 * lamp shadows are off or there are no lamps. */
const lamp_shadow_maps *scene_pass_lamp_shadows(const scene_pass *pass);
/* The sun's shadow map the surfaces are shadowed with (rendered by each run whose sun
 * differs from the map's, the first included): for the fog's light shafts, drawn after a
 * run. */
const sun_shadow_map *scene_pass_sun_shadow(const scene_pass *pass);
/* Texels per side of the sun's shadow map: 2048 cover the default 1200-unit terrain at
 * ~0.8 units a texel. */
#define SCENE_SUN_SHADOW_SIZE 2048
/* Terrain level of detail (render/terrain_lod.h): each run draws every visible tile at the
 * coarsest level whose height error spans at most max_pixels on screen, seams stitched
 * watertight. 0 (the state at creation): the full mesh, exactly the triangles
 * terrain_intersect hits. The shadow map always draws the full mesh. */
int scene_pass_set_terrain_lod(scene_pass *pass, double max_pixels, fog_error *err);
/* Triangles the last run drew: the terrain tiles in the camera's view, and the boxes. */
long scene_pass_triangles_drawn(const scene_pass *pass);
/* Whether the scene pass may cull the terrain's back faces for this camera (above the
 * height field: no ray from there meets a back face first). */
bool scene_terrain_back_faces_hidden(const terrain *t, const camera *cam);

/* A render target with the scene pass's layout (RGBA32F colour, R32F distance, RGBA32F
 * sun-lit share, RGBA32F lamps' share, depth). */
int scene_target_create(gl_target *target, int width, int height, fog_error *err);

#endif
