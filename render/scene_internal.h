/* The scene pass's insides (render/scene.h), shared by the files that draw with it:
 * scene.c (the surfaces and the sun's shadow map) and scene_lamp_shadow.c (the lamps'
 * shadow cubes). Not a public header: nothing outside render/scene*.c includes it. */
#ifndef FOGPIPE_RENDER_SCENE_INTERNAL_H
#define FOGPIPE_RENDER_SCENE_INTERNAL_H

#include "render/lamp_shadow_map.h"
#include "render/scene.h"
#include "render/terrain_lod.h"

typedef struct scene_tile_order {
  double distance; /* squared, camera to the tile's box */
  int tile;
} scene_tile_order;

typedef struct scene_tile {
  double lo[3], hi[3]; /* world; the float vertices as the GPU gets them */
  GLsizei first, count; /* index range: one triangle strip per row of quads */
  int triangles;
} scene_tile;

struct scene_pass {
  const scene_geometry *geo;
  GLuint surface_program, sky_program;
  GLuint vao, vertex_buffer, index_buffer;
  GLsizei index_count;
  scene_tile *tiles;
  int tile_count;
  GLsizei box_first; /* the boxes' indices: [box_first, index_count), always drawn */
  GLsizei *draw_counts; /* per frame: the merged index ranges of the drawn tiles */
  const void **draw_offsets;
  long triangles_drawn;
  /* Terrain LOD (render/terrain_lod.h): off while lod_pixels is 0 (the full mesh, drawn
   * from the static strips above); on, each run streams the visible tiles' triangles. */
  double lod_pixels;
  terrain_lod lod;
  GLuint lod_index_buffer;
  uint32_t *lod_indices;
  scene_tile_order *lod_order; /* the visible tiles, sorted near to far */
  /* The sun's shadow map (render/sun_shadow_map.h), rendered for `shadow.sun`. */
  sun_shadow_map shadow;
  GLuint shadow_framebuffer;
  bool shadow_rendered;
  /* uniform locations */
  GLint u_offset, u_view, u_projection, u_far_plane, u_sun_direction, u_sun_colour, u_ambient;
  GLint u_sun_from_relative, u_sun_visibility, u_sun_normal_offset, u_lod_lift;
  GLint u_lamp_count, u_lamp_position, u_lamp_intensity, u_lamp_axis, u_lamp_cone;
  fog_lamps lamps; /* scene_pass_set_lamps: they light the surfaces too */
  /* The lamps' shadow cubes (render/scene_lamp_shadow.c); lamp_shadow_size 0: none. */
  int lamp_shadow_size;
  lamp_shadow_maps lamp_shadows;
  GLuint lamp_shadow_program, lamp_shadow_framebuffer;
  GLint u_shadow_offset, u_shadow_clip, u_shadow_inv_far;
  GLint u_lamp_shadow_map, u_lamp_shadow_inv_far, u_lamp_shadow_slack, u_lamp_shadows_on,
      u_lamp_shadow_lift;
  GLint u_sky_right, u_sky_up, u_sky_forward, u_sky_viewport, u_sky_horizon, u_sky_zenith,
      u_sky_sun_direction, u_sky_sun_colour;
};

/* The terrain tiles to draw into draw_counts / draw_offsets, adjacent ones merged: those
 * whose box, relative to eye, `culled` keeps (returns false for). Their range count; the
 * triangles they hold in *triangles (if non-NULL). */
typedef bool (*scene_box_culled)(const void *user, const double lo[3], const double hi[3]);
GLsizei scene_tile_ranges(scene_pass *pass, const double eye[3], scene_box_culled culled,
                          const void *user, long *triangles);

/* The lamps' shadow cubes: render those whose lamp moved (scene_pass_set_lamps and
 * scene_pass_set_lamp_shadows; they leave framebuffer 0 bound and the GL state of their
 * draw, which scene_pass_run and the fog pass set again), and release them. */
int scene_lamp_shadows_update(scene_pass *pass, fog_error *err);
void scene_lamp_shadows_destroy(scene_pass *pass);
/* The surface program's lamp-shadow uniforms (lamp_shadow.glsl; the program in use), the
 * cubes on texture unit `unit`. */
void scene_lamp_shadows_bind(const scene_pass *pass, int unit);

#endif
