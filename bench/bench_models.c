/* fogpipe bench models: the other rows of the fog-model table (docs/architecture.md,
 * render/fog_models.h), each integrated exactly and by uniform ray marching, side by side
 * in one run:
 *   - on configs/rbf_fog_banks.ini's valley and view (terrain, boxes, camera):
 *     homogeneous fog, K = 0.002 (exact only: marching a constant is exact at any step);
 *     height fog, K = 0.01 exp(-(y - 40)/25); the config's six Gaussian fog banks (RBFs);
 *     marching N = 8 .. 256 midpoint steps (to the surface, or for the sky to where the fog
 *     ends: fog_models.glsl);
 *   - on configs/vdb_plume_volume.ini's view: the plume's VDB frame as a 3D volume, exact
 *     (3D DDA, two Gauss nodes per lattice cell) and marched at 2 .. 1/8 voxel steps;
 *   - on the valley again: 8 quadric volumes (two spheres, two ellipsoids, two cylinders, a
 *     cone and a hyperboloid of one sheet, soft and hard edges) spread over the view, exact
 *     (closed form per volume) and marched at N = 8 .. 256;
 *   - on the valley again: 64 and 3000 Gaussians spread over it (rbf_scale_rows), exact
 *     through the per-tile lists of render/fog_rbf_tiles.h;
 *   - on the valley again: Perlin turbulence fog (4 octaves, render/fog_perlin.h), exact per
 *     texel cell, Zdrojewska's single sample (its error: perlin_paper_error) and marched;
 *   - first of all, `fogpipe fit` on the plume config's VDB frame: its seconds (fit_s).
 * Time: GL, glFinish before and after, median of --frames rounds after a warm-up, rows
 * interleaved. Error: tau against the double-precision CPU model on the same rays to the
 * scene pass's read-back distances; RMSE and max over all pixels.
 * Writes models.csv and models_chart.{csv,png} (max error vs ms, log-log, a series per
 * model and method). Last line: `models: rbf_exact_ms=... rbf_march_speedup_at_matched_error=
 * ... height_exact_ms=... height_march_speedup_at_matched_error=... volume_exact_ms=...
 * volume_march_speedup_at_matched_error=... volume_empty_skip_speedup=... quadric_exact_ms=...
 * quadric_march_speedup_at_matched_error=... rbf_64_ms=... rbf_3000_ms=... fit_s=...
 * perlin_exact_ms=... perlin_march_speedup_at_matched_error=... perlin_paper_error=...
 * unmatched=...`, a speedup being the time of the cheapest marching with max error <= 1e-3
 * over the exact time (the most accurate marching's where none gets there: unmatched names
 * those models). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "app/cli_options.h"
#include "bench/bench.h"
#include "app/chart.h"
#include "app/clock.h"
#include "app/fit.h"
#include "render/fog_rbf_tiles.h"
#include "render/render.h"

#define ERROR_FLOOR 1e-9
#define MATCHED_ERROR 1e-3

static const int march_steps[] = {8, 16, 32, 64, 128, 256};
static const double volume_steps[] = {2.0, 1.0, 0.5, 0.25, 0.125}; /* voxels */
enum {
  MARCH_COUNT = 6,
  VOLUME_STEP_COUNT = 5,
  MODEL_COUNT = 9,
  SCENE_COUNT = 2,
  QUADRIC_COUNT = 8,
  PERLIN = 7, /* the Perlin row: exact, the paper's single sample, marched */
  QUADRIC_NOISE = 8, /* the quadric volumes with noise inside (the Perlin row's octaves) */
  MAX_ROWS = 1 + 3 * (1 + MARCH_COUNT) + 3 + VOLUME_STEP_COUNT + 2 + 2 + MARCH_COUNT +
             1 + MARCH_COUNT
};
/* The table's rows this bench times (render/fog_models.def: names and labels come from it). */
static const fog_model_kind model_kinds[MODEL_COUNT] = {
    FOG_MODEL_HOMOGENEOUS, FOG_MODEL_HEIGHT, FOG_MODEL_RBF, FOG_MODEL_VOLUME, FOG_MODEL_QUADRIC,
    FOG_MODEL_LINEAR, FOG_MODEL_EXP2, FOG_MODEL_PERLIN, FOG_MODEL_QUADRIC};
/* The rows' names: the table's, but the noisy quadric volumes' own. */
static const char *model_name(int m) {
  return m == QUADRIC_NOISE ? "quadric-noise" : fog_model_table[model_kinds[m]].name;
}
static const char *const scene_configs[SCENE_COUNT] = {"rbf_fog_banks.ini",
                                                       "vdb_plume_volume.ini"};
