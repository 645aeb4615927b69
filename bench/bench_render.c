/* fogpipe bench render: the fog pass's integrators side by side on one fixed scene.
 *
 * Scene (fixed, headless EGL): the default config's procedural valley (terrain seed 4) with
 * data/fogmap_sample.png (256 x 256, cell 4 world units, extinction 0.02, exponential ground
 * fog: g = 1 below y0 = 50, scale height 25, box 0..220), seen from a camera 35 units above
 * the terrain inside the fog, looking across the whole map at a low angle, so rays are long
 * and cross many cells. The surface distance comes from SCENE's scene pass (its R32F
 * distance texture); the same read-back distances clip the CPU reference rays, so the errors
 * below are the integrators' alone, not the rasteriser's.
 *
 * Rows (each timed on the GL: glFinish, draw, glFinish; median over --frames rounds after a
 * warm-up round; all rows run interleaved in every round so machine noise hits them alike):
 *   - uniform ray marching, N = 8 .. 512 steps, midpoints and per-pixel jitter (linear basis);
 *   - the exact knot-cell walk (Gauss-Legendre per piece) per basis: haar, linear, quadratic,
 *     with manual fetch, and linear/quadratic with hardware filtering (haar's hardware variant
 *     is the same texelFetch: not repeated);
 *   - LOD by distance over a 3-level linear pyramid, mu = 1 .. 0, both methods: the paper's
 *     sum of deconstructed details and approximation switching;
 *   - two more fogmaps in the same box, each its exact linear walk and marching at N = 64 ..
 *     2048: detailed fog (Perlin turbulence, 256 x 256, feature size 16 cells, 4 octaves:
 *     what `fogpipe design --perlin --feature-size 16 --seed 0` makes; X2) and the default scene's
 *     simulated fog at frame 48 (configs/default.ini's simulation at 24 fps; X printed);
 *   - the Mantaflow ground fog with and without empty-space skipping (S), and marched at
 *     N = 64 .. 2048 (X on a shipped scene, printed).
 * Every row runs with the fog pass's defaults otherwise: the exact walks (single grid, LOD
 * switching) stop at FOG_PASS_TRANSMITTANCE_CUTOFF (tau below 1e-4), the marcher and the sum of
 * (signed) details integrate whole rays.
 * Error: tau = exp(-optical depth) read back from the fog pass's transmittance target,
 * against the double-precision exact CPU integral of the SAME model on the same rays
 * (render/fog_field.h: fog_optical_depth / fog_optical_depth_lod), RMSE and max over all
 * pixels. LOD rows also give the error against the full model (the fogmap itself). The CPU
 * reference is computed once per model (per basis; per mu for LOD, with the switching method
 * - both methods integrate the same function A_0 + D_1 + .. + D_l = A_l) on two threads.
 *
 * Last line: `render: exact_speedup_at_matched_error=X lod_switch_speedup_vs_sum=Y
 * lod_overhead_at_mu1=Z empty_skip_speedup=S exact_speedup_at_matched_error_detailed=X2`
 * (see print_help). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "app/cli_options.h"
#include "bench/bench.h"
#include "bench/bench_upload.h"
#include "app/chart.h"
#include "render/render.h"
#include "sim/sim.h"

#define LOD_LEVELS 3
#define ERROR_FLOOR 1e-9 /* log axis of the chart: errors below are drawn at the floor */
#define MAX_ROWS 64

static const int march_steps[] = {8, 16, 32, 64, 128, 256, 512};
static const double lod_mu[] = {1.0, 0.8, 0.6, 0.4, 0.2, 0.0};
/* The extra fogmaps' marching: up to 2048 steps, so that a row within 1e-3 exists. */
static const int detailed_steps[] = {64, 128, 256, 512, 1024, 2048};
enum { MARCH_COUNT = 7, MU_COUNT = 6, DETAILED_COUNT = 6 };
/* The extra fogmaps (their own pass and CPU reference each): 0 detailed, 1 simulated. */
enum { EXTRA_DETAILED, EXTRA_SIMULATED, EXTRA_COUNT };
static const char *const extra_names[EXTRA_COUNT] = {"detailed", "simulated"};
#define SIMULATED_FRAME 48


/* ---- the CPU reference (double), two threads ------------------------------------------ */

typedef struct reference_job {
  const fog_volume *volume;
  const camera *cam;
  const transform_grid *grid; /* single grid, or NULL: lod */
  const fog_lod *lod;
  const float *distance;      /* scene distance read back from the GL, rows top first */
  int width, height, first_row, row_step;
  double *tau;                /* width * height, rows top first */
} reference_job;

static double surface_distance(float d) { return d >= 1e29f ? HUGE_VAL : (double)d; }

static void *reference_rows(void *arg) {
  const reference_job *job = arg;
  for (int py = job->first_row; py < job->height; py += job->row_step)
    for (int px = 0; px < job->width; px++) {
      double o[3], d[3];
      size_t k = (size_t)py * job->width + px;
      camera_ray(job->cam, px, py, job->width, job->height, o, d);
      double ts = surface_distance(job->distance[k]);
      double depth = job->grid ? fog_optical_depth(job->volume, job->grid, o, d, 0.0, ts)
                               : fog_optical_depth_lod(job->volume, job->lod, FOG_LOD_SWITCH, o,
                                                       d, ts);
      job->tau[k] = fog_transmittance(depth);
    }
  return NULL;
}

static void reference_tau(reference_job job) {
  reference_job jobs[2] = {job, job};
  jobs[0].first_row = 0, jobs[1].first_row = 1;
  jobs[0].row_step = jobs[1].row_step = 2;
  pthread_t worker;
  int threaded = pthread_create(&worker, NULL, reference_rows, &jobs[1]) == 0;
  reference_rows(&jobs[0]);
  if (threaded)
    pthread_join(worker, NULL);
  else
    reference_rows(&jobs[1]);
}

/* ---- cells crossed (the LOD prediction) ----------------------------------------------- */

/* Knot cells of grid g the ray crosses on [a, b] clipped to [lo, hi]: 1 + knot lines
 * crossed in x and in z (the profile's breaks cut more pieces: profile_breaks). */
