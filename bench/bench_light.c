/* fogpipe bench light: the fog's shadow on itself (docs/light.md), speed against accuracy,
 * side by side in one run, on the lit default scene (its fogmap, static, through `render`'s
 * fog) and on the plume volume (configs/vdb_plume_volume.ini, the sun from the side):
 *   - unlit: the sun's in-scatter without T_s (fog_self_shadow off): the baseline;
 *   - ours: the tau K-weighted T_s mean over 2..32 segments of one midpoint and 1..16 of two
 *     Gauss nodes, with the sun's optical-depth volume at 48^3 (the default), and the
 *     product's default (8 x 2) at 24^3 and 96^3; the live setting (the fog pass at half
 *     resolution, upsampled, as the demo runs on a software renderer) at the default and
 *     half its segments, and a quarter of the resolution;
 *   - uniform marching of tau and in-scatter together (8..512 samples, every power of 2),
 *     and the engines' froxel grid (160 x 90 x 64 and 2x, FOG_INTEGRATOR_FROXEL) fed the
 *     same fog and light.
 * Time: the fog pass, GL, glFinish before and after, median of --frames rounds after a
 * warm-up; the volume's compute beside it (wall ms on 2 threads, median of 5 after one). Error: the in-scattered radiance
 * against the CPU twin in double converged (FOG_BENCH_LIGHT_STEPS segments, a
 * FOG_BENCH_LIGHT_VOLUME^3 volume) on a grid of pixels; that converged twin agrees with the
 * independent nested-quadrature reference (test_fog_shadow) to its volume's interpolation
 * error. Relative to the largest in-scatter in view; max and mean.
 * Writes light.csv and light_chart.{csv,png} (max error vs ms). Last line:
 * `light: lit_over_unlit=A lit_over_unlit_full=A2 shadow_volume_ms=V live_max_error=E
 * froxel_error_ratio_at_equal_time=B march_speedup_at_matched_error=C`:
 * A = the live setting's fog pass / the unlit one at the same (half) resolution, A2 the
 * same at full resolution with the default settings, V the default volume's ms, E the
 * live setting's max relative error, B the froxel grid's (1x) max error over our most
 * accurate setting costing no more time (default scene), C the cheapest marching within
 * MATCHED_ERROR over our cheapest full-resolution setting within it. */
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
#include "render/render.h"
#include "sim/image.h"

#define FOG_BENCH_LIGHT_STEPS 1024
#define FOG_BENCH_LIGHT_VOLUME 160
#define VOLUME_RUNS 5 /* timed computes of each sun volume */
/* The error on every 8th pixel of every 8th row, from 256 pixels wide; a smaller image
 * keeps about 32 samples a row (down to every pixel), or a smoke size's 2 x 2 samples
 * could all miss the fog and leave the errors 0 / 0. */
static int error_stride(int width) {
  return width >= 256 ? 8 : (width / 32 > 1 ? width / 32 : 1);
}
#define MATCHED_ERROR 1e-2 /* the 1e-3 is below the 48^3 sun volume's floor (7e-3) */

static const int step_counts[] = {2, 4, 8, 16, 32};
static const int resolutions[] = {24, 48, 96};
static const int march_samples[] = {8, 16, 32, 64, 128, 256, 512};
enum { STEP_COUNT = 5, RESOLUTION_COUNT = 3, MARCH_COUNT = 7, SCENE_COUNT = 2, MAX_ROWS = 58 };
/* Ours with two Gauss nodes a segment: 1 .. 16 segments (2 .. 32 samples). */
enum { NODE_STEP_COUNT = 5 };
/* The froxel baseline: the engines' 160 x 90 x 64 grid and one 2x finer in each axis. */
enum { FROXEL_COUNT = 2, FROXEL_COLUMNS = 160, FROXEL_ROWS = 90, FROXEL_SLICES = 64 };
enum { SCENE_ROWS = 2 + STEP_COUNT + NODE_STEP_COUNT + 8 + MARCH_COUNT + FROXEL_COUNT };
/* Where a scene's rows start: unlit (full, half), ours midpoint 2..32 steps, ours two nodes
 * 1..16 steps, the product's default setting at 24^3 and 96^3, live (half resolution) at
 * the default and at half its steps, 96^3 x 64 x 2 nodes, a quarter of the resolution
 * (default, half the steps), per piece of the exact walk (two nodes), marching, froxels. */
