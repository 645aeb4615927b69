/* app/chart.c: a chart whose folder and series names hold a quote, or shell text, is drawn
 * (a real PNG, its CSV the data of record) and nothing of the path is run as a command;
 * no temporary or script is left, and a user's file beside it is never one; a path with a
 * line break is refused, nothing written; a chart with no finite point is refused with a
 * clear message, nothing written (gnuplot failed on a bare `plot`: `fit --chart` whose every
 * rung was refused); chart_floor keeps a NaN (not measured) out of the chart. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/chart.h"
#include "test_util.h"

static bool exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

int main(void) {
  char root[] = "/tmp/fogpipe-chart-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  /* The scratch folder is the working folder: a command the path let run makes PWNED there. */
  CHECK(chdir(root) == 0, "chdir %s", root);
  char folder[600], png[700], csv[700], marker[600];
  snprintf(marker, sizeof marker, "%s/PWNED", root);
  /* one folder name that breaks a shell's single quotes and would run `touch` if it did */
  snprintf(folder, sizeof folder, "%s/it'$(touch PWNED)'s \"x\"", root);
  CHECK(mkdir(folder, 0755) == 0, "mkdir %s", folder);
  snprintf(png, sizeof png, "%s/chart.png", folder);
  snprintf(csv, sizeof csv, "%s/chart.csv", folder);
  const chart_point points[] = {{.series = "a rung's time", .x = 1, .y = 1e-3},
                                {.series = "a rung's time", .x = 2, .y = 1e-4},
                                {.series = "other", .x = 3, .y = 1e-2}};
  const chart_desc desc = {.title = "it's a chart", .x_label = "ms", .y_label = "error",
                           .log_y = true};
  char error[1024] = "";
  int status = chart_write(&desc, points, 3, csv, png, error, sizeof error);
  CHECK(status == 0, "chart_write: %s", error);
  CHECK(!exists(marker), "the path ran as shell text: %s exists", marker);
  FILE *f = fopen(png, "rb");
  unsigned char magic[8] = {0};
  CHECK(f && fread(magic, 1, 8, f) == 8 && !memcmp(magic, "\x89PNG\r\n\x1a\n", 8),
        "%s is not a PNG", png);
  if (f) fclose(f);
  char text[256] = "";
  f = fopen(csv, "r");
  size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
  text[n] = '\0';
  if (f) fclose(f);
  CHECK(!strcmp(text, "series,x,y\na rung's time,1,0.001\na rung's time,2,0.0001\n"
                      "other,3,0.01\n"),
        "CSV: %s", text);
  CHECK(test_folder_entries(folder) == 2, "%d files beside the chart (a script or temporary "
        "left?)", test_folder_entries(folder));

  /* the temporaries are the write's own: a user's files named as the old ones were
   * (NAME.tmp, NAME.gp) are left as they were (they were written over and removed) */
  {
    const char *users[3] = {"chart.png.tmp", "chart.png.gp", "chart.csv.tmp"};
    char paths[3][800];
    for (int i = 0; i < 3; i++) {
      snprintf(paths[i], sizeof paths[i], "%s/%s", folder, users[i]);
      test_write_text(paths[i], "a user's own file\n");
    }
    status = chart_write(&desc, points, 3, csv, png, error, sizeof error);
    CHECK(status == 0, "chart_write beside a user's files: %s", error);
    for (int i = 0; i < 3; i++) {
      char kept[64] = "";
      FILE *k = fopen(paths[i], "r");
      size_t got = k ? fread(kept, 1, sizeof kept - 1, k) : 0;
      kept[got] = '\0';
      if (k) fclose(k);
      CHECK(!strcmp(kept, "a user's own file\n"), "%s was written over or removed: '%s'",
            users[i], kept);
      unlink(paths[i]);
    }
    CHECK(test_folder_entries(folder) == 2, "%d files beside the chart after a second write",
          test_folder_entries(folder));
  }

  /* gnuplot's own commands in a name: `set output '|cmd'` and `plot '<cmd'` pipe through a
   * shell; relative names here (the working folder is the scratch one) */
  const char *piped[2][2] = {{"|touch PIPED_OUT", "chart"}, {"<touch PIPED_CSV", "x"}};
  for (int i = 0; i < 2; i++) {
    CHECK(mkdir(piped[i][0], 0755) == 0, "mkdir %s", piped[i][0]);
    char p_png[700], p_csv[700];
    snprintf(p_png, sizeof p_png, "%s/%s.png", piped[i][0], piped[i][1]);
    snprintf(p_csv, sizeof p_csv, "%s/%s.csv", piped[i][0], piped[i][1]);
    status = chart_write(&desc, points, 3, p_csv, p_png, error, sizeof error);
    CHECK(status == 0 && access(p_png, F_OK) == 0, "chart %s: %s", p_png, error);
  }
  CHECK(access("PIPED_OUT", F_OK) != 0 && access("PIPED_CSV", F_OK) != 0,
        "a '|' or '<' name ran a command");

  /* a line break would end gnuplot's command inside the quotes: refused */
  char broken[600], broken_csv[600];
  snprintf(broken, sizeof broken, "%s/two\nlines.png", root);
  snprintf(broken_csv, sizeof broken_csv, "%s/two\nlines.csv", root);
  status = chart_write(&desc, points, 3, broken_csv, broken, error, sizeof error);
  CHECK(status != 0 && strstr(error, "line break"), "a path with a line break: %d %s", status,
        error);
  CHECK(!exists(broken) && !exists(broken_csv), "a refused chart left a file");

  /* nothing to draw: refused, said as such, nothing written */
  {
    const chart_point unmeasured[] = {{.series = "a", .x = 1, .y = NAN},
                                      {.series = "a", .x = INFINITY, .y = 1}};
    char empty_png[700], empty_csv[700];
    snprintf(empty_png, sizeof empty_png, "%s/empty.png", root);
    snprintf(empty_csv, sizeof empty_csv, "%s/empty.csv", root);
    for (int count = 0; count <= 2; count += 2) {
      error[0] = '\0';
      status = chart_write(&desc, unmeasured, count, empty_csv, empty_png, error, sizeof error);
      CHECK(status == CHART_FAILED && strstr(error, "nothing to chart"), "%d points, none "
            "finite: status %d, '%s'", count, status, error);
      CHECK(!exists(empty_png) && !exists(empty_csv), "%d points, none finite: a file written",
            count);
    }
  }
  CHECK(isnan(chart_floor(NAN, 1e-6)) && chart_floor(1e-9, 1e-6) == 1e-6 &&
            chart_floor(0.5, 1e-6) == 0.5,
        "chart_floor: %g %g %g", chart_floor(NAN, 1e-6), chart_floor(1e-9, 1e-6),
        chart_floor(0.5, 1e-6));
  CHECK(chdir("/") == 0, "chdir /");
  test_remove_tree(root);
  return test_finish("test_chart");
}