static const int scene_of_model[MODEL_COUNT] = {0, 0, 0, 1, 0, 0, 0, 0, 0};
/* The rows with marches: the classic factors and homogeneous fog are closed forms of the
 * distance alone (nothing to march). */
static bool marched(int m) { return (m >= 1 && m <= 4) || m == PERLIN || m == QUADRIC_NOISE; }

/* The quadric row's volumes on the valley of scene_configs[0]. */
static void bench_quadrics(fog_quadric q[QUADRIC_COUNT]) {
  q[0] = fog_quadric_sphere((double[3]){-170, 70, -60}, 90, 0.02, 0.6);
  q[1] = fog_quadric_sphere((double[3]){150, 40, 120}, 50, 0.03, 0.0);
  q[2] = fog_quadric_ellipsoid((double[3]){90, 0, -160}, (double[3]){220, 45, 120}, 0.012, 0.5);
  q[3] = fog_quadric_ellipsoid((double[3]){-100, 20, 200}, (double[3]){80, 30, 50}, 0.02, 0.3);
  q[4] = fog_quadric_cylinder((double[3]){70, 0, -30}, 22, 260, 0.03, 0.4);
  q[5] = fog_quadric_cylinder((double[3]){-40, 0, 60}, 15, 120, 0.04, 0.0);
  q[6] = fog_quadric_cone((double[3]){-300, 0, -330}, 130, 220, 0.015, 0.3);
  /* ((x - 260)^2 + (z + 20)^2)/35^2 - ((y - 150)/90)^2 - 1 in its box */
  const double a = 1.0 / (35.0 * 35.0), b = 1.0 / (90.0 * 90.0);
  q[7] = (fog_quadric){.q = {a, -b, a, 0, 0, 0, -520 * a, 300 * b, 40 * a,
                             (260.0 * 260 + 20 * 20) * a - 150.0 * 150 * b - 1},
                       .lo = {160, 0, -200}, .hi = {360, 300, 160}, .density = 0.02, .edge = 0.5};
}

typedef struct model_row {
  int model;        /* index into model_kinds */
  double setting;   /* 0: exact; marching: steps (analytic) or the step in voxels (volume) */
  bool hardware;    /* the volume's exact walk sampling with the hardware's filter */
  bool unskipped;   /* the volume's exact walk without empty-space skipping */
  bool paper;       /* Perlin: Zdrojewska's single sample (FOG_PERLIN_PAPER) */
  char series[48];
  fog_pass_params params;
  double ms, rmse, max_error;
} model_row;

/* One scene: a config and its terrain, boxes and camera drawn (app/render_frame.h). */
typedef struct bench_scene {
  scene_config *cfg;
  render_scene drawn;
} bench_scene;

static int scene_create(bench_scene *s, const char *name, int W, int H, fog_error *err) {
  return bench_load_source_config(name, &s->cfg, err) ||
         render_scene_create(&s->drawn, s->cfg, W, H, err);
}

static void scene_destroy(bench_scene *s) {
  render_scene_destroy(&s->drawn);
  free(s->cfg);
}


static const char *row_method(const model_row *r) {
  return r->setting ? "march" : r->hardware ? "exact-hardware"
         : r->unskipped ? "exact-no-skip" : r->paper ? "paper" : "exact";
}

/* The cheapest marching row of a model within MATCHED_ERROR (else its most accurate one,
 * *matched false) over its exact row. */
static double march_speedup(const model_row *rows, int count, int model, bool *matched) {
  int exact = -1, cheapest = -1, best = -1;
  for (int i = 0; i < count; i++) {
    if (rows[i].model != model) continue;
    if (!rows[i].setting) {
      if (!rows[i].hardware && !rows[i].unskipped && !rows[i].paper) exact = i;
      continue;
    }
    if (rows[i].max_error <= MATCHED_ERROR && (cheapest < 0 || rows[i].ms < rows[cheapest].ms))
      cheapest = i;
    if (best < 0 || rows[i].max_error < rows[best].max_error) best = i;
  }
  *matched = cheapest >= 0;
  int use = cheapest >= 0 ? cheapest : best;
  return exact >= 0 && use >= 0 ? rows[use].ms / rows[exact].ms : NAN;
}

