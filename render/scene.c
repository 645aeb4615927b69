/* The scene: CPU geometry (terrain + boxes, exact ray hits) and its GL pass. */
#include "render/scene.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <stdio.h>

#include "render/fog_light.h"
#include "render/frustum.h"
#include "render/scene_internal.h"

#define DEG (3.14159265358979323846 / 180.0)

int scene_geometry_create(scene_geometry *geo, const scene_desc *desc, fog_error *err) {
  *geo = (scene_geometry){0};
  if (desc->box_count < 0 || desc->box_count > SCENE_MAX_BOXES) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%d boxes: at most %d", desc->box_count,
             SCENE_MAX_BOXES);
    return 1;
  }
  if (terrain_create(&geo->terrain, &desc->terrain, err)) return 1;
  const terrain *t = &geo->terrain;
  for (int b = 0; b < desc->box_count; b++) {
    const scene_box_desc *d = &desc->boxes[b];
    if (!(d->size[0] > 0 && d->size[1] > 0 && d->size[2] > 0)) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "box %d has size %g x %g x %g: expected > 0", b + 1,
               d->size[0], d->size[1], d->size[2]);
      terrain_destroy(&geo->terrain);
      return 1;
    }
    scene_box *box = &geo->boxes[geo->box_count++];
    double hx = 0.5 * d->size[0], hz = 0.5 * d->size[2];
    /* The lowest ground under the footprint, exact, so the box never floats (5 x 5
     * samples missed the mesh's dips between them: a slit of up to 6 units under a wide
     * box's walls, through which its open bottom showed) */
    const double ground = terrain_lowest_in(t, d->center[0] - hx, d->center[0] + hx,
                                            d->center[1] - hz, d->center[1] + hz);
    box->min[0] = d->center[0] - hx, box->max[0] = d->center[0] + hx;
    box->min[2] = d->center[1] - hz, box->max[2] = d->center[1] + hz;
    box->min[1] = ground, box->max[1] = ground + d->size[1];
    memcpy(box->colour, d->colour, sizeof box->colour);
  }
  geo->light = desc->light;
  scene_light_sun_direction(&geo->light, geo->sun_direction);
  return 0;
}

void scene_geometry_destroy(scene_geometry *geo) {
  terrain_destroy(&geo->terrain);
  *geo = (scene_geometry){0};
}

void scene_geometry_bounds(const scene_geometry *geo, double lo[3], double hi[3]) {
  const terrain *t = &geo->terrain;
  lo[0] = t->origin[0], lo[1] = t->min_y, lo[2] = t->origin[2];
  hi[0] = t->origin[0] + t->size[0], hi[1] = t->max_y, hi[2] = t->origin[2] + t->size[1];
  for (int b = 0; b < geo->box_count; b++)
    for (int c = 0; c < 3; c++)
      lo[c] = fmin(lo[c], geo->boxes[b].min[c]), hi[c] = fmax(hi[c], geo->boxes[b].max[c]);
}

/* Ray-box (slabs, Kay & Kajiya 1986): nearest s > 0 on the box's surface, which has no
 * bottom face (the GL draws none: it lay in flat ground's plane and z-fought it). */
static bool box_hit(const scene_box *box, const double o[3], const double d[3], double *s,
                    int *axis, int *sign) {
  double s0 = -INFINITY, s1 = INFINITY;
  int a0 = 0, a1 = 0;
  for (int k = 0; k < 3; k++) {
    if (d[k] == 0.0) {
      if (o[k] < box->min[k] || o[k] > box->max[k]) return false;
      continue;
    }
    double a = (box->min[k] - o[k]) / d[k], b = (box->max[k] - o[k]) / d[k];
    if (a > b) { double tmp = a; a = b; b = tmp; }
    if (a > s0) s0 = a, a0 = k;
    if (b < s1) s1 = b, a1 = k;
  }
  if (s0 > s1 || s1 <= 0) return false;
  /* From outside: the entry face; from inside (camera in a box), or in through the open
   * bottom: the exit face, as the rasteriser draws both sides; out through the bottom: no
   * face at all. */
  const bool in_through_bottom = a0 == 1 && d[1] > 0;
  if (s0 > 0 && !in_through_bottom) {
    *s = s0, *axis = a0, *sign = d[a0] > 0 ? -1 : 1;
  } else {
    if (a1 == 1 && d[1] < 0) return false;
    *s = s1, *axis = a1, *sign = d[a1] > 0 ? 1 : -1;
  }
  return true;
}

