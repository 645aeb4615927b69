/* The scene pass with terrain LOD (scene_pass_set_terrain_lod) against the full mesh, on
 * the default scene's terrain (257 x 257, rough fBm) from four views (the default, low over
 * the terrain, high above, near the ground looking at a hill):
 * - no cracks: no pixel the full mesh covers with terrain well inside its surface (all
 *   pixels within 1 + 2 x the budget of it terrain too) shows the sky with LOD;
 * - the LOD draws fewer triangles (at 1 pixel: under 70 % of the full mesh's in the
 *   default view, fewer still at 4);
 * - the surface moves by about its pixel budget: the LOD hit point's height against the
 *   exact terrain under it, seen from the camera, within 2x the budget in pixels for
 *   99.5 % of the terrain pixels (silhouettes, where the surface behind changes, excepted). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/render.h"
#include "scene_test_gl.h"
#include "test_util.h"

enum { W = 320, H = 180 };

int main(void) {
  fog_error err = {0};
  scene_desc desc = {
      .terrain = {.origin = {-600, 0, -600}, .size = {1200, 1200}, .height = 160,
                  .resolution = 257, .seed = 4, .octaves = 6, .frequency = 2.2,
                  .persistence = 0.5},
      .light = scene_light_default(),
  };
  desc.light.sun_azimuth = 150, desc.light.sun_elevation = 30;
  scene_test_gl s;
  if (!scene_test_gl_open(&s, &desc, W, H, &err)) return test_finish("test_scene_lod");
  static float full[W * H], lod[W * H];
  const double views[4][6] = {{0, 230, 560, 0, 30, -60},
                              {-300, 0, 400, 200, 0, -500},
                              {100, 900, 300, -50, 0, -100},
                              {250, 0, -100, -200, 40, -400}};
  const double budgets[2] = {1.0, 4.0};
  for (int v = 0; v < 4; v++) {
    camera cam = {.fov_y = 55.0 * 3.14159265358979323846 / 180.0,
        .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    for (int c = 0; c < 3; c++) cam.position[c] = views[v][c];
    if (views[v][1] == 0)
      cam.position[1] = terrain_height_at(&s.geo.terrain, cam.position[0], cam.position[2]) + 25.0;
    camera_look_at(&cam, &views[v][3]);
    CHECK(scene_pass_set_terrain_lod(s.pass, 0.0, &err) == 0, "%s", err.message);
    scene_pass_run(s.pass, &cam, &s.target);
    const long full_triangles = scene_pass_triangles_drawn(s.pass);
    CHECK(gl_target_read(&s.target, 1, 1, full, &err) == 0, "%s", err.message);
    const double ppu = H / (2.0 * tan(0.5 * cam.fov_y));
    for (int b = 0; b < 2; b++) {
      CHECK(scene_pass_set_terrain_lod(s.pass, budgets[b], &err) == 0, "%s", err.message);
      scene_pass_run(s.pass, &cam, &s.target);
      const long triangles = scene_pass_triangles_drawn(s.pass);
      CHECK(gl_target_read(&s.target, 1, 1, lod, &err) == 0, "%s", err.message);
      int holes = 0, terrain_pixels = 0, over = 0;
      double worst_px = 0.0;
      for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
          const int k = y * W + x;
          if (full[k] >= SCENE_SKY_DISTANCE) continue;
          /* well inside: the LOD may move a silhouette by up to ~2x its budget */
          const int m = 1 + (int)ceil(2.0 * budgets[b]);
          bool interior = x >= m && y >= m && x < W - m && y < H - m;
          for (int dy = -m; interior && dy <= m; dy++)
            for (int dx = -m; interior && dx <= m; dx++)
              interior = full[k + dy * W + dx] < SCENE_SKY_DISTANCE;
          if (!interior) continue;
          if (lod[k] >= SCENE_SKY_DISTANCE) {
            holes++;
            continue;
          }
          if (fabs(lod[k] - full[k]) > 0.1 * full[k]) continue; /* a silhouette moved */
          terrain_pixels++;
          double o[3], d[3];
          camera_ray(&cam, x, y, W, H, o, d);
          double p[3];
          for (int c = 0; c < 3; c++) p[c] = o[c] + lod[k] * d[c];
          double dy_world = fabs(p[1] - terrain_height_at(&s.geo.terrain, p[0], p[2]));
          double px = dy_world * ppu / lod[k];
          worst_px = fmax(worst_px, px);
          over += px > 2.0 * budgets[b];
        }
      printf("view %d, %g px: %ld of %ld triangles (%.0f %%), %d holes, height error up to "
             "%.2f px, %d of %d pixels over 2x the budget\n",
             v, budgets[b], triangles, full_triangles, 100.0 * triangles / full_triangles, holes,
             worst_px, over, terrain_pixels);
      CHECK(holes == 0, "view %d, %g px: %d pixels show the sky through the terrain", v,
            budgets[b], holes);
      CHECK(over <= 0.005 * terrain_pixels, "view %d, %g px: %d of %d pixels off by > 2x the "
            "budget", v, budgets[b], over, terrain_pixels);
      if (v == 0)
        CHECK(triangles < (b ? 0.4 : 0.7) * full_triangles, "view 0, %g px: %ld of %ld triangles",
              budgets[b], triangles, full_triangles);
    }
  }
  scene_test_gl_teardown(&s);
  return test_finish("test_scene_lod");
}