enum {
  ROW_UNLIT_FULL = 0,
  ROW_UNLIT_HALF = 1,
  ROW_DEFAULT_24 = 2 + STEP_COUNT + NODE_STEP_COUNT,
  ROW_LIVE = ROW_DEFAULT_24 + 2,
  ROW_NEAR_CONVERGED = ROW_LIVE + 2,
  ROW_FROXEL = SCENE_ROWS - FROXEL_COUNT,
};
_Static_assert(SCENE_COUNT * SCENE_ROWS <= MAX_ROWS, "the rows of both scenes");
static const char *const scene_configs[SCENE_COUNT] = {"default.ini", "vdb_plume_volume.ini"};
static const char *const scene_names[SCENE_COUNT] = {"default", "plume"};

typedef struct light_row {
  int scene;
  int resolution; /* of the volume; 0: unlit */
  int steps;
  int divisor;    /* fog pass resolution divisor */
  bool march;     /* uniform ray marching of the whole integral: tau too, `steps` samples */
  int froxel;     /* > 0: the froxel baseline, its grid this many times the engines' */
  int nodes;      /* ours: samples per segment (1 midpoint, 2 Gauss-Legendre) */
  bool pieces;    /* ours per piece of the exact walk */
  char series[64];
  double ms, max_error, mean_error;
} light_row;

typedef struct light_scene {
  scene_config *cfg;
  render_scene drawn;
  render_fog fog;
  fog_model model;
  fog_sun_shadow_kind kind; /* how the model's T_s is found (the shadowed rows') */
  vdb_frame frame; /* the volume's grid, kept for the model */
  volume_grid_desc grid;
  fog_sun_shadow volumes[RESOLUTION_COUNT], converged;
  double volume_ms[RESOLUTION_COUNT];
  double *reference; /* converged in-scatter, 3 per error pixel */
  double peak;       /* the largest reference in-scatter */
} light_scene;

static int scene_create(light_scene *s, const char *name, int W, int H, fog_error *err) {
  if (bench_load_source_config(name, &s->cfg, err)) return 1;
  scene_config *cfg = s->cfg;
  cfg->fog.albedo = cfg->fog.albedo > 0 ? cfg->fog.albedo : 0.9;
  cfg->shadow.fog_self_shadow = 1;
  if (cfg->fog.model == FOG_MODEL_VOLUME) { /* the plume lit from the side */
    cfg->light.sun_azimuth = 75, cfg->light.sun_elevation = 20;
    if (render_fog_load_volume(cfg, &s->frame, &s->grid, err)) return 1;
  }
  if (render_scene_create(&s->drawn, cfg, W, H, err) || render_fog_create(&s->fog, cfg, err))
    return 1;
  s->fog.grid3d = &s->grid;
  s->model = render_fog_model(&s->fog);
  s->kind = s->fog.params.self_shadow;
  if (s->kind != FOG_SUN_SHADOW_VOLUME) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: expected a fog with a sun volume", name);
    return 1;
  }
  const double *sun = s->fog.params.sun.direction;
  for (int r = 0; r < RESOLUTION_COUNT; r++) {
    int n = resolutions[r];
    if (fog_sun_shadow_create(&s->volumes[r], &(fog_sun_shadow_desc){.across = n, .along = n},
                              err))
      return 1;
    /* wall time of the 2-thread compute: the median of VOLUME_RUNS after one untimed */
    double runs[VOLUME_RUNS];
    for (int k = -1; k < VOLUME_RUNS; k++) {
      double t0 = app_clock_seconds();
      if (fog_sun_shadow_compute(&s->volumes[r], &s->model, sun, 2, err)) return 1;
      if (k >= 0) runs[k] = 1e3 * (app_clock_seconds() - t0);
    }
    s->volume_ms[r] = app_median(runs, VOLUME_RUNS);
  }
  const int n = FOG_BENCH_LIGHT_VOLUME;
  return fog_sun_shadow_create(&s->converged, &(fog_sun_shadow_desc){.across = n, .along = n},
                               err) ||
         fog_sun_shadow_compute(&s->converged, &s->model, sun, 2, err);
}

