/* The scene pass's distance texture is the exact first-hit distance: at sampled pixels
 * the GL R32F distance matches an independent CPU ray cast (double precision, the same
 * triangles) within 1e-4 relative (float vertex positions and interpolation); sky pixels
 * hold SCENE_SKY_DISTANCE exactly. A pixel whose centre lies on a silhouette edge may
 * pick the other surface in the rasteriser: it must then match the CPU ray jittered by
 * at most 0.02 pixel, and such pixels must be rare (< 2%).
 * Also: the DDA terrain walk gives the same hits as testing every triangle; and the
 * same holds from views where the pass culls terrain tiles outside the frustum (looking
 * down, sideways along the terrain's edge, from outside it, from far above), with fewer
 * triangles drawn than the terrain has in some and all of them in another; and from the
 * views where it culls the terrain's back faces (above the surface) as from those where
 * it must not (under the surface, outside the footprint). */
#include <math.h>
#include <stdlib.h>

#include "render/render.h"
#include "scene_test_gl.h"
#include "test_util.h"

static bool close_enough(double gl, double cpu) {
  if (cpu >= SCENE_SKY_DISTANCE) return gl == SCENE_SKY_DISTANCE;
  return fabs(gl - cpu) <= 1e-4 * cpu + 1e-3;
}

static double jittered(const scene_geometry *geo, const camera *cam, double px, double py,
                       int w, int h) {
  double o[3], d[3], s;
  camera_ray(cam, px, py, w, h, o, d);
  return scene_geometry_intersect(geo, o, d, INFINITY, &s, NULL) ? s : SCENE_SKY_DISTANCE;
}

static void test_dda_matches_brute_force(void) {
  fog_error err = {0};
  terrain t;
  int status = terrain_create(&t, &(terrain_desc){.origin = {-200, 10, -300}, .size = {400, 600},
                                                  .height = 120, .resolution = 65, .seed = 7,
                                                  .octaves = 6, .frequency = 3,
                                                  .persistence = 0.5},
                              &err);
  CHECK(status == 0, "terrain: %s", err.message);
  if (status) return;
  unsigned state = 12345;
  int hits = 0, disagreements = 0;
  for (int r = 0; r < 400; r++) {
    double v[6];
    for (int k = 0; k < 6; k++) {
      state = state * 1664525u + 1013904223u;
      v[k] = (state >> 8) / 16777216.0;
    }
    double o[3] = {-300 + 600 * v[0], 20 + 200 * v[1], -400 + 800 * v[2]};
    double d[3] = {v[3] - 0.5, -0.8 * v[4], v[5] - 0.5};
    if (r % 10 == 0) d[0] = d[2] = 0.0, d[1] = -1.0; /* vertical rays: no DDA steps */
    double s1 = -1, s2 = -1;
    bool h1 = terrain_intersect(&t, o, d, INFINITY, &s1, NULL);
    bool h2 = terrain_intersect_brute(&t, o, d, INFINITY, &s2);
    hits += h2;
    if (h1 != h2 || (h1 && fabs(s1 - s2) > 1e-9 * (1 + s2))) {
      if (disagreements++ < 3)
        fprintf(stderr, "ray %d: dda %d %.12g, brute %d %.12g\n", r, h1, s1, h2, s2);
    }
  }
  CHECK(disagreements == 0, "%d of 400 rays: DDA differs from brute force", disagreements);
  CHECK(hits > 100, "only %d rays hit: the test would not test much", hits);
  terrain_destroy(&t);
}

typedef struct view_stats {
  int sampled, sky, boxes, edge, failed;
} view_stats;