static int cells_crossed(const fog_volume *v, const transform_grid *g, const double o[3],
                         const double d[3], double a, double b, double lo, double hi) {
  if (a < lo) a = lo;
  if (b > hi) b = hi;
  if (!(a < b)) return 0;
  double h = v->cell_size > 0 ? v->cell_size : 1.0, off = (g->degree % 2 == 0) ? -0.5 : 0.0;
  long cell[2][2];
  for (int e = 0; e < 2; e++) {
    double t = e ? b : a;
    double u = (o[0] + t * d[0] - v->origin_x) / h - 0.5;
    double w = (o[2] + t * d[2] - v->origin_z) / h - 0.5;
    cell[e][0] = (long)floor((u - g->origin_u) / g->spacing - off);
    cell[e][1] = (long)floor((w - g->origin_v) / g->spacing - off);
  }
  return 1 + (int)(labs(cell[1][0] - cell[0][0]) + labs(cell[1][1] - cell[0][1]));
}

/* Profile breaks the GLSL walk adds on [a, b] clipped to [lo, hi]: the exponential
 * profile's lines y0 + k H/2 (fog_integral.glsl, fog_optical_depth_inside) or the
 * B-spline profile's knots; a slab has none. They cut pieces whatever the grid's level. */
static int profile_breaks(const fog_volume *v, const double o[3], const double d[3], double a,
                          double b, double lo, double hi) {
  if (a < lo) a = lo;
  if (b > hi) b = hi;
  if (!(a < b)) return 0;
  const fog_profile *p = &v->profile;
  double scale, start, off = 0.0;
  if (p->kind == FOG_PROFILE_EXPONENTIAL)
    scale = 2.0 / p->scale_height, start = p->y0;
  else if (p->kind == FOG_PROFILE_BSPLINE)
    scale = 1.0 / p->spacing, start = p->origin, off = (p->degree % 2 == 0) ? -0.5 : 0.0;
  else
    return 0;
  double ua = (o[1] + a * d[1] - start) * scale - off;
  double ub = (o[1] + b * d[1] - start) * scale - off;
  return (int)fabs(floor(ub) - floor(ua));
}

/* What the LOD methods walk per pixel at one mu, averaged over the pixels: knot cells
 * crossed, pieces (cells and profile breaks), and pieces as a SIMD lane group pays for
 * them (llvmpipe shades 4 x 2 pixels per 8-lane group, and a loop runs until its last lane
 * is done: each walk costs the group its longest lane). */
typedef struct lod_walk_counts {
  double cells, pieces, group_pieces;
} lod_walk_counts;

enum { LOD_GROUP_W = 4, LOD_GROUP_H = 2 };

/* The pieces of each walk of one pixel (mirrors fog_pass_fs.glsl): walk 0 of the sum is
 * A_0 on [0, op], walk l its band l on [0, op mu^l]; walk l of switching is A_l on
 * (op mu^{l+1}, op mu^l], walk J A_J on [0, op mu^J]. Returns 0 where the ray misses. */
static int lod_pixel_walks(const fog_volume *v, const fog_lod *lod, const double o[3],
                           const double d[3], double op, double mu, int cells[2][LOD_LEVELS + 1],
                           int pieces[2][LOD_LEVELS + 1]) {
  double te, tx;
  int J = lod->levels;
  for (int m = 0; m < 2; m++)
    for (int l = 0; l <= J; l++) cells[m][l] = pieces[m][l] = 0;
  if (!(op > 0.0) || !fog_box_entry_exit(v, o, d, &te, &tx)) return 0;
  double lo = te > 0.0 ? te : 0.0, hi = op;
  double dl = op;
  for (int l = 0; l <= J; l++, dl *= mu) {
    if (dl <= 0.0) break;
    const transform_grid *g = l == 0 ? &lod->approx[0] : &lod->detail[l - 1];
    cells[0][l] = cells_crossed(v, g, o, d, 0.0, dl, lo, hi);
    pieces[0][l] = cells[0][l] + profile_breaks(v, o, d, 0.0, dl, lo, hi);
  }
  double far_t = op;
  for (int l = 0; l <= J; l++) {
    double near_t = l == J ? 0.0 : far_t * mu;
    if (far_t > near_t) {
      cells[1][l] = cells_crossed(v, &lod->approx[l], o, d, near_t, far_t, lo, hi);
      pieces[1][l] = cells[1][l] + profile_breaks(v, o, d, near_t, far_t, lo, hi);
    }
    far_t = near_t;
  }
  return 1;
}

/* counts[0]: sum of details, counts[1]: approximation switching. */
static void lod_cells(const fog_volume *v, const fog_lod *lod, const camera *cam,
                      const float *distance, int width, int height, double mu,
                      lod_walk_counts counts[2]) {
  int J = lod->levels;
  double pixels = (double)width * height;
  counts[0] = counts[1] = (lod_walk_counts){0};
  for (int gy = 0; gy < height; gy += LOD_GROUP_H)
    for (int gx = 0; gx < width; gx += LOD_GROUP_W) {
      int longest[2][LOD_LEVELS + 1] = {{0}}, lanes = 0;
      for (int py = gy; py < gy + LOD_GROUP_H && py < height; py++)
        for (int px = gx; px < gx + LOD_GROUP_W && px < width; px++) {
          double o[3], d[3];
          int cells[2][LOD_LEVELS + 1], pieces[2][LOD_LEVELS + 1];
          camera_ray(cam, px, py, width, height, o, d);
          double ts = surface_distance(distance[(size_t)py * width + px]);
          double op = fog_lod_ray_length(v, o, d, ts);
          lanes++;
          if (!lod_pixel_walks(v, lod, o, d, op, mu, cells, pieces)) continue;
          for (int m = 0; m < 2; m++)
            for (int l = 0; l <= J; l++) {
              counts[m].cells += cells[m][l] / pixels;
              counts[m].pieces += pieces[m][l] / pixels;
              if (pieces[m][l] > longest[m][l]) longest[m][l] = pieces[m][l];
            }
        }
      for (int m = 0; m < 2; m++)
        for (int l = 0; l <= J; l++) counts[m].group_pieces += lanes * longest[m][l] / pixels;
    }
}

/* ---- rows ------------------------------------------------------------------------------ */

