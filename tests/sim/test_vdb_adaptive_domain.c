/* Adaptive-domain Mantaflow caches store only a sub-box of the domain and write a wrong
 * voxel size into the VDB (domain size / current sub-box resolution): placement must come
 * from the config (p0, p1, base_res, res_min + shift, the object matrix), with a warning,
 * and the VDB's own voxel size be ignored. Checked on a config built in memory against the
 * placement worked out here by hand: voxel n of the sub-box is centred at
 * t + s (p0 + (res_min + shift + n + 1/2) (p1 - p0) / base_res) in Blender's Z-up world,
 * fogpipe (X, Y, Z) = (x, z, -y). Also: a non-adaptive config whose VDB voxel size is
 * neither its cell nor a whole fraction of it is refused; one at half its cell is a noise
 * grid of the doubled domain; a rotated domain object is refused. */
#include <math.h>
#include <string.h>

#include "sim/sim.h"
#include "tests/test_util.h"

static mantaflow_config adaptive_config(void) {
  mantaflow_config cfg = {
      .res = {20, 12, 8}, .base_res = {64, 64, 32}, .res_min = {10, 30, 4},
      .res_max = {30, 42, 12}, .shift = {1, -2, 0},
      .p0 = {-1.0f, -1.0f, -1.0f}, .p1 = {1.0f, 1.0f, 0.5f},
      .obmat = {{3, 0, 0, 5}, {0, 3, 0, -4}, {0, 0, 3, 2}, {0, 0, 0, 1}},
  };
  return cfg;
}

/* Blender world coordinate of source axis c at continuous sub-box index u. */
static double blender_world(const mantaflow_config *cfg, int c, double u) {
  double dx = ((double)cfg->p1[c] - cfg->p0[c]) / cfg->base_res[c];
  return cfg->obmat[c][3] +
         cfg->obmat[c][c] * (cfg->p0[c] + (cfg->res_min[c] + cfg->shift[c] + u + 0.5) * dx);
}

int main(void) {
  float values[20 * 12 * 8] = {0};
  vdb_dense_grid grid = {.dim = {20, 12, 8}, .voxel_size = {0.3, 0.3, 0.3},
                         .translation = {0.7, 0.7, 0.7}, .values = values};
  mantaflow_config cfg = adaptive_config();
  vdb_world_map map;
  fog_error err = {0};
  int status = vdb_world_map_make(&grid, &(vdb_placement){.config = &cfg}, &map, &err);
  CHECK(status == 0, "adaptive placement: %s", err.message);
  CHECK(map.used_config == 1, "the config was not used");
  CHECK(strstr(map.warning, "adaptive") != NULL, "no adaptive-domain warning: '%s'", map.warning);
  /* fogpipe X = x, Y = z, Z = -y (Z-up source) */
  const int source_of[3] = {0, 2, 1};
  const double sign[3] = {1, 1, -1};
  double worst = 0;
  for (int a = 0; a < 3; a++) {
    CHECK(map.index_axis[a] == source_of[a], "world axis %d fed by source axis %d, expected %d",
          a, map.index_axis[a], source_of[a]);
    for (double u = -0.5; u <= 20.0; u += 0.75) {
      double want = sign[a] * blender_world(&cfg, source_of[a], u);
      double got = map.base[a] + map.step[a] * u;
      worst = fmax(worst, fabs(got - want));
    }
  }
  CHECK(worst < 1e-9, "adaptive placement off by %.3g world units", worst);
  /* the true cell, not the VDB's 0.3: 3 * 2/64 = 0.09375 along x */
  CHECK(fabs(fabs(map.step[0]) - 0.09375) < 1e-12, "x cell %.6g, expected 0.09375", map.step[0]);

  /* Whole domain (not adaptive), but the VDB's voxels are neither the config's cells nor a
   * whole fraction of them: the config does not describe the grid (placed by it, the mass
   * would be off by the cube of the ratio): refused, naming both sizes and the way out. */
  mantaflow_config whole = adaptive_config();
  memcpy(whole.res, whole.base_res, sizeof whole.res);
  memset(whole.res_min, 0, sizeof whole.res_min);
  memset(whole.shift, 0, sizeof whole.shift);
  status = vdb_world_map_make(&grid, &(vdb_placement){.config = &whole}, &map, &err);
  CHECK(status != 0 && strstr(err.message, "0.3") && strstr(err.message, "0.09375") &&
            strstr(err.message, "--config none"),
        "a grid the config does not describe: %s", status ? err.message : "accepted");

  /* A noise grid: voxels half the config's cells on every axis (Mantaflow's upres 2): cell n
   * of the doubled domain is centred at t + s (p0 + (n + 1/2) dx / 2), the domain's index
   * box doubles, and a warning says so. */
  grid.voxel_size[0] = 3.0 * 2.0 / 64 / 2, grid.voxel_size[1] = 3.0 * 2.0 / 64 / 2;
  grid.voxel_size[2] = 3.0 * 1.5 / 32 / 2;
  status = vdb_world_map_make(&grid, &(vdb_placement){.config = &whole}, &map, &err);
  CHECK(status == 0 && strstr(map.warning, "noise grid"), "noise grid: %s",
        status ? err.message : map.warning);
  double noise_worst = 0;
  for (int a = 0; a < 3 && status == 0; a++) {
    const int c = source_of[a];
    for (double u = -0.5; u <= 20.0; u += 0.75) {
      const double dx = ((double)whole.p1[c] - whole.p0[c]) / whole.base_res[c] / 2;
      const double want =
          sign[a] * (whole.obmat[c][3] + whole.obmat[c][c] * (whole.p0[c] + (u + 0.5) * dx));
      noise_worst = fmax(noise_worst, fabs(map.base[a] + map.step[a] * u - want));
    }
    CHECK(map.domain_max[c] == 2 * whole.res[c] - 1, "noise grid: domain on axis %d to %d, "
          "expected %d", c, map.domain_max[c], 2 * whole.res[c] - 1);
  }
  CHECK(noise_worst < 1e-9, "noise grid placement off by %.3g world units", noise_worst);

  /* A config whose VDB voxel size agrees: no warning. */
  grid.voxel_size[0] = 3.0 * 2.0 / 64, grid.voxel_size[1] = 3.0 * 2.0 / 64;
  grid.voxel_size[2] = 3.0 * 1.5 / 32;
  status = vdb_world_map_make(&grid, &(vdb_placement){.config = &whole}, &map, &err);
  CHECK(status == 0 && map.warning[0] == '\0', "agreeing sizes warned: '%s'", map.warning);

  /* A rotated domain object is refused, naming the matrix entry. */
  mantaflow_config rotated = adaptive_config();
  rotated.obmat[0][1] = 0.5f;
  status = vdb_world_map_make(&grid, &(vdb_placement){.config = &rotated}, &map, &err);
  CHECK(status != 0 && strstr(err.message, "rotated"), "rotated domain accepted: %s",
        err.message);
  return test_finish("test_vdb_adaptive_domain");
}