/* Renders cam's view and compares every `step`-th pixel's distance with the CPU ray cast. */
static view_stats compare_view(const scene_geometry *geo, scene_pass *pass,
                               const gl_target *target, const camera *cam, int step,
                               float *distance) {
  view_stats v = {0};
  fog_error err = {0};
  int W = target->width, H = target->height;
  scene_pass_run(pass, cam, target);
  CHECK(gl_target_read(target, 1, 1, distance, &err) == 0, "read: %s", err.message);
  for (int py = 0; py < H; py += step)
    for (int px = 0; px < W; px += step) {
      double gl = distance[py * W + px];
      double o[3], d[3], s = 0;
      camera_ray(cam, px, py, W, H, o, d);
      bool hit = scene_geometry_intersect(geo, o, d, INFINITY, &s, NULL);
      double cpu = hit ? s : SCENE_SKY_DISTANCE;
      CHECK(fabs(cpu - scene_geometry_pixel_distance(geo, cam, px, py, W, H)) == 0,
            "pixel_distance differs at %d,%d", px, py);
      v.sampled++;
      v.sky += !hit;
      if (hit) {
        double p[3] = {o[0] + s * d[0], o[1] + s * d[1], o[2] + s * d[2]};
        for (int b = 0; b < geo->box_count; b++)
          if (p[0] >= geo->boxes[b].min[0] - 1e-6 && p[0] <= geo->boxes[b].max[0] + 1e-6 &&
              p[1] >= geo->boxes[b].min[1] - 1e-6 && p[1] <= geo->boxes[b].max[1] + 1e-6 &&
              p[2] >= geo->boxes[b].min[2] - 1e-6 && p[2] <= geo->boxes[b].max[2] + 1e-6)
            v.boxes++;
      }
      if (close_enough(gl, cpu)) continue;
      bool near_edge = false;
      for (int k = 0; k < 8 && !near_edge; k++) {
        double jx = px + 0.02 * cos(k * 0.785398), jy = py + 0.02 * sin(k * 0.785398);
        near_edge = close_enough(gl, jittered(geo, cam, jx, jy, W, H));
      }
      if (near_edge) {
        v.edge++;
      } else if (v.failed++ < 5) {
        fprintf(stderr, "pixel (%d,%d): GL %.7g, CPU %.7g\n", px, py, gl, cpu);
      }
    }
  return v;
}

