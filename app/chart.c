/* Charts via gnuplot: the CSV is the data of record; the PNG is drawn from it. */
#define _POSIX_C_SOURCE 200809L
#include "app/chart.h"

#include "sim/atomic_file.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

int chart_table_open(chart_table *table, const char *path, char *error, int size) {
  *table = (chart_table){.path = path};
  table->stream = open_memstream(&table->text, &table->length);
  if (!table->stream) snprintf(error, (size_t)size, "%.900s: out of memory", path);
  return table->stream ? 0 : 1;
}

int chart_table_write(chart_table *table, char *error, int size) {
  const bool whole = !(ferror(table->stream) | fclose(table->stream));
  fog_error err = {0};
  int status = 0;
  if (!whole) {
    snprintf(error, (size_t)size, "%.900s: out of memory", table->path);
    status = 1;
  } else if (atomic_file_write(table->path, table->text, table->length, &err)) {
    snprintf(error, (size_t)size, "%s", err.message);
    status = 1;
  }
  free(table->text);
  *table = (chart_table){0};
  return status;
}

static int write_csv(const chart_point *points, int count, const char *path, char *error,
                     int error_size) {
  chart_table table;
  if (chart_table_open(&table, path, error, error_size)) return 1;
  fprintf(table.stream, "series,x,y\n");
  for (int i = 0; i < count; i++)
    fprintf(table.stream, "%s,%.9g,%.9g\n", points[i].series, points[i].x, points[i].y);
  return chart_table_write(&table, error, error_size);
}

/* Series names in first-appearance order. */
static int collect_series(const chart_point *points, int count, const char **names, int max) {
  int n = 0;
  for (int i = 0; i < count; i++) {
    int seen = 0;
    for (int j = 0; j < n && !seen; j++) seen = !strcmp(names[j], points[i].series);
    if (!seen && n < max) names[n++] = points[i].series;
  }
  return n;
}

/* A gnuplot single-quoted string: a quote inside is doubled ("a rung's time", a folder
 * "bob's"); nothing else is special between single quotes. */
static void put_string(FILE *f, const char *text) {
  fputc('\'', f);
  for (const char *c = text ? text : ""; *c; c++) fputs(*c == '\'' ? "''" : (char[2]){*c, 0}, f);
  fputc('\'', f);
}

/* path as gnuplot may be given it: a relative one behind "./", since gnuplot runs `set
 * output '|cmd'`, `plot '<cmd'` (spaces before them too) and a script argument `<cmd` as
 * shell commands. Returns out. */
static const char *gnuplot_path(const char *path, char *out, size_t size) {
  snprintf(out, size, "%s%s", path[0] == '/' ? "" : "./", path);
  return out;
}

/* A path as a gnuplot string (gnuplot_path, quoted). */
static void put_path(FILE *f, const char *path) {
  char text[4200];
  put_string(f, gnuplot_path(path, text, sizeof text));
}

static void put_quoted(FILE *f, const char *prefix, const char *text) {
  fputs(prefix, f);
  put_string(f, text);
  fputc('\n', f);
}

/* Runs gnuplot with argv (argv[0] "gnuplot") without a shell (a path is never command
 * text), its stdout and stderr into output. Returns the exit status, 127 when gnuplot
 * cannot be started. */