bool scene_geometry_intersect(const scene_geometry *geo, const double origin[3],
                              const double dir[3], double s_max, double *s, double normal[3]) {
  double best = s_max, hit_s;
  bool found = false;
  if (terrain_intersect(&geo->terrain, origin, dir, best, &hit_s, normal)) {
    best = hit_s;
    found = true;
  }
  for (int b = 0; b < geo->box_count; b++) {
    int axis, sign;
    if (box_hit(&geo->boxes[b], origin, dir, &hit_s, &axis, &sign) && hit_s < best) {
      best = hit_s;
      found = true;
      if (normal) {
        normal[0] = normal[1] = normal[2] = 0.0;
        normal[axis] = sign;
      }
    }
  }
  if (found) *s = best;
  /* the side the ray sees, as the shader turns the normal towards the camera: a box's
   * inside seen from in it, the terrain from below */
  if (found && normal && normal[0] * dir[0] + normal[1] * dir[1] + normal[2] * dir[2] > 0)
    for (int c = 0; c < 3; c++) normal[c] = -normal[c];
  return found;
}

double scene_geometry_pixel_distance(const scene_geometry *geo, const camera *cam, int px,
                                     int py, int width, int height) {
  double o[3], d[3], s;
  camera_ray(cam, px, py, width, height, o, d);
  return scene_geometry_intersect(geo, o, d, INFINITY, &s, NULL) ? s : SCENE_SKY_DISTANCE;
}

/* ---------------- GL ---------------- */

/* The terrain is drawn in tiles of TILE x TILE quads, each a contiguous range of the index
 * buffer with its bounding box, and a frame draws only the tiles its frustum does not cull:
 * on llvmpipe the scene pass costs about its triangle count (half the terrain's
 * triangles: 15 -> 9 ms per frame). The default view keeps 76 % of the tiles, a view down
 * or along an edge far fewer (test_scene_distance); 8 x 8 tiles measured the same. Each
 * tile is a triangle strip per row of quads, separated by restart indices: the same
 * triangles as a list, 0.5-1.7 ms faster on llvmpipe (six A/B pairs), 2.6x fewer indices. */
#define TILE 16
#define RESTART 0xFFFFFFFFu /* GL_PRIMITIVE_RESTART_FIXED_INDEX for unsigned int */

typedef struct vertex {
  float position[3]; /* relative to the terrain origin */
  float normal[3];
  float albedo[3];
} vertex;

/* The terrain's vertices, relative to its origin, with smooth normals and albedo. */
static void terrain_mesh_vertices(const terrain *t, vertex *vertices) {
  int rx = t->resolution_x, rz = t->resolution_z;
  double dx = t->size[0] / (rx - 1), dz = t->size[1] / (rz - 1);
  const float *h = t->h;
  for (int j = 0; j < rz; j++)
    for (int i = 0; i < rx; i++) {
      double p[3];
      terrain_vertex(t, i, j, p);
      /* Smooth normal from central differences of the heights. */
      int i0 = i > 0 ? i - 1 : i, i1 = i < rx - 1 ? i + 1 : i;
      int j0 = j > 0 ? j - 1 : j, j1 = j < rz - 1 ? j + 1 : j;
      double gx = t->height * (h[(size_t)j * rx + i1] - h[(size_t)j * rx + i0]) / ((i1 - i0) * dx);
      double gz = t->height * (h[(size_t)j1 * rx + i] - h[(size_t)j0 * rx + i]) / ((j1 - j0) * dz);
      double n[3] = {-gx, 1.0, -gz}, len = sqrt(n[0] * n[0] + 1.0 + n[2] * n[2]);
      vertex *v = &vertices[(size_t)j * rx + i];
      for (int c = 0; c < 3; c++) {
        v->position[c] = (float)(p[c] - t->origin[c]);
        v->normal[c] = (float)(n[c] / len);
      }
      terrain_albedo(h[(size_t)j * rx + i], n[1] / len, t->height, v->albedo);
    }
}

/* The terrain's triangles, tile by tile (pass->tiles: index ranges and bounding boxes, from
 * the float vertices the GPU draws). Returns the number of indices written. */
static size_t terrain_mesh_tiles(scene_pass *pass, const terrain *t, const vertex *vertices,
                                 GLuint *indices) {
  int rx = t->resolution_x, rz = t->resolution_z;
  int tiles_x = (rx - 1 + TILE - 1) / TILE, tiles_z = (rz - 1 + TILE - 1) / TILE;
  size_t k = 0;
  for (int tz = 0; tz < tiles_z; tz++)
    for (int tx = 0; tx < tiles_x; tx++) {
      scene_tile *tile = &pass->tiles[pass->tile_count++];
      int i0 = tx * TILE, j0 = tz * TILE;
      int i1 = i0 + TILE < rx - 1 ? i0 + TILE : rx - 1;
      int j1 = j0 + TILE < rz - 1 ? j0 + TILE : rz - 1;
      tile->first = (GLsizei)k;
      /* One strip per row of quads: (i, j), (i, j+1), (i+1, j), ... gives the triangles
       * (a, c, b) and (b, c, d) of quad a = (i, j), b = a + 1, c = a + rx, d = c + 1: the
       * triangulation terrain.h documents (diagonal (i+1,j)-(i,j+1)), same winding. */
      for (int j = j0; j < j1; j++) {
        for (int i = i0; i <= i1; i++) {
          indices[k++] = (GLuint)(j * rx + i);
          indices[k++] = (GLuint)((j + 1) * rx + i);
        }
        indices[k++] = RESTART;
      }
      tile->count = (GLsizei)k - tile->first;
      tile->triangles = 2 * (i1 - i0) * (j1 - j0);
      for (int c = 0; c < 3; c++) tile->lo[c] = INFINITY, tile->hi[c] = -INFINITY;
      for (int j = j0; j <= j1; j++)
        for (int i = i0; i <= i1; i++)
          for (int c = 0; c < 3; c++) {
            double p = t->origin[c] + vertices[(size_t)j * rx + i].position[c];
            tile->lo[c] = fmin(tile->lo[c], p);
            tile->hi[c] = fmax(tile->hi[c], p);
          }
    }
  return k;
}