static void scene_destroy(light_scene *s) {
  for (int r = 0; r < RESOLUTION_COUNT; r++) fog_sun_shadow_destroy(&s->volumes[r]);
  fog_sun_shadow_destroy(&s->converged);
  render_fog_destroy(&s->fog);
  render_scene_destroy(&s->drawn);
  vdb_frame_destroy(&s->frame);
  free(s->reference);
  free(s->cfg);
}

static double phase_hg(double g, double mu) {
  return (1 - g * g) / (4 * 3.14159265358979323846 * pow(1 + g * g - 2 * g * mu, 1.5));
}

/* The converged in-scatter at the error pixels, with tau from the GL's unlit draw (tau is
 * the same exact integral in every row). */
static int scene_reference(light_scene *s, const float *tau, int W, int H) {
  const int stride = error_stride(W);
  const int cols = (W + stride - 1) / stride, rows = (H + stride - 1) / stride;
  if (!(s->reference = malloc((size_t)cols * rows * 3 * sizeof(double)))) return 1;
  const fog_pass_params *p = &s->fog.params;
  const fog_sun *sun = &p->sun;
  s->peak = 0;
  for (int j = 0; j < rows; j++)
    for (int i = 0; i < cols; i++) {
      int px, py;
      bench_error_pixel(i, j, stride, W, H, &px, &py);
      size_t k = (size_t)py * W + px;
      double o[3], d[3];
      camera_ray(&s->drawn.cam, px, py, W, H, o, d);
      double ts = s->drawn.distance[k] >= 1e29f ? HUGE_VAL : (double)s->drawn.distance[k];
      double mean = fog_sun_mean_transmittance(&s->model, s->kind, &s->converged,
                                               (fog_light_rule){.steps = FOG_BENCH_LIGHT_STEPS, .nodes = 2},
                                               fog_pass_depth_limit(p->walk.transmittance_cutoff), o,
                                               d, ts);
      double ph = phase_hg(sun->phase_g, d[0] * sun->direction[0] + d[1] * sun->direction[1] +
                                             d[2] * sun->direction[2]);
      for (int c = 0; c < 3; c++) {
        double v = (p->fog_colour[c] + sun->albedo * sun->radiance[c] * ph * mean) * (1 - tau[k]);
        s->reference[((size_t)j * cols + i) * 3 + c] = v;
        s->peak = fmax(s->peak, v);
      }
    }
  return 0;
}

static void row_errors(light_row *r, const light_scene *s, const float *inscatter, int W, int H) {
  const int stride = error_stride(W);
  const int cols = (W + stride - 1) / stride, rows = (H + stride - 1) / stride;
  double worst = 0, sum = 0;
  for (int j = 0; j < rows; j++)
    for (int i = 0; i < cols; i++) {
      int px, py;
      bench_error_pixel(i, j, stride, W, H, &px, &py);
      size_t k = (size_t)py * W + px;
      for (int c = 0; c < 3; c++) {
        double e = fabs(inscatter[3 * k + c] - s->reference[((size_t)j * cols + i) * 3 + c]);
        if (!(e == e)) e = HUGE_VAL;
        worst = fmax(worst, e);
        sum += e;
      }
    }
  r->max_error = worst / s->peak;
  r->mean_error = sum / (3.0 * cols * rows) / s->peak;
}

/* The froxel grid `scale` times the engines' (0: none), its slices from the fog's box's
 * nearest point (the camera's near plane inside it) to its farthest corner. */
