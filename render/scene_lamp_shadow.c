/* The lamps' shadow cubes (render/lamp_shadow_map.h), rendered by the scene pass from its
 * terrain and boxes: each lamp's six faces (a spot's reached faces), the terrain's tiles
 * culled to each face, whenever the lamp moved since its cube was rendered. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "render/scene_internal.h"

/* Allocates the cube array for `count` lamps at `size` (at least one cube, so the
 * surfaces' sampler always has a complete texture) and the framebuffer and program on first
 * use. Every cube is marked unrendered. */
static int lamp_shadows_allocate(scene_pass *pass, int count, fog_error *err) {
  lamp_shadow_maps *maps = &pass->lamp_shadows;
  if (!pass->lamp_shadow_program) {
    pass->lamp_shadow_program = gl_util_program("lamp_shadow_vs.glsl", "lamp_shadow_fs.glsl", err);
    if (!pass->lamp_shadow_program) return 1;
    GLuint p = pass->lamp_shadow_program;
    pass->u_shadow_offset = glGetUniformLocation(p, "offset");
    pass->u_shadow_clip = glGetUniformLocation(p, "face_clip");
    pass->u_shadow_inv_far = glGetUniformLocation(p, "inv_far");
    glGenFramebuffers(1, &pass->lamp_shadow_framebuffer);
  }
  if (maps->texture) glDeleteTextures(1, &(GLuint){maps->texture});
  GLuint tex = 0;
  glGenTextures(1, &tex);
  maps->texture = tex;
  maps->size = pass->lamp_shadow_size;
  maps->count = 0;
  maps->capacity = count > 0 ? count : 1;
  glBindTexture(GL_TEXTURE_CUBE_MAP_ARRAY, tex);
  glTexStorage3D(GL_TEXTURE_CUBE_MAP_ARRAY, 1, GL_DEPTH_COMPONENT32F, maps->size, maps->size,
                 6 * maps->capacity);
  gl_util_set_sampling(GL_TEXTURE_CUBE_MAP_ARRAY,
                       &(gl_sampling){.filter = GL_LINEAR,
                                      .wrap = {GL_CLAMP_TO_EDGE, GL_CLAMP_TO_EDGE},
                                      .compare = true});
  glBindTexture(GL_TEXTURE_CUBE_MAP_ARRAY, 0);
  /* the 2 x 2 filter reads across a face's edge into its neighbour, not a clamped texel */
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  return gl_util_check("lamp shadow cubes", err);
}

static bool face_culled(const void *user, const double lo[3], const double hi[3]) {
  return lamp_shadow_face_culls_box(*(const int *)user, lo, hi);
}

/* Lamp i's cube: every face cleared to 1 (nothing), the faces its light reaches drawn. */
static void render_cube(scene_pass *pass, int i, const double lo[3], const double hi[3]) {
  const fog_lamp *lamp = &pass->lamps.lamp[i];
  lamp_shadow_maps *maps = &pass->lamp_shadows;
  const double *p = lamp->position, *o = pass->geo->terrain.origin;
  const double far_plane = lamp_shadow_far(p, lo, hi);
  const double near_plane = fmin(1e-2, 1e-4 * far_plane);
  maps->far[i] = far_plane;
  maps->rendered[i] = *lamp;
  glUniform3f(pass->u_shadow_offset, (float)(o[0] - p[0]), (float)(o[1] - p[1]),
              (float)(o[2] - p[2]));
  glUniform1f(pass->u_shadow_inv_far, (float)(1.0 / far_plane));
  for (int face = 0; face < 6; face++) {
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, maps->texture, 0, 6 * i + face);
    glClear(GL_DEPTH_BUFFER_BIT);
    if (!lamp_shadow_face_needed(lamp, face)) continue;
    double m[4][4];
    float rows[16];
    lamp_shadow_face_clip(face, near_plane, far_plane, m);
    for (int r = 0; r < 4; r++)
      for (int c = 0; c < 4; c++) rows[4 * r + c] = (float)m[r][c];
    glUniformMatrix4fv(pass->u_shadow_clip, 1, GL_TRUE, rows);
    GLsizei ranges = scene_tile_ranges(pass, p, face_culled, &face, NULL);
    glMultiDrawElements(GL_TRIANGLE_STRIP, pass->draw_counts, GL_UNSIGNED_INT,
                        pass->draw_offsets, ranges);
    glDrawElements(GL_TRIANGLE_STRIP, pass->index_count - pass->box_first, GL_UNSIGNED_INT,
                   (const void *)(uintptr_t)(pass->box_first * sizeof(GLuint)));
  }
}