/* The boxes: 5 faces x 4 vertices with flat normals, from vertex `base` on. Returns the
 * number of indices written. No bottom face: a box stands at the lowest terrain height
 * under it, so the terrain hides that face from outside and is the floor seen from inside,
 * where on flat ground the face lay in the terrain's plane and fought it for depth
 * (stripes). */
static size_t box_mesh(const scene_geometry *geo, size_t base, vertex *vertices,
                       GLuint *indices) {
  const double *origin = geo->terrain.origin;
  size_t k = 0;
  for (int b = 0; b < geo->box_count; b++) {
    const scene_box *box = &geo->boxes[b];
    for (int axis = 0; axis < 3; axis++)
      for (int side = 0; side < 2; side++) {
        if (axis == 1 && side == 0) continue; /* the bottom */
        int u = (axis + 1) % 3, w = (axis + 2) % 3;
        for (int corner = 0; corner < 4; corner++) {
          double p[3];
          p[axis] = side ? box->max[axis] : box->min[axis];
          p[u] = (corner & 1) ? box->max[u] : box->min[u];
          p[w] = (corner & 2) ? box->max[w] : box->min[w];
          vertex *v = &vertices[base + corner];
          for (int c = 0; c < 3; c++) {
            v->position[c] = (float)(p[c] - origin[c]);
            v->normal[c] = c == axis ? (side ? 1.0f : -1.0f) : 0.0f;
            v->albedo[c] = box->colour[c];
          }
        }
        GLuint q = (GLuint)base; /* the strip's triangles: (q, q+1, q+2), (q+2, q+1, q+3) */
        indices[k++] = q, indices[k++] = q + 1, indices[k++] = q + 2, indices[k++] = q + 3;
        indices[k++] = RESTART;
        base += 4;
      }
  }
  return k;
}

static int upload_geometry(scene_pass *pass, fog_error *err) {
  const scene_geometry *geo = pass->geo;
  const terrain *t = &geo->terrain;
  int rx = t->resolution_x, rz = t->resolution_z;
  size_t terrain_vertices = (size_t)rx * rz;
  size_t vertex_count = terrain_vertices + 20 * (size_t)geo->box_count;
  size_t tiles_x = (size_t)(rx - 1 + TILE - 1) / TILE;
  size_t tiles = tiles_x * ((size_t)(rz - 1 + TILE - 1) / TILE);
  /* per row of quads, one strip per tile: 2 indices per vertex column and a restart; per
   * box face a 4-index strip and a restart */
  size_t index_count = (size_t)(rz - 1) * (2 * (size_t)(rx - 1) + 3 * tiles_x) +
                       25 * (size_t)geo->box_count;
  vertex *vertices = malloc(vertex_count * sizeof *vertices);
  GLuint *indices = malloc(index_count * sizeof *indices);
  pass->tiles = malloc(tiles * sizeof *pass->tiles);
  pass->draw_counts = malloc(tiles * sizeof *pass->draw_counts);
  pass->draw_offsets = malloc(tiles * sizeof *pass->draw_offsets);
  if (!vertices || !indices || !pass->tiles || !pass->draw_counts || !pass->draw_offsets) {
    free(vertices);
    free(indices);
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the scene meshes");
    return 1; /* the tiles and draw arrays go with the pass */
  }
  terrain_mesh_vertices(t, vertices);
  size_t k = terrain_mesh_tiles(pass, t, vertices, indices);
  pass->box_first = (GLsizei)k;
  k += box_mesh(geo, terrain_vertices, vertices, indices + k);
  if (k != index_count) { /* the count above and the meshes disagree: a bug, not input */
    free(vertices);
    free(indices);
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "scene meshes: %zu indices, %zu expected", k,
             index_count);
    return 1;
  }
  glGenVertexArrays(1, &pass->vao);
  glBindVertexArray(pass->vao);
  glGenBuffers(1, &pass->vertex_buffer);
  glBindBuffer(GL_ARRAY_BUFFER, pass->vertex_buffer);
  glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(vertex_count * sizeof *vertices), vertices,
               GL_STATIC_DRAW);
  glGenBuffers(1, &pass->index_buffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, pass->index_buffer);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(k * sizeof *indices), indices,
               GL_STATIC_DRAW);
  for (GLuint a = 0; a < 3; a++) {
    glEnableVertexAttribArray(a);
    glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, sizeof(vertex),
                          (const void *)(a * 3 * sizeof(float)));
  }
  glBindVertexArray(0);
  pass->index_count = (GLsizei)k;
  free(vertices);
  free(indices);
  return gl_util_check("uploading the scene meshes", err);
}

