/* fogpipe benchmarks: `fogpipe bench STAGE`. Speed targets live here, never in tests.
 * Each stage measures its figures side by side in one run and ends with one line
 * `STAGE: key=value ...`. */
#ifndef FOGPIPE_BENCH_H
#define FOGPIPE_BENCH_H

/* Stages time with app_clock_seconds(), the clock the pipeline times with too. */
#include <stdbool.h>
#include <stddef.h>

#include "app/clock.h"
#include "transform/fog_error.h"

#define FOG_BENCH(name, summary) int bench_##name(int argc, char **argv);
#include "bench/stages.def"
#undef FOG_BENCH

/* The stage named argv[1] runs as `fogpipe bench STAGE` through cmd_bench (app/commands.h),
 * which this library defines. */

/* Error pixel (i, j) of a grid of one every stride pixels in a width x height image: moved
 * within its cell by (j mod 4, i mod 4) where stride >= 4, so that the pixels fall on every
 * phase of a reduced pass's 2 x 2 and 4 x 4 blocks. A plain grid sat on one phase: at half
 * resolution every sampled row lay on the traced samples' own row, and the vertical half of
 * the upsampling (horizon, layer and shaft edges) was never measured. */
static inline void bench_error_pixel(int i, int j, int stride, int width, int height, int *px,
                                     int *py) {
  const int dx = stride >= 4 ? j % 4 : 0, dy = stride >= 4 ? i % 4 : 0;
  *px = i * stride + dx < width ? i * stride + dx : width - 1;
  *py = j * stride + dy < height ? j * stride + dy : height - 1;
}

/* Prints one line naming the build measured (type, -march=native or portable, compiler). */
void bench_print_build(void);
/* The build's line, then the GL's: "GL: platform, version, renderer; WxH, median of N frames
 * after 1 warm-up (glFinish before and after)". */
struct gl_context;
void bench_print_gl(struct gl_context *ctx, int width, int height, int frames);
/* A stage's table and chart files in its --out folder: DIR/STAGE.csv, DIR/STAGE_chart.csv
 * and DIR/STAGE_chart.png. */
typedef struct bench_outputs {
  char table[4200], chart_csv[4200], chart_png[4200];
} bench_outputs;
void bench_outputs_in(bench_outputs *outputs, const char *dir, const char *stage);
/* The options of the image benches (render, models, light, lights, soak): --size WxH,
 * --frames N, --out DIR. */
typedef struct bench_image_options {
  int width, height, frames;
  const char *out_dir;
} bench_image_options;

/* A stage's command line by an option table (app/cli_options.h: one parser and one
 * message style for every command, --help generated): with image options, their --size,
 * --frames and --out rows first (their defaults, the values in *image, in the help), then
 * the stage's own rows. usage follows "fogpipe bench STAGE "; about and footer frame the
 * options in --help. Operands (at most max_operands, named operand) go to operands.
 * Creates image->out_dir when set (and removes what it made at exit if the stage wrote
 * nothing there). Returns -1 when the stage should run, else the
 * process's exit status (0 after --help, 2 for a bad command line, 1 when the folder
 * cannot be made). */
typedef struct bench_command {
  const char *stage, *usage, *about, *footer;
  bench_image_options *image;      /* NULL: the stage takes no image options */
  bool without_out;                /* the image options but --out (a stage writing no files) */
  const char *frames_help, *out_help; /* the image rows' help (NULL: generic) */
  int frames_min;                  /* the least --frames the stage measures with (0: 1) */
  const struct cli_option *options; /* the stage's own rows */
  int option_count;
  const char *operand;
  const char **operands;
  int max_operands;
} bench_command;
int bench_parse(const bench_command *command, int argc, char **argv);

/* GL draws timed side by side: `frames` rounds, each drawing every row once, so a host that
 * slows down during the run slows every row alike. Per row and round: prepare (untimed, may
 * be NULL: uploads, binding the target, the round's jitter), then draw between two
 * glFinish (fog_pass_finish). Row i's median over the rounds, in milliseconds, goes to
 * ms[i * ms_stride bytes]: a field of the caller's row structs (`.ms = &rows[0].ms,
 * .ms_stride = sizeof rows[0]`). Stops at the first error (err filled by the callback, or
 * out of memory). */
typedef struct bench_timed_rows {
  int count, frames;
  void *user;
  int (*prepare)(void *user, int row, int round, fog_error *err);
  int (*draw)(void *user, int row, fog_error *err);
  double *ms;
  size_t ms_stride;
} bench_timed_rows;
int bench_time_rows(const bench_timed_rows *rows, fog_error *err);
/* A stage's way out: when status is non-zero, prints "fogpipe bench STAGE: " and err's
 * message to stderr. Returns status. */
int bench_report(const char *stage, int status, const fog_error *err);
/* Tables: chart_table_open / chart_table_write (app/chart.h). */
#include "app/chart.h"
/* A stage's table and chart, written after its timing. The chart's CSV always, its PNG
 * where gnuplot runs; without gnuplot (the GPU kit ships none) the PNG is skipped with a
 * note on stdout (drawn false). A stage of minutes keeps its figures when its files fail:
 * failed and error say so, the stage prints "files: ERROR (the figures follow)", goes on
 * to its summary line and fails after it (bench_files_report). */
typedef struct bench_files_written {
  bool failed, drawn;
  char error[1024];
} bench_files_written;
/* table_failed: the stage's table writer's status (its message in written->error). */
void bench_write_files(bench_files_written *written, int table_failed,
                       const chart_desc *desc, const chart_point *points, int count,
                       const bench_outputs *files);
/* The stage's status once its summary line is out: 0, or 1 with err naming the file that
 * failed. */
int bench_files_report(const bench_files_written *written, fog_error *err);
/* mkdir -p; non-zero and a message naming the folder on failure. */
int bench_make_folder(const char *path, char *error, int size);
/* RMSE and max of |gpu - ref| over n values (a NaN from the GL counts as the worst), and
 * where the max is. */
void bench_tau_errors(const float *gpu, const double *ref, size_t n, double *rmse,
                      double *max_error, size_t *where);

/* The valley the fogmap benches (render, paper) look at: a 1200-unit procedural terrain
 * (257^2 samples), two boxes, the sun at azimuth 150 and 30 degrees up; the camera inside
 * the fog near the map's +Z edge (the box [-512, 512]^2), 35 units above the ground, looking
 * across the map towards -Z and slightly down: rays run up to ~1000 units through the fog.
 * *geo: scene_geometry_destroy when done. */
struct scene_geometry;
struct camera;
int bench_valley_scene(struct scene_geometry *geo, struct camera *cam, fog_error *err);

struct scene_config;
/* configs/NAME of the source tree, loaded into a new *cfg (the caller free()s it, also after
 * a failure): 0, or 1 with err filled. */
int bench_load_source_config(const char *name, struct scene_config **cfg, fog_error *err);
/* The scene config at config_path loaded into *cfg and a headless GL context for it
 * (gl_context_destroy when done): 0, or 1 with `fogpipe bench STAGE: ...` printed. */
struct gl_context;
int bench_open_scene(const char *stage, const char *config_path, struct scene_config *cfg,
                     struct gl_context **gl);

/* The density the simulation of the scene at config_path holds at frame `frame` (1-based, at
 * fps frames per second: what `fogpipe record` frame n shows), into *out (fogmap_create'd
 * here; fogmap_destroy it). Non-zero and a message when the scene has no simulation. */
struct fogmap;
int bench_simulated_density(const char *config_path, int frame, double fps,
                            struct fogmap *out, char *error, size_t cap);

#endif
