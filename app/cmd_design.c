/* fogpipe design: writes a designed fogmap (Perlin turbulence, Gaussian blobs, or
 * turbulence modulated by blobs) to EXR or PNG. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "app/commands.h"
#include "sim/designed_fog.h"
#include "sim/fogmap.h"

enum { max_blobs = 256 };

static void print_help(FILE *out) {
  fprintf(out,
          "usage: fogpipe design (--perlin | --blobs N | --blob X,Z,SIGMA,PEAK)... --size WxH\n"
          "                      --out FILE.exr|FILE.png [options]\n"
          "\n"
          "Writes a designed fogmap. Perlin turbulence (Perlin 2002 improved noise, summed\n"
          "over octaves, drifting with --velocity over --time as in Zdrojewska 2004), Gaussian\n"
          "blobs c*exp(-|x-b|^2/(2 sigma^2)), or, with both, the turbulence multiplied by\n"
          "(--blob-base + the blob sum): turbulence modulated by Gaussian banks.\n"
          "Positions and sizes are in fogmap cells; cell (x, z) is at (x, z), z = image row.\n"
          "\n"
          "what:\n"
          "  --perlin               Perlin turbulence base + gain * T(p - velocity * time)\n"
          "  --blobs N              N Gaussian blobs placed at random from --seed\n"
          "  --blob X,Z,SIGMA,PEAK  one Gaussian blob (repeatable, at most %d blobs in all)\n"
          "output:\n"
          "  --size WxH             fogmap size in cells (required)\n"
          "  --out FILE             .exr: one float channel \"Y\" (exactly what fogmap_load reads);\n"
          "                         .png: 16-bit grey, density / png-max * 65535 (required)\n"
          "  --half                 EXR: store the channel as 16-bit half floats\n"
          "  --png-max D            PNG: the density stored as 65535 (default: the map's maximum;\n"
          "                         load the PNG with density_scale D to get densities back)\n"
          "Perlin turbulence:\n"
          "  --seed N               permutation seed, also places random blobs (default 1;\n"
          "                         0 is Perlin's reference permutation)\n"
          "  --time T               animation time (default 0)\n"
          "  --velocity VX,VZ       drift of the noise in cells per unit time (default 0,0)\n"
          "  --feature-size S       noise lattice spacing in cells, the largest eddies (default 32)\n"
          "  --octaves N            turbulence octaves (default 4)\n"
          "  --gain G               turbulence gain (default 1)\n"
          "  --base B               density added to the turbulence (default 0)\n"
          "  --slice S              the noise's third coordinate (default 0)\n"
          "  --slice-rate R         slice change per unit time: evolving, not only drifting fog\n"
          "blobs:\n"
          "  --blob-base B          density added to the blob sum (default 0; with --perlin it\n"
          "                         is the turbulence left between the banks)\n"
          "  --help                 this text\n",
          max_blobs);
}

static int takes_value(const char *opt) {
  static const char *const valued[] = {
      "--size",  "--out",  "--seed", "--blobs", "--blob",  "--time",       "--velocity",
      "--feature-size", "--octaves", "--gain", "--base", "--slice", "--slice-rate",
      "--blob-base", "--png-max"};
  for (size_t i = 0; i < sizeof valued / sizeof valued[0]; i++)
    if (!strcmp(opt, valued[i])) return 1;
  return 0;
}

/* Parses exactly `count` comma-separated finite numbers. */
static int parse_numbers(const char *text, double *values, int count) {
  const char *p = text;
  for (int i = 0; i < count; i++) {
    char *end;
    values[i] = strtod(p, &end);
    if (end == p || !isfinite(values[i])) return 1;
    p = end;
    if (i + 1 < count) {
      if (*p != ',') return 1;
      p++;
    }
  }
  return *p != '\0';
}

static int ends_with(const char *s, const char *suffix) {
  size_t n = strlen(s), m = strlen(suffix);
  if (n < m) return 0;
  for (size_t i = 0; i < m; i++) {
    char c = s[n - m + i];
    if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
    if (c != suffix[i]) return 0;
  }
  return 1;
}

/* splitmix64: random blob placement from the seed, the same on every platform. */
static double next_uniform(uint64_t *state) {
  uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return (double)(z >> 11) / 9007199254740992.0;
}

typedef struct design_options {
  int perlin, half, random_blobs, blob_count;
  long width, height, seed;
  const char *out;
  double png_max, blob_base;
  fog_blob blobs[max_blobs];
  perlin_fog_desc noise;
} design_options;