/* The depth texture (compare mode: sampler2DShadow, 2 x 2 filtered) and its framebuffer. */
static int shadow_map_create(scene_pass *pass, fog_error *err) {
  GLuint tex = 0;
  pass->shadow.size = SCENE_SUN_SHADOW_SIZE;
  glGenTextures(1, &tex);
  pass->shadow.texture = tex;
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, pass->shadow.size, pass->shadow.size);
  /* beyond the map: depth 1, nothing in front of the sun */
  gl_util_set_sampling(GL_TEXTURE_2D,
                       &(gl_sampling){.filter = GL_LINEAR,
                                      .wrap = {GL_CLAMP_TO_BORDER, GL_CLAMP_TO_BORDER},
                                      .border = {1, 1, 1, 1}, .compare = true});
  glBindTexture(GL_TEXTURE_2D, 0);
  glGenFramebuffers(1, &pass->shadow_framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, pass->shadow_framebuffer);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, tex, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    fog_fail(err, FOG_ERR_GRAPHICS, "sun shadow map: framebuffer incomplete (%#x)", status);
    return 1;
  }
  return gl_util_check("sun shadow map", err);
}

/* Renders the terrain and boxes' depth seen from the sun, fitted around their bounds: all
 * of them (no frustum culling), both faces (a terrain seen from below the horizon's sun
 * shadows with its back faces too). */
static void shadow_map_render(scene_pass *pass) {
  const scene_geometry *geo = pass->geo;
  double lo[3], hi[3];
  scene_geometry_bounds(geo, lo, hi);
  sun_shadow_map *map = &pass->shadow;
  sun_shadow_map_fit(map, geo->sun_direction, lo, hi);
  /* view: rows e0, e1, sun (column-major below); projection: light space to NDC, depth
   * (hi - z)/(hi - lo) as sun_shadow_map_matrix has it */
  float view[16] = {0}, projection[16] = {0};
  for (int a = 0; a < 3; a++)
    for (int c = 0; c < 3; c++) view[c * 4 + a] = (float)map->axis[a][c];
  view[15] = 1.0f;
  for (int a = 0; a < 3; a++) {
    double span = map->hi[a] - map->lo[a];
    double k = a < 2 ? 2.0 / span : -2.0 / span;
    double base = a < 2 ? -2.0 * map->lo[a] / span - 1.0 : 2.0 * map->hi[a] / span - 1.0;
    projection[a * 4 + a] = (float)k;
    projection[12 + a] = (float)base;
  }
  projection[15] = 1.0f;
  glBindFramebuffer(GL_FRAMEBUFFER, pass->shadow_framebuffer);
  glViewport(0, 0, map->size, map->size);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glDisable(GL_CULL_FACE);
  glUseProgram(pass->surface_program);
  const double *o = geo->terrain.origin;
  glUniform3f(pass->u_offset, (float)(o[0] - map->centre[0]), (float)(o[1] - map->centre[1]),
              (float)(o[2] - map->centre[2]));
  glUniformMatrix4fv(pass->u_view, 1, GL_FALSE, view);
  glUniformMatrix4fv(pass->u_projection, 1, GL_FALSE, projection);
  /* no far cut here (GL_CLIP_DISTANCE0 is off, but llvmpipe clipped the map's triangles by
   * the distance the shader writes all the same: the shafts changed) */
  glUniform1f(pass->u_far_plane, FLT_MAX);
  glActiveTexture(GL_TEXTURE0); /* not the map itself while it is the target */
  glBindTexture(GL_TEXTURE_2D, 0);
  glUniform1i(pass->u_sun_visibility, 0);
  glBindVertexArray(pass->vao);
  glEnable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
  glDrawElements(GL_TRIANGLE_STRIP, pass->index_count, GL_UNSIGNED_INT, NULL);
  glDisable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  pass->shadow_rendered = true;
}

const sun_shadow_map *scene_pass_sun_shadow(const scene_pass *pass) { return &pass->shadow; }