static fog_froxel_grid froxel_grid(const light_scene *s, int scale) {
  if (!scale) return (fog_froxel_grid){0};
  double lo[3], hi[3], near2 = 0, far2 = 0;
  fog_model_bounds(&s->model, lo, hi);
  const double *c = s->drawn.cam.position;
  for (int a = 0; a < 3; a++) {
    double below = lo[a] - c[a], above = c[a] - hi[a], gap = fmax(0, fmax(below, above));
    double reach = fmax(fabs(lo[a] - c[a]), fabs(hi[a] - c[a]));
    near2 += gap * gap, far2 += reach * reach;
  }
  return (fog_froxel_grid){.columns = FROXEL_COLUMNS * scale, .rows = FROXEL_ROWS * scale,
                           .slices = FROXEL_SLICES * scale,
                           .near_distance = fmax(sqrt(near2), s->drawn.cam.near_plane),
                           .far_distance = sqrt(far2)};
}

/* One draw of row r into out (the volume of its resolution already uploaded). */
static int draw_row(light_scene *s, const light_row *r, const gl_target *out, fog_error *err) {
  fog_pass_params *p = &s->fog.params;
  p->self_shadow = r->resolution ? s->kind : FOG_SUN_SHADOW_NONE;
  s->fog.ground_shadow = r->resolution != 0;
  p->shadow_steps = r->steps;
  p->shadow_nodes = r->nodes;
  p->shadow_pieces = r->pieces;
  p->resolution_divisor = r->divisor;
  p->integrator = r->froxel ? FOG_INTEGRATOR_FROXEL
                  : r->march ? FOG_INTEGRATOR_MARCH : FOG_INTEGRATOR_EXACT;
  p->froxel = froxel_grid(s, r->froxel);
  p->march_steps = r->steps;
  if (p->model == FOG_MODEL_VOLUME) { /* the volume marches at a step: its diagonal / N */
    double lo[3], hi[3];
    fog_model_bounds(&s->model, lo, hi);
    p->model_grid3d_step =
        sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
             (hi[2] - lo[2]) * (hi[2] - lo[2])) / r->steps;
  }
  return render_fog_draw(&s->fog, &s->drawn.cam, &s->drawn.target, out, err);
}

static int upload_for(light_scene *s, const light_row *r, fog_error *err) {
  for (int q = 0; q < RESOLUTION_COUNT; q++)
    if (resolutions[q] == r->resolution)
      return fog_pass_upload_sun_shadow(s->fog.pass, &s->volumes[q], err);
  return 0;
}

/* bench_time_rows' callbacks: the row's sun volume uploaded, then its draw timed. */
typedef struct timing_user {
  light_scene *scenes;
  light_row *rows;
  const gl_target *out;
} timing_user;
/* The fog pass remakes its froxel grid (14.7 MB at 1x, 118 MB at 2x) and its reduced
 * target when their sizes change, and llvmpipe zeroes each new texture: every row draws
 * once untimed first, so that no row's time holds an allocation (the froxels' did, every
 * round, until the sixteenth session), and every row's timed draw finds its caches as warm
 * as the others' (only the remade rows drew first, the live and full rows timed cold). */
static int timing_prepare(void *user, int row, int round, fog_error *err) {
  (void)round;
  timing_user *u = user;
  const light_row *r = &u->rows[row];
  light_scene *s = &u->scenes[r->scene];
  if (upload_for(s, r, err)) return 1;
  return draw_row(s, r, u->out, err);
}
static int timing_draw(void *user, int row, fog_error *err) {
  timing_user *u = user;
  return draw_row(&u->scenes[u->rows[row].scene], &u->rows[row], u->out, err);
}

/* B's partner on one scene's rows: the most accurate of our settings (any image
 * resolution) whose fog pass costs no more time than the froxel baseline's 1x grid and
 * reads no finer sun volume than the froxels are fed (the 96^3 volume's CPU compute, 45-115
 * ms a refresh, is in no row's time: a 96^3 row made the plume's B 50.7); NULL where none
 * does. */