typedef struct bench_row {
  const char *method;  /* table */
  char setting[32];
  const char *series;  /* chart (no commas or quotes: CSV and gnuplot) */
  int pass;            /* which fog_pass holds its grids: 0..2 full grid per degree, 3 LOD */
  fog_pass_params params;
  int reference;       /* index of the same-model CPU reference */
  int full_reference;  /* LOD rows: the full model's reference; -1 otherwise */
  double ms, rmse, max_error, rmse_full, max_full;
  size_t worst_pixel;         /* where max_error is (rows top first) */
  double worst_gpu, worst_cpu; /* tau there */
  uint64_t tau_hash;           /* FNV-1a of the read-back tau's bytes: bit-for-bit checks */
} bench_row;

/* bench_time_rows' callbacks: the round's jitter frame and the fog target, then the row's
 * fog pass timed. */
typedef struct timing_user {
  bench_row *rows;
  fog_pass **passes;
  const camera *cam;
  const gl_target *scene, *target;
  int width, height;
} timing_user;
static int timing_prepare(void *user, int row, int round, fog_error *err) {
  (void)err;
  timing_user *u = user;
  u->rows[row].params.frame = (unsigned)round;
  gl_target_bind(u->target);
  return 0;
}
static int timing_draw(void *user, int row, fog_error *err) {
  timing_user *u = user;
  const bench_row *r = &u->rows[row];
  return fog_pass_draw(u->passes[r->pass], u->cam, &r->params, u->scene->color[0],
                       u->scene->color[1], u->width, u->height, err);
}

static uint64_t fnv1a(const void *data, size_t bytes) {
  const unsigned char *p = data;
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < bytes; i++) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

static int write_table_csv(const char *path, const bench_row *rows, int count, char *error,
                           int size) {
  chart_table table;
  if (chart_table_open(&table, path, error, size)) return 1;
  FILE *f = table.stream;
  fprintf(f, "method,setting,ms_per_frame,rmse,max_error,rmse_vs_full,max_error_vs_full\n");
  for (int i = 0; i < count; i++) {
    const bench_row *r = &rows[i];
    fprintf(f, "%s,%s,%.6g,%.6g,%.6g,", r->method, r->setting, r->ms, r->rmse, r->max_error);
    if (r->full_reference >= 0)
      fprintf(f, "%.6g,%.6g\n", r->rmse_full, r->max_full);
    else
      fprintf(f, ",\n");
  }
  return chart_table_write(&table, error, size);
}

/* The cheapest marching row on `pass` with max error <= 1e-3 (*matched), else the most
 * accurate one. */
static int matched_march(const bench_row *rows, int count, int pass, bool *matched) {
  int cheapest = -1, best = -1;
  for (int i = 0; i < count; i++) {
    if (rows[i].params.integrator != FOG_INTEGRATOR_MARCH || rows[i].pass != pass) continue;
    if (rows[i].max_error <= 1e-3 && (cheapest < 0 || rows[i].ms < rows[cheapest].ms)) cheapest = i;
    if (best < 0 || rows[i].max_error < rows[best].max_error) best = i;
  }
  *matched = cheapest >= 0;
  return cheapest >= 0 ? cheapest : best;
}

/* folder/name from the working directory, else from the source tree. */
static const char *source_file(const char *folder, const char *name) {
  static char path[3][4096];
  static int next;
  char *out = path[next++ % 3];
  struct stat st;
  snprintf(out, sizeof path[0], "%s/%s", folder, name);
  if (stat(out, &st) == 0) return out;
  snprintf(out, sizeof path[0], "%s/%s/%s", FOGPIPE_SOURCE_DIR, folder, name);
  return out;
}