scene_pass *scene_pass_create(const scene_geometry *geo, fog_error *err) {
  scene_pass *pass = calloc(1, sizeof *pass);
  if (!pass) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the scene pass");
    return NULL;
  }
  pass->geo = geo;
  pass->surface_program = gl_util_program("scene_surface_vs.glsl", "scene_surface_fs.glsl", err);
  if (pass->surface_program)
    pass->sky_program = gl_util_program("scene_sky_vs.glsl", "scene_sky_fs.glsl", err);
  if (!pass->sky_program || upload_geometry(pass, err)) {
    scene_pass_destroy(pass);
    return NULL;
  }
  GLuint s = pass->surface_program, k = pass->sky_program;
  pass->u_offset = glGetUniformLocation(s, "offset");
  pass->u_view = glGetUniformLocation(s, "view_rotation");
  pass->u_projection = glGetUniformLocation(s, "projection");
  pass->u_far_plane = glGetUniformLocation(s, "far_plane");
  pass->u_sun_direction = glGetUniformLocation(s, "sun_direction");
  pass->u_sun_colour = glGetUniformLocation(s, "sun_colour");
  pass->u_ambient = glGetUniformLocation(s, "ambient");
  pass->u_sun_from_relative = glGetUniformLocation(s, "sun_from_relative");
  pass->u_sun_visibility = glGetUniformLocation(s, "sun_visibility");
  pass->u_sun_normal_offset = glGetUniformLocation(s, "sun_normal_offset");
  pass->u_lod_lift = glGetUniformLocation(s, "lod_lift_per_distance");
  pass->u_lamp_count = glGetUniformLocation(s, "lamp_count");
  pass->u_lamp_position = glGetUniformLocation(s, "lamp_position");
  pass->u_lamp_intensity = glGetUniformLocation(s, "lamp_intensity");
  pass->u_lamp_axis = glGetUniformLocation(s, "lamp_axis");
  pass->u_lamp_cone = glGetUniformLocation(s, "lamp_cone");
  pass->u_lamp_shadow_map = glGetUniformLocation(s, "lamp_shadow_map");
  pass->u_lamp_shadow_inv_far = glGetUniformLocation(s, "lamp_shadow_inv_far");
  pass->u_lamp_shadow_slack = glGetUniformLocation(s, "lamp_shadow_slack");
  pass->u_lamp_shadows_on = glGetUniformLocation(s, "lamp_shadows_on");
  pass->u_lamp_shadow_lift = glGetUniformLocation(s, "lamp_shadow_lift");
  pass->lamp_shadow_size = LAMP_SHADOW_SIZE;
  /* the samplers' units, apart from the start: two sampler types may not share a unit, even
   * unused (the sun's shadow map is drawn with this program too) */
  glUseProgram(s);
  glUniform1i(pass->u_sun_visibility, 0);
  glUniform1i(pass->u_lamp_shadow_map, 1);
  glUseProgram(0);
  if (shadow_map_create(pass, err)) {
    scene_pass_destroy(pass);
    return NULL;
  }
  pass->u_sky_right = glGetUniformLocation(k, "camera_right");
  pass->u_sky_up = glGetUniformLocation(k, "camera_up");
  pass->u_sky_forward = glGetUniformLocation(k, "camera_forward");
  pass->u_sky_viewport = glGetUniformLocation(k, "viewport_size");
  pass->u_sky_horizon = glGetUniformLocation(k, "sky_horizon");
  pass->u_sky_zenith = glGetUniformLocation(k, "sky_zenith");
  pass->u_sky_sun_direction = glGetUniformLocation(k, "sun_direction");
  pass->u_sky_sun_colour = glGetUniformLocation(k, "sun_colour");
  return pass;
}

void scene_pass_destroy(scene_pass *pass) {
  if (!pass) return;
  if (pass->shadow.texture) glDeleteTextures(1, &(GLuint){pass->shadow.texture});
  if (pass->shadow_framebuffer) glDeleteFramebuffers(1, &pass->shadow_framebuffer);
  scene_lamp_shadows_destroy(pass);
  if (pass->surface_program) glDeleteProgram(pass->surface_program);
  if (pass->sky_program) glDeleteProgram(pass->sky_program);
  if (pass->vertex_buffer) glDeleteBuffers(1, &pass->vertex_buffer);
  if (pass->index_buffer) glDeleteBuffers(1, &pass->index_buffer);
  if (pass->vao) glDeleteVertexArrays(1, &pass->vao);
  free(pass->tiles);
  free(pass->draw_counts);
  free(pass->draw_offsets);
  if (pass->lod_index_buffer) glDeleteBuffers(1, &pass->lod_index_buffer);
  free(pass->lod_indices);
  free(pass->lod_order);
  terrain_lod_destroy(&pass->lod);
  free(pass);
}

