/* Empty-space skipping in the GL walk (FOG_SKIP, fog_integral.glsl) against the same walk
 * without it, on fog in patches over zero (fog_test_patch_grid), read back as tau:
 * - FOG_SKIP_EMPTY: every pixel the same float, bit for bit, for every degree, every
 *   profile, manual and hardware fetch, one grid and LOD by both methods, a camera inside
 *   the fog and one above it;
 * - FOG_SKIP_BELOW with eps over a background of values <= eps: within the stated bound
 *   eps * extinction * g_max * L of the unskipped walk (plus float noise), and not equal
 *   everywhere (blocks were skipped);
 * - the skipped walk against the CPU twin in double (fog_optical_depth): max |delta tau|
 *   <= 2e-4, as the unskipped walk's tests;
 * - the volume's DDA brick by brick (fog_bricks_build): bit for bit the unskipped walk on
 *   a grid of 12 random boxes of fog in zero (both fetches), within eps * L over a background <= eps,
 *   and against its CPU twin (fog_grid3d_optical_depth). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/render.h"
#include "fog_test_gl.h"
#include "fog_test_scene.h"
#include "test_util.h"

enum { W = 96, H = 54, LEVELS = 2 };
static const double ground_y = 0.5;

static double profile_max(const fog_profile *p) {
  if (p->kind != FOG_PROFILE_BSPLINE) return 1.0;
  double m = 0.0;
  for (int k = 0; k < p->count; k++) m = fmax(m, fabs(p->coefficients[k]));
  return m;
}

/* The coarser levels of a pyramid by averaging: any grids will do (both sides walk the
 * same ones); each level's spacing doubles and its origin shifts as fog_walk_coarser's
 * dyadic rule expects. */
static transform_grid coarser(const transform_grid *f) {
  transform_grid c;
  fog_error err;
  transform_grid_create(&c, (f->width + 1) / 2 + 1, (f->height + 1) / 2 + 1, &err);
  c.degree = f->degree;
  c.spacing = 2.0 * f->spacing;
  c.origin_u = f->origin_u - f->spacing;
  c.origin_v = f->origin_v - f->spacing;
  for (int j = 0; j < c.height; j++)
    for (int i = 0; i < c.width; i++) {
      int fi = 2 * i - 1, fj = 2 * j - 1;
      float m = 0.0f;
      for (int b = 0; b < 2; b++)
        for (int a = 0; a < 2; a++)
          if (fi + a >= 0 && fj + b >= 0 && fi + a < f->width && fj + b < f->height)
            m = fmaxf(m, f->coefficients[(size_t)(fj + b) * f->width + fi + a]);
      c.coefficients[(size_t)j * c.width + i] = m;
    }
  return c;
}