int bench_render(int argc, char **argv) {
  bench_image_options options = {.width = 640, .height = 360, .frames = 3,
                                 .out_dir = "build/bench/render"};
  const char *fogmap_path = NULL;
  static const char *const profiles[] = {"slab", "exponential", NULL}; /* fog_profile_kind */
  int profile = FOG_PROFILE_EXPONENTIAL;
  const cli_option stage_options[] = {
      {.kind = CLI_CHOICE, .name = "--profile", .value = "P", .target = &profile,
       .choices = profiles,
       .help = "vertical profile: exponential (default: g = 1 below y = 50, then\n"
               "exp(-(y - 50)/25)) or slab (g = 1 on 0..220)"},
      {.kind = CLI_TEXT, .name = "--fogmap", .value = "F", .target = &fogmap_path,
       .help = "the fogmap (default data/fogmap_sample.png, else\n"
               "<source>/data/fogmap_sample.png)"},
  };
  const bench_command command = {
      .stage = "render",
      .usage = "[--size WxH] [--frames N] [--out DIR]\n"
               "                           [--profile exponential|slab] [--fogmap FILE]",
      .image = &options, .options = stage_options,
      .option_count = sizeof stage_options / sizeof stage_options[0],
      .frames_help = "timed rounds; each row's time is the median of N frames after one\n"
                     "warm-up frame",
      .out_help = "where render.csv, render_chart.csv, render_chart.png and\n"
                  "render_tau.png go, relative to the working directory",
      .about =
          "Last line: render: exact_speedup_at_matched_error=X lod_switch_speedup_vs_sum=Y\n"
          "lod_overhead_at_mu1=Z empty_skip_speedup=S exact_speedup_at_matched_error_detailed=X2,\n"
          "where X = time of the cheapest ray marching with max tau error <= 1e-3 / exact linear\n"
          "time (targets X >= 5; X2 the same on detailed Perlin fog, marching to 2048 steps), Y =\n"
          "sum-of-details time / approximation-switching time at mu = 0.6, 3 levels (Y >= 1.5),\n"
          "Z = switching time at mu = 1 / the fogmap alone without decomposition (Z <= 1.05),\n"
          "S = the exact linear walk on the ground fog (data/fogmap_groundfog.exr) without\n"
          "empty-space skipping / with it (the pass's default)."};
  int exit_status = bench_parse(&command, argc, argv);
  if (exit_status >= 0) return exit_status;
  const int W = options.width, H = options.height, frames = options.frames;
  const char *out_dir = options.out_dir;
  if (!fogmap_path) fogmap_path = source_file("data", "fogmap_sample.png");
  /* The empty-space skipping rows' ground fog (data/README.md): the Mantaflow bake's frame
   * 24 as a 128 x 128 fogmap, 60 % of its blocks empty, over the same box. */
  const char *ground_path = source_file("data", "fogmap_groundfog.exr");
  char message[1024] = "";

  /* ---- the fogmap, its full grid per basis and the linear LOD pyramid ---- */
  fogmap map = {0};
  fog_error serr;
  if (fogmap_load(fogmap_path, &(fogmap_load_desc){0}, &map, &serr))
    return bench_report("render", 1, &serr);
  int status = 1;
  fog_error terr = {0};
  fogmap ground = {0};
  transform_plan *ground_plan = NULL;
  transform_grid ground_grid = {0};
  transform_grid full[3] = {{0}}, approx[LOD_LEVELS + 1] = {{0}}, detail[LOD_LEVELS] = {{0}};
  size_t cells = (size_t)map.width * map.height;
  float *coefficients = malloc(cells * sizeof(float));
  float *level_approx[LOD_LEVELS + 1] = {0}, *level_detail[LOD_LEVELS + 1] = {0};
  transform_plan *plans[3] = {0}, *lod_plan = NULL;
  gl_context *ctx = NULL;
  scene_geometry geo = {0};
  int have_geo = 0;
  scene_pass *spass = NULL;
  enum { PASS_COUNT = 5 + EXTRA_COUNT };
  fog_pass *passes[PASS_COUNT] = {0}; /* 0..2 full grid per degree, 3 LOD, 4 the ground fog,
                                         5 + k extra fogmap k */
  fogmap extra[EXTRA_COUNT] = {{0}};
  transform_plan *extra_plan[EXTRA_COUNT] = {0};
  transform_grid extra_grid[EXTRA_COUNT] = {{0}};
  gl_target scene_target = {0}, fog_target = {0};
  float *distance = NULL, *gpu_tau = NULL;
  enum { REFERENCE_COUNT = 4 + MU_COUNT + EXTRA_COUNT };
  double *references[REFERENCE_COUNT] = {0}; /* per degree, per mu, the ground fog, extras */
  bench_row rows[MAX_ROWS];
  int row_count = 0;
  chart_point points[MAX_ROWS];
  fog_error rerr = {0};
  size_t pixels = (size_t)W * H;
  if (!coefficients) goto out_of_memory;
  for (int d = 0; d < 3; d++) {
    /* levels = 0: the grid of the fogmap itself in that basis (ghosts from the symmetric
     * extension). */
    transform_desc desc = {.width = map.width, .height = map.height, .levels = 0,
                           .basis = transform_basis_of_degree(d)};
    if (!(plans[d] = transform_plan_create(&desc, &terr)) ||
        transform_grid_create_level(plans[d], 0, map.density, &full[d], &terr))
      goto transform_failed;
  }
  {
    transform_desc desc = {.width = map.width, .height = map.height, .levels = LOD_LEVELS,
                           .basis = TRANSFORM_LINEAR};
    if (!(lod_plan = transform_plan_create(&desc, &terr))) goto transform_failed;
    for (int l = 0; l <= LOD_LEVELS; l++) {
      int w, h;
      transform_level_size(lod_plan, l, &w, &h);
      level_approx[l] = malloc((size_t)w * h * sizeof(float));
      level_detail[l] = malloc((size_t)w * h * sizeof(float));
      if (!level_approx[l] || !level_detail[l]) goto out_of_memory;
    }
    transform_forward(lod_plan, map.density, coefficients);
    if (transform_density_pyramid(lod_plan, map.density, coefficients, level_approx,
                                  level_detail, &terr))
      goto transform_failed;
    for (int l = 0; l <= LOD_LEVELS; l++)
      if (transform_grid_create_level(lod_plan, l, level_approx[l], &approx[l], &terr) ||
          (l > 0 &&
           transform_grid_create_level(lod_plan, l, level_detail[l], &detail[l - 1], &terr)))
        goto transform_failed;
  }
  fog_lod lod = {.levels = LOD_LEVELS, .approx = approx, .detail = detail, .mu = 1.0};
  if (fogmap_load(ground_path, &(fogmap_load_desc){0}, &ground, &serr)) {
    fog_error_pass(&rerr, &serr);
    goto done;
  }
  {
    transform_desc desc = {.width = ground.width, .height = ground.height, .levels = 0,
                           .basis = TRANSFORM_LINEAR};
    if (!(ground_plan = transform_plan_create(&desc, &terr)) ||
        transform_grid_create_level(ground_plan, 0, ground.density, &ground_grid, &terr))
      goto transform_failed;
  }

  /* The detailed fog: Perlin turbulence at the sample map's size, so in the same box. The
   * simulated fog: the default scene's frame 48 (made before this bench's GL context). */
  perlin_fog_desc detailed = perlin_fog_desc_default();  /* as `fogpipe design --perlin` */
  detailed.seed = 0;
  detailed.feature_size = 16.0f;
  if (fogmap_create(&extra[EXTRA_DETAILED], map.width, map.height, &serr) ||
      designed_fog_perlin(&extra[EXTRA_DETAILED], &detailed, &serr)) {
    fog_error_wrap(&rerr, &serr, "detailed fog: ");
    goto done;
  }
  if (bench_simulated_density(source_file("configs", "default.ini"), SIMULATED_FRAME, 24.0,
                              &extra[EXTRA_SIMULATED], message, sizeof message)) {
    fog_fail(&rerr, FOG_ERR_BAD_FILE, "simulated fog: %s", message);
    goto done;
  }
  for (int k = 0; k < EXTRA_COUNT; k++) {
    transform_desc desc = {.width = extra[k].width, .height = extra[k].height, .levels = 0,
                           .basis = TRANSFORM_LINEAR};
    if (!(extra_plan[k] = transform_plan_create(&desc, &terr)) ||
        transform_grid_create_level(extra_plan[k], 0, extra[k].density, &extra_grid[k], &terr))
      goto transform_failed;
  }

  /* ---- GL: context, scene, fog passes ---- */
  ctx = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &rerr);
  if (!ctx) goto done;
  camera cam;
  if (bench_valley_scene(&geo, &cam, &rerr)) goto done;
  have_geo = 1;
  const fog_volume volume = {
      .map_width = map.width, .map_height = map.height, .origin_x = -512.0, .origin_z = -512.0,
      .cell_size = 4.0 * 256.0 / (map.width > map.height ? map.width : map.height),
      .extinction = 0.02,
      .profile = {.kind = profile, .y_floor = 0.0, .y_top = 220.0, .y0 = 50.0,
                  .scale_height = 25.0},
  };

  spass = scene_pass_create(&geo, &rerr);
  if (!spass || scene_target_create(&scene_target, W, H, &rerr)) goto done;
  if (gl_target_create(&fog_target, &(gl_target_desc){.width = W, .height = H,
                                                       .color_formats = {GL_RGBA32F, GL_R32F}},
                       &rerr))
    goto done;
  scene_pass_run(spass, &cam, &scene_target);
  distance = malloc(pixels * sizeof(float));
  gpu_tau = malloc(pixels * sizeof(float));
  if (!distance || !gpu_tau) goto out_of_memory;
  if (gl_target_read(&scene_target, 1, 1, distance, &rerr)) goto done;
  for (int p = 0; p < PASS_COUNT; p++) {
    if (!(passes[p] = fog_pass_create(&rerr))) goto done;
    if (p < 3 ? fog_pass_upload_grid(passes[p], 0, &full[p], &rerr)
        : p == 3 ? fog_pass_upload_lod(passes[p], &lod, &rerr)
        : fog_pass_upload_grid(passes[p], 0, p == 4 ? &ground_grid : &extra_grid[p - 5], &rerr))
      goto done;
  }

  /* ---- the CPU references, one per model ---- */
  double t_ref = app_clock_seconds();
  const fog_volume ground_volume = {
      .map_width = ground.width, .map_height = ground.height, .origin_x = volume.origin_x,
      .origin_z = volume.origin_z,
      /* the sample map's box (1024 units a side), whatever the maps' shapes */
      .cell_size = 4.0 * 256.0 / (ground.width > ground.height ? ground.width : ground.height),
      .extinction = volume.extinction * 4.0, .profile = volume.profile};
  /* The extra fogmaps in the sample map's box (cell size from their width, as the sample's). */
  fog_volume extra_volume[EXTRA_COUNT];
  for (int k = 0; k < EXTRA_COUNT; k++) {
    extra_volume[k] = volume;
    extra_volume[k].map_width = extra[k].width, extra_volume[k].map_height = extra[k].height;
    extra_volume[k].cell_size =
        4.0 * 256.0 / (extra[k].width > extra[k].height ? extra[k].width : extra[k].height);
  }
  const int ground_reference = 3 + MU_COUNT, extra_reference = 4 + MU_COUNT;
  for (int r = 0; r < REFERENCE_COUNT; r++) {
    references[r] = malloc(pixels * sizeof(double));
    if (!references[r]) goto out_of_memory;
    fog_lod model = lod;
    if (r >= 3 && r < ground_reference) model.mu = lod_mu[r - 3];
    const int k = r - extra_reference; /* >= 0: extra fogmap k */
    reference_tau((reference_job){.volume = r == ground_reference ? &ground_volume
                                            : k >= 0 ? &extra_volume[k] : &volume,
                                  .cam = &cam,
                                  .grid = r < 3 ? &full[r]
                                          : r == ground_reference ? &ground_grid
                                          : k >= 0 ? &extra_grid[k] : NULL,
                                  .lod = &model,
                                  .distance = distance, .width = W, .height = H,
                                  .tau = references[r]});
  }
  t_ref = app_clock_seconds() - t_ref;
  fprintf(stderr, "bench render: CPU references done (%.1f s); GL rows...\n", t_ref);

  /* ---- the rows ---- */
  /* The product's walk settings ([render] defaults): early termination at tau < 1e-4. */
  const fog_pass_params base = {.volume = &volume, .fog_colour = {0.75f, 0.78f, 0.82f},
                                .walk = {.transmittance_cutoff = FOG_PASS_TRANSMITTANCE_CUTOFF}};
  for (int jitter = 0; jitter <= 1; jitter++)
    for (int s = 0; s < MARCH_COUNT; s++) {
      bench_row *r = &rows[row_count++];
      *r = (bench_row){.method = jitter ? "march jittered" : "march", .pass = 1,
                       .series = jitter ? "ray marching (jittered)" : "ray marching",
                       .params = base, .reference = 1, .full_reference = -1};
      snprintf(r->setting, sizeof r->setting, "N=%d", march_steps[s]);
      r->params.integrator = FOG_INTEGRATOR_MARCH;
      r->params.march_steps = march_steps[s];
      r->params.march_jitter = jitter;
    }
  static const char *basis_names[3] = {"haar", "linear", "quadratic"};
  int exact_linear = -1;
  for (int fetch = 0; fetch <= 1; fetch++)
    for (int d = fetch; d < 3; d++) {
      if (fetch == 0 && d == 1) exact_linear = row_count;
      bench_row *r = &rows[row_count++];
      *r = (bench_row){.method = fetch ? "exact hardware" : "exact", .pass = d,
                       .series = fetch ? "exact hardware (lin quad)" : "exact manual (haar lin quad)",
                       .params = base, .reference = d, .full_reference = -1};
      snprintf(r->setting, sizeof r->setting, "%s", basis_names[d]);
      r->params.fetch = fetch ? FOG_FETCH_HARDWARE : FOG_FETCH_MANUAL;
    }
  /* The exact linear walk of whole rays (no early termination, as the marchers run): X
   * against it too, so that the stop at opacity is not counted to the walk's credit alone. */
  const int exact_whole = row_count;
  {
    bench_row *r = &rows[row_count++];
    *r = rows[exact_linear];
    r->method = "exact whole rays";
    r->series = "exact manual, whole rays (linear)";
    r->params.walk.transmittance_cutoff = 0.0;
  }
  /* Empty-space skipping (render/fog_occupancy.h) on the ground fog: the linear walk with
   * the pass's default (FOG_SKIP_EMPTY: the same integral bit for bit), forced on
   * (FOG_SKIP_BELOW 0: the same blocks), and without it. */
  int ground_rows = row_count;
  for (int k = 0; k < 3; k++) {
    static const fog_skip modes[3] = {FOG_SKIP_EMPTY, FOG_SKIP_BELOW, FOG_SKIP_NONE};
    static const char *names[3] = {"default", "skip", "no skip"};
    bench_row *r = &rows[row_count++];
    *r = (bench_row){.method = "ground fog", .pass = 4, .series = "exact ground fog (linear)",
                     .params = base, .reference = ground_reference, .full_reference = -1};
    snprintf(r->setting, sizeof r->setting, "%s", names[k]);
    r->params.volume = &ground_volume;
    r->params.walk.skip = modes[k];
  }
  /* What a threshold buys on fog that is nowhere zero (the sample map, as the simulation
   * starts from it): the linear walk skipping blocks whose bound of f is <= eps. */
  static const double skip_eps[2] = {0.1, 0.2};
  int threshold_rows = row_count;
  for (int k = 0; k < 2; k++) {
    bench_row *r = &rows[row_count++];
    *r = (bench_row){.method = "exact skip<eps", .pass = 1, .series = "exact linear skip below eps",
                     .params = base, .reference = 1, .full_reference = -1};
    snprintf(r->setting, sizeof r->setting, "eps=%.1f", skip_eps[k]);
    r->params.walk.skip = FOG_SKIP_BELOW;
    r->params.walk.skip_below = (float)skip_eps[k];
  }
  int sum_at_06 = -1, switch_at_06 = -1, switch_at_1 = -1;
  for (int m = 0; m <= 1; m++)
    for (int k = 0; k < MU_COUNT; k++) {
      if (fabs(lod_mu[k] - 0.6) < 1e-9) *(m ? &switch_at_06 : &sum_at_06) = row_count;
      if (m == 1 && lod_mu[k] == 1.0) switch_at_1 = row_count;
      bench_row *r = &rows[row_count++];
      *r = (bench_row){.method = m ? "LOD switch" : "LOD sum", .pass = 3,
                       .series = m ? "LOD switching (vs full model)" : "LOD sum of details (vs full model)",
                       .params = base, .reference = 3 + k, .full_reference = 1};
      snprintf(r->setting, sizeof r->setting, "J=%d mu=%.1f", LOD_LEVELS, lod_mu[k]);
      r->params.levels = LOD_LEVELS;
      r->params.mu = lod_mu[k];
      r->params.lod_method = m ? FOG_LOD_SWITCH : FOG_LOD_SUM_OF_DETAILS;
    }
  /* The extra fogmaps: the exact linear walk, then marching to 2048 steps. */
  static const char *const extra_methods[EXTRA_COUNT][2] = {
      {"detailed exact", "detailed march"}, {"simulated exact", "simulated march"}};
  static const char *const extra_series[EXTRA_COUNT][2] = {
      {"exact detailed fog (linear)", "ray marching detailed fog"},
      {"exact simulated fog (linear)", "ray marching simulated fog"}};
  int extra_rows[EXTRA_COUNT];
  for (int k = 0; k < EXTRA_COUNT; k++) {
    extra_rows[k] = row_count;
    for (int s = -1; s < DETAILED_COUNT; s++) { /* s = -1: the exact walk */
      bench_row *r = &rows[row_count++];
      *r = (bench_row){.method = extra_methods[k][s >= 0], .pass = 5 + k,
                       .series = extra_series[k][s >= 0], .params = base,
                       .reference = extra_reference + k, .full_reference = -1};
      r->params.volume = &extra_volume[k];
      snprintf(r->setting, sizeof r->setting, s < 0 ? "linear" : "N=%d",
               s < 0 ? 0 : detailed_steps[s]);
      if (s >= 0) {
        r->params.integrator = FOG_INTEGRATOR_MARCH;
        r->params.march_steps = detailed_steps[s];
      }
    }
  }
  /* The ground fog marched (against its exact rows above): X on a shipped scene. */
  for (int s = 0; s < DETAILED_COUNT; s++) {
    bench_row *r = &rows[row_count++];
    *r = (bench_row){.method = "ground march", .pass = 4, .series = "ray marching ground fog",
                     .params = base, .reference = ground_reference, .full_reference = -1};
    snprintf(r->setting, sizeof r->setting, "N=%d", detailed_steps[s]);
    r->params.volume = &ground_volume;
    r->params.integrator = FOG_INTEGRATOR_MARCH;
    r->params.march_steps = detailed_steps[s];
  }

  /* Warm-up round (shader JIT on first draw of each variant) and the error read-back. */
  for (int i = 0; i < row_count; i++) {
    bench_row *r = &rows[i];
    gl_target_bind(&fog_target);
    if (fog_pass_draw(passes[r->pass], &cam, &r->params, scene_target.color[0],
                      scene_target.color[1], W, H, &rerr) ||
        gl_target_read(&fog_target, 1, 1, gpu_tau, &rerr))
      goto done;
    size_t where;
    bench_tau_errors(gpu_tau, references[r->reference], pixels, &r->rmse, &r->max_error,
               &r->worst_pixel);
    r->worst_gpu = gpu_tau[r->worst_pixel];
    r->tau_hash = fnv1a(gpu_tau, pixels * sizeof(float));
    r->worst_cpu = references[r->reference][r->worst_pixel];
    if (r->full_reference >= 0)
      bench_tau_errors(gpu_tau, references[r->full_reference], pixels, &r->rmse_full, &r->max_full,
                 &where);
    if (i == exact_linear) {
      /* A picture of the fog's transmittance, to see what is measured. */
      float *grey = malloc(pixels * sizeof(float));
      if (grey) {
        for (size_t k = 0; k < pixels; k++) grey[k] = gpu_tau[k];
        char png[4200];
        snprintf(png, sizeof png, "%s/render_tau.png", out_dir);
        if (image_write_png(png, W, H, 1, grey, &serr))
          fprintf(stderr, "fogpipe bench render: %s\n", serr.message);
        free(grey);
      }
    }
  }
  /* Timed rounds, all rows interleaved. */
  timing_user user = {rows, passes, &cam, &scene_target, &fog_target, W, H};
  if (bench_time_rows(&(bench_timed_rows){.count = row_count, .frames = frames, .user = &user,
                                          .prepare = timing_prepare, .draw = timing_draw,
                                          .ms = &rows[0].ms, .ms_stride = sizeof rows[0]},
                      &rerr))
    goto done;
  bench_upload_timing upload = {0};
  if (bench_time_uploads(&lod, 21, &upload, &rerr)) goto done;

  /* ---- report ---- */
  double full_cells = 0.0, tau_mean = 0.0;
  lod_walk_counts at_06[2], at_1[2];
  lod_cells(&volume, &lod, &cam, distance, W, H, 0.6, at_06);
  lod_cells(&volume, &lod, &cam, distance, W, H, 1.0, at_1);
  full_cells = at_1[1].cells;
  for (size_t k = 0; k < pixels; k++) tau_mean += references[1][k] / (double)pixels;
  bench_print_gl(ctx, W, H, frames);
  printf("scene: %s %dx%d, cell %g, extinction %g, %s fog (y0 %g, H %g); terrain\n"
         "distance from the scene pass; mean tau %.3f; mean cells crossed per ray (full map,\n"
         "linear) %.1f; CPU reference (double, 2 threads, once per model) %.1f s\n",
         fogmap_path, map.width, map.height, volume.cell_size, volume.extinction,
         profile == FOG_PROFILE_SLAB ? "slab" : "exponential", volume.profile.y0, volume.profile.scale_height, tau_mean, full_cells, t_ref);
  printf("errors: tau vs the exact CPU integral of the same model; LOD rows also vs the full\n"
         "model (the fogmap, linear). RMSE and max over all pixels. Exact walks stop at the\n"
         "product's transmittance cut-off (tau < %.0e: optical depth %.2f); marching and the\n"
         "sum of details integrate whole rays.\n\n",
         FOG_PASS_TRANSMITTANCE_CUTOFF, fog_pass_depth_limit(FOG_PASS_TRANSMITTANCE_CUTOFF));
  printf("%-15s %-12s %10s %10s %10s %12s %12s\n", "method", "setting", "ms/frame", "RMSE",
         "max err", "RMSE(full)", "max(full)");
  for (int i = 0; i < row_count; i++) {
    const bench_row *r = &rows[i];
    printf("%-15s %-12s %10.2f %10.2e %10.2e", r->method, r->setting, r->ms, r->rmse,
           r->max_error);
    if (r->full_reference >= 0)
      printf(" %12.2e %12.2e\n", r->rmse_full, r->max_full);
    else
      printf("\n");
  }

  /* The exact integrators should agree with their reference to float rounding: say where
   * one does not, so the discrepancy can be looked at. Skipping faint blocks (skip_below)
   * is an approximation of its own, measured below. */
  for (int i = 0; i < row_count; i++) {
    const bench_row *r = &rows[i];
    if (r->params.integrator == FOG_INTEGRATOR_EXACT && r->params.walk.skip_below == 0.0f &&
        r->max_error > 1e-4)
      printf("note: %s %s: max error at pixel (%d, %d) (row 0 at the top): GPU tau %.6f, CPU "
             "%.6f, surface distance %g\n",
             r->method, r->setting, (int)(r->worst_pixel % (size_t)W),
             (int)(r->worst_pixel / (size_t)W), r->worst_gpu, r->worst_cpu,
             (double)distance[r->worst_pixel]);
  }

  /* Chart: max error (floored) vs ms, one series per method, LOD against the full model. */
  int point_count = 0;
  for (int i = 0; i < row_count; i++) {
    const bench_row *r = &rows[i];
    double y = r->full_reference >= 0 ? r->max_full : r->max_error;
    points[point_count++] = (chart_point){.series = r->series, .x = r->ms,
                                          .y = chart_floor(y, ERROR_FLOOR)};
  }
  bench_outputs files;
  bench_outputs_in(&files, out_dir, "render");
  /* (gnuplot's enhanced text: no underscores in labels) */
  char title[256];
  snprintf(title, sizeof title,
           "fog pass %dx%d: max tau error vs GL time (LOD: vs full model; floor 1e-9)", W, H);
  chart_desc chart = {.title = title,
                      .x_label = "GL time per frame (ms)",
                      .y_label = "max |tau - CPU reference|",
                      .log_x = true, .log_y = true};
  /* a file that fails costs the stage its status, not its figures */
  bench_files_written written;
  bench_write_files(&written,
                    write_table_csv(files.table, rows, row_count, written.error,
                                 sizeof written.error),
                    &chart, points, point_count, &files);

  /* X: the cheapest marching of the sample map with max error <= 1e-3 over the exact linear
   * walk; X2 the same on the detailed fog. */
  bool matched_sample, matched_extra[EXTRA_COUNT];
  int matched = matched_march(rows, row_count, 1, &matched_sample), matched_at[EXTRA_COUNT];
  for (int k = 0; k < EXTRA_COUNT; k++)
    matched_at[k] = matched_march(rows, row_count, 5 + k, &matched_extra[k]);
  bool matched_ground;
  int matched3 = matched_march(rows, row_count, 4, &matched_ground);
  double X = rows[matched].ms / rows[exact_linear].ms;
  const int exact_detailed = extra_rows[EXTRA_DETAILED], matched2 = matched_at[EXTRA_DETAILED];
  double X2 = rows[matched2].ms / rows[exact_detailed].ms;
  double Y = rows[sum_at_06].ms / rows[switch_at_06].ms;
  double Z = rows[switch_at_1].ms / rows[exact_linear].ms;
  printf("\nupload of the J=%d pyramid (%d textures, R32F grids + RGBA32F cell polynomials, "
         "%.2f MB), median of 21:\n  glTexSubImage2D from client memory %.3f ms; through a "
         "pixel-unpack buffer %.3f ms (%.2fx)\n",
         LOD_LEVELS, upload.textures, upload.bytes / 1e6, upload.direct_ms, upload.staged_ms,
         upload.direct_ms / upload.staged_ms);
  printf("\nCSV: %s (table), %s (chart data)\nPNG: %s; tau image: %s/render_tau.png\n",
         files.table, files.chart_csv, written.drawn ? files.chart_png : "not drawn", out_dir);
  if (!matched_sample)
    printf("note: no ray marching reached max error <= 1e-3; X uses the most accurate one\n");
  for (int k = 0; k < EXTRA_COUNT; k++)
    if (!matched_extra[k])
      printf("note: no marching of the %s fog reached max error <= 1e-3; its X uses the most "
             "accurate one\n", extra_names[k]);
  printf("X: %s %s (%.2f ms, max err %.2e) / exact linear (%.2f ms)\n", rows[matched].method,
         rows[matched].setting, rows[matched].ms, rows[matched].max_error, rows[exact_linear].ms);
  printf("X against the exact walk of whole rays (no stop at opacity, as the marchers): %.2f "
         "ms, X = %.3f\n", rows[exact_whole].ms, rows[matched].ms / rows[exact_whole].ms);
  printf("X2: detailed fog (Perlin, feature size 16, 4 octaves) %s %s (%.2f ms, max err %.2e) / "
         "exact linear (%.2f ms, max err %.2e)\n", rows[matched2].method, rows[matched2].setting,
         rows[matched2].ms, rows[matched2].max_error, rows[exact_detailed].ms,
         rows[exact_detailed].max_error);
  {
    const int e = extra_rows[EXTRA_SIMULATED], m = matched_at[EXTRA_SIMULATED];
    printf("X on the simulated fog (configs/default.ini, frame %d, %dx%d): %s %s (%.2f ms, max "
           "err %.2e) / exact linear (%.2f ms, max err %.2e) = %.2f\n", SIMULATED_FRAME,
           extra[EXTRA_SIMULATED].width, extra[EXTRA_SIMULATED].height, rows[m].method,
           rows[m].setting, rows[m].ms, rows[m].max_error, rows[e].ms, rows[e].max_error,
           rows[m].ms / rows[e].ms);
  }
  printf("X on the ground fog: %s %s (%.2f ms, max err %.2e%s) / its exact walk with skipping "
         "(%.2f ms) = %.2f\n", rows[matched3].method, rows[matched3].setting, rows[matched3].ms,
         rows[matched3].max_error, matched_ground ? "" : ", the most accurate: none within 1e-3",
         rows[ground_rows].ms, rows[matched3].ms / rows[ground_rows].ms);
  printf("Y: LOD sum %.2f ms / LOD switch %.2f ms at mu = 0.6 = %.2f; predicted per ray by\n"
         "   cells crossed: sum %.1f / switch %.1f = %.2f; pieces walked (cells and profile\n"
         "   breaks): %.1f / %.1f = %.2f; pieces as 4x2-pixel lane groups pay: %.1f / %.1f"
         " = %.2f\n",
         rows[sum_at_06].ms, rows[switch_at_06].ms, Y,
         at_06[0].cells, at_06[1].cells, at_06[0].cells / at_06[1].cells, at_06[0].pieces,
         at_06[1].pieces, at_06[0].pieces / at_06[1].pieces, at_06[0].group_pieces,
         at_06[1].group_pieces, at_06[0].group_pieces / at_06[1].group_pieces);
  printf("Z: LOD switch at mu = 1 %.2f ms / fogmap alone, levels = 0 (exact linear) %.2f ms\n",
         rows[switch_at_1].ms, rows[exact_linear].ms);
  const double S = rows[ground_rows + 2].ms / rows[ground_rows].ms;
  const bool identical = rows[ground_rows].tau_hash == rows[ground_rows + 2].tau_hash &&
                         rows[ground_rows + 1].tau_hash == rows[ground_rows + 2].tau_hash;
  printf("S: ground fog (%s, %dx%d, linear) without skipping %.2f ms / with the default %.2f ms"
         " (forced on %.2f ms); tau images %s\n",
         ground_path, ground.width, ground.height, rows[ground_rows + 2].ms,
         rows[ground_rows].ms, rows[ground_rows + 1].ms,
         identical ? "identical bit for bit" : "DIFFER (skipping is meant to be exact)");
  for (int k = 0; k < 2; k++) {
    const bench_row *r = &rows[threshold_rows + k];
    printf("threshold: sample map, linear, skipping blocks with f <= %.1f: %.2f ms (exact walk "
           "%.2f ms), max |dtau| %.2e (bound per ray eps sigma L: %.2f per 1000 units)\n",
           skip_eps[k], r->ms, rows[exact_linear].ms, r->max_error,
           skip_eps[k] * volume.extinction * 1000.0);
  }
  printf("render: exact_speedup_at_matched_error=%.3f lod_switch_speedup_vs_sum=%.3f "
         "lod_overhead_at_mu1=%.3f empty_skip_speedup=%.3f "
         "exact_speedup_at_matched_error_detailed=%.3f\n",
         X, Y, Z, S, X2);
  status = bench_files_report(&written, &rerr);
  goto done;