int scene_pass_set_terrain_lod(scene_pass *pass, double max_pixels, fog_error *err) {
  if (!(max_pixels >= 0 && isfinite(max_pixels))) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "terrain LOD error %g pixels: expected a finite number >= 0 (0: the full mesh)",
             max_pixels);
    return 1;
  }
  if (max_pixels > 0 && !pass->lod.level) {
    if (terrain_lod_create(&pass->lod, &pass->geo->terrain, err)) return 1;
    const size_t tiles = (size_t)pass->lod.tiles_x * pass->lod.tiles_z;
    pass->lod_indices =
        malloc(terrain_lod_all_max_indices(&pass->lod) * sizeof *pass->lod_indices);
    pass->lod_order = malloc(tiles * sizeof *pass->lod_order);
    if (!pass->lod_indices || !pass->lod_order) {
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the terrain's LOD mesh");
      return 1;
    }
    glGenBuffers(1, &pass->lod_index_buffer);
  }
  pass->lod_pixels = max_pixels;
  return 0;
}

static int tile_order_compare(const void *a, const void *b) {
  const scene_tile_order *p = a, *q = b;
  return (p->distance > q->distance) - (p->distance < q->distance);
}

/* The visible tiles' LOD triangles into lod_index_buffer (streamed); their index count. */
static GLsizei lod_tiles(scene_pass *pass, const camera *cam, int width, int height) {
  terrain_lod *lod = &pass->lod;
  double near_plane, far_plane;
  camera_depth_range(cam, &near_plane, &far_plane);
  const double pixels_per_unit = height / (2.0 * tan(0.5 * cam->fov_y));
  terrain_lod_choose(lod, cam->position, pixels_per_unit, pass->lod_pixels);
  frustum f;
  frustum_from_camera(&f, cam, width, height);
  /* The visible tiles near to far: the depth test then rejects what nearer hills hide
   * before it is shaded (llvmpipe tests depth early for this shader). */
  int visible = 0;
  const int tiles = lod->tiles_x * lod->tiles_z;
  for (int k = 0; k < tiles; k++) {
    double lo[3], hi[3], d2 = 0.0;
    for (int c = 0; c < 3; c++) {
      lo[c] = lod->lo[3 * k + c] - cam->position[c], hi[c] = lod->hi[3 * k + c] - cam->position[c];
      double g = fmax(0.0, fmax(lo[c], -hi[c]));
      d2 += g * g;
    }
    if (frustum_culls_box(&f, lo, hi)) continue;
    pass->lod_order[visible++] = (scene_tile_order){.distance = d2, .tile = k};
  }
  qsort(pass->lod_order, (size_t)visible, sizeof *pass->lod_order, tile_order_compare);
  size_t n = 0;
  for (int v = 0; v < visible; v++)
    n += terrain_lod_emit(lod, pass->lod_order[v].tile, pass->lod_indices + n);
  pass->triangles_drawn = 10L * pass->geo->box_count + (long)(n / 3);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, pass->lod_index_buffer);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(n * sizeof(uint32_t)), pass->lod_indices,
               GL_STREAM_DRAW);
  return (GLsizei)n;
}

GLsizei scene_tile_ranges(scene_pass *pass, const double eye[3], scene_box_culled culled,
                          const void *user, long *triangles) {
  GLsizei n = 0, end = -1;
  long drawn = 0;
  for (int k = 0; k < pass->tile_count; k++) {
    const scene_tile *tile = &pass->tiles[k];
    double lo[3], hi[3];
    for (int c = 0; c < 3; c++) lo[c] = tile->lo[c] - eye[c], hi[c] = tile->hi[c] - eye[c];
    if (tile->count == 0 || culled(user, lo, hi)) continue;
    if (tile->first == end) {
      pass->draw_counts[n - 1] += tile->count;
    } else {
      pass->draw_counts[n] = tile->count;
      pass->draw_offsets[n++] = (const void *)(uintptr_t)(tile->first * sizeof(GLuint));
    }
    end = tile->first + tile->count;
    drawn += tile->triangles;
  }
  if (triangles) *triangles = drawn;
  return n;
}

static bool frustum_culled(const void *user, const double lo[3], const double hi[3]) {
  return frustum_culls_box(user, lo, hi);
}

/* The terrain's index ranges the camera's frustum keeps; triangles_drawn counts the boxes
 * too. */
static GLsizei cull_tiles(scene_pass *pass, const camera *cam, int width, int height) {
  frustum f;
  frustum_from_camera(&f, cam, width, height);
  long triangles = 0;
  GLsizei n = scene_tile_ranges(pass, cam->position, frustum_culled, &f, &triangles);
  pass->triangles_drawn = 10L * pass->geo->box_count + triangles;
  return n;
}

long scene_pass_triangles_drawn(const scene_pass *pass) { return pass->triangles_drawn; }

/* Whether the terrain's back faces (facing down) can be skipped: the surface is a height
 * field, so a ray from a point above it meets it first going down, on a front face. That
 * holds for a camera above the surface inside the footprint (a ray leaves the footprint
 * only once). From below, or from outside the footprint, even high above it, a ray can
 * enter the footprint under the surface's edge and meet a back face first
 * (test_scene_distance's view from outside failed that way). The margin (the near
 * plane) keeps float rounding of the drawn vertices out of the decision. */
