/* The lamps' shadow cubes (render/lamp_shadow_map.h).
 *
 * On the CPU, the faces' geometry from its definitions: every direction lands inside the
 * window of exactly the face of its largest component (GL's cube-map face selection), at
 * depth -1 on the near plane and +1 on the far one; a face culls a box only when none of
 * 4000 points sampled in it is inside the face's pyramid; a spot skips a face only when
 * none of 20000 directions sampled in its outer cone falls on it.
 *
 * The cut at a shadow's edge integrates the rest of the integrand over a stretch of a piece
 * as the cubic through its 4 Gauss nodes (fog_lamp_lagrange_integrals): exact for cubics
 * on any stretch, the Gauss weights over the whole piece, additive.
 *
 * On GL, the scene pass's lamp share of each surface pixel (attachment 3) against exact ray
 * casts (scene_geometry_intersect from the surface point to the lamp): dark where the ray
 * meets the terrain or a box, lit where it meets nothing, but for pixels within a couple of
 * texels of a shadow's edge (counted and bounded), for a point lamp among boxes on hills
 * and a spot. With the cubes off the same comparison fails (printed, and asserted to
 * disagree many times more). Two lamps at once give the sum of each alone, per pixel: each
 * lamp reads its own cube. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "scene_test_gl.h"
#include "test_util.h"

enum { W = 200, H = 120 };
static const double pi = 3.14159265358979323846;

static double urand(unsigned *s) {
  *s = *s * 1664525u + 1013904223u;
  return (*s >> 8) / 16777216.0;
}

/* The face GL picks for direction v: the largest |component|, its sign (spec 8.13). */
static int major_face(const double v[3]) {
  int a = 0;
  for (int c = 1; c < 3; c++)
    if (fabs(v[c]) > fabs(v[a])) a = c;
  return 2 * a + (v[a] < 0);
}

static void clip_of(const double m[4][4], const double v[3], double out[4]) {
  for (int r = 0; r < 4; r++) out[r] = m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2] + m[r][3];
}

static bool in_window(const double c[4]) {
  return c[3] > 0 && fabs(c[0]) <= c[3] * (1 + 1e-12) && fabs(c[1]) <= c[3] * (1 + 1e-12);
}

