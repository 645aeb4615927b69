/* The sun's shadow map (render/sun_shadow_map.h) against exact ray casts: the scene pass's
 * sun-lit share (attachment 2) of each surface pixel is 0 where the CPU's ray from the
 * surface point towards the sun meets the terrain or a box (scene_geometry_intersect, the
 * exact DDA walk of the mesh), and > 0 where it meets nothing; only pixels within a couple
 * of shadow-map texels of a shadow's edge may disagree (PCF and the map's resolution),
 * counted and bounded. Low suns from three sides over a hilly terrain with boxes.
 *
 * Where it fails, shown: a post thinner than a texel (0.8 units against the map's ~2)
 * casts a shadow the map largely misses; the fraction of its exact shadow that the GL
 * finds is printed (and asserted to be below the fraction for a post 8 texels wide). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "scene_test_gl.h"
#include "test_util.h"

enum { W = 200, H = 120 };
static const double pi = 3.14159265358979323846;

typedef struct shadow_stats {
  int lit_faces;   /* surface pixels facing the sun (n . sun > 0.15) */
  int shadowed;    /* of those, in the exact shadow */
  int wrong;       /* GL lit where the exact shadow is, or dark where it is not */
  double texel;
} shadow_stats;

/* The exact visibility of the sun from surface point p with normal n. */
static bool sun_visible(const scene_geometry *geo, const double p[3], const double n[3]) {
  double q[3], s;
  for (int a = 0; a < 3; a++) q[a] = p[a] + 1e-3 * n[a];
  return !scene_geometry_intersect(geo, q, geo->sun_direction, INFINITY, &s, NULL);
}

/* Exact shadow of pixel k's surface; -1 where the pixel is sky or faces away. */
static int exact_shadow(const scene_geometry *geo, const camera *cam, int px, int py) {
  double o[3], d[3], s, n[3], p[3];
  camera_ray(cam, px, py, W, H, o, d);
  if (!scene_geometry_intersect(geo, o, d, INFINITY, &s, n)) return -1;
  const double *sun = geo->sun_direction;
  if (n[0] * sun[0] + n[1] * sun[1] + n[2] * sun[2] < 0.15) return -1;
  for (int a = 0; a < 3; a++) p[a] = o[a] + s * d[a];
  return sun_visible(geo, p, n) ? 0 : 1;
}

static shadow_stats compare(const scene_geometry *geo, scene_pass *pass, const gl_target *t,
                            const camera *cam, float *share) {
  fog_error err = {0};
  scene_pass_run(pass, cam, t);
  CHECK(gl_target_read(t, 2, 3, share, &err) == 0, "read: %s", err.message);
  shadow_stats st = {.texel = sun_shadow_map_texel(scene_pass_sun_shadow(pass))};
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      int e = exact_shadow(geo, cam, px, py);
      if (e < 0) continue;
      st.lit_faces++;
      st.shadowed += e;
      const float *c = &share[3 * (py * W + px)];
      bool dark = c[0] + c[1] + c[2] < 1e-5f;
      if (dark != (e == 1)) st.wrong++;
    }
  return st;
}

static void set_sun(scene_geometry *geo, double azimuth_deg, double elevation_deg) {
  geo->light.sun_azimuth = azimuth_deg, geo->light.sun_elevation = elevation_deg;
  scene_light_sun_direction(&geo->light, geo->sun_direction);
}

/* The exact shadow of a post of the given width (its own scene, in the current context): the
 * fraction of its exactly shadowed ground pixels the GL finds dark. */
static double post_shadow_found(double width) {
  fog_error err = {0};
  scene_desc desc = {
      .terrain = {.origin = {-2000, 0, -2000}, .size = {4000, 4000}, .height = 1e-3,
                  .resolution = 9, .seed = 1, .octaves = 6, .frequency = 3,
                  .persistence = 0.5},
      .boxes = {{.center = {0, 0}, .size = {width, 40, width}, .colour = SCENE_BOX_GREY}},
      .box_count = 1,
      .light = scene_light_default(),
  };
  desc.light.sun_azimuth = 90, desc.light.sun_elevation = 20;
  scene_test_gl s;
  if (!scene_test_gl_setup(&s, &desc, W, H, &err)) return NAN;
  /* looking down at the ground west of the post, where its shadow falls */
  camera cam = {.position = {-60, 12, 0.01}, .fov_y = 1.0, .yaw = -0.5 * pi, .pitch = -1.45,
                .near_plane = 0.1, .far_plane = 1000};
  static float share[3 * W * H];
  shadow_stats st = compare(&s.geo, s.pass, &s.target, &cam, share);
  int found = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++)
      if (exact_shadow(&s.geo, &cam, px, py) == 1) {
        const float *c = &share[3 * (py * W + px)];
        found += c[0] + c[1] + c[2] < 0.1f; /* lit ground: ~1.0 */
      }
  double fraction = st.shadowed ? (double)found / st.shadowed : NAN;
  printf("a post %.2f wide (%.2f shadow-map texels): %d exactly shadowed pixels, the map "
         "darkens %.0f %% of them\n", width, width / st.texel, st.shadowed, 100 * fraction);
  scene_test_gl_teardown(&s);
  return fraction;
}

int main(void) {
  fog_error err = {0};
  const scene_desc desc = scene_test_valley();
  scene_test_gl s;
  if (!scene_test_gl_open(&s, &desc, W, H, &err)) return test_finish("test_sun_shadow_map");
  camera cam = {.position = {-20, 0, 60}, .fov_y = 1.0, .yaw = 0.15, .pitch = -0.25,
                .near_plane = 0.1, .far_plane = 100000};
  cam.position[1] = terrain_height_at(&s.geo.terrain, -20, 60) + 60;
  static float share[3 * W * H];
  const double suns[3][2] = {{90, 12}, {-60, 18}, {170, 25}};
  for (int k = 0; k < 3; k++) {
    set_sun(&s.geo, suns[k][0], suns[k][1]);
    shadow_stats st = compare(&s.geo, s.pass, &s.target, &cam, share);
    double wrong = st.lit_faces ? (double)st.wrong / st.lit_faces : 1.0;
    printf("sun azimuth %g, elevation %g: %d pixels face the sun, %d in the exact shadow; "
           "the map disagrees on %d (%.2f %%; texel %.2f units)\n", suns[k][0], suns[k][1],
           st.lit_faces, st.shadowed, st.wrong, 100 * wrong, st.texel);
    CHECK(st.shadowed > st.lit_faces / 50, "sun %d: too little shadow in view to test", k);
    CHECK(wrong < 0.03, "sun %d: the map disagrees with the ray casts on %.2f %%", k, 100 * wrong);
  }
  /* the post scene's map: ~2 units a texel (a 4000-unit ground on 2048 texels) */
  double thin = post_shadow_found(0.8), wide = post_shadow_found(16);
  CHECK(wide > 0.8, "a post 8 texels wide: only %.0f %% of its shadow", 100 * wide);
  CHECK(thin < 0.5 && thin < wide, "a sub-texel post's shadow is found as well as a wide one's (%.2f, %.2f)",
        thin, wide);
  scene_test_gl_teardown(&s);
  return test_finish("test_sun_shadow_map");
}