bool scene_terrain_back_faces_hidden(const terrain *t, const camera *cam) {
  const double *p = cam->position;
  double near_plane, far_plane;
  camera_depth_range(cam, &near_plane, &far_plane);
  bool inside = p[0] >= t->origin[0] && p[0] <= t->origin[0] + t->size[0] &&
                p[2] >= t->origin[2] && p[2] <= t->origin[2] + t->size[1];
  return inside && p[1] > terrain_height_at(t, p[0], p[2]) + near_plane;
}

_Static_assert(FOG_MAX_LAMPS == 16, "scene_surface_fs.glsl's SCENE_MAX_LAMPS is 16");

int scene_pass_set_lamps(scene_pass *pass, const fog_lamps *lamps, fog_error *err) {
  pass->lamps = *lamps;
  if (pass->lamps.count < 0) pass->lamps.count = 0;
  if (pass->lamps.count > FOG_MAX_LAMPS) pass->lamps.count = FOG_MAX_LAMPS;
  return scene_lamp_shadows_update(pass, err);
}

int scene_pass_set_lamp_shadows(scene_pass *pass, int size, fog_error *err) {
  if (size != 0 && !(size >= LAMP_SHADOW_SIZE_MIN && size <= LAMP_SHADOW_SIZE_MAX)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "lamp shadow cubes of %d texels: expected 0 (none) or %d..%d", size,
             LAMP_SHADOW_SIZE_MIN, LAMP_SHADOW_SIZE_MAX);
    return 1;
  }
  pass->lamp_shadow_size = size;
  if (size == 0) {
    scene_lamp_shadows_destroy(pass);
    return 0;
  }
  return scene_lamp_shadows_update(pass, err);
}

const lamp_shadow_maps *scene_pass_lamp_shadows(const scene_pass *pass) {
  const lamp_shadow_maps *maps = &pass->lamp_shadows;
  return pass->lamp_shadow_size > 0 && pass->lamps.count > 0 && maps->texture &&
                 maps->count >= pass->lamps.count
             ? maps
             : NULL;
}

/* The lamps on the surfaces (scene_surface_fs.glsl): camera-relative, in double first. */
static void scene_pass_lamp_uniforms(const scene_pass *pass, const camera *cam) {
  const fog_lamps *lamps = &pass->lamps;
  fog_lamp_uniforms u;
  fog_lamps_pack(lamps, cam->position, 1.0, &u);
  glUniform1i(pass->u_lamp_count, lamps->count);
  if (lamps->count == 0) return;
  glUniform3fv(pass->u_lamp_position, lamps->count, &u.position[0][0]);
  glUniform3fv(pass->u_lamp_intensity, lamps->count, &u.intensity[0][0]);
  glUniform4fv(pass->u_lamp_axis, lamps->count, &u.axis[0][0]);
  glUniform3fv(pass->u_lamp_cone, lamps->count, &u.cone[0][0]);
}