static int write_table(const char *path, const model_row *rows, int count, char *error,
                       int size) {
  chart_table table;
  if (chart_table_open(&table, path, error, size)) return 1;
  FILE *f = table.stream;
  fprintf(f, "model,method,setting,ms_per_frame,rmse,max_error\n");
  for (int i = 0; i < count; i++)
    fprintf(f, "%s,%s,%g,%.6g,%.6g,%.6g\n", model_name(rows[i].model), row_method(&rows[i]),
            rows[i].setting, rows[i].ms, rows[i].rmse, rows[i].max_error);
  return chart_table_write(&table, error, size);
}

/* bench_time_rows' callbacks: the fog target bound, then the row's fog pass timed. */
typedef struct timing_user {
  bench_scene *scenes;
  model_row *rows;
  fog_pass *pass;
  const gl_target *target;
  int width, height;
} timing_user;
static int timing_prepare(void *user, int row, int round, fog_error *err) {
  (void)row, (void)round, (void)err;
  gl_target_bind(((timing_user *)user)->target);
  return 0;
}
static int timing_draw(void *user, int row, fog_error *err) {
  timing_user *u = user;
  const render_scene *sc = &u->scenes[scene_of_model[u->rows[row].model]].drawn;
  return fog_pass_draw(u->pass, &sc->cam, &u->rows[row].params, sc->target.color[0],
                       sc->target.color[1], u->width, u->height, err);
}

/* Gaussian banks at scale (render/fog_rbf_tiles.h): `count` Gaussians spread over the
 * valley of scene_configs[0] (radii shrinking as the count grows, so the fog's amount stays
 * alike), the exact integral per pixel through the per-tile lists. ms: median of `frames`
 * after a warm-up; listed_error: tau against the CPU's sum of the Gaussians the pixel's
 * tile lists (every pixel); max_error: against the sum of all of them (the culling's error
 * too), on every full_stride-th pixel of every full_stride-th row (about 2e7 closed forms:
 * every pixel for 64 Gaussians; the full sum over every pixel would take a minute for 3000). */
typedef struct rbf_scale_row {
  int count;
  fog_rbf *rbfs;
  double ms, max_error, listed_error, listed_share;
  int full_stride;
} rbf_scale_row;

static int rbf_scale_rows(fog_pass *pass, const render_scene *sc, gl_target *target, int W, int H,
                          int frames, rbf_scale_row *rows, int count, float *gpu_tau,
                          fog_error *err) {
  uint64_t seed = 0x5DEECE66Dull;
  for (int r = 0; r < count; r++) {
    double radius_max = 90.0 / sqrt(rows[r].count / 64.0), density = 0.012;
    for (int i = 0; i < rows[r].count; i++) {
      double u[5];
      for (int k = 0; k < 5; k++) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        u[k] = (double)(seed >> 11) / 9007199254740992.0;
      }
      rows[r].rbfs[i] = (fog_rbf){.centre = {-500 + 1000 * u[0], 80 * u[1], -500 + 1000 * u[2]},
                                  .radius = radius_max * (0.4 + 0.6 * u[3]),
                                  .density = density * (0.5 + u[4])};
    }
  }
  double *times = malloc(sizeof(double) * (size_t)frames * count);
  if (!times) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    return 1;
  }
  for (int f = -1; f < frames; f++)
    for (int r = 0; r < count; r++) {
      fog_pass_params params = {.model = FOG_MODEL_RBF, .model_rbfs = rows[r].rbfs,
                                .model_rbf_count = rows[r].count,
                                .fog_colour = {0.75f, 0.78f, 0.82f},
                                .walk = {.transmittance_cutoff = FOG_PASS_TRANSMITTANCE_CUTOFF}};
      gl_target_bind(target);
      fog_pass_finish();
      double t0 = app_clock_seconds();
      if (fog_pass_draw(pass, &sc->cam, &params, sc->target.color[0], sc->target.color[1], W, H,
                        err)) {
        free(times);
        return 1;
      }
      fog_pass_finish();
      if (f >= 0) {
        times[r * frames + f] = app_clock_seconds() - t0;
        continue;
      }
      /* the warm-up draw: its error against the CPU */
      if (gl_target_read(target, 1, 1, gpu_tau, err)) {
        free(times);
        return 1;
      }
      fog_rbf_tiles tiles = {0};
      if (fog_rbf_tiles_build(&tiles, &sc->cam, W, H, rows[r].rbfs, rows[r].count, err)) {
        free(times);
        return 1;
      }
      double worst = 0.0, worst_all = 0.0;
      const double closed_forms = (double)W * H * rows[r].count;
      const int full_stride = closed_forms > 2e7 ? (int)ceil(sqrt(closed_forms / 2e7)) : 1;
      for (int py = 0; py < H; py++)
        for (int px = 0; px < W; px++) {
          double o[3], d[3], depth = 0.0;
          camera_ray(&sc->cam, px, py, W, H, o, d);
          size_t k = (size_t)py * W + px;
          double ts = sc->distance[k] >= 1e29f ? HUGE_VAL : (double)sc->distance[k];
          const uint32_t *range =
              &tiles.ranges[2 * ((size_t)((H - 1 - py) / FOG_RBF_TILE_SIZE) * tiles.tiles_x +
                                 px / FOG_RBF_TILE_SIZE)];
          for (uint32_t j = 0; j < range[1]; j++)
            depth += fog_rbf_optical_depth(0.0, &rows[r].rbfs[tiles.indices[range[0] + j]], 1,
                                           o, d, ts);
          /* a NaN pixel is an infinite error (fmax drops a NaN) */
          const double listed = fabs(exp(-depth) - gpu_tau[k]);
          worst = fmax(worst, listed == listed ? listed : INFINITY);
          rows[r].listed_share += range[1] / ((double)rows[r].count * W * H);
          if (px % full_stride || py % full_stride) continue;
          const double all = fog_rbf_optical_depth(0.0, rows[r].rbfs, rows[r].count, o, d, ts);
          const double whole = fabs(exp(-all) - gpu_tau[k]);
          worst_all = fmax(worst_all, whole == whole ? whole : INFINITY);
        }
      rows[r].listed_error = worst;
      rows[r].max_error = worst_all;
      rows[r].full_stride = full_stride;
      fog_rbf_tiles_destroy(&tiles);
    }
  for (int r = 0; r < count; r++) rows[r].ms = 1e3 * app_median(times + r * frames, frames);
  free(times);
  return 0;
}