static const light_row *ours_at_froxel_time(const light_row *rows, const light_row *froxel) {
  const light_row *best = NULL;
  for (int i = 0; i < SCENE_ROWS; i++) {
    const light_row *r = &rows[i];
    if (!r->resolution || r->march || r->froxel || r->ms > froxel->ms ||
        r->resolution > froxel->resolution)
      continue;
    if (!best || r->max_error < best->max_error) best = r;
  }
  return best;
}

/* froxel_1x (B's baseline) and froxel_2x told apart: their other columns are alike */
static const char *row_method(const light_row *r) {
  return !r->resolution ? "unlit" : r->march ? "march"
         : r->froxel    ? (r->froxel > 1 ? "froxel_2x" : "froxel_1x")
         : r->pieces    ? "pieces" : "ours";
}

static int write_table(const char *path, const light_row *rows, int count, char *error,
                       int size) {
  chart_table table;
  if (chart_table_open(&table, path, error, size)) return 1;
  FILE *f = table.stream;
  fprintf(f, "scene,method,volume,steps,nodes,divisor,ms_per_frame,max_error,mean_error\n");
  for (int i = 0; i < count; i++)
    fprintf(f, "%s,%s,%d,%d,%d,%d,%.6g,%.6g,%.6g\n", scene_configs[rows[i].scene],
            row_method(&rows[i]),
            rows[i].resolution, rows[i].steps, rows[i].nodes,
            rows[i].divisor, rows[i].ms, rows[i].max_error, rows[i].mean_error);
  return chart_table_write(&table, error, size);
}

static light_row *add_row(light_row *rows, int *count, int scene, int resolution, int steps,
                          int nodes, int divisor) {
  light_row *r = &rows[(*count)++];
  *r = (light_row){.scene = scene, .resolution = resolution, .steps = steps, .divisor = divisor,
                   .march = steps < 0, .nodes = nodes};
  if (r->march) r->steps = -steps;
  snprintf(r->series, sizeof r->series, "%s %s", scene_names[scene],
           !resolution        ? "unlit"
           : r->march         ? "uniform marching 48^3 8..512 samples"
           : divisor > 2      ? "ours at 1/4 resolution"
           : divisor > 1      ? "live (1/2)"
           : resolution != 48 ? "ours 24^3 / 96^3 volume"
           : nodes == 2       ? "ours 48^3 2 nodes x 1..16 steps"
                              : "ours 48^3 midpoints 2..32 steps");
  return r;
}

