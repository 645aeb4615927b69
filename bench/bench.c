/* The bench dispatcher and the small timing helpers every stage shares. */
#define _POSIX_C_SOURCE 200809L
#include "bench/bench.h"
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/config.h"
#include "render/gl_context.h"
#include "render/fog_pass.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <time.h>

typedef struct bench_stage {
  const char *name;
  const char *summary;
  int (*run)(int argc, char **argv);
} bench_stage;

static const bench_stage stages[] = {
#define FOG_BENCH(name, summary) {#name, summary, bench_##name},
#include "bench/stages.def"
#undef FOG_BENCH
    {NULL, NULL, NULL}};

static void print_stages(FILE *out) {
  fprintf(out, "usage: fogpipe bench STAGE [options]\n\nstages:\n");
  for (int i = 0; stages[i].name; i++)
    fprintf(out, "  %-10s %s\n", stages[i].name, stages[i].summary);
}

/* `fogpipe bench`: the entry point app/commands.def names; the bench library defines it,
 * so that app/ includes nothing of bench/. */
int cmd_bench(int argc, char **argv) {
  if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    print_stages(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  for (int i = 0; stages[i].name; i++)
    if (!strcmp(argv[1], stages[i].name)) return stages[i].run(argc - 1, argv + 1);
  fprintf(stderr, "fogpipe bench: unknown stage '%s'\n\n", argv[1]);
  print_stages(stderr);
  return 2;
}


void bench_print_build(void) {
  printf("build: %s, %s, gcc %d.%d\n", FOGPIPE_BUILD_TYPE,
         FOGPIPE_NATIVE_BUILD ? "-march=native" : "portable (no -march=native)",
         __GNUC__, __GNUC_MINOR__);
}

/* The first folder level a run's --out made (bench_parse), and the path down to --out: what
 * remove_unused_out_folder takes away again at exit when the stage wrote nothing into it
 * (it failed before its first file), so a failed run leaves no empty folder behind. */
static char made_first[4096], made_out[4096];

static void remove_unused_out_folder(void) {
  char level[4096];
  snprintf(level, sizeof level, "%s", made_out);
  /* rmdir removes only empty folders: from --out up to the first level this run made,
   * stopping at one that holds something (a level past a failed mkdir is passed over) */
  while (made_first[0]) {
    if (rmdir(level) != 0 && (errno == ENOTEMPTY || errno == EEXIST)) break;
    char *slash = strrchr(level, '/');
    if (!strcmp(level, made_first) || !slash || slash == level) break;
    *slash = 0;
  }
}

/* mkdir -p; *first_made (when not NULL, size 4096) gets the first level it made ("" if none). */
static int make_folder(const char *path, char *first_made, char *error, int size) {
  char buffer[4096];
  snprintf(buffer, sizeof buffer, "%s", path);
  for (size_t n = strlen(buffer); n > 1 && buffer[n - 1] == '/'; n--) buffer[n - 1] = 0;
  if (first_made) first_made[0] = 0;
  for (char *p = buffer + 1;; p++) {
    char c = *p;
    if (c == '/' || c == 0) {
      *p = 0;
      if (mkdir(buffer, 0777) == 0) {
        if (first_made && !first_made[0]) snprintf(first_made, 4096, "%s", buffer);
      } else if (errno != EEXIST) {
        snprintf(error, (size_t)size, "%.900s: cannot create the folder (%s)", buffer,
                 strerror(errno));
        return 1;
      }
      *p = c;
      if (!c) break;
    }
  }
  /* there already, it must be a folder: a file of that name fails now, not after the bench */
  struct stat st;
  if (stat(buffer, &st) != 0 || !S_ISDIR(st.st_mode)) {
    snprintf(error, (size_t)size, "%.900s: exists and is not a folder", buffer);
    return 1;
  }
  return 0;
}

int bench_make_folder(const char *path, char *error, int size) {
  return make_folder(path, NULL, error, size);
}

void bench_print_gl(gl_context *ctx, int width, int height, int frames) {
  bench_print_build();
  printf("GL: %s, %s, %s; %dx%d, median of %d frames after 1 warm-up (glFinish before and "
         "after)\n", gl_context_platform(ctx), gl_context_version(ctx), gl_context_renderer(ctx),
         width, height, frames);
}

void bench_outputs_in(bench_outputs *o, const char *dir, const char *stage) {
  snprintf(o->table, sizeof o->table, "%s/%s.csv", dir, stage);
  snprintf(o->chart_csv, sizeof o->chart_csv, "%s/%s_chart.csv", dir, stage);
  snprintf(o->chart_png, sizeof o->chart_png, "%s/%s_chart.png", dir, stage);
}

int bench_parse(const bench_command *c, int argc, char **argv) {
  enum { max_rows = 32 };
  cli_option rows[max_rows];
  int n = 0;
  char size_help[64], frames_help[128], out_help[256], command[64];
  bench_image_options *image = c->image;
  if (image) {
    snprintf(size_help, sizeof size_help, "image size (default %dx%d)", image->width,
             image->height);
    snprintf(frames_help, sizeof frames_help, "%s (default %d)",
             c->frames_help ? c->frames_help : "timed rounds per row, median after one warm-up",
             image->frames);
    const char *what = c->out_help ? c->out_help : "output folder";
    if (image->out_dir)
      snprintf(out_help, sizeof out_help, "%s\n(default %s; created if missing)", what,
               image->out_dir);
    else
      snprintf(out_help, sizeof out_help, "%s", what);
    /* width and height: two adjacent ints, CLI_SIZE's pair */
    rows[n++] = (cli_option){.kind = CLI_SIZE, .name = "--size", .value = "WxH",
                             .target = &image->width, .help = size_help};
    rows[n++] = (cli_option){.kind = CLI_INT, .name = "--frames", .value = "N",
                             .target = &image->frames,
                             .min = c->frames_min > 0 ? c->frames_min : 1, .max = 100000000,
                             .help = frames_help};
    if (!c->without_out)
      rows[n++] = (cli_option){.kind = CLI_TEXT, .name = "--out", .value = "DIR",
                               .target = &image->out_dir, .help = out_help};
  }
  for (int k = 0; k < c->option_count && n < max_rows; k++) rows[n++] = c->options[k];
  snprintf(command, sizeof command, "bench %s", c->stage);
  const cli_spec spec = {.command = command, .usage = c->usage, .about = c->about,
                         .footer = c->footer, .operand = c->operand ? c->operand : "operand",
                         .max_operands = c->max_operands, .options = rows, .option_count = n};
  const char *none = NULL;
  int count = 0;
  int parsed = cli_parse(&spec, argc, argv, c->operands ? c->operands : &none, &count);
  if (parsed) return parsed == CLI_HELP ? 0 : parsed;
  char error[1024];
  if (image && image->out_dir) {
    snprintf(made_out, sizeof made_out, "%s", image->out_dir);
    for (size_t n = strlen(made_out); n > 1 && made_out[n - 1] == '/'; n--) made_out[n - 1] = 0;
    if (make_folder(made_out, made_first, error, sizeof error)) {
      fprintf(stderr, "fogpipe bench %s: %s\n", c->stage, error);
      remove_unused_out_folder(); /* the levels made before the one that failed */
      return 1;
    }
    if (made_first[0]) atexit(remove_unused_out_folder);
  }
  return -1;
}

int bench_valley_scene(scene_geometry *geo, camera *cam, fog_error *err) {
  scene_desc sdesc = {
      .terrain = {.origin = {-600, 0, -600}, .size = {1200, 1200}, .height = 160,
                  .resolution = 257, .seed = 4, .octaves = 6, .frequency = 2.2,
                  .persistence = 0.5},
      .boxes = {{.center = {-40, 60}, .size = {24, 30, 24}, .colour = {0.55f, 0.25f, 0.18f}},
                {.center = {70, -30}, .size = {16, 70, 16}, .colour = SCENE_BOX_GREY}},
      .box_count = 2,
      .light = scene_light_default(),
  };
  sdesc.light.sun_azimuth = 150, sdesc.light.sun_elevation = 30;
  if (scene_geometry_create(geo, &sdesc, err)) return 1;
  *cam = (camera){.fov_y = 55.0 * 3.14159265358979323846 / 180.0,
                  .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
  cam->position[0] = 30.0;
  cam->position[2] = 470.0;
  cam->position[1] = terrain_height_at(&geo->terrain, cam->position[0], cam->position[2]) + 35.0;
  camera_look_at(cam, (double[3]){-40.0, cam->position[1] - 45.0, -500.0});
  return 0;
}

void bench_write_files(bench_files_written *w, int table_failed, const chart_desc *desc,
                       const chart_point *points, int count, const bench_outputs *files) {
  w->failed = table_failed != 0, w->drawn = false;
  if (!w->failed) {
    char why[256];
    w->drawn = chart_can_draw(why, sizeof why);
    if (!w->drawn)
      printf("chart: the PNG is not drawn (%s); its points are in %s%s%s\n", why,
             files->chart_csv,
             access(files->chart_png, F_OK) == 0 ? "; the PNG there is an earlier run's: " : "",
             access(files->chart_png, F_OK) == 0 ? files->chart_png : "");
    w->failed = chart_write(desc, points, count, files->chart_csv,
                            w->drawn ? files->chart_png : NULL, w->error,
                            (int)sizeof w->error) != 0;
  }
  if (w->failed) printf("files: %s (the figures follow)\n", w->error);
}

int bench_files_report(const bench_files_written *w, fog_error *err) {
  return w->failed ? fog_fail(err, FOG_ERR_FILE_ACCESS, "%s", w->error) : 0;
}

int bench_report(const char *stage, int status, const fog_error *err) {
  if (status) fprintf(stderr, "fogpipe bench %s: %s\n", stage, err->message);
  return status;
}

int bench_load_source_config(const char *name, scene_config **cfg, fog_error *err) {
  char path[1024];
  snprintf(path, sizeof path, "%s/configs/%s", FOGPIPE_SOURCE_DIR, name);
  if (!(*cfg = malloc(sizeof **cfg))) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
  return scene_config_load(path, *cfg, err);
}

int bench_open_scene(const char *stage, const char *config_path, scene_config *cfg,
                     gl_context **gl) {
  fog_error err = {0};
  *gl = NULL;
  if (!scene_config_load(config_path, cfg, &err))
    *gl = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &err);
  if (*gl) return 0;
  fprintf(stderr, "fogpipe bench %s: %s\n", stage, err.message);
  return 1;
}

void bench_tau_errors(const float *gpu, const double *ref, size_t n, double *rmse,
                      double *max_error, size_t *where) {
  double sq = 0.0, worst = 0.0;
  *where = 0;
  for (size_t k = 0; k < n; k++) {
    double e = fabs((double)gpu[k] - ref[k]);
    if (!(e == e)) e = INFINITY; /* NaN from the GL counts as the worst error */
    sq += e * e;
    if (e > worst) worst = e, *where = k;
  }
  *rmse = sqrt(sq / (double)n);
  *max_error = worst;
}

int bench_time_rows(const bench_timed_rows *t, fog_error *err) {
  double *seconds = malloc(sizeof(double) * (size_t)t->count * (size_t)t->frames);
  if (!seconds) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
  int status = 0;
  for (int f = 0; f < t->frames && !status; f++)
    for (int i = 0; i < t->count && !status; i++) {
      status = t->prepare ? t->prepare(t->user, i, f, err) : 0;
      fog_pass_finish();
      double t0 = app_clock_seconds();
      status = status ? status : t->draw(t->user, i, err);
      fog_pass_finish();
      seconds[(size_t)i * t->frames + f] = app_clock_seconds() - t0;
    }
  for (int i = 0; i < t->count && !status; i++)
    *(double *)((char *)t->ms + (size_t)i * t->ms_stride) =
        1e3 * app_median(seconds + (size_t)i * t->frames, t->frames);
  free(seconds);
  return status;
}
