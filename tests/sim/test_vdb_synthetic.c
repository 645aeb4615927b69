/* VDB import on grids written through OpenVDB by this test (analytic Gaussian blobs and
 * slabs): every compression reads back bit for bit, projected mass = analytic mass, fogmap total = voxel mass (area-weighted
 * resampling), orientation under Z-up and Y-up, tiles and voxels project the same, the
 * exponential profile recovers its scale height. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sim/sim.h"
#include "test_util.h"

static char dir[256];

static double fogmap_mass(const vdb_frame *f) {
  double s = 0;
  for (int n = 0; n < f->map.width * f->map.height; n++) s += f->map.density[n];
  return s * f->fogmap_place.cell_size * f->fogmap_place.cell_size * f->profile.thickness;
}

/* A dense grid of the given size whose values come from fn(world position of centre). */
static vdb_dense_grid make_grid(const int dim[3], const int lo[3], double h, const double t[3],
                                double (*fn)(double, double, double)) {
  vdb_dense_grid g = {.dim = {dim[0], dim[1], dim[2]},
                      .index_min = {lo[0], lo[1], lo[2]},
                      .voxel_size = {h, h, h},
                      .translation = {t[0], t[1], t[2]}};
  g.values = malloc((size_t)dim[0] * dim[1] * dim[2] * sizeof(float));
  size_t n = 0;
  for (int k = 0; k < dim[2]; k++)
    for (int j = 0; j < dim[1]; j++)
      for (int i = 0; i < dim[0]; i++)
        g.values[n++] = (float)fn(t[0] + h * (i + lo[0]), t[1] + h * (j + lo[1]),
                                  t[2] + h * (k + lo[2]));
  return g;
}

/* A Gaussian blob off-centre: mean (1.0, 0.8, 1.2) in the file's own axes, sigma 0.3. */
static const double blob_c[3] = {1.0, 0.8, 1.2}, blob_sigma = 0.3, blob_amp = 2.0;
static double blob(double x, double y, double z) {
  const double r2 = (x - blob_c[0]) * (x - blob_c[0]) + (y - blob_c[1]) * (y - blob_c[1]) +
                    (z - blob_c[2]) * (z - blob_c[2]);
  return blob_amp * exp(-r2 / (2 * blob_sigma * blob_sigma));
}

static double slab(double x, double y, double z) { return 0.5; }

static const double expo_H = 0.4;
static double expo(double x, double y, double z) { return exp(-z / expo_H); }

