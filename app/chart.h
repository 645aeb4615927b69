/* Speed/accuracy charts: a CSV of (series, x, y) points and a PNG plot drawn by gnuplot
 * (Debian's gnuplot-nox, pngcairo), one line per series. Used by the benchmarks and by
 * `fogpipe import --report`. */
#ifndef FOGPIPE_APP_CHART_H
#define FOGPIPE_APP_CHART_H

#include <stdbool.h>
#include <stdio.h>

/* A table written whole or not at all: chart_table_open gives a stream in memory to print
 * to; chart_table_write writes it to path through sim/atomic_file.h (non-zero and a
 * message naming the file if that fails, the file as it was) and frees it, either way. */
typedef struct chart_table {
  FILE *stream;     /* print the table here */
  const char *path; /* not owned */
  char *text;
  size_t length;
} chart_table;
int chart_table_open(chart_table *table, const char *path, char *error, int size);
int chart_table_write(chart_table *table, char *error, int size);

typedef struct chart_point {
  const char *series; /* points of one series are joined in the order given */
  double x, y;
} chart_point;

typedef struct chart_desc {
  const char *title;
  const char *x_label, *y_label;
  bool log_x, log_y;
  int width, height;  /* pixels; 0 means 960 x 600 */
} chart_desc;

/* y raised to floor (a log axis's exact rows), a NaN y kept NaN: the chart leaves that
 * point out (raised to the floor, an error that was not measured drew as the most accurate
 * row). */
static inline double chart_floor(double y, double floor) {
  return y != y || y > floor ? y : floor;
}

/* Writes csv_path (columns series,x,y) and, when png_path is not NULL, the PNG chart.
 * Both are written to temporary names and renamed. Returns 0, or with a message in error
 * (size error_size) naming the file or the missing gnuplot: CHART_FAILED (nothing
 * written) or CHART_CSV_WRITTEN (the CSV is there, the PNG is not: a caller that must
 * leave nothing removes it). With a PNG asked for, points of which none has a finite x and
 * y are CHART_FAILED (gnuplot took a bare `plot` for a syntax error). */
enum { CHART_FAILED = 1, CHART_CSV_WRITTEN = 2 };
int chart_write(const chart_desc *desc, const chart_point *points, int count,
                const char *csv_path, const char *png_path, char *error, int error_size);

/* Whether gnuplot runs (`gnuplot --version`): a command asks before its work, so that a
 * chart it cannot draw does not cost the run. false with a message in error otherwise. */
bool chart_can_draw(char *error, int error_size);

#endif
