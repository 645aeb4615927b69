/* fuzz_options.c's way into fogpipe design's option parser: this file compiles
 * app/cmd_design.c itself, so its static parse_design_options (the command's whole argv
 * stage: app/cli_options.c's table parser with design's rows) is callable, and checks
 * what it promises the command on success. Each argument is also given to the value
 * parsers the rows use (parse_numbers, the shared ones in app/cli.h). */
#include "app/cmd_design.c"

#include <stdlib.h>

static void check_design_parse(int argc, char **argv) {
  design_options o = {.seed = 1, .noise = perlin_fog_desc_default()};
  int status = parse_design_options(argc, argv, &o);
  if (status == 0) {
    if (o.width < 1 || o.width > CLI_MAX_SIZE || o.height < 1 || o.height > CLI_MAX_SIZE) abort();
    if (!o.out || !(cli_ends_with(o.out, ".png") || cli_ends_with(o.out, ".exr"))) abort();
    if (!o.perlin && !o.random_blobs && !o.blob_count) abort();
    if (o.blob_count < 0 || o.random_blobs < 0 || o.random_blobs + o.blob_count > max_blobs)
      abort();
    for (int b = 0; b < o.blob_count; b++)
      if (!(o.blobs[b].sigma > 0) || !(o.blobs[b].peak >= 0) || !isfinite(o.blobs[b].x) ||
          !isfinite(o.blobs[b].z))
        abort();
    if (o.seed < 0 || o.noise.octaves < 1 || o.noise.octaves > 30) abort();
    if (!(o.noise.feature_size >= 1e-3f) || !(o.noise.gain > 0) || !(o.noise.base >= 0)) abort();
  } else if (status != 2 && status != CLI_HELP) {
    abort(); /* a usage error (2) or --help */
  }
}

void fuzz_design_parse(int argc, char **argv) {
  check_design_parse(argc, argv);
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    double v[4];
    for (int count = 1; count <= 4; count++)
      if (!parse_numbers(a, v, count))
        for (int k = 0; k < count; k++)
          if (!isfinite(v[k])) abort();
    /* The shared value parsers (app/cli.h) the rows call: what they accept is in range. */
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
