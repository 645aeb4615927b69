/* fogpipe design: writes a designed fogmap (Perlin turbulence, Gaussian blobs, or
 * turbulence modulated by blobs) to EXR or PNG. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/stop_signals.h"
#include "sim/designed_fog.h"
#include "sim/fogmap.h"

enum { max_blobs = 256 };

/* Parses exactly `count` comma-separated numbers, each as every option reads one
 * (cli_parse_double: decimal, no blanks) and within float's range (blobs and velocities
 * are floats: 1e39 turned infinite past the check, 0x1p2 and " 1" were taken). */
static int parse_numbers(const char *text, double *values, int count) {
  const char *p = text;
  for (int i = 0; i < count; i++) {
    const size_t length = strcspn(p, ",");
    char part[64];
    if (length == 0 || length >= sizeof part) return 1;
    memcpy(part, p, length);
    part[length] = '\0';
    if (!cli_parse_double(part, -FLT_MAX, FLT_MAX, &values[i])) return 1;
    p += length;
    if (i + 1 < count) {
      if (*p != ',') return 1;
      p++;
    }
  }
  return *p != '\0';
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

/* --blob X,Z,SIGMA,PEAK, appended. */
static int parse_blob(const char *command, const char *option, const char *text, void *target) {
  design_options *o = target;
  double v[4];
  /* SIGMA of at least 1e-6 cells: 1e-50 became a float 0 past the check */
  if (parse_numbers(text, v, 4) || !(v[2] >= 1e-6) || !(v[3] >= 0))
    return cli_usage_error(command, "%s '%s': expected X,Z,SIGMA,PEAK, decimal numbers (in "
                           "cells) with SIGMA >= 1e-6 and PEAK >= 0, each at most %g in size",
                           option, text, (double)FLT_MAX);
  if (o->blob_count >= max_blobs)
    return cli_usage_error(command, "%s: more than %d blobs (--blob and --blobs N together)",
                           option, max_blobs);
  o->blobs[o->blob_count++] = (fog_blob){(float)v[0], (float)v[1], (float)v[2], (float)v[3]};
  return 0;
}

/* --velocity VX,VZ */
static int parse_velocity(const char *command, const char *option, const char *text,
                          void *target) {
  double v[2];
  if (parse_numbers(text, v, 2))
    return cli_usage_error(command, "%s '%s': expected VX,VZ (two decimal numbers, each at "
                           "most %g in size)", option, text, (double)FLT_MAX);
  float *velocity = target;
  velocity[0] = (float)v[0], velocity[1] = (float)v[1];
  return 0;
}

/* 0 to go on, CLI_HELP, or the exit status of a bad command line. */
static int parse_design_options(int argc, char **argv, design_options *o) {
  int size[2] = {0, 0}, seed = 1;
  bool perlin = false, half = false, seed_given = false;
  bool blob_base_given = false; /* 0 too: an option of the blobs needs blobs */
  /* the turbulence's options, in this order: given without --perlin they would do nothing */
  enum { NOISE_OPTIONS = 8 };
  bool noise_given[NOISE_OPTIONS] = {false};
  const cli_option options[] = {
      {.kind = CLI_SECTION, .name = "what:"},
      {.kind = CLI_FLAG, .name = "--perlin", .target = &perlin,
       .help = "Perlin turbulence base + gain * T(p - velocity * time)"},
      {.kind = CLI_INT, .name = "--blobs", .value = "N", .target = &o->random_blobs, .min = 1,
       .max = max_blobs, .help = "N Gaussian blobs placed at random from --seed"},
      {.kind = CLI_CUSTOM, .name = "--blob", .value = "X,Z,SIGMA,PEAK", .target = o,
       .parse = parse_blob, .repeats = true,
       .help = "one Gaussian blob (repeatable, at most 256 blobs in all)"},
      {.kind = CLI_SECTION, .name = "output:"},
      {.kind = CLI_SIZE, .name = "--size", .value = "WxH", .target = size,
       .required = true, .help = "fogmap size in cells (required)"},
      {.kind = CLI_OUTPUT, .name = "--out", .value = "FILE", .target = &o->out,
       .extensions = (const char *const[]){".exr", ".png", NULL},
       .required = true, .help = ".exr: one float channel \"Y\" (exactly what fogmap_load reads);\n"
               ".png: 16-bit grey, density / png-max * 65535 (required)"},
      {.kind = CLI_FLAG, .name = "--half", .target = &half,
       .help = "EXR: store the channel as 16-bit half floats"},
      {.kind = CLI_NUMBER, .name = "--png-max", .value = "D", .target = &o->png_max,
       .min = 1e-30, .max = 1e30,
       .help = "PNG: the density stored as 65535 (default: the map's maximum;\n"
               "load the PNG with density_scale D to get densities back)"},
      {.kind = CLI_SECTION, .name = "Perlin turbulence:"},
      {.kind = CLI_INT, .name = "--seed", .value = "N", .target = &seed, .min = 0,
       .max = 0x7fffffff, .given = &seed_given,
       .help = "permutation seed, also places random blobs (default 1;\n"
               "0 is Perlin's reference permutation)"},
      {.kind = CLI_FLOAT, .name = "--time", .value = "T", .target = &o->noise.time, .min = -1e9,
       .max = 1e9, .given = &noise_given[0], .help = "animation time (default 0)"},
      {.kind = CLI_CUSTOM, .name = "--velocity", .value = "VX,VZ", .target = o->noise.velocity,
       .parse = parse_velocity, .given = &noise_given[1],
       .help = "drift of the noise in cells per unit time (default 0,0)"},
      {.kind = CLI_FLOAT, .name = "--feature-size", .value = "S", .target = &o->noise.feature_size,
       .min = 1e-3, .max = 1e9, .given = &noise_given[2],
       .help = "noise lattice spacing in cells, the largest eddies (default 32)"},
      {.kind = CLI_INT, .name = "--octaves", .value = "N", .target = &o->noise.octaves, .min = 1,
       .max = 30, .given = &noise_given[3], .help = "turbulence octaves (default 4)"},
      {.kind = CLI_FLOAT, .name = "--gain", .value = "G", .target = &o->noise.gain, .min = 1e-9,
       .max = 1e9, .given = &noise_given[4], .help = "turbulence gain (default 1)"},
      {.kind = CLI_FLOAT, .name = "--base", .value = "B", .target = &o->noise.base, .min = 0,
       .max = 1e9, .given = &noise_given[5], .help = "density added to the turbulence (default 0)"},
      {.kind = CLI_FLOAT, .name = "--slice", .value = "S", .target = &o->noise.slice, .min = -1e9,
       .max = 1e9, .given = &noise_given[6],
       .help = "the noise's third coordinate (default 1/3: off every\n"
               "octave's lattice planes; on one, slice 0, the turbulence is 0\n"
               "on a grid one feature size apart)"},
      {.kind = CLI_FLOAT, .name = "--slice-rate", .value = "R", .target = &o->noise.slice_rate,
       .min = -1e9, .max = 1e9, .given = &noise_given[7],
       .help = "slice change per unit time: evolving, not only drifting fog"},
      {.kind = CLI_SECTION, .name = "blobs:"},
      {.kind = CLI_NUMBER, .name = "--blob-base", .value = "B", .target = &o->blob_base,
       .min = 0, .max = 1e9, .given = &blob_base_given,
       .help = "density added to the blob sum (default 0; with --perlin it\n"
               "is the turbulence left between the banks)"},
  };
  const cli_spec spec = {
      .command = "design",
      .usage = "(--perlin | --blobs N | --blob X,Z,SIGMA,PEAK)... --size WxH\n"
               "                      --out FILE.exr|FILE.png [options]",
      .about = "Writes a designed fogmap. Perlin turbulence (Perlin 2002 improved noise, summed\n"
               "over octaves, drifting with --velocity over --time as in Zdrojewska 2004), Gaussian\n"
               "blobs c*exp(-|x-b|^2/(2 sigma^2)), or, with both, the turbulence multiplied by\n"
               "(--blob-base + the blob sum): turbulence modulated by Gaussian banks.\n"
               "Positions and sizes are in fogmap cells; cell (x, z) is at (x, z), z = image row.",
      CLI_OPTIONS(options)};
  int parsed = cli_parse_one(&spec, argc, argv, NULL);
  if (parsed) return parsed;
  o->perlin = perlin, o->half = half, o->seed = seed;
  o->width = size[0], o->height = size[1];
  if (!o->perlin && !o->random_blobs && !o->blob_count)
    return cli_usage_error("design", "say what to design: --perlin, --blobs N and/or --blob X,Z,SIGMA,PEAK");
  if (o->random_blobs + o->blob_count > max_blobs)
    return cli_usage_error("design", "--blobs %d and %d --blob: %d blobs, expected at most %d",
                           o->random_blobs, o->blob_count, o->random_blobs + o->blob_count,
                           max_blobs);
  /* an option the output or the design does not use would be dropped without a word */
  const bool png = cli_ends_with(o->out, ".png");
  if (half && png) return cli_usage_error("design", "--half stores an EXR's channel: not for .png");
  if (o->png_max > 0 && !png)
    return cli_usage_error("design", "--png-max scales a .png: an EXR keeps the densities");
  if (blob_base_given && !o->random_blobs && !o->blob_count)
    return cli_usage_error("design", "--blob-base is added to the blobs: give --blob or --blobs");
  static const char *const noise_names[NOISE_OPTIONS] = {
      "--time", "--velocity", "--feature-size", "--octaves", "--gain", "--base", "--slice",
      "--slice-rate"};
  for (int i = 0; i < NOISE_OPTIONS && !o->perlin; i++)
    if (noise_given[i])
      return cli_usage_error("design", "%s shapes the Perlin turbulence: give --perlin",
                             noise_names[i]);
  if (seed_given && !o->perlin && !o->random_blobs)
    return cli_usage_error("design", "--seed draws the Perlin permutation and places random "
                           "blobs: give --perlin or --blobs N");
  return 0;
}

/* The fogmap: Perlin turbulence and/or the blobs (random banks added to the given ones),
 * the turbulence multiplied by the banks when both are asked for. */
static int design_fogmap(design_options *o, fogmap *map, fog_error *err) {
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
  o->noise.stop = stop_signals_flag(); /* Ctrl-C stops between rows, not after all of them */
  if (!status && o->perlin) status = designed_fog_perlin(map, &o->noise, err);
  if (!status && o->blob_count) {
    fogmap *target = o->perlin ? &banks : map;
    if (o->perlin) status = fogmap_create(&banks, (int)width, (int)height, err);
    blob_fog_desc blobs = blob_fog_desc_default();
    blobs.blobs = o->blobs, blobs.blob_count = o->blob_count, blobs.stop = stop_signals_flag();
    if (!status) status = designed_fog_blobs(target, &blobs, err);
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
  if (parsed) return parsed == CLI_HELP ? 0 : parsed;
  const int png = cli_ends_with(o.out, ".png");
  /* Ctrl-C or SIGTERM while designing: nothing written, exit 130 (a second one ends it at
   * once); held while the file is written, so that it is whole (a signal there left
   * .OUT.tmp.PID.N, 64 MB at 4096x4096, that no later run removes) */
  stop_signals stop;
  stop_signals_clear();
  stop_signals_catch(&stop, true);
  fog_error err;
  fogmap map = {0};
  int status = design_fogmap(&o, &map, &err);
  if (stop_signals_caught()) { /* between rows (the design fails, "stopped") or after */
    fprintf(stderr, "fogpipe design: interrupted: nothing written\n");
    stop_signals_restore(&stop);
    fogmap_destroy(&map);
    return 130;
  }
  float max = status ? 0.0f : fogmap_max_density(&map);
  /* What fogmap_load refuses (render, transform, record) is not written: a peak of 1e30
   * would make a file no other command reads. */
  if (!status && !(max <= FOGMAP_MAX_DENSITY))
    status = fog_fail(&err, FOG_ERR_INVALID_ARGUMENT,
                      "%s: the designed fog peaks at %g, above the %g a fogmap may hold "
                      "(lower the blobs' PEAK, --gain or --base)", o.out, (double)max,
                      (double)FOGMAP_MAX_DENSITY);
  if (!status && png && o.png_max > 0 && max > o.png_max) {
    size_t clipped = 0;
    for (size_t i = 0; i < (size_t)o.width * (size_t)o.height; i++)
      clipped += map.density[i] > o.png_max;
    fprintf(stderr, "fogpipe design: warning: %zu cell%s above --png-max %g (the map peaks at "
            "%g) stored as 65535, i.e. %g\n", clipped, clipped == 1 ? "" : "s", o.png_max,
            (double)max, o.png_max);
  }
  /* Half floats keep 11 bits from 6.1e-5 up (the smallest normal); below, fewer, and under
   * 2.98e-8 (half the smallest subnormal) nothing: said, as the PNG's clipping is, for the
   * cells that matter (within 2^-10 of the peak: a Gaussian's far tail does not). */
  if (!status && o.half) {
    size_t coarse = 0, zeroed = 0;
    for (size_t i = 0; i < (size_t)o.width * (size_t)o.height; i++) {
      const float v = map.density[i];
      if (!(v >= max * 0x1p-10f)) continue;
      coarse += v > 0.0f && v < 6.103515625e-05f;
      zeroed += v > 0.0f && v < 2.98023224e-08f;
    }
    if (coarse)
      fprintf(stderr, "fogpipe design: warning: --half: %zu cell%s below 6.1e-05 (the smallest "
              "normal half) stored with fewer bits, %zu of them as 0 (the map peaks at %g; "
              "without --half the EXR keeps 32-bit floats)\n", coarse, coarse == 1 ? "" : "s",
              zeroed, (double)max);
  }
  if (!status) {
    stop_signals_hold(&stop);
    if (png) {
      status = fogmap_save_png16(o.out, &map, (float)o.png_max, &err);
    } else {
      image_channel y = {.name = "Y", .pixels = map.density, .as_half = o.half};
      status = image_write_exr(o.out, map.width, map.height, &y, 1, &err);
    }
    stop_signals_release(&stop); /* one held now only sets the flag: the file is whole */
  }
  stop_signals_restore(&stop);
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