/* One option with its value; 0, or the usage error's exit status. */
static int design_value(design_options *o, const char *opt, const char *value) {
  double v[4];
  long n;
  if (!strcmp(opt, "--size")) {
    int w, h;
    if (cli_size("design", "--size", value, &w, &h)) return 2;
    o->width = w, o->height = h;
  } else if (!strcmp(opt, "--out")) {
    o->out = value;
  } else if (!strcmp(opt, "--seed")) {
    if (!cli_parse_long(value, 0, 0x7fffffffL, &o->seed))
      return cli_usage_error("design", "--seed expects an integer 0 to 2147483647, got '%s'", value);
  } else if (!strcmp(opt, "--blobs")) {
    if (!cli_parse_long(value, 1, max_blobs, &n))
      return cli_usage_error("design", "--blobs expects a count 1 to 256, got '%s'", value);
    o->random_blobs = (int)n;
  } else if (!strcmp(opt, "--blob")) {
    if (parse_numbers(value, v, 4) || !(v[2] > 0) || !(v[3] >= 0))
      return cli_usage_error("design", "--blob expects X,Z,SIGMA,PEAK with SIGMA > 0 and PEAK >= 0, got "
                         "'%s'", value);
    if (o->blob_count >= max_blobs) return cli_usage_error("design", "more than 256 blobs");
    o->blobs[o->blob_count++] = (fog_blob){(float)v[0], (float)v[1], (float)v[2], (float)v[3]};
  } else if (!strcmp(opt, "--time")) {
    if (parse_numbers(value, v, 1)) return cli_usage_error("design", "--time expects a number, got '%s'", value);
    o->noise.time = (float)v[0];
  } else if (!strcmp(opt, "--velocity")) {
    if (parse_numbers(value, v, 2))
      return cli_usage_error("design", "--velocity expects VX,VZ (two numbers), got '%s'", value);
    o->noise.velocity[0] = (float)v[0];
    o->noise.velocity[1] = (float)v[1];
  } else if (!strcmp(opt, "--feature-size")) {
    if (parse_numbers(value, v, 1) || !(v[0] > 0))
      return cli_usage_error("design", "--feature-size expects a positive number of cells, got '%s'",
                         value);
    o->noise.feature_size = (float)v[0];
  } else if (!strcmp(opt, "--octaves")) {
    if (!cli_parse_long(value, 1, 30, &n))
      return cli_usage_error("design", "--octaves expects 1 to 30, got '%s'", value);
    o->noise.octaves = (int)n;
  } else if (!strcmp(opt, "--gain")) {
    if (parse_numbers(value, v, 1) || !(v[0] > 0))
      return cli_usage_error("design", "--gain expects a positive number, got '%s'", value);
    o->noise.gain = (float)v[0];
  } else if (!strcmp(opt, "--base")) {
    if (parse_numbers(value, v, 1) || !(v[0] >= 0))
      return cli_usage_error("design", "--base expects a number >= 0, got '%s'", value);
    o->noise.base = (float)v[0];
  } else if (!strcmp(opt, "--slice")) {
    if (parse_numbers(value, v, 1)) return cli_usage_error("design", "--slice expects a number, got '%s'", value);
    o->noise.slice = (float)v[0];
  } else if (!strcmp(opt, "--slice-rate")) {
    if (parse_numbers(value, v, 1))
      return cli_usage_error("design", "--slice-rate expects a number, got '%s'", value);
    o->noise.slice_rate = (float)v[0];
  } else if (!strcmp(opt, "--blob-base")) {
    if (parse_numbers(value, v, 1) || !(v[0] >= 0))
      return cli_usage_error("design", "--blob-base expects a number >= 0, got '%s'", value);
    o->blob_base = v[0];
  } else if (!strcmp(opt, "--png-max")) {
    if (parse_numbers(value, v, 1) || !(v[0] > 0))
      return cli_usage_error("design", "--png-max expects a positive density, got '%s'", value);
    o->png_max = v[0];
  } else {
    return cli_usage_error("design", "unknown option '%s'", opt);
  }
  return 0;
}