/* `fogpipe fit` on one VDB frame (the plume config's, a 3D volume) at the command's
 * defaults: its wall seconds (target <= 30), and what it picks at three tolerances. Run
 * before the benchmark's own GL context exists: fit makes a context per rung. */
static int time_fit(double *seconds, char *error, int size) {
  scene_config cfg;
  fog_error cerr;
  if (scene_config_load(FOGPIPE_SOURCE_DIR "/configs/vdb_plume_volume.ini", &cfg, &cerr)) {
    snprintf(error, (size_t)size, "%s", cerr.message);
    return 1;
  }
  fit_result r;
  fog_error ferr;
  double t0 = app_clock_seconds();
  if (fit_run(&(fit_desc){.input = &cfg, .tolerance = 0.02, .rays_per_side = FIT_RAYS_PER_SIDE,
                          .sample_side = FIT_SAMPLE_SIDE, .width = FIT_WIDTH,
                          .height = FIT_HEIGHT, .timed_frames = FIT_TIMED_FRAMES},
              &r, &ferr)) {
    snprintf(error, (size_t)size, "fit: %s", ferr.message);
    return 1;
  }
  *seconds = app_clock_seconds() - t0;
  printf("fit: configs/vdb_plume_volume.ini (frame %d as a volume): %d rungs on %d rays in "
         "%.1f s (target <= 30); picks", cfg.fog.vdb_frame, r.count, r.rays, *seconds);
  const double tolerances[] = {0.005, 0.02, 0.1, 0.5};
  for (int t = 0; t < 4; t++) {
    int pick = fit_choose(&r, tolerances[t], false);
    printf("%s %s at %g", t ? "," : "", pick < 0 ? "none" : r.rungs[pick].name, tolerances[t]);
  }
  printf(" (max |dtau|)\n");
  fit_result_destroy(&r);
  return 0;
}