int bench_light(int argc, char **argv) {
  bench_image_options options = {.width = 640, .height = 360, .frames = 5,
                                 .out_dir = "build/bench/light"};
  const bench_command command = {
      .stage = "light", .usage = "[--size WxH] [--frames N] [--out DIR]", .image = &options,
      .out_help = "light.csv, light_chart.csv, light_chart.png",
      .about = "Last line: light: lit_over_unlit=A lit_over_unlit_full=A2 shadow_volume_ms=V\n"
               "live_max_error=E froxel_error_ratio_at_equal_time=B march_speedup_at_matched_error=C\n"
               "(see the header of bench/bench_light.c)."};
  int exit_status = bench_parse(&command, argc, argv);
  if (exit_status >= 0) return exit_status;
  const int W = options.width, H = options.height, frames = options.frames;
  int status = 1, row_count = 0;
  size_t pixels = (size_t)W * H;
  fog_error rerr = {0};
  light_scene scenes[SCENE_COUNT] = {{0}};
  light_row rows[MAX_ROWS] = {{0}};
  gl_target out = {0};
  float *tau = malloc(pixels * sizeof(float)), *inscatter = malloc(3 * pixels * sizeof(float));
  gl_context *ctx = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &rerr);
  if (!tau || !inscatter) goto out_of_memory;
  if (!ctx || gl_target_create(&out, &(gl_target_desc){.width = W, .height = H,
                                                       .color_formats = {GL_RGBA32F, GL_R32F,
                                                                         GL_RGBA32F}},
                               &rerr))
    goto done;
  /* the product's default light settings ([light] shadow_steps, shadow_nodes) */
  scene_config defaults;
  scene_config_init(&defaults);
  for (int s = 0; s < SCENE_COUNT; s++) {
    if (scene_create(&scenes[s], scene_configs[s], W, H, &rerr)) goto done;
    const int D = defaults.shadow.steps, N = defaults.shadow.nodes;
    add_row(rows, &row_count, s, 0, 1, 1, 1);
    add_row(rows, &row_count, s, 0, 1, 1, 2);
    for (int q = 0; q < STEP_COUNT; q++)
      add_row(rows, &row_count, s, 48, step_counts[q], 1, 1);
    for (int q = 0; q < NODE_STEP_COUNT; q++)
      add_row(rows, &row_count, s, 48, 1 << q, 2, 1);
    add_row(rows, &row_count, s, 24, D, N, 1);
    add_row(rows, &row_count, s, 96, D, N, 1);
    add_row(rows, &row_count, s, 48, D, N, 2);
    add_row(rows, &row_count, s, 48, (D + 1) / 2, N, 2);
    add_row(rows, &row_count, s, 96, 64, 2, 1);
    /* ours at a quarter of the resolution (the fogmap's walk; the volume ignores it) */
    add_row(rows, &row_count, s, 48, D, N, 4);
    add_row(rows, &row_count, s, 48, (D + 1) / 2, N, 4);
    /* ours per piece of the exact walk, two nodes */
    light_row *piece_row = add_row(rows, &row_count, s, 48, D, 2, 1);
    piece_row->pieces = true;
    snprintf(piece_row->series, sizeof piece_row->series, "%s ours 48^3 per piece",
             scene_names[s]);
    /* uniform marching of tau and the in-scatter together (negative steps: the marcher) */
    for (int q = 0; q < MARCH_COUNT; q++)
      add_row(rows, &row_count, s, 48, -march_samples[q], 1, 1);
    /* the froxel baseline, fed the same density, sun, T_s volume and shadow map */
    for (int q = 1; q <= FROXEL_COUNT; q++) {
      light_row *r = add_row(rows, &row_count, s, 48, 1, 1, 1);
      r->froxel = q;
      snprintf(r->series, sizeof r->series, "%s froxels 160x90x64 / 2x", scene_names[s]);
    }
  }
  /* Warm-up and errors (the unlit full-resolution draw gives the reference its tau), then
   * the timed rounds, rows of one scene and volume interleaved. */
  for (int i = 0; i < row_count; i++) {
    light_row *r = &rows[i];
    light_scene *s = &scenes[r->scene];
    if (upload_for(s, r, &rerr) || draw_row(s, r, &out, &rerr) ||
        gl_target_read(&out, 1, 1, tau, &rerr) || gl_target_read(&out, 2, 3, inscatter, &rerr))
      goto done;
    if (!s->reference && scene_reference(s, tau, W, H)) goto out_of_memory;
    row_errors(r, s, inscatter, W, H);
    /* to look at: ours live, ours at 96^3 x 64 steps (near the reference), froxels 1x */
    int in_scene = i % SCENE_ROWS;
    if (in_scene == ROW_LIVE || in_scene == ROW_NEAR_CONVERGED || in_scene == ROW_FROXEL) {
      char path[4200];
      snprintf(path, sizeof path, "%s/light_%s_%s.png", options.out_dir, scene_names[r->scene],
               in_scene == ROW_LIVE ? "ours_live" : in_scene == ROW_NEAR_CONVERGED ? "ours_96_64"
                                                                                   : "froxels_1x");
      if (gl_target_read(&out, 0, 3, inscatter, &rerr) ||
          image_write_png_srgb(path, W, H, 3, inscatter, SRGB8_DITHER, &rerr))
        goto done;
    }
  }
  timing_user user = {scenes, rows, &out};
  if (bench_time_rows(&(bench_timed_rows){.count = row_count, .frames = frames, .user = &user,
                                          .prepare = timing_prepare, .draw = timing_draw,
                                          .ms = &rows[0].ms, .ms_stride = sizeof rows[0]},
                      &rerr))
    goto done;

  bench_print_gl(ctx, W, H, frames);
  printf("error: in-scatter vs the CPU twin converged (%d segments, a %d^3 volume) on every\n"
         "%dth pixel of every %dth row (moved up to 3 within its cell, onto every phase of the\n"
         "reduced passes' blocks), relative to the largest in-scatter in view\n\n",
         FOG_BENCH_LIGHT_STEPS, FOG_BENCH_LIGHT_VOLUME, error_stride(W), error_stride(W));
  for (int s = 0; s < SCENE_COUNT; s++)
    printf("%s: sun volume ms (wall, 2 threads, median of %d) %.1f (24^3) %.1f (48^3) "
           "%.1f (96^3)\n",
           scene_configs[s], VOLUME_RUNS, scenes[s].volume_ms[0], scenes[s].volume_ms[1],
           scenes[s].volume_ms[2]);
  printf("\n%-22s %-8s %7s %6s %5s %8s %10s %10s %10s\n", "scene", "method", "volume", "steps",
         "nodes", "res", "ms/frame", "max err", "mean err");
  chart_point points[MAX_ROWS];
  for (int i = 0; i < row_count; i++) {
    const light_row *r = &rows[i];
    char volume[16] = "-";
    if (r->resolution) snprintf(volume, sizeof volume, "%d^3", r->resolution);
    char steps[16];
    if (r->froxel)
      snprintf(steps, sizeof steps, "%dx", r->froxel);
    else if (r->pieces)
      snprintf(steps, sizeof steps, "piece");
    else
      snprintf(steps, sizeof steps, "%d", r->resolution ? r->steps : 0);
    printf("%-22s %-8s %7s %6s %5d %8s %10.2f %10.2e %10.2e\n", scene_configs[r->scene],
           row_method(r), volume, steps, r->resolution && !r->march && !r->froxel ? r->nodes : 0,
           r->divisor > 2 ? "1/4" : r->divisor > 1 ? "1/2" : "full", r->ms, r->max_error,
           r->mean_error);
    points[i] = (chart_point){.series = r->series, .x = r->ms,
                              .y = chart_floor(r->max_error, 1e-6)};
  }
  char title[128];
  bench_outputs files;
  bench_outputs_in(&files, options.out_dir, "light");
  snprintf(title, sizeof title, "self-shadowed sunlight %dx%d: max in-scatter error vs fog pass ms",
           W, H);
  chart_desc chart = {.title = title, .x_label = "fog pass per frame (ms)",
                      .y_label = "max |in-scatter - reference| / max in-scatter", .log_x = true,
                      .log_y = true};
  /* a file that fails costs the stage its status, not its figures */
  bench_files_written written;
  bench_write_files(&written,
                    write_table(files.table, rows, row_count, written.error,
                                 sizeof written.error),
                    &chart, points, row_count, &files);
  printf("\nCSV: %s, %s; PNG: %s\n", files.table, files.chart_csv,
         written.drawn ? files.chart_png : "not drawn");
  /* The default scene's rows: unlit at full and half resolution, ours at the product's
   * defaults (48^3, [light] shadow_steps and shadow_nodes) at full and half (live). */
  const light_row *unlit_full = &rows[ROW_UNLIT_FULL], *unlit_half = &rows[ROW_UNLIT_HALF],
                  *live = &rows[ROW_LIVE], *ours_full = NULL;
  for (int i = 0; i < SCENE_ROWS; i++)
    if (rows[i].resolution == 48 && rows[i].divisor == 1 && !rows[i].march && !rows[i].froxel &&
        !rows[i].pieces && rows[i].steps == live->steps && rows[i].nodes == live->nodes)
      ours_full = &rows[i];
  /* C: the cheapest marching within MATCHED_ERROR over our cheapest full-resolution setting
   * within it (each the default scene's) that reads no finer sun volume than the marchers
   * (B's rule: the 96^3 volume's CPU compute is in no row's time); NAN where either has
   * none. */
  int march_resolution = 0;
  for (int i = 0; i < SCENE_ROWS; i++)
    if (rows[i].march) march_resolution = rows[i].resolution;
  double march_ms = NAN, ours_ms = NAN;
  for (int i = 0; i < SCENE_ROWS; i++) {
    const light_row *r = &rows[i];
    if (!r->resolution || r->divisor > 1 || r->froxel || !(r->max_error <= MATCHED_ERROR) ||
        (!r->march && r->resolution > march_resolution))
      continue;
    double *best = r->march ? &march_ms : &ours_ms;
    if (!(*best <= r->ms)) *best = r->ms;
  }
  if (!(march_ms == march_ms) || !(ours_ms == ours_ms))
    printf("note: %s within max error %g on the default scene; march_speedup_at_matched_error "
           "is nan\n", march_ms == march_ms ? "none of our settings is" : "no marching is",
           MATCHED_ERROR);
  else /* said every run: the issue asks for 1e-3, below what the 48^3 sun volume allows */
    printf("C matched at max error %g (not the issue's 1e-3: the 48^3 sun volume both methods "
           "read has an error floor of about 7e-3 against the %d^3 reference): the cheapest "
           "marching %.2f ms, ours %.2f ms\n", MATCHED_ERROR,
           FOG_BENCH_LIGHT_VOLUME, march_ms, ours_ms);
  /* B on each scene: the froxel grid's error over ours at no more time */
  double froxel_ratio[SCENE_COUNT];
  for (int sc = 0; sc < SCENE_COUNT; sc++) {
    const light_row *scene_rows = &rows[sc * SCENE_ROWS];
    const light_row *froxel = &scene_rows[ROW_FROXEL];
    const light_row *ours = ours_at_froxel_time(scene_rows, froxel);
    froxel_ratio[sc] = ours ? froxel->max_error / ours->max_error : NAN;
    if (ours)
      printf("%s: froxels 1x %.2f ms, max error %.2e (mean %.2e); ours at no more time: %s %d "
             "steps on the %d^3 volume at %s, %.2f ms, max %.2e (mean %.2e): max ratio %.2f, "
             "mean ratio %.2f\n",
             scene_configs[sc], froxel->ms, froxel->max_error, froxel->mean_error,
             ours->divisor > 1 ? "the reduced pass" : "full resolution", ours->steps,
             ours->resolution,
             ours->divisor > 2 ? "1/4" : ours->divisor > 1 ? "1/2" : "1/1", ours->ms,
             ours->max_error, ours->mean_error, froxel_ratio[sc],
             froxel->mean_error / ours->mean_error);
    else
      printf("%s: froxels 1x %.2f ms, max error %.2e (mean %.2e); none of our settings is as "
             "fast: froxel_error_ratio_at_equal_time is nan\n", scene_configs[sc], froxel->ms,
             froxel->max_error, froxel->mean_error);
  }
  printf("light: lit_over_unlit=%.2f lit_over_unlit_full=%.2f shadow_volume_ms=%.1f "
         "live_max_error=%.3g froxel_error_ratio_at_equal_time=%.2f "
         "march_speedup_at_matched_error=%.2f\n",
         live->ms / unlit_half->ms, ours_full ? ours_full->ms / unlit_full->ms : NAN,
         scenes[0].volume_ms[1],
         live->max_error, froxel_ratio[0], march_ms / ours_ms);
  status = bench_files_report(&written, &rerr);
  goto done;

out_of_memory:
  fog_fail(&rerr, FOG_ERR_OUT_OF_MEMORY, "out of memory");
done:
  free(tau);
  free(inscatter);
  for (int s = 0; s < SCENE_COUNT; s++) scene_destroy(&scenes[s]);
  if (out.framebuffer) gl_target_destroy(&out);
  if (ctx) gl_context_destroy(ctx);
  return bench_report("light", status, &rerr);
}
