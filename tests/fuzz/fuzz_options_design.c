/* fuzz_options.c's way into fogpipe design's value parsers: this file compiles
 * app/cmd_design.c itself, so its static helpers are callable. Each argument is parsed the
 * ways the command parses option values. */
#include "app/cmd_design.c"

#include <stdlib.h>

void fuzz_design_parse(int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    (void)takes_value(a);
    (void)ends_with(a, ".png");
    (void)ends_with(a, ".exr");
    double v[4];
    for (int count = 1; count <= 4; count++)
      if (!parse_numbers(a, v, count))
        for (int k = 0; k < count; k++)
          if (!isfinite(v[k])) abort();
    /* The shared value parsers (app/cli.h) the commands call: what they accept is in
     * range. */
    long n;
    static const long bounds[][2] = {{1, 16384}, {0, 0x7fffffffL}, {1, max_blobs}, {1, 30}};
    for (size_t b = 0; b < sizeof bounds / sizeof bounds[0]; b++)
      if (cli_parse_long(a, bounds[b][0], bounds[b][1], &n) && (n < bounds[b][0] || n > bounds[b][1]))
        abort();
    double d;
    if (cli_parse_double(a, -1e9, 1e9, &d) && !(d >= -1e9 && d <= 1e9)) abort();
    int w = 0, h = 0, first = 0, last = 0;
    bool single;
    if (cli_size("design", "--size", a, &w, &h) == 0 &&
        (w < 1 || w > CLI_MAX_SIZE || h < 1 || h > CLI_MAX_SIZE))
      abort();
    if (cli_range("record", "--frames", a, 1, 9999999, &first, &last, &single) == 0 &&
        (first < 1 || last > 9999999 || first > last || (single && first != last)))
      abort();
  }
}
