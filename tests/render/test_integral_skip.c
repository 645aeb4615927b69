/* Empty-space skipping of the exact walk (render/fog_occupancy.h) against the walk without
 * it, on the CPU twin:
 * - skip_below = 0 on grids of fog patches in zero background, every degree, spacings 1
 *   and 2, every profile, random rays and the special ones (axis-parallel, along a knot
 *   line, starting inside an empty block, grazing a patch's corner): the optical depth is
 *   the same double, bit for bit;
 * - skip_below = eps > 0 on the same patches over a background of values in (0, eps]: the
 *   difference stays within the stated bound eps * extinction * g_max * L (L the ray's
 *   length in the box) and is not zero on some rays (the blocks were skipped);
 * - the block bounds are >= |f| at random points (the bound's claim, sampled);
 * - skip_below = 0 on the same grids with the right half's patches negated (a detail band's
 *   signed coefficients): bit for bit too. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "render/fog_field.h"
#include "render/fog_occupancy.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { MAP_W = FOG_TEST_PATCH_W, MAP_H = FOG_TEST_PATCH_H };

static double profile_max(const fog_profile *p) {
  if (p->kind != FOG_PROFILE_BSPLINE) return 1.0;
  double m = 0.0;
  for (int k = 0; k < p->count; k++) m = fmax(m, fabs(p->coefficients[k]));
  return m;
}

static double box_length(const fog_volume *v, const double cam[3], const double dir[3]) {
  double t0, t1;
  if (!fog_box_entry_exit(v, cam, dir, &t0, &t1)) return 0.0;
  return fmax(0.0, t1 - fmax(t0, 0.0));
}

static int rays, differing;
static double worst_ratio;

static void check_ray(const char *what, const fog_volume *v, const transform_grid *g,
                      const fog_occupancy *o, float eps, const double cam[3],
                      const double dir[3], double t_stop) {
  double plain = fog_optical_depth(v, g, cam, dir, 0.0, t_stop);
  double skipped = fog_optical_depth_skipping(v, g, o, eps, cam, dir, 0.0, t_stop);
  rays++;
  if (eps == 0.0f) {
    CHECK(memcmp(&plain, &skipped, sizeof plain) == 0,
          "%s: degree %d spacing %g profile %d: skipping %.17g, walk %.17g (cam %g %g %g dir "
          "%.17g %.17g %.17g)",
          what, g->degree, g->spacing, v->profile.kind, skipped, plain, cam[0], cam[1], cam[2],
          dir[0], dir[1], dir[2]);
    return;
  }
  double bound = eps * v->extinction * profile_max(&v->profile) * box_length(v, cam, dir);
  double diff = fabs(plain - skipped);
  if (diff > 0.0) differing++;
  if (bound > 0.0 && diff / bound > worst_ratio) worst_ratio = diff / bound;
  CHECK(diff <= bound * (1 + 1e-9) + 1e-15,
        "%s: degree %d profile %d eps %g: |delta| %.3e above the bound %.3e", what, g->degree,
        v->profile.kind, eps, diff, bound);
}

static void special_rays(const fog_volume *v, const transform_grid *g, const fog_occupancy *o,
                         float eps) {
  double lo[3], hi[3], cam[3], dir[3];
  fog_volume_box(v, lo, hi);
  for (int a = 0; a < 3; a++) /* axis-parallel, both ways */
    for (int sign = -1; sign <= 1; sign += 2)
      for (int k = 0; k < 4; k++) {
        for (int c = 0; c < 3; c++) {
          cam[c] = fog_test_range(lo[c], hi[c]);
          dir[c] = 0.0;
        }
        cam[a] = sign > 0 ? lo[a] - 3.0 : hi[a] + 3.0;
        dir[a] = sign;
        check_ray("axis-parallel", v, g, o, eps, cam, dir, HUGE_VAL);
      }
  /* Along and across knot lines: camera on a knot (grid coordinates -> world). */
  double h = v->cell_size, off = (g->degree % 2 == 0) ? -0.5 : 0.0;
  for (int k = 0; k < 16; k++) {
    double xk = 8 * (k % 5) + off + 3, zk = 8 * (k % 3) + off + 5;
    cam[0] = v->origin_x + ((xk * g->spacing + g->origin_u) + 0.5) * h;
    cam[2] = v->origin_z + ((zk * g->spacing + g->origin_v) + 0.5) * h;
    cam[1] = fog_test_range(lo[1], hi[1]);
    dir[0] = (k % 2) ? 1.0 : -1.0;
    dir[1] = fog_test_range(-0.1, 0.1);
    dir[2] = (k % 4 == 0) ? 0.0 : (k % 4 == 1 ? 1.0 : 0.37);
    fog_test_unit(dir);
    check_ray("across knot lines", v, g, o, eps, cam, dir, HUGE_VAL);
    dir[0] = 0.0, dir[2] = (k % 2) ? 1.0 : -1.0;
    fog_test_unit(dir);
    check_ray("along a knot line", v, g, o, eps, cam, dir, HUGE_VAL);
    dir[0] = dir[2] = 1.0; /* a diagonal through knot corners */
    dir[1] = 0.0;
    fog_test_unit(dir);
    check_ray("through knot corners", v, g, o, eps, cam, dir, 0.7 * (hi[0] - lo[0]));
  }
}

