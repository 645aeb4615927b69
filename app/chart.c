/* Charts via gnuplot: the CSV is the data of record; the PNG is drawn from it. */
#define _POSIX_C_SOURCE 200809L
#include "app/chart.h"

#include <errno.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

FILE *chart_csv_open(const char *path, char *error, int size) {
  char temp[4200];
  snprintf(temp, sizeof temp, "%.4000s.tmp", path);
  FILE *f = fopen(temp, "w");
  if (!f) snprintf(error, (size_t)size, "%.900s: cannot write (folder missing or not writable)", path);
  return f;
}

int chart_csv_close(FILE *f, const char *path, char *error, int size) {
  char temp[4200];
  snprintf(temp, sizeof temp, "%.4000s.tmp", path);
  if (fclose(f) != 0 || rename(temp, path) != 0) {
    remove(temp);
    snprintf(error, (size_t)size, "%.900s: write failed (disk full?)", path);
    return 1;
  }
  return 0;
}

static int write_csv(const chart_point *points, int count, const char *path, char *error,
                     int error_size) {
  FILE *file = chart_csv_open(path, error, error_size);
  if (!file) return 1;
  fprintf(file, "series,x,y\n");
  for (int i = 0; i < count; i++)
    fprintf(file, "%s,%.9g,%.9g\n", points[i].series, points[i].x, points[i].y);
  return chart_csv_close(file, path, error, error_size);
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
  pid_t pid;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, NULL, argv, environ);
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
  if (write_csv(points, count, csv_path, error, error_size)) return CHART_FAILED;
  if (!png_path) return 0;

  char temp_png[4096], script_path[4096];
  snprintf(temp_png, sizeof temp_png, "%s.tmp", png_path);
  snprintf(script_path, sizeof script_path, "%s.gp", png_path);
  FILE *script = fopen(script_path, "w");
  if (!script) {
    snprintf(error, (size_t)error_size, "%s: cannot write the gnuplot script", script_path);
    return CHART_CSV_WRITTEN;
  }
  int width = desc->width ? desc->width : 960, height = desc->height ? desc->height : 600;
  fprintf(script, "set terminal pngcairo size %d,%d font 'sans,10'\n", width, height);
  fputs("set output ", script);
  put_path(script, temp_png);
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
  const int written = fclose(script) == 0;

  char output[1024], script_arg[4200];
  char *argv[] = {"gnuplot", (char *)gnuplot_path(script_path, script_arg, sizeof script_arg),
                  NULL};
  const int status = written ? run_gnuplot(argv, output, sizeof output) : -1;
  remove(script_path);
  if (status == 0 && rename(temp_png, png_path) != 0) {
    snprintf(error, (size_t)error_size, "%s: cannot move the finished chart onto it: %s",
             png_path, strerror(errno));
    remove(temp_png);
    return CHART_CSV_WRITTEN;
  }
  if (status != 0) {
    remove(temp_png);
    if (!written)
      snprintf(error, (size_t)error_size, "%s: cannot write the gnuplot script (disk full?)",
               script_path);
    else if (status == 127)
      snprintf(error, (size_t)error_size,
               "%s: gnuplot could not be run (install Debian's gnuplot-nox)", png_path);
    else
      snprintf(error, (size_t)error_size, "%s: gnuplot failed (exit %d): %.300s", png_path,
               status, output);
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
