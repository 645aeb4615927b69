/* Terrain from given heights against an analytic oracle: heights sampled from a tilted
 * plane y = y0 + a x + b z make a mesh that IS that plane (every triangle lies in it,
 * whatever the triangulation), so ray hits have a closed form:
 *   s = (y0 + a ox + b oz - oy) / (dy - a dx - b dz).
 * Checked: terrain_height_at, terrain_intersect (CPU, double) to 1e-9, and the GL
 * distance texture of the scene pass to 1e-4 relative at every pixel that sees the plane
 * away from its edges; pixels whose ray misses the plane's square see the sky. */
#include <math.h>
#include <stdlib.h>

#include "render/render.h"
#include "test_util.h"

#define N 33
static const double y0 = 10.0, slope_x = 0.05, slope_z = -0.12;
static const double origin_x = -200, origin_z = -300, size_x = 400, size_z = 500;

static double plane(double x, double z) { return y0 + slope_x * x + slope_z * z; }

int main(void) {
  /* h in [0, 1]: y = origin_y + height * h, so pick origin_y and height to fit the plane. */
  double lo = INFINITY, hi = -INFINITY;
  for (int j = 0; j < 2; j++)
    for (int i = 0; i < 2; i++) {
      double y = plane(origin_x + i * size_x, origin_z + j * size_z);
      lo = fmin(lo, y), hi = fmax(hi, y);
    }
  float heights[N * N];
  for (int j = 0; j < N; j++)
    for (int i = 0; i < N; i++) {
      double x = origin_x + i * size_x / (N - 1), z = origin_z + j * size_z / (N - 1);
      heights[j * N + i] = (float)((plane(x, z) - lo) / (hi - lo));
    }
  /* The stored heights are floats: use the plane they represent to float rounding. */
  scene_desc desc = {.terrain = {.origin = {origin_x, lo, origin_z}, .size = {size_x, size_z},
                                 .height = hi - lo, .heights = heights, .heights_width = N,
                                 .heights_height = N},
                     .light = scene_light_default()};
  fog_error err = {0};
  scene_geometry geo;
  int status = scene_geometry_create(&geo, &desc, &err);
  CHECK(status == 0, "%s", err.message);
  if (status) return test_finish("test_scene_plane");
  const terrain *t = &geo.terrain;
  CHECK(t->resolution_x == N && t->resolution_z == N, "grid %dx%d", t->resolution_x, t->resolution_z);

  double worst_h = 0;
  for (int k = 0; k < 1000; k++) {
    double x = origin_x + size_x * ((k * 37) % 1000) / 1000.0, z = origin_z + size_z * ((k * 91) % 1000) / 1000.0;
    worst_h = fmax(worst_h, fabs(terrain_height_at(t, x, z) - plane(x, z)));
  }
  /* float heights: |error| <= (hi - lo) * 2^-24 per vertex */
  CHECK(worst_h < 1e-5 * (hi - lo), "terrain_height_at differs from the plane by %g", worst_h);

  double worst_s = 0;
  int hits = 0;
  for (int k = 0; k < 500; k++) {
    double o[3] = {-150 + (k % 25) * 12.0, 120 + (k % 7) * 10.0, -250 + (k / 25) * 20.0};
    double d[3] = {sin(k * 0.7) * 0.6, -1.0, cos(k * 1.3) * 0.6};
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int c = 0; c < 3; c++) d[c] /= len;
    double s_true = (plane(o[0], o[2]) - o[1]) / (d[1] - slope_x * d[0] - slope_z * d[2]);
    double px = o[0] + s_true * d[0], pz = o[2] + s_true * d[2];
    bool inside = px > origin_x + 1 && px < origin_x + size_x - 1 && pz > origin_z + 1 &&
                  pz < origin_z + size_z - 1;
    double s;
    bool hit = terrain_intersect(t, o, d, INFINITY, &s, NULL);
    if (!inside) continue;
    hits++;
    CHECK(hit, "ray %d misses the plane (analytic s = %g)", k, s_true);
    if (hit) worst_s = fmax(worst_s, fabs(s - s_true) / s_true);
  }
  printf("CPU: %d rays, worst relative error %.3g\n", hits, worst_s);
  CHECK(hits > 300, "only %d rays inside", hits);
  CHECK(worst_s < 1e-6, "CPU intersection off by %g relative", worst_s);

  /* GL: the distance texture against the analytic distance. */
  gl_context *ctx = gl_context_create(NULL, &err);
  CHECK(ctx != NULL, "%s", err.message);
  if (ctx) {
    scene_pass *pass = scene_pass_create(&geo, &err);
    CHECK(pass != NULL, "%s", err.message);
    enum { W = 96, H = 64 };
    gl_target target;
    CHECK(scene_target_create(&target, W, H, &err) == 0, "%s", err.message);
    camera cam = {.position = {0, 90, 150}, .fov_y = 1.1,
        .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
    double at[3] = {0, 0, -150};
    camera_look_at(&cam, at);
    float *distance = malloc(sizeof(float) * W * H);
    if (pass) {
      scene_pass_run(pass, &cam, &target);
      CHECK(gl_target_read(&target, 1, 1, distance, &err) == 0, "%s", err.message);
      int plane_pixels = 0, sky_pixels = 0, wrong = 0;
      for (int py = 0; py < H; py++)
        for (int px = 0; px < W; px++) {
          double o[3], d[3];
          camera_ray(&cam, px, py, W, H, o, d);
          double denom = d[1] - slope_x * d[0] - slope_z * d[2];
          double s_true = denom < 0 ? (plane(o[0], o[2]) - o[1]) / denom : INFINITY;
          double hx = o[0] + s_true * d[0], hz = o[2] + s_true * d[2];
          double margin = 3.0; /* world units away from the square's edges */
          bool on = isfinite(s_true) && hx > origin_x + margin && hx < origin_x + size_x - margin &&
                    hz > origin_z + margin && hz < origin_z + size_z - margin;
          bool off = !isfinite(s_true) || hx < origin_x - margin || hx > origin_x + size_x + margin ||
                     hz < origin_z - margin || hz > origin_z + size_z + margin;
          double gl = distance[py * W + px];
          if (on) {
            plane_pixels++;
            if (fabs(gl - s_true) > 1e-4 * s_true) {
              if (wrong++ < 3) fprintf(stderr, "pixel (%d,%d): GL %g, plane %g\n", px, py, gl, s_true);
            }
          } else if (off) {
            sky_pixels++;
            if (gl != SCENE_SKY_DISTANCE && wrong++ < 3)
              fprintf(stderr, "pixel (%d,%d): GL %g, expected sky\n", px, py, gl);
          }
        }
      printf("GL: %d plane pixels, %d sky pixels, %d wrong\n", plane_pixels, sky_pixels, wrong);
      CHECK(wrong == 0, "%d pixels differ from the analytic distance", wrong);
      CHECK(plane_pixels > W * H / 3 && sky_pixels > W * H / 20, "view: %d plane, %d sky",
            plane_pixels, sky_pixels);
    }
    free(distance);
    gl_target_destroy(&target);
    scene_pass_destroy(pass);
    gl_context_destroy(ctx);
  }
  scene_geometry_destroy(&geo);
  return test_finish("test_scene_plane");
}
