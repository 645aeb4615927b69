/* The option-value parsers every command uses (app/cli.h): whole texts only, ranges
 * inclusive, no overflow, and the bad value's exit status 2; an output file's name that
 * is an existing folder is refused before any work. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/cli.h"
#include "test_util.h"

int main(void) {
  long l = -7;
  CHECK(cli_parse_long("12", 0, 100, &l) && l == 12, "12");
  CHECK(cli_parse_long("0", 0, 100, &l) && l == 0 && cli_parse_long("100", 0, 100, &l) && l == 100,
        "the range's ends are in it");
  l = -7;
  const char *bad_longs[] = {"", "12x", " 12", "12 ", "101", "-1", "1e3", "0x10",
                             "99999999999999999999999", "4294967297"};
  for (size_t i = 0; i < sizeof bad_longs / sizeof bad_longs[0]; i++, l = -7)
    CHECK(!cli_parse_long(bad_longs[i], 0, 100, &l) && l == -7, "'%s' read as a number",
          bad_longs[i]);

  double d = -7;
  CHECK(cli_parse_double("0.25", 0, 1, &d) && d == 0.25, "0.25");
  CHECK(cli_parse_double("1e-3", 0, 1, &d) && d == 1e-3, "1e-3");
  /* below double's normal range (strtod: ERANGE) but a number inside [0, 1]: the nearest */
  CHECK(cli_parse_double("1e-320", 0, 1, &d) && d > 0 && d < 1e-319, "1e-320: %g", d);
  CHECK(cli_parse_double("1e-400", 0, 1, &d) && d == 0, "1e-400: %g", d);
  const char *bad_doubles[] = {"", "nan", "inf", "1e400", "2", "-0.5", "0.5x", ".", " 0.5",
                               "0x1p-1" /* hexadecimal: strtod reads it, we do not */};
  d = -7;
  for (size_t i = 0; i < sizeof bad_doubles / sizeof bad_doubles[0]; i++, d = -7)
    CHECK(!cli_parse_double(bad_doubles[i], 0, 1, &d) && d == -7, "'%s' read as a number",
          bad_doubles[i]);

  int w = -1, h = -1;
  CHECK(cli_size("test", "--size", "640x360", &w, &h) == 0 && w == 640 && h == 360, "640x360");
  CHECK(cli_size("test", "--size", "1X1", &w, &h) == 0 && w == 1 && h == 1, "1X1");
  CHECK(cli_size("test", "--size", "16384x16384", &w, &h) == 0 && w == CLI_MAX_SIZE, "the cap");
  const char *bad_sizes[] = {"", "640", "x360", "640x", "0x360", "640x0", "16385x2", "64x36x2",
                             "-64x36", "640 x360", "640x360 "};
  w = h = -1;
  for (size_t i = 0; i < sizeof bad_sizes / sizeof bad_sizes[0]; i++, w = h = -1)
    CHECK(cli_size("test", "--size", bad_sizes[i], &w, &h) == 2 && w == -1 && h == -1,
          "--size '%s' accepted", bad_sizes[i]);

  int first = 0, last = 0;
  bool single = false;
  CHECK(cli_range("test", "--frames", "5", 1, 100, &first, &last, &single) == 0 && first == 5 &&
            last == 5 && single, "5");
  CHECK(cli_range("test", "--frames", "3-7", 1, 100, &first, &last, &single) == 0 &&
            first == 3 && last == 7 && !single, "3-7");
  CHECK(cli_range("test", "--frames", "4-4", 1, 100, &first, &last, &single) == 0 &&
            first == 4 && last == 4 && !single, "4-4");
  const char *bad_ranges[] = {"", "7-3", "0-3", "3-", "-3", "3-101", "a-b", "3--5", "3-5-7"};
  first = last = -1;
  for (size_t i = 0; i < sizeof bad_ranges / sizeof bad_ranges[0]; i++, first = last = -1)
    CHECK(cli_range("test", "--frames", bad_ranges[i], 1, 100, &first, &last, &single) == 2 &&
              first == -1 && last == -1, "--frames '%s' accepted", bad_ranges[i]);

  int v = -1;
  CHECK(cli_int("test", "--n", "2147483647", 0, INT_MAX, &v) == 0 && v == INT_MAX, "INT_MAX");
  CHECK(cli_int("test", "--n", "2147483648", 0, INT_MAX, &v) == 2 && v == INT_MAX, "past it");
  double x = -1;
  CHECK(cli_number("test", "--x", "0.1", 0.1, 1000, &x) == 0 && x == 0.1, "0.1");
  CHECK(cli_number("test", "--x", "1e-9", 0.1, 1000, &x) == 2 && x == 0.1, "1e-9");

  char folder[] = "/tmp/fogpipe-cli-values-XXXXXX", png[64];
  CHECK(mkdtemp(folder) != NULL, "mkdtemp");
  snprintf(png, sizeof png, "%s/x.png", folder);
  CHECK(cli_output_file("test", "--out", png) == 0, "a new file's name was refused");
  CHECK(mkdir(png, 0700) == 0, "mkdir %s", png);
  CHECK(cli_output_file("test", "--out", png) == 2, "a folder named x.png was taken as a file");
  rmdir(png);
  rmdir(folder);
  return test_finish("test_cli_values");
}