static void check_faces(void) {
  unsigned seed = 7;
  int wrong = 0, depth_wrong = 0;
  for (int k = 0; k < 4000; k++) {
    double v[3];
    for (int c = 0; c < 3; c++) v[c] = 2 * urand(&seed) - 1;
    const int own = major_face(v);
    for (int f = 0; f < 6; f++) {
      double m[4][4], c[4];
      lamp_shadow_face_clip(f, 0.5, 300.0, m);
      clip_of(m, v, c);
      if (in_window(c) != (f == own)) wrong++;
      if (f != own) continue;
      /* the same direction scaled onto the near and far planes along the face's axis */
      const double ma = fabs(v[own / 2]);
      for (int end = 0; end < 2; end++) {
        double p[3], q[4];
        for (int a = 0; a < 3; a++) p[a] = v[a] / ma * (end ? 300.0 : 0.5);
        clip_of(m, p, q);
        if (fabs(q[2] / q[3] - (end ? 1.0 : -1.0)) > 1e-9) depth_wrong++;
      }
    }
  }
  printf("faces: %d of 24000 direction-face pairs disagree with the major axis, %d depths off\n",
         wrong, depth_wrong);
  CHECK(wrong == 0 && depth_wrong == 0, "cube faces: %d windows, %d depths wrong", wrong,
        depth_wrong);

  int culled = 0, wrong_cull = 0;
  for (int k = 0; k < 600; k++) {
    double lo[3], hi[3];
    for (int c = 0; c < 3; c++) {
      double a = 40 * urand(&seed) - 20, b = a + 10 * urand(&seed);
      lo[c] = a, hi[c] = b;
    }
    for (int f = 0; f < 6; f++) {
      double m[4][4];
      lamp_shadow_face_clip(f, 0.01, 1e3, m);
      bool seen = false;
      for (int s = 0; s < 4000 && !seen; s++) {
        double p[3], c[4];
        for (int a = 0; a < 3; a++) p[a] = lo[a] + urand(&seed) * (hi[a] - lo[a]);
        clip_of(m, p, c);
        seen = in_window(c);
      }
      bool culls = lamp_shadow_face_culls_box(f, lo, hi);
      culled += culls;
      wrong_cull += culls && seen;
    }
  }
  printf("face culling: %d of 3600 box-face pairs culled, %d of them wrongly\n", culled,
         wrong_cull);
  CHECK(wrong_cull == 0, "%d boxes culled from a face that sees them", wrong_cull);
  CHECK(culled > 900, "only %d box-face pairs culled: the test sees nothing", culled);

  int skipped = 0, wrong_skip = 0;
  for (int k = 0; k < 60; k++) {
    fog_lamp spot = {.kind = FOG_LAMP_SPOT, .radius = 0.5};
    double n = 0;
    for (int c = 0; c < 3; c++) spot.axis[c] = 2 * urand(&seed) - 1, n += spot.axis[c] * spot.axis[c];
    for (int c = 0; c < 3; c++) spot.axis[c] /= sqrt(n);
    const double outer = (5 + 80 * urand(&seed)) * pi / 180;
    spot.cos_outer = cos(outer), spot.cos_inner = cos(0.5 * outer);
    bool hit[6] = {0};
    for (int s = 0; s < 20000; s++) {
      double v[3], len = 0;
      for (int c = 0; c < 3; c++) v[c] = 2 * urand(&seed) - 1, len += v[c] * v[c];
      len = sqrt(len);
      /* a direction inside the cone: towards the axis until it is */
      double along = (v[0] * spot.axis[0] + v[1] * spot.axis[1] + v[2] * spot.axis[2]) / len;
      if (along < spot.cos_outer) continue;
      hit[major_face(v)] = true;
    }
    for (int f = 0; f < 6; f++) {
      bool needed = lamp_shadow_face_needed(&spot, f);
      skipped += !needed;
      wrong_skip += !needed && hit[f];
    }
  }
  printf("spots: %d of 360 faces skipped, %d of them wrongly\n", skipped, wrong_skip);
  CHECK(wrong_skip == 0, "%d faces a spot lights were skipped", wrong_skip);
  CHECK(skipped > 60, "only %d faces skipped", skipped);
}

static void check_lagrange(void) {
  static const double gauss_w[4] = {0.34785484513745386, 0.65214515486254614,
                                    0.65214515486254614, 0.34785484513745386};
  static const double gauss_x[4] = {-0.86113631159405258, -0.33998104358485626,
                                    0.33998104358485626, 0.86113631159405258};
  double w[4], worst = 0;
  fog_lamp_lagrange_integrals(-1.0, 1.0, w);
  for (int n = 0; n < 4; n++) worst = fmax(worst, fabs(w[n] - gauss_w[n]));
  unsigned seed = 11;
  for (int k = 0; k < 200; k++) {
    double c[4], u0 = 2 * urand(&seed) - 1, u1 = 2 * urand(&seed) - 1, mid = 2 * urand(&seed) - 1;
    for (int j = 0; j < 4; j++) c[j] = 4 * urand(&seed) - 2;
    /* the cubic's exact integral against the nodes' values times the weights */
    double exact = 0, by_nodes = 0, a[4], b[4];
    for (int j = 0; j < 4; j++) exact += c[j] * (pow(u1, j + 1) - pow(u0, j + 1)) / (j + 1);
    fog_lamp_lagrange_integrals(u0, u1, w);
    fog_lamp_lagrange_integrals(u0, mid, a);
    fog_lamp_lagrange_integrals(mid, u1, b);
    for (int n = 0; n < 4; n++) {
      double x = gauss_x[n], p = c[0] + x * (c[1] + x * (c[2] + x * c[3]));
      by_nodes += p * w[n];
      worst = fmax(worst, fabs(a[n] + b[n] - w[n]));
    }
    worst = fmax(worst, fabs(by_nodes - exact));
  }
  printf("the cut's cubic: weights, exactness on 200 cubics and stretches, additivity: %.2e\n",
         worst);
  CHECK(worst < 1e-13, "fog_lamp_lagrange_integrals off by %.2e", worst);
}