/* Views that make the pass cull terrain tiles (and one that must draw them all). */
static void test_culled_views(const scene_geometry *geo, scene_pass *pass,
                              const gl_target *target, float *distance) {
  const terrain *t = &geo->terrain;
  long terrain_triangles = 2L * (t->resolution_x - 1) * (t->resolution_z - 1);
  /* position[1] 0: `above` the surface there (negative: under it); cull: whether the pass
   * may cull the terrain's back faces (above the surface inside the footprint only) */
  struct {
    const char *name;
    double position[3], yaw, pitch, fov_y;
    double above;
    bool cull;
  } views[] = {
      {"steeply down", {100, 0, -100}, 0.3, -1.3, 0.8, 25, true},
      {"inward from the -x edge", {-480, 0, 0}, 1.5708, -0.05, 1.0, 25, true},
      {"along the -x edge", {-490, 0, 300}, 0.0, -0.1, 1.2, 25, true},
      {"from outside, toward the corner", {-800, 240, 700}, 0.98, -0.2, 0.6, 0, false},
      {"low, into a valley, narrow", {0, 0, 300}, -0.7, -0.02, 0.3, 25, true},
      {"from far above, all of it", {0, 4000, 0}, 0.0, -1.5707, 0.6, 0, true},
      {"from under the terrain, up", {100, 0, -100}, 0.4, 0.8, 0.8, -15, false},
  };
  int n = (int)(sizeof views / sizeof views[0]), fewer = 0, all = 0, culled = 0;
  for (int k = 0; k < n; k++) {
    camera cam = {.position = {views[k].position[0], 0, views[k].position[2]},
                  .yaw = views[k].yaw, .pitch = views[k].pitch, .fov_y = views[k].fov_y,
                      .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    cam.position[1] = views[k].position[1] > 0
                          ? views[k].position[1]
                          : terrain_height_at(t, cam.position[0], cam.position[2]) +
                                views[k].above;
    /* back faces are culled exactly for the cameras above the surface inside the
     * footprint: not from under it, nor from outside (even far above) */
    bool cull = scene_terrain_back_faces_hidden(t, &cam);
    CHECK(cull == views[k].cull, "view %s: back-face culling %s", views[k].name,
          cull ? "on" : "off");
    culled += cull;
    view_stats v = compare_view(geo, pass, target, &cam, 2, distance);
    long drawn = scene_pass_triangles_drawn(pass) - 10L * geo->box_count; /* 5 faces a box */
    printf("view %-32s %5.1f%% of the terrain's triangles drawn; %d pixels sampled, %d sky, "
           "%d edge, %d wrong\n", views[k].name, 100.0 * drawn / terrain_triangles, v.sampled,
           v.sky, v.edge, v.failed);
    CHECK(v.failed == 0, "view %s: %d of %d pixels: GL distance != CPU distance",
          views[k].name, v.failed, v.sampled);
    CHECK(v.edge * 50 < v.sampled, "view %s: %d edge pixels of %d", views[k].name, v.edge,
          v.sampled);
    CHECK(v.sky < v.sampled, "view %s sees no terrain", views[k].name);
    fewer += drawn < terrain_triangles / 4;
    all += drawn == terrain_triangles;
  }
  CHECK(all == 1, "%d views drew the whole terrain, expected only the one from far above", all);
  CHECK(culled == 5, "%d views culled back faces, expected the 5 above the surface", culled);
  CHECK(fewer >= 2, "only %d views drew under a quarter of the terrain", fewer);
}

int main(void) {
  test_dda_matches_brute_force();

  fog_error err = {0};
  scene_desc desc = scene_test_valley();
  desc.boxes[1].colour[0] = 0.6f, desc.boxes[1].colour[1] = 0.2f, desc.boxes[1].colour[2] = 0.1f;
  enum { W = 160, H = 90 };
  scene_test_gl s;
  if (!scene_test_gl_open(&s, &desc, W, H, &err)) return test_finish("test_scene_distance");
  /* A camera above the terrain looking over the boxes toward the horizon (sky visible). */
  camera cam = {.position = {-20, 0, 60}, .fov_y = 1.0,
      .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
  cam.position[1] = terrain_height_at(&s.geo.terrain, -20, 60) + 40;
  cam.yaw = 0.15;
  cam.pitch = -0.12;
  {
    float *distance = malloc(sizeof(float) * W * H);
    float *colour = malloc(sizeof(float) * W * H * 4);
    view_stats v = compare_view(&s.geo, s.pass, &s.target, &cam, 3, distance);
    CHECK(gl_target_read(&s.target, 0, 4, colour, &err) == 0, "read: %s", err.message);
    printf("%d pixels sampled: %d sky, %d on boxes, %d on silhouette edges, %d wrong\n",
           v.sampled, v.sky, v.boxes, v.edge, v.failed);
    CHECK(v.failed == 0, "%d of %d sampled pixels: GL distance != CPU distance", v.failed,
          v.sampled);
    CHECK(v.edge * 50 < v.sampled, "%d edge pixels of %d: too many", v.edge, v.sampled);
    CHECK(v.sky > v.sampled / 20 && v.sky < v.sampled / 2, "the view should show some sky: %d",
          v.sky);
    CHECK(v.boxes > 10, "the view should show the boxes: %d samples on them", v.boxes);
    /* Colours are finite, lit (not black) and opaque. */
    int bad_colour = 0;
    for (int k = 0; k < W * H; k++) {
      const float *c = colour + 4 * k;
      if (!(c[0] >= 0 && c[0] < 10 && c[1] >= 0 && c[2] >= 0 && c[3] == 1.0f) ||
          c[0] + c[1] + c[2] < 0.01f)
        bad_colour++;
    }
    CHECK(bad_colour == 0, "%d pixels with a black, negative or non-opaque colour", bad_colour);
    test_culled_views(&s.geo, s.pass, &s.target, distance);
    free(distance);
    free(colour);
  }
  CHECK(gl_util_check("scene pass", &err) == 0, "%s", err.message);
  scene_test_gl_teardown(&s);
  return test_finish("test_scene_distance");
}