int scene_lamp_shadows_update(scene_pass *pass, fog_error *err) {
  lamp_shadow_maps *maps = &pass->lamp_shadows;
  const int count = pass->lamps.count;
  if (pass->lamp_shadow_size == 0 || count == 0) return 0;
  /* a new size, or more lamps than cubes: allocate afresh (every cube again) */
  if (!maps->texture || maps->size != pass->lamp_shadow_size || maps->capacity < count) {
    if (lamp_shadows_allocate(pass, count, err)) return 1;
  }
  bool stale = false;
  for (int i = 0; i < count && !stale; i++)
    stale = i >= maps->count || !lamp_shadow_same_placement(&maps->rendered[i], &pass->lamps.lamp[i]);
  if (!stale) {
    maps->count = count;
    return 0;
  }
  double lo[3], hi[3];
  scene_geometry_bounds(pass->geo, lo, hi);
  glBindFramebuffer(GL_FRAMEBUFFER, pass->lamp_shadow_framebuffer);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  glViewport(0, 0, maps->size, maps->size);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glUseProgram(pass->lamp_shadow_program);
  glBindVertexArray(pass->vao);
  glEnable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
  /* Not clipped at the near plane: the depth written is the distance over far (gl_FragDepth),
   * and a lamp a hair inside a wall or roof (the lamp tool puts one there about half the
   * time) had the face looking into it draw nothing nearer than 1 cm: the light escaped
   * through the surface in a 90-degree pyramid (test_lamp_in_surface). */
  glEnable(GL_DEPTH_CLAMP);
  for (int i = 0; i < count; i++)
    if (i >= maps->count || !lamp_shadow_same_placement(&maps->rendered[i], &pass->lamps.lamp[i]))
      render_cube(pass, i, lo, hi);
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  maps->count = count;
  return gl_util_check("rendering the lamp shadow cubes", err);
}

void scene_lamp_shadows_bind(const scene_pass *pass, int unit) {
  const lamp_shadow_maps *maps = &pass->lamp_shadows;
  const bool on = pass->lamp_shadow_size > 0 && pass->lamps.count > 0 && maps->texture;
  glUniform1i(pass->u_lamp_shadows_on, on);
  /* its own unit even when off: two sampler types may not share one */
  glUniform1i(pass->u_lamp_shadow_map, unit);
  if (!on) return;
  const lamp_shadow_uniforms u = lamp_shadow_maps_uniforms(maps);
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_CUBE_MAP_ARRAY, maps->texture);
  glUniform1fv(pass->u_lamp_shadow_inv_far, FOG_MAX_LAMPS, u.inv_far);
  glUniform1f(pass->u_lamp_shadow_slack, u.slack);
  glUniform1f(pass->u_lamp_shadow_lift, u.lift);
  glActiveTexture(GL_TEXTURE0);
}

void scene_lamp_shadows_destroy(scene_pass *pass) {
  if (pass->lamp_shadows.texture) glDeleteTextures(1, &(GLuint){pass->lamp_shadows.texture});
  if (pass->lamp_shadow_framebuffer) glDeleteFramebuffers(1, &pass->lamp_shadow_framebuffer);
  if (pass->lamp_shadow_program) glDeleteProgram(pass->lamp_shadow_program);
  pass->lamp_shadows = (lamp_shadow_maps){0};
  pass->lamp_shadow_framebuffer = pass->lamp_shadow_program = 0;
}