static void bound_covers_f(const fog_volume *v, const transform_grid *g, const fog_occupancy *o) {
  /* |f| at random points <= the bound of the block holding the point's knot cell. */
  double off = (g->degree % 2 == 0) ? -0.5 : 0.0;
  int bad = 0;
  for (int s = 0; s < 4000; s++) {
    double p[3] = {v->origin_x + fog_test_range(0, MAP_W) * v->cell_size, 1.0,
                   v->origin_z + fog_test_range(0, MAP_H) * v->cell_size};
    double f = fog_extinction_point(v, g, p) / v->extinction; /* g(y = 1) = 1 below y0 */
    double x = ((p[0] - v->origin_x) / v->cell_size - 0.5 - g->origin_u) / g->spacing;
    double z = ((p[2] - v->origin_z) / v->cell_size - 0.5 - g->origin_v) / g->spacing;
    float b = fog_occupancy_at(o, (int)floor(x - off), (int)floor(z - off));
    if (fabs(f) > b * (1 + 1e-6)) bad++;
  }
  CHECK(bad == 0, "degree %d: %d sampled |f| above their block's bound", g->degree, bad);
}

int main(void) {
  const fog_profile_kind kinds[3] = {FOG_PROFILE_SLAB, FOG_PROFILE_EXPONENTIAL,
                                     FOG_PROFILE_BSPLINE};
  /* pass 2: the patches of the grid's right half negated, as a wavelet detail band's
   * signed coefficients (the sum of details skips those bands' blocks): a block of
   * negative coefficients alone is not empty (the bound is of |c|; with c, a detail band's
   * skip changed its optical depth by 0.03 to 0.3) */
  for (int pass = 0; pass < 3; pass++) {
    float eps = pass == 1 ? 0.01f : 0.0f;
    for (int degree = 0; degree <= 2; degree++)
      for (int sp = 0; sp < 2; sp++)
        for (int k = 0; k < 3; k++) {
          fog_volume v = fog_test_patch_volume(kinds[k]);
          transform_grid g = fog_test_patch_grid(degree, sp ? 2.0 : 1.0, eps);
          for (int j = 0; pass == 2 && j < g.height; j++)
            for (int i = g.width / 2; i < g.width; i++)
              g.coefficients[(size_t)j * (size_t)g.width + (size_t)i] *= -1.0f;
          fog_occupancy o;
          fog_error oerr = {0};
          CHECK(fog_occupancy_create(&o, &g, &oerr) == 0, "occupancy: %s", oerr.message);
          if (k == 1) bound_covers_f(&v, &g, &o);
          for (int r = 0; r < 400; r++) {
            double cam[3], dir[3];
            fog_test_ray(&v, cam, dir);
            double t_stop = (r % 4 == 0) ? fog_test_range(0, 400) : HUGE_VAL;
            check_ray("random", &v, &g, &o, eps, cam, dir, t_stop);
          }
          special_rays(&v, &g, &o, eps);
          fog_occupancy_destroy(&o);
          transform_grid_destroy(&g);
        }
  }
  printf("%d rays; with eps > 0 %d differ, worst |delta| / bound %.3f\n", rays, differing,
         worst_ratio);
  CHECK(differing > 100, "eps > 0 changed only %d rays: were the blocks skipped?", differing);
  return test_finish("test_integral_skip");
}
