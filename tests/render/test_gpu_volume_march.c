/* The GL ray march of a 3D grid (render/volume_march.h) against a double-precision march
 * written here: same rays, same midpoint samples, trilinear density with a zero border.
 * The grid is an anisotropic Gaussian blob plus a sharp slab in a Z-up index frame (world
 * y from index k, as Blender's VDBs), so a wrong axis map, half-texel offset, border or
 * flipped read-back shows as a large error. Views at 5..90 degrees of elevation. */
#define _USE_MATH_DEFINES
#include <math.h>
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#include <stdlib.h>

#include "render/render.h"
#include "tests/test_util.h"

enum { NX = 24, NY = 20, NZ = 12, SIDE = 24 };

/* Index frame: i = (x - 1) / 0.5, j = (z + 2) / 0.5, k = y / 0.5 (world y up from index k). */
static const double M[3][3] = {{2, 0, 0}, {0, 0, 2}, {0, 2, 0}};
static const double OFF[3] = {-2, 4, 0};

static double voxel(const float *v, int i, int j, int k) {
  if (i < 0 || j < 0 || k < 0 || i >= NX || j >= NY || k >= NZ) return 0.0;
  return v[((size_t)k * NY + j) * NX + i];
}

static double trilinear(const float *v, const double p[3]) {
  double u[3];
  for (int c = 0; c < 3; c++) u[c] = M[c][0] * p[0] + M[c][1] * p[1] + M[c][2] * p[2] + OFF[c];
  int i0 = (int)floor(u[0]), j0 = (int)floor(u[1]), k0 = (int)floor(u[2]);
  double fx = u[0] - i0, fy = u[1] - j0, fz = u[2] - k0, sum = 0.0;
  for (int dk = 0; dk < 2; dk++)
    for (int dj = 0; dj < 2; dj++)
      for (int di = 0; di < 2; di++)
        sum += (di ? fx : 1 - fx) * (dj ? fy : 1 - fy) * (dk ? fz : 1 - fz) *
               voxel(v, i0 + di, j0 + dj, k0 + dk);
  return sum;
}

static double cpu_depth(const float *v, const volume_view_desc *view, int ix, int iz) {
  const double *lo = view->lo, *hi = view->hi, *d = view->dir;
  double o[3] = {lo[0] + (ix + 0.5) * (hi[0] - lo[0]) / view->side, view->y_mid,
                 lo[2] + (iz + 0.5) * (hi[2] - lo[2]) / view->side};
  double t0 = -1e300, t1 = 1e300;
  for (int a = 0; a < 3; a++) {
    if (fabs(d[a]) < 1e-15) {
      if (o[a] < lo[a] || o[a] > hi[a]) return -1.0;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    t0 = fmax(t0, fmin(ta, tb));
    t1 = fmin(t1, fmax(ta, tb));
  }
  if (!(t0 <= t1)) return -1.0;
  int n = (int)ceil((t1 - t0) / view->step);
  if (n < 1) n = 1;
  double dt = (t1 - t0) / n, sum = 0.0;
  for (int s = 0; s < n; s++) {
    double t = t0 + (s + 0.5) * dt, p[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
    sum += trilinear(v, p);
  }
  return sum * dt;
}

int main(void) {
  fog_error err = {0};
  gl_context *ctx = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &err);
  CHECK(ctx != NULL, "headless GL context: %s", err.message);
  if (!ctx) return test_finish("test_gpu_volume_march");
  float *values = malloc(sizeof(float) * NX * NY * NZ);
  for (int k = 0; k < NZ; k++)
    for (int j = 0; j < NY; j++)
      for (int i = 0; i < NX; i++) {
        double a = (i - 9.0) / 4.0, b = (j - 11.0) / 6.0, c = (k - 3.0) / 2.5;
        values[((size_t)k * NY + j) * NX + i] =
            (float)(0.8 * exp(-0.5 * (a * a + b * b + c * c)) + (i >= 16 && k <= 2 ? 0.3 : 0.0));
      }
  volume_grid_desc grid = {.dim = {NX, NY, NZ}, .values = values, .index_offset = {OFF[0], OFF[1], OFF[2]}};
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) grid.index_from_world[r][c] = M[r][c];
  volume_march *march = volume_march_create(&grid, &err);
  CHECK(march != NULL, "volume_march_create: %s", err.message);
  /* The grid's box (index -1 .. dim, the zero border included) in world units. */
  volume_view_desc view = {.lo = {0.5, -0.5, -2.5}, .hi = {13.0, 6.0, 8.0}, .y_mid = 2.75,
                           .side = SIDE, .step = 0.125};
  static const double elevations[] = {5, 20, 45, 75, 90};
  float depth[SIDE * SIDE];
  double worst = 0.0, worst_depth = 0.0, max_depth = 0.0;
  int compared = 0, misses_differ = 0;
  for (int e = 0; e < 5 && march; e++)
    for (int az = 0; az < 3; az++) {
      double el = elevations[e] * M_PI / 180, phi = (az + 0.5) * 2 * M_PI / 3;
      view.dir[0] = cos(el) * cos(phi), view.dir[1] = -sin(el), view.dir[2] = cos(el) * sin(phi);
      int status = volume_march_view(march, &view, depth, &err);
      CHECK(status == 0, "volume_march_view: %s", err.message);
      if (status) continue;
      for (int iz = 0; iz < SIDE; iz++)
        for (int ix = 0; ix < SIDE; ix++) {
          double ref = cpu_depth(values, &view, ix, iz), gpu = depth[iz * SIDE + ix];
          if ((ref < 0) != (gpu < 0)) {
            misses_differ++;
            continue;
          }
          if (ref < 0) continue;
          compared++;
          max_depth = fmax(max_depth, ref);
          worst_depth = fmax(worst_depth, fabs(gpu - ref));
          worst = fmax(worst, fabs(exp(-gpu) - exp(-ref)));
        }
    }
  printf("%d rays: max |dT| %.3g, max |d depth| %.3g (max depth %.3g)\n", compared, worst,
         worst_depth, max_depth);
  CHECK(compared > 1000, "only %d rays compared", compared);
  CHECK(max_depth > 1.0, "the views see too little fog (max depth %g): the test is weak",
        max_depth);
  CHECK(misses_differ == 0, "%d rays hit the box on one side only", misses_differ);
  CHECK(worst <= 1e-4, "GL march vs double march: max |dT| = %.3g", worst);
  volume_march_destroy(march);
  free(values);
  gl_context_destroy(ctx);
  return test_finish("test_gpu_volume_march");
}
