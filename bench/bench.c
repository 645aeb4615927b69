/* The bench dispatcher and the small timing helpers every stage shares. */
#define _POSIX_C_SOURCE 200809L
#include "bench/bench.h"
#include "app/commands.h"
#include "render/fog_pass.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
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


static int compare_doubles(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

double bench_median(double *values, int n) {
  qsort(values, (size_t)n, sizeof *values, compare_doubles);
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void bench_print_build(void) {
  printf("build: %s, %s, gcc %d.%d\n", FOGPIPE_BUILD_TYPE,
         FOGPIPE_NATIVE_BUILD ? "-march=native" : "portable (no -march=native)",
         __GNUC__, __GNUC_MINOR__);
}

int bench_image_option(const char *stage, int argc, char **argv, int *i,
                       bench_image_options *o) {
  const char *arg = argv[*i];
  if (*i + 1 >= argc) return 0;
  if (!strcmp(arg, "--size")) {
    char tail = 0;
    const char *value = argv[++*i];
    if (sscanf(value, "%dx%d%c", &o->width, &o->height, &tail) != 2 || o->width < 8 ||
        o->height < 8 || o->width > 8192 || o->height > 8192) {
      fprintf(stderr, "fogpipe bench %s: --size '%s': expected WxH, 8..8192 each, e.g. 640x360\n",
              stage, value);
      return -1;
    }
    return 1;
  }
  if (!strcmp(arg, "--frames")) {
    o->frames = atoi(argv[++*i]);
    if (o->frames < 1) {
      fprintf(stderr, "fogpipe bench %s: --frames needs a positive number\n", stage);
      return -1;
    }
    return 1;
  }
  if (!strcmp(arg, "--out")) {
    o->out_dir = argv[++*i];
    return 1;
  }
  return 0;
}

int bench_image_command(const char *stage, int argc, char **argv, bench_image_options *options,
                        void (*print_help)(void)) {
  for (int i = 1; i < argc; i++) {
    int common = bench_image_option(stage, argc, argv, &i, options);
    if (common < 0) return 2;
    if (common) continue;
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      print_help();
      return 0;
    }
    fprintf(stderr, "fogpipe bench %s: unknown option '%s' (or it lacks its value)\n", stage,
            argv[i]);
    print_help();
    return 2;
  }
  char error[1024];
  if (bench_make_folder(options->out_dir, error, sizeof error)) {
    fprintf(stderr, "fogpipe bench %s: %s\n", stage, error);
    return 1;
  }
  return -1;
}

int bench_make_folder(const char *path, char *error, int size) {
  char buffer[4096];
  snprintf(buffer, sizeof buffer, "%s", path);
  for (char *p = buffer + 1;; p++) {
    char c = *p;
    if (c == '/' || c == 0) {
      *p = 0;
      if (mkdir(buffer, 0777) != 0 && errno != EEXIST) {
        snprintf(error, (size_t)size, "%.900s: cannot create the folder (%s)", buffer, strerror(errno));
        return 1;
      }
      *p = c;
      if (!c) return 0;
    }
  }
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

int bench_time_rows(const bench_timed_rows *t, render_error *err) {
  for (int f = 0; f < t->frames; f++)
    for (int i = 0; i < t->count; i++) {
      if (t->prepare && t->prepare(t->user, i, f, err)) return 1;
      fog_pass_finish();
      double t0 = app_clock_seconds();
      if (t->draw(t->user, i, err)) return 1;
      fog_pass_finish();
      t->times(t->user, i)[f] = app_clock_seconds() - t0;
    }
  return 0;
}
