/* The sun's mean per piece of the exact walk ([light] shadow_pieces, fog_piece_light): with
 * the light 1 everywhere (no shadow, no shaft) the mean S / (1 - e^{-D}) is 1, exactly up
 * to rounding, however thick a piece is: each piece weighs e^{-D}(1 - e^{-dD}), whose sum
 * telescopes to 1 - e^{-D}. Gauss on tau K itself missed it once a piece was optically
 * thick: through a dense volume the fully lit mean was 0.07 (1 node) and 1.37 (2 nodes,
 * brighter than the sun allows). And a light that is half 0, half 1 along the ray gives a
 * mean between 0 and 1. The volume's walk (fog_grid3d_light_integral) and the fogmap's
 * (fog_fogmap_light_integral) share the piece rule.
 * A piece whose first node holds no fog (K 0: a wavelet approximation's ringing clamped)
 * and whose second is dense puts all of its weight on the second: with the light 0 at the
 * first node and 1 at the second the mean is 1 at any density (the weights were taken
 * relative to the empty node's; the dense node's underflowed from h K ~ 1290 on, both were
 * 0, and the mean fell back to the plain average 0.5: denser fog drew half-lit). */
#include <math.h>
#include <stdio.h>

#include "render/render.h"
#include "test_util.h"

enum { N = 8 };
static float voxels[N * N * N];

static double light_one(const void *user, const double p[3]) {
  (void)user, (void)p;
  return 1.0;
}
static double light_far_half(const void *user, const double p[3]) {
  (void)user;
  return p[0] > 4.0 ? 1.0 : 0.0; /* the half of the volume beyond x = 4 is lit */
}

int main(void) {
  volume_grid_desc g = {.dim = {N, N, N}, .values = voxels};
  for (int a = 0; a < 3; a++) g.index_from_world[a][a] = 1.0; /* voxel u at world u */
  const double densities[] = {0.5, 5.0, 10.0, 20.0};
  const double outside[3] = {-3.0, 3.3, 3.6}, inside[3] = {1.2, 3.3, 3.6};
  const double dir[3] = {1.0, 0.0, 0.0};
  for (int k = 0; k < 4; k++) {
    for (int i = 0; i < N * N * N; i++) voxels[i] = (float)densities[k];
    for (int nodes = 1; nodes <= 2; nodes++)
      for (int start = 0; start < 2; start++) {
        const double *o = start ? inside : outside;
        double D = 0.0;
        const double S =
            fog_grid3d_light_integral(&g, o, dir, 100.0, nodes, 1e30, light_one, NULL, &D);
        const double mean = S / -expm1(-D);
        printf("density %4g, %d node%s, camera %s: depth %.4g, lit mean %.15f\n",
               densities[k], nodes, nodes > 1 ? "s" : " ", start ? "inside " : "outside", D,
               mean);
        CHECK(D > 0 && fabs(mean - 1.0) <= 1e-12, "density %g, %d nodes, camera %s: the fully "
              "lit mean is %.15f", densities[k], nodes, start ? "inside" : "outside", mean);
        const double half = fog_grid3d_light_integral(&g, o, dir, 100.0, nodes, 1e30,
                                                      light_far_half, NULL, &D) /
                            -expm1(-D);
        CHECK(half >= 0.0 && half <= 1.0, "density %g, %d nodes: a half-lit mean of %g",
              densities[k], nodes, half);
      }
  }
  {
    double x[FOG_PIECE_MAX_NODES], w[FOG_PIECE_MAX_NODES];
    double partial[FOG_PIECE_MAX_NODES][FOG_PIECE_MAX_NODES];
    fog_gauss_rule(2, x, w, partial);
    double worst = 0.0;
    for (double K1 = 10.0; K1 <= 1e6; K1 *= 10.0) {
      const double K[FOG_PIECE_MAX_NODES] = {0.0, K1}, f[FOG_PIECE_MAX_NODES] = {0.0, 1.0};
      double D = 0.0;
      const double S = fog_piece_light(2, w, partial, 0.5, K, f, &D);
      const double mean = S / -expm1(-D);
      CHECK(fabs(mean - 1.0) < 1e-12, "K = {0, %g}: mean %.6f, expected 1 (all the weight on "
            "the fogged node)", K1, mean);
      worst = fmax(worst, fabs(mean - 1.0));
    }
    printf("an empty node beside a dense one (K 10 .. 1e6): the mean within %.1e of 1\n",
           worst);
  }
  return test_finish("test_piece_light_mean");
}