typedef struct lamp_stats {
  int facing;   /* surface pixels facing the lamp, inside its cone */
  int shadowed; /* of those, in the exact shadow */
  int wrong;    /* GL lit in the exact shadow, or dark outside it */
} lamp_stats;

/* Surface point, normal and the lamp's unshadowed irradiance factor at pixel (px, py); false
 * for the sky, faces turned away and the spot's rim (S < 0.05). */
static bool lamp_pixel(const scene_geometry *geo, const camera *cam, const fog_lamp *lamp,
                       int px, int py, double p[3], double n[3], double *to_lamp_dist) {
  double o[3], d[3], s;
  camera_ray(cam, px, py, W, H, o, d);
  if (!scene_geometry_intersect(geo, o, d, INFINITY, &s, n)) return false;
  double l[3], dist = 0;
  for (int a = 0; a < 3; a++) p[a] = o[a] + s * d[a], l[a] = lamp->position[a] - p[a];
  dist = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  *to_lamp_dist = dist;
  if ((n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / dist < 0.15) return false;
  return fog_lamp_spot(lamp, p) > 0.05;
}

static lamp_stats compare(const scene_geometry *geo, scene_pass *pass, const gl_target *t,
                          const camera *cam, const fog_lamp *lamp, float *share) {
  fog_error err = {0};
  const fog_lamps lamps = {.lamp = {*lamp}, .count = 1};
  CHECK(scene_pass_set_lamps(pass, &lamps, &err) == 0, "lamps: %s", err.message);
  scene_pass_run(pass, cam, t);
  CHECK(gl_target_read(t, 3, 4, share, &err) == 0, "read: %s", err.message);
  lamp_stats st = {0};
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double p[3], n[3], dist;
      if (!lamp_pixel(geo, cam, lamp, px, py, p, n, &dist)) continue;
      double q[3], w[3], s;
      for (int a = 0; a < 3; a++) q[a] = p[a] + 1e-3 * n[a], w[a] = (lamp->position[a] - p[a]) / dist;
      bool blocked = scene_geometry_intersect(geo, q, w, dist, &s, NULL);
      /* lit: albedo (>= 0.05) x I cos S / (pi (d^2 + r^2)); dark: 2 % of that at most */
      double cos_n = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
      double lit = 0.05 * lamp->intensity[0] * cos_n * fog_lamp_spot(lamp, p) /
                   (pi * (dist * dist + lamp->radius * lamp->radius));
      const float *c = &share[4 * (py * W + px)];
      bool dark = c[0] < 0.02 * lit;
      st.facing++;
      st.shadowed += blocked;
      st.wrong += dark != blocked;
    }
  return st;
}