static int run_gnuplot(char *const argv[], char *output, size_t size) {
  int fds[2];
  output[0] = '\0';
  if (pipe(fds) != 0) return 127;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addclose(&actions, fds[1]);
  /* gnuplot starts with no signal blocked: a caller that holds SIGINT/SIGTERM while its
   * outputs are written (fit) passed the blocked mask on, and a gnuplot that hung could
   * then be stopped by SIGKILL alone */
  posix_spawnattr_t attributes;
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  pid_t pid;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, &attributes, argv, environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  size_t used = 0;
  for (ssize_t got; (got = read(fds[0], output + used, size - 1 - used)) > 0;) {
    used += (size_t)got;
    if (used == size - 1) { /* keep the start; drain the rest */
      char sink[512];
      while (read(fds[0], sink, sizeof sink) > 0) {
      }
      break;
    }
  }
  output[used] = '\0';
  close(fds[0]);
  if (spawned != 0) return 127;
  int status;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return 127;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int chart_write(const chart_desc *desc, const chart_point *points, int count,
                const char *csv_path, const char *png_path, char *error, int error_size) {
  /* gnuplot ends a command at a line break, also inside quotes */
  if (png_path && (strchr(png_path, '\n') || strchr(csv_path, '\n'))) {
    snprintf(error, (size_t)error_size, "%.900s: a chart path cannot hold a line break",
             png_path);
    return CHART_FAILED;
  }
  int drawable = 0;
  for (int i = 0; i < count; i++) drawable += isfinite(points[i].x) && isfinite(points[i].y);
  if (png_path && drawable == 0) {
    snprintf(error, (size_t)error_size, "%.900s: nothing to chart: none of the %d point%s has "
             "a finite x and y", png_path, count, count == 1 ? "" : "s");
    return CHART_FAILED;
  }
  if (write_csv(points, count, csv_path, error, error_size)) return CHART_FAILED;
  if (!png_path) return 0;

  /* gnuplot draws into the PNG's temporary and runs a script written to a temporary of
   * its own: neither is a name a user's file could have ("chart.png.tmp" and
   * "chart.png.gp" were written over and removed) */
  atomic_file png, script_file;
  fog_error ferr = {0};
  char script_name[4200];
  snprintf(script_name, sizeof script_name, "%.4000s.gp", png_path);
  if (atomic_file_open(&png, png_path, &ferr)) {
    snprintf(error, (size_t)error_size, "%s", ferr.message);
    return CHART_CSV_WRITTEN;
  }
  if (atomic_file_open(&script_file, script_name, &ferr)) {
    atomic_file_abandon(&png);
    snprintf(error, (size_t)error_size, "%s", ferr.message);
    return CHART_CSV_WRITTEN;
  }
  const char *script_path = script_file.temp_path;
  FILE *script = fdopen(script_file.fd, "w");
  if (!script) {
    atomic_file_abandon(&script_file);
    atomic_file_abandon(&png);
    snprintf(error, (size_t)error_size, "%s: cannot write the gnuplot script", script_path);
    return CHART_CSV_WRITTEN;
  }
  script_file.fd = -1; /* the stream's now */
  int width = desc->width ? desc->width : 960, height = desc->height ? desc->height : 600;
  fprintf(script, "set terminal pngcairo size %d,%d font 'sans,10'\n", width, height);
  fputs("set output ", script);
  put_path(script, png.temp_path);
  fputc('\n', script);
  fprintf(script, "set datafile separator ','\nset key below\nset colorsequence podo\n"
                  "set grid\n");
  put_quoted(script, "set title ", desc->title);
  put_quoted(script, "set xlabel ", desc->x_label);
  put_quoted(script, "set ylabel ", desc->y_label);
  fprintf(script, "%s%s",
          desc->log_x ? "set logscale x\nset format x '10^{%L}'\n" : "",
          desc->log_y ? "set logscale y\nset format y '10^{%L}'\n" : "");
  const char *names[64];
  int series = collect_series(points, count, names, 64);
  fprintf(script, "plot ");
  for (int s = 0; s < series; s++) {
    fputs(s ? ", \\\n     " : "", script);
    put_path(script, csv_path);
    fputs(" using ($0>=0 && strcol(1) eq ", script);
    put_string(script, names[s]);
    fputs(" ? $2 : NaN):3 with linespoints title ", script);
    put_string(script, names[s]);
  }
  fprintf(script, "\n");
  const int written = !(ferror(script) | fclose(script));

  char output[1024], script_arg[4200];
  char *argv[] = {"gnuplot", (char *)gnuplot_path(script_path, script_arg, sizeof script_arg),
                  NULL};
  const int status = written ? run_gnuplot(argv, output, sizeof output) : -1;
  atomic_file_abandon(&script_file); /* removes the script */
  if (status != 0) {
    atomic_file_abandon(&png);
    if (!written)
      snprintf(error, (size_t)error_size, "%s: cannot write the gnuplot script (disk full?)",
               script_name);
    else if (status == 127)
      snprintf(error, (size_t)error_size,
               "%s: gnuplot could not be run (install Debian's gnuplot-nox)", png_path);
    else
      snprintf(error, (size_t)error_size, "%s: gnuplot failed (exit %d): %.300s", png_path,
               status, output);
    return CHART_CSV_WRITTEN;
  }
  if (atomic_file_commit(&png, &ferr)) {
    snprintf(error, (size_t)error_size, "%s", ferr.message);
    return CHART_CSV_WRITTEN;
  }
  return 0;
}

bool chart_can_draw(char *error, int error_size) {
  char output[256];
  char *argv[] = {"gnuplot", "--version", NULL};
  const int status = run_gnuplot(argv, output, sizeof output);
  if (status == 0) return true;
  if (status == 127)
    snprintf(error, (size_t)error_size,
             "gnuplot could not be run to draw the chart (install Debian's gnuplot-nox)");
  else /* there, but broken: what it said */
    snprintf(error, (size_t)error_size, "gnuplot --version failed (exit %d): %.150s", status,
             output);
  return false;
}