static void test_blob(void) {
  const int dim[3] = {48, 40, 32}, lo[3] = {-10, -12, 0};
  const double t[3] = {0.05, -0.1, 0.0}, h = 0.1;
  vdb_dense_grid g = make_grid(dim, lo, h, t, blob);
  char path[512];
  snprintf(path, sizeof path, "%s/blob.vdb", dir);
  fog_error err = {0};
  CHECK(!vdb_write_dense(path, &g, &(vdb_write_desc){0}, &err), "%s", err.message);
  const double analytic = blob_amp * pow(2 * 3.14159265358979323846, 1.5) * pow(blob_sigma, 3);

  for (int up = 0; up < 2; up++) {
    for (int res = 0; res < 2; res++) {
      vdb_frame f;
      int status = vdb_frame_load(path,
                                  &(vdb_frame_desc){.up = up ? VDB_UP_Y : VDB_UP_Z,
                                                    .resolution = res ? 37 : 0},
                                  &f, &err);
      CHECK(!status, "%s", err.message);
      if (status) continue;
      CHECK(fabs(f.columns.mass - analytic) < 1e-4 * analytic, "mass %.8g vs analytic %.8g",
            f.columns.mass, analytic);
      const double fm = fogmap_mass(&f);
      CHECK(fabs(fm - f.columns.mass) < 1e-5 * f.columns.mass,
            "fogmap mass %.9g vs voxel mass %.9g (res %d)", fm, f.columns.mass, res ? 37 : 0);
      /* centroid of the fogmap in world X, Z and of the profile in Y */
      double sx = 0, sz = 0, s = 0;
      for (int z = 0; z < f.map.height; z++)
        for (int x = 0; x < f.map.width; x++) {
          const double v = f.map.density[z * f.map.width + x];
          sx += v * (f.fogmap_place.origin_x + (x + 0.5) * f.fogmap_place.cell_size);
          sz += v * (f.fogmap_place.origin_z + (z + 0.5) * f.fogmap_place.cell_size);
          s += v;
        }
      double sy = 0, sg = 0;
      for (int n = 0; n < 4000; n++) {
        const double y = f.profile.y_bottom + (n + 0.5) * (f.profile.y_top - f.profile.y_bottom) / 4000;
        sy += y * vdb_profile_eval(&f.profile, y);
        sg += vdb_profile_eval(&f.profile, y);
      }
      /* Z-up: fogpipe (X, Y, Z) = (x, z, -y); Y-up: identity */
      const double ex = blob_c[0], ey = up ? blob_c[1] : blob_c[2],
                   ez = up ? blob_c[2] : -blob_c[1];
      CHECK(fabs(sx / s - ex) < 0.01, "up=%s: centroid X %.4f, expected %.4f", up ? "y" : "z",
            sx / s, ex);
      CHECK(fabs(sz / s - ez) < 0.01, "up=%s: centroid Z %.4f, expected %.4f", up ? "y" : "z",
            sz / s, ez);
      CHECK(fabs(sy / sg - ey) < 0.01, "up=%s: profile centroid Y %.4f, expected %.4f",
            up ? "y" : "z", sy / sg, ey);
      /* the quadrant: Z-up blob at y = +0.8 lands at Z < 0 (row below the middle) */
      int peak = 0;
      for (int n = 0; n < f.map.width * f.map.height; n++)
        if (f.map.density[n] > f.map.density[peak]) peak = n;
      const double px = f.fogmap_place.origin_x + (peak % f.map.width + 0.5) * f.fogmap_place.cell_size;
      const double pz = f.fogmap_place.origin_z + (peak / f.map.width + 0.5) * f.fogmap_place.cell_size;
      CHECK(px > 0 && (up ? pz > 0 : pz < 0), "up=%s: peak at (%.3f, %.3f) in the wrong quadrant",
            up ? "y" : "z", px, pz);
      /* f·∫g = column integral, cell by cell at native resolution */
      if (!res) {
        double worst = 0;
        for (int n = 0; n < f.map.width * f.map.height; n++)
          worst = fmax(worst, fabs(f.map.density[n] * f.profile.thickness - f.columns.tau[n]));
        CHECK(worst < 1e-5, "native: f·T differs from the column integral by %g", worst);
      }
      vdb_frame_destroy(&f);
    }
  }
  /* half-float storage: mass within half precision */
  snprintf(path, sizeof path, "%s/blob_half.vdb", dir);
  CHECK(!vdb_write_dense(path, &g, &(vdb_write_desc){.as_half = 1}, &err), "%s", err.message);
  vdb_frame f;
  if (!vdb_frame_load(path, &(vdb_frame_desc){0}, &f, &err)) {
    CHECK(fabs(f.columns.mass - analytic) < 2e-3 * analytic, "half: mass %.6g vs %.6g",
          f.columns.mass, analytic);
    vdb_frame_destroy(&f);
  } else {
    CHECK(0, "%s", err.message);
  }
  /* every compression reads back the same voxels, bit for bit (float storage) */
  static const char *const names[4] = {"default", "none", "zip", "blosc"};
  vdb_dense_grid first = {0};
  for (int c = 0; c < 4; c++) {
    snprintf(path, sizeof path, "%s/blob_%s.vdb", dir, names[c]);
    vdb_dense_grid back;
    int status = vdb_write_dense(path, &g, &(vdb_write_desc){.compression = (vdb_compression)c},
                                 &err) ||
                 vdb_read_dense(path, NULL, &back, &err);
    CHECK(!status, "%s: %s", names[c], err.message);
    if (status) continue;
    size_t differ = 0;
    for (size_t n = 0; n < (size_t)g.dim[0] * g.dim[1] * g.dim[2]; n++)
      differ += back.values[n] != g.values[n];
    CHECK(differ == 0 && back.dim[0] == g.dim[0] && back.index_min[1] == g.index_min[1],
          "%s: %zu voxels differ after the round trip", names[c], differ);
    if (!first.values)
      first = back;
    else
      vdb_dense_grid_destroy(&back);
  }
  vdb_dense_grid_destroy(&first);
  vdb_dense_grid_destroy(&g);
}