int main(void) {
  fog_error err = {0};
  fog_test_gl gl;
  if (!fog_test_gl_setup(&gl, W, H, &err)) return test_finish("test_gpu_skip");
  static float plain[W * H], skipped[W * H];
  const fog_profile_kind kinds[3] = {FOG_PROFILE_SLAB, FOG_PROFILE_EXPONENTIAL,
                                     FOG_PROFILE_BSPLINE};
  int draws = 0, differing_below = 0;
  double worst_cpu = 0.0, worst_ratio = 0.0;
  for (int pass = 0; pass < 2; pass++) {
    const float eps = pass ? 0.02f : 0.0f;
    for (int degree = 0; degree <= 2; degree++)
      for (int k = 0; k < 3; k++) {
        fog_volume v = fog_test_patch_volume(kinds[k]);
        v.extinction = 0.08;
        transform_grid grids[LEVELS + 1]; /* approx: grids[0] coarsest, grids[LEVELS] finest */
        grids[LEVELS] = fog_test_patch_grid(degree, 1.0, eps);
        for (int l = LEVELS - 1; l >= 0; l--) grids[l] = coarser(&grids[l + 1]);
        fog_lod lod = {.levels = LEVELS, .approx = grids, .detail = grids + 1, .mu = 0.6};
        double lo[3], hi[3];
        fog_volume_box(&v, lo, hi);
        for (int view = 0; view < 2; view++) {
          camera cam = {.fov_y = 1.0,
              .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
          double target[3];
          if (view == 0) { /* inside the fog, looking across the map */
            cam.position[0] = lo[0] + 0.05 * (hi[0] - lo[0]);
            cam.position[1] = 2.0;
            cam.position[2] = lo[2] + 0.5 * (hi[2] - lo[2]);
            target[0] = hi[0], target[1] = 1.0, target[2] = lo[2] + 0.6 * (hi[2] - lo[2]);
          } else { /* above the box, looking down over it */
            cam.position[0] = lo[0] - 20.0;
            cam.position[1] = hi[1] + 60.0;
            cam.position[2] = lo[2] - 20.0;
            target[0] = lo[0] + 0.6 * (hi[0] - lo[0]), target[1] = ground_y,
            target[2] = lo[2] + 0.6 * (hi[2] - lo[2]);
          }
          camera_look_at(&cam, target);
          fog_test_gl_set_ground(&gl, &cam, ground_y);
          /* single grid (the finest), then LOD by both methods */
          for (int mode = 0; mode < 3; mode++)
            for (int fetch = 0; fetch <= (degree > 0 && mode == 0); fetch++) {
              if (mode == 0)
                CHECK(fog_pass_upload_grid(gl.pass, 0, &grids[LEVELS], &err) == 0, "upload: %s",
                      err.message);
              else
                CHECK(fog_pass_upload_lod(gl.pass, &lod, &err) == 0, "upload: %s", err.message);
              fog_pass_params params = {.volume = &v, .levels = mode ? LEVELS : 0,
                                        .lod_method = mode == 1 ? FOG_LOD_SWITCH
                                                                : FOG_LOD_SUM_OF_DETAILS,
                                        .mu = lod.mu,
                                        .fetch = fetch ? FOG_FETCH_HARDWARE : FOG_FETCH_MANUAL,
                                        .walk = {.skip = FOG_SKIP_NONE}};
              CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, plain,
                                         &err) == 0, "draw: %s", err.message);
              params.walk.skip = eps > 0 ? FOG_SKIP_BELOW : FOG_SKIP_EMPTY;
              params.walk.skip_below = eps;
              CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, skipped,
                                         &err) == 0, "draw: %s", err.message);
              draws++;
              int mismatched = 0;
              for (int py = 0; py < H; py++)
                for (int px = 0; px < W; px++) {
                  int i = py * W + px;
                  if (eps == 0.0f) {
                    mismatched += memcmp(&plain[i], &skipped[i], sizeof(float)) != 0;
                    continue;
                  }
                  double o[3], d[3], t0, t1;
                  camera_ray(&cam, px, py, W, H, o, d);
                  double len = fog_box_entry_exit(&v, o, d, &t0, &t1)
                                   ? fmax(0.0, fmin(t1, gl.dist[i]) - fmax(t0, 0.0)) : 0.0;
                  /* the stated bound on optical depth, for one grid and for LOD: the sum of
                   * details reads 1 + J grids, each skipping below eps / (1 + J) (the
                   * pass used eps for each, and the sum went up to 3x past it here) */
                  double bound = eps * v.extinction * profile_max(&v.profile) * len;
                  double diff = fabs((double)plain[i] - skipped[i]);
                  if (diff > 0) differing_below++;
                  if (bound > 1e-4 && diff / bound > worst_ratio) worst_ratio = diff / bound;
                  if (diff > bound + 2e-6) mismatched++;
                }
              CHECK(mismatched == 0,
                    "degree %d profile %d view %d mode %d fetch %d eps %g: %d pixels %s", degree,
                    kinds[k], view, mode, fetch, eps, mismatched,
                    eps > 0 ? "outside the bound" : "not bit for bit the unskipped walk");
              if (mode == 0 && eps == 0.0f && fetch == 0) {
                double worst = 0.0;
                for (int py = 0; py < H; py += 3)
                  for (int px = 0; px < W; px += 3) {
                    double o[3], d[3];
                    camera_ray(&cam, px, py, W, H, o, d);
                    double want = fog_transmittance(
                        fog_optical_depth(&v, &grids[LEVELS], o, d, 0.0, gl.dist[py * W + px]));
                    worst = fmax(worst, fabs(want - skipped[py * W + px]));
                  }
                worst_cpu = fmax(worst_cpu, worst);
                CHECK(worst <= 2e-4, "degree %d profile %d view %d: skipped walk vs CPU %.2e",
                      degree, kinds[k], view, worst);
              }
            }
        }
        for (int l = 0; l <= LEVELS; l++) transform_grid_destroy(&grids[l]);
      }
  }
  /* The volume: 48 x 24 x 40 voxels of 1.5 units over the patch box, three lumps. */
  enum { VX = 48, VY = 24, VZ = 40 };
  static float voxels[VX * VY * VZ];
  int volume_pairs = 0;
  for (int pass = 0; pass < 2; pass++) {
    const float eps = pass ? 0.01f : 0.0f;
    for (int i = 0; i < VX * VY * VZ; i++)
      voxels[i] = eps > 0 ? (float)(eps * (0.5 + 0.5 * fog_test_uniform())) : 0.0f;
    for (int lump = 0; lump < 12; lump++) { /* random boxes: some start on brick edges */
      int sx = 1 + (int)(fog_test_uniform() * 7), sy = 1 + (int)(fog_test_uniform() * 7),
          sz = 1 + (int)(fog_test_uniform() * 7);
      int x0 = (int)(fog_test_uniform() * (VX - sx)), y0 = (int)(fog_test_uniform() * (VY - sy)),
          z0 = (int)(fog_test_uniform() * (VZ - sz));
      for (int k = z0; k < z0 + sz; k++)
        for (int j = y0; j < y0 + sy; j++)
          for (int i = x0; i < x0 + sx; i++)
            voxels[((size_t)k * VY + j) * VX + i] = (float)fog_test_range(0.05, 0.3);
    }
    fog_volume box = fog_test_patch_volume(FOG_PROFILE_SLAB);
    volume_grid_desc grid3d = {.dim = {VX, VY, VZ}, .values = voxels,
                               .index_from_world = {{1 / 1.5, 0, 0}, {0, 1 / 1.5, 0}, {0, 0, 1 / 1.5}},
                               .index_offset = {-box.origin_x / 1.5, 0.0, -box.origin_z / 1.5}};
    CHECK(fog_pass_upload_grid3d(gl.pass, &grid3d, &err) == 0, "volume: %s", err.message);
    for (int view = 0; view < 2; view++) {
      camera cam = {.fov_y = 1.0,
          .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
      double target[3] = {box.origin_x + 40.0, 12.0, box.origin_z + 30.0};
      cam.position[0] = box.origin_x + (view ? -15.0 : 3.0);
      cam.position[1] = view ? 60.0 : 8.0;
      cam.position[2] = box.origin_z + (view ? -10.0 : 3.0);
      camera_look_at(&cam, target);
      fog_test_gl_set_ground(&gl, &cam, ground_y);
      for (int fetch = 0; fetch <= 1; fetch++) {
        fog_pass_params params = {.model = FOG_MODEL_VOLUME,
                                  .fetch = fetch ? FOG_FETCH_HARDWARE : FOG_FETCH_MANUAL,
                                  .walk = {.skip = FOG_SKIP_NONE}};
        CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, plain, &err) == 0,
              "volume draw: %s", err.message);
        params.walk = (fog_walk_settings){.skip = eps > 0 ? FOG_SKIP_BELOW : FOG_SKIP_EMPTY,
                                          .skip_below = eps};
        CHECK(fog_test_gl_draw_tau(&gl, &cam, &params, skipped, &err) == 0,
              "volume draw: %s", err.message);
        volume_pairs++;
        int mismatched = 0, changed = 0;
        double worst = 0.0;
        for (int py = 0; py < H; py++)
          for (int px = 0; px < W; px++) {
            const int i = py * W + px;
            double o[3], d[3];
            double t_surface = fog_test_gl_pixel_ray(&gl, &cam, px, py, o, d);
            if (eps == 0.0f) {
              mismatched += memcmp(&plain[i], &skipped[i], sizeof(float)) != 0;
              if (fetch == 0)
                worst = fmax(worst, fabs(fog_transmittance(fog_grid3d_optical_depth(
                                             &grid3d, o, d, t_surface)) - skipped[i]));
              continue;
            }
            /* the ray's length inside the grid's support (index box [-1, dim] / 1.5) */
            double lo[3] = {box.origin_x - 1.5, -1.5, box.origin_z - 1.5};
            double hi[3] = {box.origin_x + 1.5 * VX, 1.5 * VY, box.origin_z + 1.5 * VZ};
            for (int a = 0; a < 3; a++) lo[a] -= o[a], hi[a] -= o[a];
            double t0, t1, len = 0.0;
            if (fog_slab_entry_exit(lo, hi, d, &t0, &t1))
              len = fmax(0.0, fmin(t1, t_surface) - fmax(t0, 0.0));
            double diff = fabs((double)plain[i] - skipped[i]);
            changed += diff > 0;
            if (diff > eps * len + 2e-6) mismatched++;
          }
        CHECK(mismatched == 0, "volume view %d fetch %d eps %g: %d pixels %s", view, fetch, eps,
              mismatched, eps > 0 ? "outside the bound" : "not bit for bit the unskipped walk");
        if (eps > 0) CHECK(changed > 100, "volume eps %g: only %d pixels changed", eps, changed);
        if (eps == 0.0f && fetch == 0)
          CHECK(worst <= 2e-4, "volume view %d: skipped walk vs CPU %.2e", view, worst);
      }
    }
  }
  printf("volume: %d draw pairs\n", volume_pairs);
  printf("%d draw pairs; skipped vs CPU max |dtau| %.2e; eps > 0: %d pixels differ, worst "
         "|delta| / bound %.3f\n", draws, worst_cpu, differing_below, worst_ratio);
  CHECK(differing_below > 1000, "eps > 0 changed only %d pixels: were blocks skipped?",
        differing_below);
  fog_test_gl_teardown(&gl);
  return test_finish("test_gpu_skip");
}