void scene_pass_run(scene_pass *pass, const camera *cam, const gl_target *target) {
  const scene_geometry *geo = pass->geo;
  int w = target->width, h = target->height;
  if (!pass->shadow_rendered || memcmp(pass->shadow.sun, geo->sun_direction, sizeof pass->shadow.sun))
    shadow_map_render(pass);
  gl_target_bind(target);
  /* Attachment 3 (the lamps' share and the normal, for the fog pass) only with lamps: an
   * RGBA32F write per pixel costs the live demo ~9 % of its frame rate on llvmpipe. */
  static const GLenum buffers[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                    GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
  int drawn = target->color_count;
  if (drawn > 3 && pass->lamps.count == 0) drawn = 3;
  glDrawBuffers(drawn, buffers);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  double right[3], up[3], forward[3];
  camera_basis(cam, w, h, right, up, forward);

  float sun_dir[3] = {(float)geo->sun_direction[0], (float)geo->sun_direction[1],
                      (float)geo->sun_direction[2]};
  /* a sun below the horizon lights nothing (the fog pass takes the same share) */
  const float above = (float)fog_sun_above_horizon(geo->sun_direction);
  const float sun_colour[3] = {above * geo->light.sun_colour[0], above * geo->light.sun_colour[1],
                               above * geo->light.sun_colour[2]};
  /* Terrain and boxes, camera-relative: offset = terrain origin - camera (double). */
  float view[16], projection[16];
  camera_view_matrix(cam, view);
  camera_projection_matrix_infinite(cam, w, h, projection);
  const double *o = geo->terrain.origin;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUseProgram(pass->surface_program);
  glUniform3f(pass->u_offset, (float)(o[0] - cam->position[0]), (float)(o[1] - cam->position[1]),
              (float)(o[2] - cam->position[2]));
  glUniformMatrix4fv(pass->u_view, 1, GL_FALSE, view);
  glUniformMatrix4fv(pass->u_projection, 1, GL_FALSE, projection);
  /* the far plane as a clip distance (the projection's is at infinity) */
  glUniform1f(pass->u_far_plane, (float)cam->far_plane);
  glEnable(GL_CLIP_DISTANCE0);
  glUniform3fv(pass->u_sun_direction, 1, sun_dir);
  glUniform3fv(pass->u_sun_colour, 1, sun_colour);
  glUniform3fv(pass->u_ambient, 1, geo->light.ambient);
  double shadow_m[4][4];
  float shadow_rows[16];
  sun_shadow_map_matrix(&pass->shadow, cam->position, shadow_m);
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) shadow_rows[r * 4 + c] = (float)shadow_m[r][c];
  glUniformMatrix4fv(pass->u_sun_from_relative, 1, GL_TRUE, shadow_rows);
  /* the lookup moves 1.5 texels off the surface along its normal: no shadow acne */
  glUniform1f(pass->u_sun_normal_offset, (float)(1.5 * sun_shadow_map_texel(&pass->shadow)));
  const double lod_lift =
      pass->lod_pixels > 0 ? pass->lod_pixels * 2.0 * tan(0.5 * cam->fov_y) / h : 0.0;
  glUniform1f(pass->u_lod_lift, (float)lod_lift);
  pass->lamp_shadows.lift_per_distance = lod_lift; /* the fog pass's surface lookups too */
  scene_pass_lamp_uniforms(pass, cam);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, pass->shadow.texture);
  glUniform1i(pass->u_sun_visibility, 0);
  scene_lamp_shadows_bind(pass, 1);
  glBindVertexArray(pass->vao);
  const bool lod = pass->lod_pixels > 0;
  GLsizei ranges = lod ? 0 : cull_tiles(pass, cam, w, h);
  GLsizei lod_count = lod ? lod_tiles(pass, cam, w, h) : 0; /* binds its index buffer */
  /* The terrain's strips wind counter-clockwise seen from above (terrain_mesh_tiles), so
   * GL_BACK culls the faces that look down: on llvmpipe the pass costs about its
   * triangles, and half of those in view face away. The boxes are drawn two-sided: a
   * camera inside one sees its inner faces (scene_geometry_intersect). */
  glEnable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
  if (scene_terrain_back_faces_hidden(&geo->terrain, cam)) glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  if (lod) {
    glDrawElements(GL_TRIANGLES, lod_count, GL_UNSIGNED_INT, NULL);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, pass->index_buffer); /* the VAO's, for the boxes */
  } else {
    glMultiDrawElements(GL_TRIANGLE_STRIP, pass->draw_counts, GL_UNSIGNED_INT,
                        pass->draw_offsets, ranges);
  }
  glDisable(GL_CULL_FACE);
  glDrawElements(GL_TRIANGLE_STRIP, pass->index_count - pass->box_first, GL_UNSIGNED_INT,
                 (const void *)(uintptr_t)(pass->box_first * sizeof(GLuint)));
  glDisable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
  glDisable(GL_CLIP_DISTANCE0);
  glBindVertexArray(0);

  /* Sky last: a full-screen triangle at depth 1 (the far plane), rays from the same basis
   * as camera_ray(), depth-tested so that only the pixels no surface covers are shaded
   * (early depth test: the sky's sun disc and gradient cost nothing under the terrain). */
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glUseProgram(pass->sky_program);
  glUniform3f(pass->u_sky_right, (float)right[0], (float)right[1], (float)right[2]);
  glUniform3f(pass->u_sky_up, (float)up[0], (float)up[1], (float)up[2]);
  glUniform3f(pass->u_sky_forward, (float)forward[0], (float)forward[1], (float)forward[2]);
  glUniform2f(pass->u_sky_viewport, (float)w, (float)h);
  glUniform3fv(pass->u_sky_horizon, 1, geo->light.sky_horizon);
  glUniform3fv(pass->u_sky_zenith, 1, geo->light.sky_zenith);
  glUniform3fv(pass->u_sky_sun_direction, 1, sun_dir);
  glUniform3fv(pass->u_sky_sun_colour, 1, sun_colour);
  glBindVertexArray(gl_util_empty_vao());
  glDrawArrays(GL_TRIANGLES, 0, 3);

  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  glUseProgram(0);
  glDisable(GL_DEPTH_TEST);
}

int scene_target_create(gl_target *target, int width, int height, fog_error *err) {
  return gl_target_create(target,
                          &(gl_target_desc){.width = width,
                                            .height = height,
                                            .color_formats = {GL_RGBA32F, GL_R32F,
                                                              GL_RGBA32F, GL_RGBA32F},
                                            .depth = true},
                          err);
}