static void test_tiles_vs_voxels(void) {
  /* constant 0.5 over [0,32) x [0,24) x [0,16) with 8-aligned blocks: all tiles */
  const int dim[3] = {32, 24, 16}, lo[3] = {0, 0, 0};
  const double t[3] = {0, 0, 0}, h = 0.125;
  vdb_dense_grid g = make_grid(dim, lo, h, t, slab);
  /* a non-constant corner so that leaves and tiles mix */
  for (int i = 0; i < 5; i++) g.values[i] = 0.1f * (float)(i + 1);
  char voxels[512], tiles[512];
  snprintf(voxels, sizeof voxels, "%s/slab_voxels.vdb", dir);
  snprintf(tiles, sizeof tiles, "%s/slab_tiles.vdb", dir);
  fog_error err = {0};
  CHECK(!vdb_write_dense(voxels, &g, &(vdb_write_desc){0}, &err), "%s", err.message);
  CHECK(!vdb_write_dense(tiles, &g, &(vdb_write_desc){.constant_blocks_as_tiles = 1}, &err), "%s",
        err.message);
  vdb_dense_grid a, b;
  CHECK(!vdb_read_dense(voxels, NULL, &a, &err), "%s", err.message);
  CHECK(!vdb_read_dense(tiles, NULL, &b, &err), "%s", err.message);
  CHECK(a.tile_voxels == 0, "voxel file has %lld tile voxels", a.tile_voxels);
  CHECK(b.tile_voxels == 32 * 24 * 16 - 512, "tile file: %lld tile voxels, expected %d",
        b.tile_voxels, 32 * 24 * 16 - 512);
  double expected = 0;
  for (int n = 0; n < 32 * 24 * 16; n++) expected += g.values[n];
  expected *= h * h * h;
  vdb_frame fa, fb;
  CHECK(!vdb_frame_load(voxels, &(vdb_frame_desc){.resolution = 10}, &fa, &err), "%s", err.message);
  CHECK(!vdb_frame_load(tiles, &(vdb_frame_desc){.resolution = 10}, &fb, &err), "%s", err.message);
  CHECK(fa.map.width == fb.map.width && fa.map.height == fb.map.height, "sizes differ");
  double worst = 0;
  for (int n = 0; n < fa.map.width * fa.map.height; n++)
    worst = fmax(worst, fabs(fa.map.density[n] - fb.map.density[n]));
  CHECK(worst == 0, "tiles vs voxels: fogmaps differ by %g", worst);
  CHECK(fabs(fb.columns.mass - expected) < 1e-6 * expected, "tile mass %.8g vs %.8g",
        fb.columns.mass, expected);
  CHECK(fabs(fogmap_mass(&fb) - expected) < 1e-5 * expected, "tile fogmap mass %.8g vs %.8g",
        fogmap_mass(&fb), expected);
  vdb_frame_destroy(&fa);
  vdb_frame_destroy(&fb);
  vdb_dense_grid_destroy(&a);
  vdb_dense_grid_destroy(&b);
  vdb_dense_grid_destroy(&g);
}

static void test_exponential_profile(void) {
  /* rho = exp(-z/H) over z in [0, 2] (Z up), voxel 0.05: the moment fit finds 1/H */
  const int dim[3] = {8, 8, 40}, lo[3] = {0, 0, 0};
  const double h = 0.05, t[3] = {0, 0, 0.5 * h};
  vdb_dense_grid g = make_grid(dim, lo, h, t, expo);
  char path[512];
  snprintf(path, sizeof path, "%s/expo.vdb", dir);
  fog_error err = {0};
  CHECK(!vdb_write_dense(path, &g, &(vdb_write_desc){0}, &err), "%s", err.message);
  vdb_frame f;
  int status = vdb_frame_load(path, &(vdb_frame_desc){.profile.kind = VDB_PROFILE_EXPONENTIAL},
                              &f, &err);
  CHECK(!status, "%s", err.message);
  if (!status) {
    CHECK(fabs(f.profile.scale_height / expo_H - 1) < 0.01, "scale height %.5f, expected %.5f",
          f.profile.scale_height, expo_H);
    CHECK(fabs(f.profile.y_bottom) < 1e-12 && fabs(f.profile.y_top - 2.0) < 1e-12,
          "profile spans [%g, %g], expected [0, 2]", f.profile.y_bottom, f.profile.y_top);
    CHECK(fabs(fogmap_mass(&f) - f.columns.mass) < 1e-5 * f.columns.mass,
          "exponential: fogmap mass %.8g vs %.8g", fogmap_mass(&f), f.columns.mass);
    /* f is the extinction at the densest height: rho(0) = 1 (up to the fit's 1 %) */
    const double f_expected = 1.0;
    CHECK(fabs(f.map.density[0] - f_expected) < 0.01, "f %.5f, expected about %.5f",
          f.map.density[0], f_expected);
    vdb_frame_destroy(&f);
  }
  vdb_dense_grid_destroy(&g);
}

int main(void) {
  snprintf(dir, sizeof dir, "/tmp/test_vdb_synthetic_XXXXXX");
  if (!test_scratch_folder(dir)) return 1;
  test_blob();
  test_tiles_vs_voxels();
  test_exponential_profile();
  test_remove_tree(dir);
  return test_finish("test_vdb_synthetic");
}