out_of_memory:
  fog_fail(&rerr, FOG_ERR_OUT_OF_MEMORY, "out of memory");
  goto done;
transform_failed:
  fog_error_wrap(&rerr, &terr, "transform: ");
done:
  for (int r = 0; r < REFERENCE_COUNT; r++) free(references[r]);
  free(distance);
  free(gpu_tau);
  for (int p = 0; p < PASS_COUNT; p++) fog_pass_destroy(passes[p]);
  for (int k = 0; k < EXTRA_COUNT; k++) {
    transform_grid_destroy(&extra_grid[k]);
    transform_plan_destroy(extra_plan[k]);
    fogmap_destroy(&extra[k]);
  }
  transform_grid_destroy(&ground_grid);
  transform_plan_destroy(ground_plan);
  fogmap_destroy(&ground);
  if (ctx) {
    gl_target_destroy(&fog_target);
    gl_target_destroy(&scene_target);
  }
  scene_pass_destroy(spass);
  if (have_geo) scene_geometry_destroy(&geo);
  gl_context_destroy(ctx);
  for (int l = 0; l <= LOD_LEVELS; l++) {
    transform_grid_destroy(&approx[l]);
    free(level_approx[l]);
    free(level_detail[l]);
  }
  for (int l = 0; l < LOD_LEVELS; l++) transform_grid_destroy(&detail[l]);
  for (int d = 0; d < 3; d++) {
    transform_grid_destroy(&full[d]);
    transform_plan_destroy(plans[d]);
  }
  transform_plan_destroy(lod_plan);
  free(coefficients);
  fogmap_destroy(&map);
  return bench_report("render", status, &rerr);
}