int main(void) {
  check_faces();
  check_lagrange();
  fog_error err = {0};
  scene_desc desc = {
      .terrain = {.origin = {-300, -20, -300}, .size = {600, 600}, .height = 60,
                  .resolution = 129, .seed = 3, .octaves = 6, .frequency = 3,
                  .persistence = 0.5},
      .boxes = {{.center = {0, 0}, .size = {12, 30, 8}, .colour = SCENE_BOX_GREY},
                {.center = {30, 25}, .size = {6, 45, 6}, .colour = SCENE_BOX_GREY},
                {.center = {-25, 30}, .size = {20, 10, 4}, .colour = SCENE_BOX_GREY}},
      .box_count = 3,
      .light = scene_light_default(),
  };
  scene_test_gl s;
  if (!scene_test_gl_open(&s, &desc, W, H, &err)) return test_finish("test_lamp_shadow_map");
  const double ground = terrain_height_at(&s.geo.terrain, 5, 15);
  camera cam = {.position = {5, ground + 90, 95}, .fov_y = 1.1, .yaw = 0.0, .pitch = -0.75,
                .near_plane = 0.1, .far_plane = 100000};
  static float share[4 * W * H], share_a[4 * W * H], share_b[4 * W * H];
  fog_lamp point = {.kind = FOG_LAMP_POINT, .position = {8, ground + 12, 15},
                    .intensity = {3000, 3000, 3000}, .radius = 0.5};
  fog_lamp spot = {.kind = FOG_LAMP_SPOT, .position = {-40, ground + 40, -30},
                   .intensity = {20000, 20000, 20000}, .radius = 0.5,
                   .cos_inner = cos(25 * pi / 180), .cos_outer = cos(40 * pi / 180)};
  {
    double a[3] = {50, -40 - 0.0, 60}, n = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int c = 0; c < 3; c++) spot.axis[c] = a[c] / n;
  }
  const fog_lamp *cases[2] = {&point, &spot};
  const char *names[2] = {"point lamp among the boxes", "spot over the hills"};
  for (int k = 0; k < 2; k++) {
    lamp_stats st = compare(&s.geo, s.pass, &s.target, &cam, cases[k], share);
    double wrong = st.facing ? (double)st.wrong / st.facing : 1.0;
    CHECK(scene_pass_set_lamp_shadows(s.pass, 0, &err) == 0, "%s", err.message);
    lamp_stats off = compare(&s.geo, s.pass, &s.target, &cam, cases[k], share);
    CHECK(scene_pass_set_lamp_shadows(s.pass, LAMP_SHADOW_SIZE, &err) == 0, "%s", err.message);
    printf("%s: %d pixels face it, %d in its exact shadow; the cube disagrees on %d (%.2f %%), "
           "without the cube %d\n", names[k], st.facing, st.shadowed, st.wrong, 100 * wrong,
           off.wrong);
    CHECK(st.shadowed > st.facing / 20, "%s: too little shadow in view to test", names[k]);
    CHECK(wrong < 0.03, "%s: the cube disagrees with the ray casts on %.2f %%", names[k],
          100 * wrong);
    CHECK(off.wrong > 5 * st.wrong, "%s: without the cube only %d wrong", names[k], off.wrong);
  }
  /* two lamps at once: each reads its own cube, the shares add (on surfaces: the sky does
   * not write attachment 3) */
  {
    compare(&s.geo, s.pass, &s.target, &cam, &point, share_a);
    compare(&s.geo, s.pass, &s.target, &cam, &spot, share_b);
    const fog_lamps both = {.lamp = {point, spot}, .count = 2};
    CHECK(scene_pass_set_lamps(s.pass, &both, &err) == 0, "lamps: %s", err.message);
    scene_pass_run(s.pass, &cam, &s.target);
    CHECK(gl_target_read(&s.target, 3, 4, share, &err) == 0, "read: %s", err.message);
    static float distance[W * H];
    CHECK(gl_target_read(&s.target, 1, 1, distance, &err) == 0, "read: %s", err.message);
    double worst = 0, peak = 0;
    for (int k = 0; k < W * H; k++)
      for (int c = 0; c < 3 && distance[k] < SCENE_SKY_DISTANCE; c++) {
        double sum = (double)share_a[4 * k + c] + share_b[4 * k + c];
        worst = fmax(worst, fabs(share[4 * k + c] - sum));
        peak = fmax(peak, sum);
      }
    printf("two lamps: max |both - (each alone summed)| = %.3e of a peak %.3e\n", worst, peak);
    CHECK(worst <= 1e-3 * peak, "two lamps' shares do not add: %.3e", worst);
  }
  scene_test_gl_teardown(&s);
  return test_finish("test_lamp_shadow_map");
}
