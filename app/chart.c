/* Charts via gnuplot: the CSV is the data of record; the PNG is drawn from it. */
#define _POSIX_C_SOURCE 200809L
#include "app/chart.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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

/* A gnuplot single-quoted string: a quote inside is doubled ("a rung's time"). */
static void put_quoted(FILE *f, const char *prefix, const char *text) {
  fprintf(f, "%s'", prefix);
  for (const char *c = text ? text : ""; *c; c++) fputs(*c == '\'' ? "''" : (char[2]){*c, 0}, f);
  fputs("'\n", f);
}

int chart_write(const chart_desc *desc, const chart_point *points, int count,
                const char *csv_path, const char *png_path, char *error, int error_size) {
  if (write_csv(points, count, csv_path, error, error_size)) return 1;
  if (!png_path) return 0;

  char temp_png[4096], script_path[4096];
  snprintf(temp_png, sizeof temp_png, "%s.tmp", png_path);
  snprintf(script_path, sizeof script_path, "%s.gp", png_path);
  FILE *script = fopen(script_path, "w");
  if (!script) {
    snprintf(error, (size_t)error_size, "%s: cannot write the gnuplot script", script_path);
    return 1;
  }
  int width = desc->width ? desc->width : 960, height = desc->height ? desc->height : 600;
  fprintf(script,
          "set terminal pngcairo size %d,%d font 'sans,10'\nset output '%s'\n"
          "set datafile separator ','\nset key below\nset colorsequence podo\nset grid\n",
          width, height, temp_png);
  put_quoted(script, "set title ", desc->title);
  put_quoted(script, "set xlabel ", desc->x_label);
  put_quoted(script, "set ylabel ", desc->y_label);
  fprintf(script, "%s%s",
          desc->log_x ? "set logscale x\nset format x '10^{%L}'\n" : "",
          desc->log_y ? "set logscale y\nset format y '10^{%L}'\n" : "");
  const char *names[64];
  int series = collect_series(points, count, names, 64);
  fprintf(script, "plot ");
  for (int s = 0; s < series; s++)
    fprintf(script,
            "%s'%s' using ($0>=0 && strcol(1) eq '%s' ? $2 : NaN):3 with linespoints "
            "title '%s'",
            s ? ", \\\n     " : "", csv_path, names[s], names[s]);
  fprintf(script, "\n");
  fclose(script);

  char command[8192];
  snprintf(command, sizeof command, "gnuplot '%s' 2>&1", script_path);
  FILE *pipe = popen(command, "r");
  char output[1024] = "";
  size_t used = pipe ? fread(output, 1, sizeof output - 1, pipe) : 0;
  output[used] = 0;
  int status = pipe ? pclose(pipe) : -1;
  remove(script_path);
  if (status != 0 || rename(temp_png, png_path) != 0) {
    remove(temp_png);
    snprintf(error, (size_t)error_size,
             "%s: gnuplot failed (install Debian's gnuplot-nox): %.300s", png_path, output);
    return 1;
  }
  return 0;
}
