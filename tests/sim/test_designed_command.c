/* `fogpipe design` (run as $FOGPIPE_BIN): its EXR output is bit-identical to the designed
 * fog computed here with the library, its PNG output is that within 16-bit quantisation,
 * bad options fail with a clear message, a non-zero exit and no file; and the committed
 * sample fogmaps load and agree with each other. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sim/designed_fog.h"
#include "sim/fogmap.h"
#include "test_bin.h"
#include "test_util.h"

static char folder[64];
static const char *bin;

/* Runs `$FOGPIPE_BIN design ARGS`, returns the exit status and the combined output. */
static int run_design(const char *args, char *output, size_t size) {
  char command[2048];
  snprintf(command, sizeof command, "'%s' design %s 2>&1", bin, args);
  return test_run_output(command, output, size);
}

static void test_output_matches_library(void) {
  char path[256], args[1024], output[4096];
  snprintf(path, sizeof path, "%s/designed.exr", folder);
  snprintf(args, sizeof args,
           "--perlin --seed 11 --octaves 3 --feature-size 20 --velocity 1.5,-2 --time 3 "
           "--base 0.1 --gain 0.8 --slice 0.3 --blob 20,15,6,1 --blob 40.5,30,9,0.5 "
           "--blob-base 0.2 --size 64x48 --out '%s'",
           path);
  int status = run_design(args, output, sizeof output);
  CHECK(status == 0, "design exited %d: %s", status, output);

  /* the same fog with the library */
  fogmap expect, banks;
  fog_error err;
  fogmap_create(&expect, 64, 48, &err);
  fogmap_create(&banks, 64, 48, &err);
  designed_fog_perlin(&expect, &(perlin_fog_desc){.seed = 11, .octaves = 3, .feature_size = 20,
                                                  .velocity = {1.5f, -2}, .time = 3,
                                                  .base = 0.1f, .gain = 0.8f, .slice = 0.3f},
                      &err);
  fog_blob blobs[2] = {{20, 15, 6, 1}, {40.5f, 30, 9, 0.5f}};
  designed_fog_blobs(&banks,
                     &(blob_fog_desc){.blobs = blobs, .blob_count = 2, .cutoff = BLOB_FOG_CUTOFF},
                     &err);
  for (int i = 0; i < 64 * 48; i++) banks.density[i] += 0.2f;
  designed_fog_multiply(&expect, &banks, &err);

  fogmap got;
  CHECK(fogmap_load(path, NULL, &got, &err) == 0, "load: %s", err.message);
  CHECK(got.density && got.width == 64 && got.height == 48 &&
            !memcmp(got.density, expect.density, sizeof(float) * 64 * 48),
        "fogpipe design EXR differs from the library's fog");
  fogmap_destroy(&got);
  unlink(path);

  /* PNG: 16-bit, full scale --png-max */
  snprintf(path, sizeof path, "%s/designed.png", folder);
  snprintf(args, sizeof args,
           "--perlin --seed 11 --octaves 3 --feature-size 20 --velocity 1.5,-2 --time 3 "
           "--base 0.1 --gain 0.8 --slice 0.3 --blob 20,15,6,1 --blob 40.5,30,9,0.5 "
           "--blob-base 0.2 --size 64x48 --png-max 2 --out '%s'",
           path);
  status = run_design(args, output, sizeof output);
  CHECK(status == 0 && strstr(output, "density_scale 2"), "design exited %d: %s", status,
        output);
  CHECK(fogmap_load(path, NULL, &got, &err) == 0 && fogmap_scale(&got, 2.0, &err) == 0,
        "load: %s", err.message);
  double worst = 0;
  for (int i = 0; got.density && i < 64 * 48; i++)
    worst = fmax(worst, fabs((double)got.density[i] - expect.density[i]));
  CHECK(got.density && worst <= 2.0 / 65535 / 2 * 1.0001, "PNG off by %g > half a step", worst);
  fogmap_destroy(&got);
  unlink(path);
  fogmap_destroy(&expect);
  fogmap_destroy(&banks);
}