int bench_models(int argc, char **argv) {
  bench_image_options options = {.width = 640, .height = 360, .frames = 5,
                                 .out_dir = "build/bench/models"};
  const bench_command command = {
      .stage = "models", .usage = "[--size WxH] [--frames N] [--out DIR]", .image = &options,
      .frames_help = "timed rounds; each row's time is the median of N frames after one\n"
                     "warm-up frame",
      .out_help = "where models.csv, models_chart.csv and models_chart.png go",
      .about =
          "Last line: models: rbf_exact_ms=A rbf_march_speedup_at_matched_error=B\n"
          "height_exact_ms=C height_march_speedup_at_matched_error=D volume_exact_ms=E\n"
          "volume_march_speedup_at_matched_error=F volume_empty_skip_speedup=S\n"
          "quadric_exact_ms=M quadric_march_speedup_at_matched_error=Q rbf_64_ms=R64\n"
          "rbf_3000_ms=R fit_s=FS perlin_exact_ms=P perlin_march_speedup_at_matched_error=PM\n"
          "perlin_paper_error=PE unmatched=LIST: B, D, F, Q, PM = time of the cheapest ray\n"
          "marching with max tau error <= 1e-3 / the exact integral's time (where none gets\n"
          "there, the most accurate one's: LIST names those models, lower bounds; none);\n"
          "S = the volume's exact walk without empty-space skipping / with it; M: 8 quadric\n"
          "volumes; R64, R: 64 and 3000 Gaussians spread over the valley, culled per screen tile\n"
          "(target R <= 4 R64); FS: seconds for `fogpipe fit` on configs/vdb_plume_volume.ini's\n"
          "VDB frame at its defaults (target <= 30); P: Perlin\n"
          "turbulence fog (4 octaves) over the valley; PE: max |tau error| of Zdrojewska's single\n"
          "sample against the ray integral."};
  int exit_status = bench_parse(&command, argc, argv);
  if (exit_status >= 0) return exit_status;
  const int W = options.width, H = options.height, frames = options.frames;
  const char *out_dir = options.out_dir;
  char error[1024] = "";
  double fit_s = 0.0;
  if (time_fit(&fit_s, error, sizeof error)) {
    fprintf(stderr, "fogpipe bench models: %s\n", error);
    return 1;
  }
  int status = 1;
  size_t pixels = (size_t)W * H;
  fog_error rerr = {0};
  gl_context *ctx = NULL;
  bench_scene scenes[SCENE_COUNT] = {{0}};
  fog_pass *pass = NULL;
  gl_target fog_target = {0};
  vdb_frame frame = {0};
  fog_perlin perlin = {0};
  float *gpu_tau = malloc(pixels * sizeof(float));
  double *references[MODEL_COUNT] = {0};
  model_row rows[MAX_ROWS] = {{0}};
  int row_count = 0;
  if (!gpu_tau) goto out_of_memory;
  ctx = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &rerr);
  if (!ctx) goto done;
  for (int k = 0; k < SCENE_COUNT; k++)
    if (scene_create(&scenes[k], scene_configs[k], W, H, &rerr)) goto done;
  if (gl_target_create(&fog_target, &(gl_target_desc){.width = W, .height = H,
                                                      .color_formats = {GL_RGBA32F, GL_R32F}},
                       &rerr) ||
      !(pass = fog_pass_create(&rerr)))
    goto done;

  /* The models: the RBFs are the banks config's (density_scale applied, as render does),
   * the volume the plume config's VDB frame. */
  const scene_config *banks = scenes[0].cfg;
  fog_rbf rbfs[FOG_MAX_RBFS];
  for (int i = 0; i < banks->fog.rbf_count; i++) {
    rbfs[i] = banks->fog.rbfs[i];
    rbfs[i].density *= banks->fog.density_scale;
  }
  volume_grid_desc grid;
  if (render_fog_load_volume(scenes[1].cfg, &frame, &grid, &rerr) ||
      fog_pass_upload_grid3d(pass, &grid, &rerr))
    goto done;
  fog_quadric quadrics[QUADRIC_COUNT], noisy[QUADRIC_COUNT];
  bench_quadrics(quadrics);
  for (int q = 0; q < QUADRIC_COUNT; q++) noisy[q] = quadrics[q], noisy[q].noise = 0.8;
  /* Perlin turbulence over the valley: 4 octaves of 32^3, eddies of 90 units, at 10 s of
   * its drift, filling the terrain's footprint up to 70 units */
  fog_perlin_desc perlin_desc = fog_perlin_desc_default();
  perlin_desc.octaves = 4;
  perlin_desc.feature_size = 90.0;
  const scene_terrain_config *valley = &banks->terrain;
  for (int a = 0; a < 3; a += 2) {
    perlin_desc.lo[a] = valley->origin[a];
    perlin_desc.hi[a] = valley->origin[a] + valley->size[a / 2];
  }
  perlin_desc.lo[1] = -10.0, perlin_desc.hi[1] = 70.0;
  if (fog_perlin_create(&perlin, &perlin_desc, &rerr) ||
      fog_pass_upload_perlin(pass, &perlin, &rerr))
    goto done;
  double voxel = HUGE_VAL;
  for (int a = 0; a < 3; a++) voxel = fmin(voxel, fabs(frame.world.step[a]));
  const double *eye = scenes[0].drawn.cam.position; /* the classic factors' */
  const fog_model models[MODEL_COUNT] = {
      {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = 0.002},
      {.kind = FOG_MODEL_HEIGHT, .extinction = 0.01, .y0 = 40.0, .scale_height = 25.0},
      {.kind = FOG_MODEL_RBF, .extinction = banks->fog.rbf_base, .rbfs = rbfs,
       .rbf_count = banks->fog.rbf_count},
      {.kind = FOG_MODEL_VOLUME, .grid3d = &grid},
      {.kind = FOG_MODEL_QUADRIC, .quadrics = quadrics, .quadric_count = QUADRIC_COUNT},
      {.kind = FOG_MODEL_LINEAR, .fog_start = 200.0, .fog_end = 1200.0,
       .eye = {eye[0], eye[1], eye[2]}},
      {.kind = FOG_MODEL_EXP2, .extinction = 0.0015, .eye = {eye[0], eye[1], eye[2]}},
      {.kind = FOG_MODEL_PERLIN, .extinction = 0.02, .y0 = 5.0, .scale_height = 18.0,
       .perlin = &perlin, .time = 10.0},
      {.kind = FOG_MODEL_QUADRIC, .quadrics = noisy, .quadric_count = QUADRIC_COUNT,
       .perlin = &perlin, .time = 10.0}};

  /* The CPU references: tau of each model along every pixel's ray to its surface. */
  for (int m = 0; m < MODEL_COUNT; m++) {
    const render_scene *sc = &scenes[scene_of_model[m]].drawn;
    references[m] = malloc(pixels * sizeof(double));
    if (!references[m]) goto out_of_memory;
    for (int py = 0; py < H; py++)
      for (int px = 0; px < W; px++) {
        double o[3], d[3];
        size_t k = (size_t)py * W + px;
        camera_ray(&sc->cam, px, py, W, H, o, d);
        double ts = sc->distance[k] >= 1e29f ? HUGE_VAL : (double)sc->distance[k];
        references[m][k] = fog_transmittance(fog_model_optical_depth(&models[m], o, d, ts));
      }
  }

  for (int m = 0; m < MODEL_COUNT; m++) {
    /* s = -3: the volume's exact walk without empty-space skipping; -2: with hardware
     * filtering; -1: exact (the pass's defaults); >= 0: marches */
    /* s = -4: Perlin's paper variant */
    int marches = !marched(m) ? 0 : m == 3 ? VOLUME_STEP_COUNT : MARCH_COUNT;
    for (int s = m == 3 ? -3 : m == PERLIN ? -4 : -1; s < marches; s++) {
      if (m == PERLIN && (s == -3 || s == -2)) continue;
      model_row *r = &rows[row_count++];
      r->model = m;
      r->hardware = s == -2;
      r->unskipped = s == -3;
      r->paper = s == -4;
      r->setting = s < 0 ? 0.0 : m == 3 ? volume_steps[s] : march_steps[s];
      snprintf(r->series, sizeof r->series, "%s %s", model_name(m),
               s == -4   ? "paper (single sample)"
               : s == -3 ? "exact no skip"
               : s == -2 ? "exact hardware"
               : s < 0   ? "exact"
                         : "march");
      r->params = (fog_pass_params){
          .model = models[m].kind, .model_extinction = models[m].extinction,
          .model_y0 = models[m].y0, .model_scale_height = models[m].scale_height,
          .model_rbfs = models[m].rbfs, .model_rbf_count = models[m].rbf_count,
          .model_quadrics = models[m].quadrics, .model_quadric_count = models[m].quadric_count,
          .model_fog_start = models[m].fog_start, .model_fog_end = models[m].fog_end,
          .model_perlin = models[m].perlin, .model_time = models[m].time,
          .model_perlin_integral = s == -4 ? FOG_PERLIN_PAPER : FOG_PERLIN_EXACT,
          .fog_colour = {0.75f, 0.78f, 0.82f},
          .integrator = s < 0 ? FOG_INTEGRATOR_EXACT : FOG_INTEGRATOR_MARCH,
          .fetch = s == -2 ? FOG_FETCH_HARDWARE : FOG_FETCH_MANUAL,
          .march_steps = m == 3 || s < 0 ? 0 : march_steps[s],
          .model_grid3d_step = m == 3 && s >= 0 ? volume_steps[s] * voxel : 0.0,
          .walk = {.transmittance_cutoff = FOG_PASS_TRANSMITTANCE_CUTOFF,
                   .skip = s == -3 ? FOG_SKIP_NONE : FOG_SKIP_EMPTY}};
    }
  }
  /* Warm-up (shader JIT) with the error read-back, then the timed rounds interleaved. */
  for (int i = 0; i < row_count; i++) {
    model_row *r = &rows[i];
    const render_scene *sc = &scenes[scene_of_model[r->model]].drawn;
    size_t where;
    gl_target_bind(&fog_target);
    if (fog_pass_draw(pass, &sc->cam, &r->params, sc->target.color[0], sc->target.color[1], W,
                      H, &rerr) ||
        gl_target_read(&fog_target, 1, 1, gpu_tau, &rerr))
      goto done;
    bench_tau_errors(gpu_tau, references[r->model], pixels, &r->rmse, &r->max_error, &where);
  }
  timing_user user = {scenes, rows, pass, &fog_target, W, H};
  if (bench_time_rows(&(bench_timed_rows){.count = row_count, .frames = frames, .user = &user,
                                          .prepare = timing_prepare, .draw = timing_draw,
                                          .ms = &rows[0].ms, .ms_stride = sizeof rows[0]},
                      &rerr))
    goto done;
  static fog_rbf scale_rbfs[64 + 3000];
  rbf_scale_row scale[2] = {{.count = 64, .rbfs = scale_rbfs},
                            {.count = 3000, .rbfs = scale_rbfs + 64}};
  if (rbf_scale_rows(pass, &scenes[0].drawn, &fog_target, W, H, frames, scale, 2, gpu_tau,
                     &rerr))
    goto done;

  bench_print_gl(ctx, W, H, frames);
  printf("scenes: configs/%s (terrain, boxes, camera): homogeneous K = %g; height\n"
         "K = %g exp(-(y - %g)/%g); rbf: the config's %d Gaussians; configs/%s: the volume,\n"
         "%dx%dx%d voxels of %g, marched at %g..%g voxels. Errors: tau vs the double-precision\n"
         "CPU model on the same rays, over all pixels; quadric: %d volumes on the valley\n\n",
         scene_configs[0], models[0].extinction, models[1].extinction, models[1].y0,
         models[1].scale_height, models[2].rbf_count, scene_configs[1], grid.dim[0],
         grid.dim[1], grid.dim[2], voxel, volume_steps[VOLUME_STEP_COUNT - 1], volume_steps[0],
         QUADRIC_COUNT);
  printf("%-12s %-14s %8s %10s %10s %10s\n", "model", "method", "setting", "ms/frame", "RMSE",
         "max err");
  chart_point points[MAX_ROWS];
  for (int i = 0; i < row_count; i++) {
    const model_row *r = &rows[i];
    char setting[24] = "";
    if (r->setting)
      snprintf(setting, sizeof setting, r->model == 3 ? "%g vox" : "%g", r->setting);
    printf("%-12s %-14s %8s %10.2f %10.2e %10.2e\n", model_name(r->model), row_method(r),
           setting, r->ms, r->rmse, r->max_error);
    points[i] = (chart_point){.series = r->series, .x = r->ms,
                              .y = chart_floor(r->max_error, ERROR_FLOOR)};
  }
  char title[128];
  bench_outputs files;
  bench_outputs_in(&files, out_dir, "models");
  snprintf(title, sizeof title, "fog models %dx%d: max tau error vs GL time (exact and marched)", W, H);
  chart_desc chart = {.title = title, .x_label = "GL time per frame (ms)",
                      .y_label = "max |tau - CPU reference|", .log_x = true, .log_y = true};
  /* a file that fails costs the stage its status, not its figures */
  bench_files_written written;
  bench_write_files(&written,
                    write_table(files.table, rows, row_count, written.error,
                                 sizeof written.error),
                    &chart, points, row_count, &files);
  printf("\nCSV: %s, %s; PNG: %s\n", files.table, files.chart_csv,
         written.drawn ? files.chart_png : "not drawn");
  double exact_ms[MODEL_COUNT] = {0}, speedup[MODEL_COUNT] = {0}, unskipped_ms = 0.0;
  double paper_error = NAN, paper_ms = NAN;
  for (int i = 0; i < row_count; i++)
    if (rows[i].paper) paper_error = rows[i].max_error, paper_ms = rows[i].ms;
  /* the models whose "matched" speedup is the most accurate march's (none within
   * MATCHED_ERROR): lower bounds, named in the summary */
  char unmatched[256] = "";
  for (int m = 1; m < MODEL_COUNT; m++) {
    if (!marched(m)) continue;
    bool matched;
    speedup[m] = march_speedup(rows, row_count, m, &matched);
    if (!matched && m != QUADRIC_NOISE)
      snprintf(unmatched + strlen(unmatched), sizeof unmatched - strlen(unmatched), "%s%s",
               unmatched[0] ? "+" : "", model_name(m));
    for (int i = 0; i < row_count; i++)
      if (rows[i].model == m && !rows[i].setting && !rows[i].hardware && !rows[i].paper) {
        if (rows[i].unskipped)
          unskipped_ms = rows[i].ms;
        else
          exact_ms[m] = rows[i].ms;
      }
    if (!matched)
      printf("note: no marching of %s reached max error <= %g; its speedup uses the most "
             "accurate one\n", model_name(m), MATCHED_ERROR);
  }
  printf("volume: exact walk without empty-space skipping %.2f ms / with it (brick by brick, "
         "the default) %.2f ms = %.2f\n", unskipped_ms, exact_ms[3], unskipped_ms / exact_ms[3]);
  for (int r = 0; r < 2; r++) {
    char where[64] = "every pixel";
    if (scale[r].full_stride > 1)
      snprintf(where, sizeof where, "1 pixel in %d x %d", scale[r].full_stride,
               scale[r].full_stride);
    printf("rbf banks at scale: %4d Gaussians spread over the valley: %.2f ms, max |dtau| %.2e "
           "against the CPU's sum of those a pixel's tile lists (%.1f %% of them), %.2e against "
           "the sum of all (%s)\n", scale[r].count, scale[r].ms, scale[r].listed_error,
           100.0 * scale[r].listed_share, scale[r].max_error, where);
  }
  printf("rbf: 3000 Gaussians / 64 = %.2f (target <= 4)\n", scale[1].ms / scale[0].ms);
  printf("perlin: the paper's single sample %.2f ms, max |dtau| %.3f against the ray integral "
         "(exact %.2f ms)\n", paper_ms, paper_error, exact_ms[PERLIN]);
  printf("quadric volumes with noise 0.8 inside (the Perlin row's octaves): exact %.2f ms, "
         "%.2f x the homogeneous volumes' %.2f ms; marching within %g: speedup %.2f\n",
         exact_ms[QUADRIC_NOISE], exact_ms[QUADRIC_NOISE] / exact_ms[4], exact_ms[4],
         MATCHED_ERROR, speedup[QUADRIC_NOISE]);
  printf("models: rbf_exact_ms=%.3f rbf_march_speedup_at_matched_error=%.2f "
         "height_exact_ms=%.3f height_march_speedup_at_matched_error=%.2f "
         "volume_exact_ms=%.3f volume_march_speedup_at_matched_error=%.2f "
         "volume_empty_skip_speedup=%.2f quadric_exact_ms=%.3f "
         "quadric_march_speedup_at_matched_error=%.2f rbf_64_ms=%.3f rbf_3000_ms=%.3f "
         "fit_s=%.2f perlin_exact_ms=%.3f perlin_march_speedup_at_matched_error=%.2f "
         "perlin_paper_error=%.4f unmatched=%s\n",
         exact_ms[2], speedup[2], exact_ms[1], speedup[1], exact_ms[3], speedup[3],
         unskipped_ms / exact_ms[3], exact_ms[4], speedup[4], scale[0].ms, scale[1].ms, fit_s,
         exact_ms[PERLIN], speedup[PERLIN], paper_error, unmatched[0] ? unmatched : "none");
  status = bench_files_report(&written, &rerr);
  goto done;

out_of_memory:
  fog_fail(&rerr, FOG_ERR_OUT_OF_MEMORY, "out of memory");
done:
  for (int m = 0; m < MODEL_COUNT; m++) free(references[m]);
  vdb_frame_destroy(&frame);
  fog_perlin_destroy(&perlin);
  if (pass) fog_pass_destroy(pass);
  if (fog_target.framebuffer) gl_target_destroy(&fog_target);
  for (int k = 0; k < SCENE_COUNT; k++) scene_destroy(&scenes[k]);
  if (ctx) gl_context_destroy(ctx);
  free(gpu_tau);
  return bench_report("models", status, &rerr);
}