/* -1 to go on, else the exit status. */
static int parse_design_options(int argc, char **argv, design_options *o) {
  for (int i = 1; i < argc; i++) {
    const char *opt = argv[i];
    if (!strcmp(opt, "--help") || !strcmp(opt, "-h")) {
      print_help(stdout);
      return 0;
    }
    if (!strcmp(opt, "--perlin")) {
      o->perlin = 1;
      continue;
    }
    if (!strcmp(opt, "--half")) {
      o->half = 1;
      continue;
    }
    if (!takes_value(opt)) return cli_usage_error("design", "unknown option '%s'", opt);
    if (i + 1 >= argc) return cli_usage_error("design", "%s needs a value", opt);
    int status = design_value(o, opt, argv[++i]);
    if (status) return status;
  }
  if (!o->perlin && !o->random_blobs && !o->blob_count)
    return cli_usage_error("design", "say what to design: --perlin, --blobs N and/or --blob X,Z,SIGMA,PEAK");
  if (!o->width) return cli_usage_error("design", "--size WxH is required");
  if (!o->out) return cli_usage_error("design", "--out FILE.exr or FILE.png is required");
  if (!ends_with(o->out, ".png") && !ends_with(o->out, ".exr"))
    return cli_usage_error("design", "--out '%s': the name must end in .exr or .png", o->out);
  if (o->random_blobs + o->blob_count > max_blobs)
    return cli_usage_error("design", "more than 256 blobs");
  return -1;
}

/* The fogmap: Perlin turbulence and/or the blobs (random banks added to the given ones),
 * the turbulence multiplied by the banks when both are asked for. */
static int design_fogmap(design_options *o, fogmap *map, sim_error *err) {
  /* Random banks: centres inside the middle 80%, widths 1/16 to 1/5 of the smaller side. */
  uint64_t state = (uint64_t)o->seed * 0x2545f4914f6cdd1dull + 1;
  const long width = o->width, height = o->height;
  double side = width < height ? (double)width : (double)height;
  for (int i = 0; i < o->random_blobs; i++) {
    double x = width * (0.1 + 0.8 * next_uniform(&state));
    double z = height * (0.1 + 0.8 * next_uniform(&state));
    double sigma = side * (1.0 / 16 + (1.0 / 5 - 1.0 / 16) * next_uniform(&state));
    double peak = 0.4 + 0.6 * next_uniform(&state);
    o->blobs[o->blob_count++] = (fog_blob){(float)x, (float)z, (float)sigma, (float)peak};
  }
  fogmap banks = {0};
  int status = fogmap_create(map, (int)width, (int)height, err);
  o->noise.seed = (uint64_t)o->seed;
  if (!status && o->perlin) status = designed_fog_perlin(map, &o->noise, err);
  if (!status && o->blob_count) {
    fogmap *target = o->perlin ? &banks : map;
    if (o->perlin) status = fogmap_create(&banks, (int)width, (int)height, err);
    if (!status)
      status = designed_fog_blobs(
          target, &(blob_fog_desc){.blobs = o->blobs, .blob_count = o->blob_count}, err);
    for (size_t i = 0; !status && i < (size_t)width * (size_t)height; i++)
      target->density[i] += (float)o->blob_base;
    if (!status && o->perlin) status = designed_fog_multiply(map, &banks, err);
  }
  fogmap_destroy(&banks);
  return status;
}

int cmd_design(int argc, char **argv) {
  design_options o = {.seed = 1, .noise = perlin_fog_desc_default()};
  int parsed = parse_design_options(argc, argv, &o);
  if (parsed >= 0) return parsed;
  const int png = ends_with(o.out, ".png");
  sim_error err;
  fogmap map = {0};
  int status = design_fogmap(&o, &map, &err);
  float max = status ? 0.0f : fogmap_max_density(&map);
  if (!status) {
    if (png) {
      status = fogmap_save_png16(o.out, &map, (float)o.png_max, &err);
    } else {
      image_channel y = {.name = "Y", .pixels = map.density, .as_half = o.half};
      status = image_write_exr(o.out, map.width, map.height, &y, 1, &err);
    }
  }
  if (status) {
    fprintf(stderr, "fogpipe design: %s\n", err.message);
  } else {
    float min = map.density[0];
    for (size_t i = 0; i < (size_t)o.width * (size_t)o.height; i++)
      if (map.density[i] < min) min = map.density[i];
    printf("fogpipe design: wrote %s (%ldx%ld, densities %g to %g", o.out, o.width, o.height,
           (double)min, (double)max);
    double full_scale = o.png_max ? o.png_max : (max > 0.0f ? (double)max : 1.0);
    if (png) printf("; PNG full scale %g: load with density_scale %g", full_scale, full_scale);
    printf(")\n");
  }
  fogmap_destroy(&map);
  return status ? 1 : 0;
}