static void test_bad_options(void) {
  char path[256], args[512], output[4096];
  snprintf(path, sizeof path, "%s/bad.exr", folder);
  const struct {
    const char *args, *expect;
  } cases[] = {
      {"--perlin --size 0x5", "--size"},
      {"--perlin --size 64x64 --bogus 3", "unknown option '--bogus'"},
      {"--perlin --size 64x64 --octaves many", "--octaves"},
      {"--blob 1,2,0,1 --size 64x64", "SIGMA >= 1e-6"},
      {"--size 64x64", "--perlin"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    snprintf(args, sizeof args, "%s --out '%s'", cases[i].args, path);
    int status = run_design(args, output, sizeof output);
    CHECK(status != 0, "'%s' exited 0", cases[i].args);
    CHECK(strstr(output, "fogpipe design: ") && strstr(output, cases[i].expect),
          "'%s' said \"%s\", expected a message with \"%s\"", cases[i].args, output,
          cases[i].expect);
    CHECK(access(path, F_OK) != 0, "'%s' left %s behind", cases[i].args, path);
  }
  int status = run_design("--help", output, sizeof output);
  const char *options[] = {"--perlin", "--blobs", "--blob ",  "--size",    "--out",
                           "--half",   "--png-max", "--seed", "--time",   "--velocity",
                           "--feature-size", "--octaves", "--gain", "--base",
                           "--slice ", "--slice-rate", "--blob-base", "--help"};
  CHECK(status == 0, "--help exited %d", status);
  for (size_t i = 0; i < sizeof options / sizeof options[0]; i++)
    CHECK(strstr(output, options[i]), "--help does not list %s", options[i]);
}

static void test_sample_data(void) {
  fogmap png, exr;
  fog_error err;
  CHECK(fogmap_load("data/fogmap_sample.png", NULL, &png, &err) == 0, "%s", err.message);
  CHECK(fogmap_load("data/fogmap_sample.exr", NULL, &exr, &err) == 0, "%s", err.message);
  CHECK(png.width == 256 && png.height == 256 && exr.width == 256 && exr.height == 256,
        "sample sizes");
  double worst = 0, max = 0;
  for (int i = 0; png.density && exr.density && i < 256 * 256; i++) {
    worst = fmax(worst, fabs((double)png.density[i] - exr.density[i]));
    max = fmax(max, exr.density[i]);
  }
  CHECK(worst <= 0.5 / 65535 * 1.0001, "sample PNG and EXR differ by %g", worst);
  CHECK(max > 0.5 && max <= 1.0, "sample EXR maximum %g (the PNG's full scale is 1)", max);
  fogmap_destroy(&png);
  fogmap_destroy(&exr);
}

/* --half: a map whose cells that matter lie below the smallest normal half (6.1e-5) is
 * written with a warning naming the loss (a peak of 1e-9 stored as all zeros); a map
 * peaking at 1, whose Gaussian tails alone go below it, without one. The half file holds
 * what the warning says. */
static void test_half_precision(void) {
  char path[256], args[512], output[4096];
  snprintf(path, sizeof path, "%s/half.exr", folder);
  snprintf(args, sizeof args, "--blob 1,1,1,1e-9 --size 4x4 --half --out '%s'", path);
  int status = run_design(args, output, sizeof output);
  CHECK(status == 0 && strstr(output, "warning: --half: 16 cells below 6.1e-05") &&
            strstr(output, "16 of them as 0"),
        "a 1e-9 peak in half floats: exit %d, %s", status, output);
  fogmap map = {0};
  fog_error err = {0};
  CHECK(fogmap_load(path, NULL, &map, &err) == 0 && fogmap_max_density(&map) == 0.0f,
        "the half file: %s, peak %g", err.message, map.density ? fogmap_max_density(&map) : -1);
  fogmap_destroy(&map);
  unlink(path);
  snprintf(args, sizeof args, "--blob 8,8,3,1 --size 16x16 --half --out '%s'", path);
  status = run_design(args, output, sizeof output);
  CHECK(status == 0 && !strstr(output, "warning"), "a peak of 1 in half floats: %s", output);
  unlink(path);
}

int main(void) {
  bin = getenv("FOGPIPE_BIN");
  if (!bin || access(bin, X_OK) != 0) {
    fprintf(stderr, "FOGPIPE_BIN is not set to the fogpipe binary\n");
    return 1;
  }
  snprintf(folder, sizeof folder, "/tmp/fogmap_design.XXXXXX");
  if (!mkdtemp(folder)) return 1;
  test_output_matches_library();
  test_bad_options();
  test_sample_data();
  test_half_precision();
  CHECK(rmdir(folder) == 0, "temporary folder %s not empty afterwards", folder);
  return test_finish("test_designed_command");
}
