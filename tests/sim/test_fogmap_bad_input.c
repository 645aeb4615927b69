/* Every bad input fails cleanly: non-zero status, a message naming the file and what was
 * expected (checked by substring), nothing allocated, and no output or temporary file
 * left behind (checked by listing the folder). Writers that fail (missing folder, a full
 * disk simulated with RLIMIT_FSIZE) leave an existing target byte-for-byte untouched. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <math.h>
#include <signal.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "sim/sim.h"
#include "exr_unchecked_writer.h"
#include "test_util.h"

static char folder[64];

static char *in_folder(const char *name) {
  static char path[8][256];
  static int next;
  char *p = path[next++ % 8];
  snprintf(p, 256, "%s/%s", folder, name);
  return p;
}

static void write_bytes(const char *path, const void *bytes, size_t n) {
  FILE *f = fopen(path, "wb");
  if (n) fwrite(bytes, 1, n, f);
  fclose(f);
}

static unsigned char *read_bytes(const char *path, size_t *n) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  *n = (size_t)ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char *b = malloc(*n + 1);
  *n = fread(b, 1, *n, f);
  fclose(f);
  return b;
}

/* The folder holds exactly the files named (a space-separated, sorted list). */
static void check_listing(const char *expected, const char *when) {
  char names[32][256];
  int count = 0;
  DIR *dir = opendir(folder);
  struct dirent *e;
  while (dir && (e = readdir(dir)))
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..") && count < 32)
      snprintf(names[count++], 256, "%s", e->d_name);
  if (dir) closedir(dir);
  qsort(names, (size_t)count, 256, (int (*)(const void *, const void *))strcmp);
  char listing[4096] = "";
  for (int i = 0; i < count; i++) {
    strcat(listing, i ? " " : "");
    strcat(listing, names[i]);
  }
  CHECK(!strcmp(listing, expected), "after %s the folder holds \"%s\", expected \"%s\"", when,
        listing, expected);
}

/* fogmap_load fails, nothing allocated, the message names the file and has each part. */
static void expect_failure(const char *path, const fogmap_load_desc *desc, const char *part1,
                           const char *part2, bool absent_channel) {
  fogmap map = {.width = 99, .density = (float *)&map};
  fog_error err = {0};
  int status = fogmap_load(path, desc, &map, &err);
  CHECK(status != 0, "loading %s succeeded", path);
  CHECK(map.density == NULL && map.width == 0 && map.height == 0,
        "failed load of %s left a fogmap behind", path);
  CHECK(strstr(err.message, path) != NULL, "message does not name the file: %s", err.message);
  CHECK(!part1 || strstr(err.message, part1), "message lacks \"%s\": %s", part1, err.message);
  CHECK(!part2 || strstr(err.message, part2), "message lacks \"%s\": %s", part2, err.message);
  /* a file that cannot be opened is an access failure; a channel named that the image
   * lacks, its own code (a caller tries another name); whatever else its bytes say, a bad
   * file */
  const bool unopened = part1 && (!strcmp(part1, "cannot open") || !strcmp(part1, "folder"));
  const fog_result want = unopened ? FOG_ERR_FILE_ACCESS
                          : absent_channel ? FOG_ERR_NO_SUCH_CHANNEL
                                           : FOG_ERR_BAD_FILE;
  CHECK(err.code == want, "%s: code %s, expected %s", path, fog_result_text(err.code),
        fog_result_text(want));
  printf("  ok: %s\n", err.message);
}

static void expect_load_failure(const char *path, const fogmap_load_desc *desc,
                                const char *part1, const char *part2) {
  expect_failure(path, desc, part1, part2, false);
}

/* A channel asked for by name that the image does not have. */
static void expect_absent_channel(const char *path, const char *channel, const char *part1,
                                  const char *part2) {
  expect_failure(path, &(fogmap_load_desc){.channel = channel}, part1, part2, true);
}

/* PNG chunk CRC (ISO 3309 / PNG spec 5.5), so a crafted header is valid but for its size. */
static uint32_t crc32_png(const unsigned char *p, size_t n) {
  uint32_t c = 0xffffffffu;
  for (size_t i = 0; i < n; i++) {
    c ^= p[i];
    for (int k = 0; k < 8; k++) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return c ^ 0xffffffffu;
}

static void test_bad_files(void) {
  fog_error err;
  expect_load_failure(in_folder("missing.png"), NULL, "cannot open", "No such file");
  check_listing("", "a missing file");
  expect_load_failure(folder, NULL, "folder", "PNG or EXR");

  write_bytes(in_folder("empty.exr"), "", 0);
  expect_load_failure(in_folder("empty.exr"), NULL, "empty", "PNG or EXR");
  write_bytes(in_folder("notes.png"), "density = 1.0\n", 14);
  expect_load_failure(in_folder("notes.png"), NULL, "not a PNG or EXR", "text");
  const unsigned char jpeg[] = {0xff, 0xd8, 0xff, 0xe0, 0, 0x10, 'J', 'F', 'I', 'F'};
  write_bytes(in_folder("photo.png"), jpeg, sizeof jpeg);
  expect_load_failure(in_folder("photo.png"), NULL, "not a PNG or EXR", "JPEG");
  const unsigned char vdb[] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0, 0xdd, 0, 0, 0};
  write_bytes(in_folder("smoke.exr"), vdb, sizeof vdb);
  expect_load_failure(in_folder("smoke.exr"), NULL, "not a PNG or EXR", "OpenVDB");

  /* zero-size PNG: a valid signature and IHDR chunk (correct CRC) with width 0 */
  unsigned char png[8 + 25] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13,
                               'I',  'H', 'D', 'R', 0,    0,    0,    0,    0, 0, 0, 5,
                               16,   0,   0,   0,   0};
  uint32_t crc = crc32_png(png + 12, 17);
  png[29] = (unsigned char)(crc >> 24), png[30] = (unsigned char)(crc >> 16);
  png[31] = (unsigned char)(crc >> 8), png[32] = (unsigned char)crc;
  write_bytes(in_folder("zero.png"), png, sizeof png);
  expect_load_failure(in_folder("zero.png"), NULL, "size", "width");

  /* truncated files: a real PNG and a real EXR cut short */
  float ramp[64 * 64];
  for (int i = 0; i < 64 * 64; i++) ramp[i] = (float)(i % 61) / 60.0f;
  CHECK(image_write_png(in_folder("ok.png"), 64, 64, 1, ramp, &err) == 0, "%s", err.message);
  fogmap ramp_map = {.width = 64, .height = 64, .density = ramp};
  CHECK(fogmap_save_exr(in_folder("ok.exr"), &ramp_map, &err) == 0, "%s", err.message);
  size_t n = 0;
  unsigned char *bytes = read_bytes(in_folder("ok.png"), &n);
  write_bytes(in_folder("cut.png"), bytes, n / 2);
  free(bytes);
  expect_load_failure(in_folder("cut.png"), NULL, "PNG", NULL);
  bytes = read_bytes(in_folder("ok.exr"), &n);
  write_bytes(in_folder("cut.exr"), bytes, n * 2 / 3);
  write_bytes(in_folder("header.exr"), bytes, 40);
  free(bytes);
  expect_load_failure(in_folder("cut.exr"), NULL, "EXR", NULL);
  expect_load_failure(in_folder("header.exr"), NULL, "EXR", NULL);

  /* channels: ambiguous or absent names list what exists */
  float rgb[8 * 8 * 3] = {0};
  CHECK(image_write_png(in_folder("rgb.png"), 8, 8, 3, rgb, &err) == 0, "%s", err.message);
  expect_load_failure(in_folder("rgb.png"), NULL, "\"R\", \"G\", \"B\"", "RGB");
  expect_absent_channel(in_folder("rgb.png"), "A", "\"A\"", "\"R\", \"G\", \"B\"");
  expect_absent_channel(in_folder("ok.png"), "R", "no channel", "\"grey\"");
  image_channel three[3] = {{"depth", ramp, 0}, {"B", ramp, 1}, {"A", ramp, 0}};
  CHECK(image_write_exr(in_folder("three.exr"), 64, 64, three, 3, &err) == 0, "%s",
        err.message);
  expect_load_failure(in_folder("three.exr"), NULL, "3 channels", "\"A\", \"B\", \"depth\"");
  expect_absent_channel(in_folder("three.exr"), "Y", "\"Y\"", "\"A\", \"B\", \"depth\"");

  /* bad densities: the first offending pixel is named (x, y) with its value */
  float bad[16 * 8];
  for (int i = 0; i < 16 * 8; i++) bad[i] = 0.25f;
  bad[5 * 16 + 3] = NAN;
  bad[6 * 16 + 9] = -2.0f;
  fogmap bad_map = {.width = 16, .height = 8, .density = bad};
  CHECK(fogmap_save_exr(in_folder("nan.exr"), &bad_map, &err) != 0 &&
            strstr(err.message, "pixel (3, 5) of channel \"Y\" is NaN"),
        "the writer wrote a NaN pixel: %s", err.message);
  CHECK(exr_write_unchecked(in_folder("nan.exr"), "Y", 16, 8, bad) == 0, "cannot write nan.exr");
  expect_load_failure(in_folder("nan.exr"), NULL, "pixel (3, 5)", "NaN");
  bad[5 * 16 + 3] = 0.0f;
  bad[2 * 16 + 7] = -0.5f;
  image_channel half = {.name = "Y", .pixels = bad, .as_half = 1};
  CHECK(image_write_exr(in_folder("negative.exr"), 16, 8, &half, 1, &err) == 0, "%s",
        err.message);
  expect_load_failure(in_folder("negative.exr"), NULL, "pixel (7, 2)", "negative (-0.5)");
  bad[2 * 16 + 7] = INFINITY;
  CHECK(fogmap_save_exr(in_folder("inf.exr"), &bad_map, &err) != 0 &&
            strstr(err.message, "pixel (7, 2) of channel \"Y\" is infinite"),
        "the writer wrote an infinite pixel: %s", err.message);
  CHECK(exr_write_unchecked(in_folder("inf.exr"), "Y", 16, 8, bad) == 0, "cannot write inf.exr");
  expect_load_failure(in_folder("inf.exr"), NULL, "pixel (7, 2)", "infinite");
  bad[2 * 16 + 7] = 3e38f; /* finite, but overflows the transforms and the renderer */
  CHECK(fogmap_save_exr(in_folder("huge.exr"), &bad_map, &err) == 0, "%s", err.message);
  expect_load_failure(in_folder("huge.exr"), NULL, "pixel (7, 2)", "too large");

  check_listing("cut.exr cut.png empty.exr header.exr huge.exr inf.exr nan.exr negative.exr notes.png "
                "ok.exr ok.png photo.png rgb.png smoke.exr three.exr zero.png",
                "the bad-file cases");
  const char *made[] = {"cut.exr",  "cut.png",   "empty.exr", "header.exr", "huge.exr", "inf.exr",
                        "nan.exr",  "negative.exr", "notes.png", "ok.exr",  "ok.png",
                        "photo.png", "rgb.png",  "smoke.exr", "three.exr", "zero.png"};
  for (size_t i = 0; i < sizeof made / sizeof made[0]; i++) unlink(in_folder(made[i]));
}

/* A failed write leaves no file, or the old one untouched, and no temporary. */
static void expect_write_failure(int status, const fog_error *err, const char *path,
                                 const char *part1, const char *part2) {
  CHECK(status != 0, "writing %s succeeded", path);
  CHECK(strstr(err->message, path) != NULL, "message does not name the file: %s",
        err->message);
  CHECK(!part1 || strstr(err->message, part1), "message lacks \"%s\": %s", part1,
        err->message);
  CHECK(!part2 || strstr(err->message, part2), "message lacks \"%s\": %s", part2,
        err->message);
  /* the file system refused, or the caller passed pixels no image can hold */
  const bool refused = part1 && (!strcmp(part1, "cannot create") || !strcmp(part1, "write failed"));
  const fog_result want = refused ? FOG_ERR_FILE_ACCESS : FOG_ERR_INVALID_ARGUMENT;
  CHECK(err->code == want, "%s: code %s, expected %s", path, fog_result_text(err->code),
        fog_result_text(want));
  printf("  ok: %s\n", err->message);
}

static void test_failed_writes(void) {
  const int w = 256, h = 256;
  float *noise = malloc(sizeof(float) * w * h * 3);
  uint32_t s = 99;
  for (int i = 0; i < w * h * 3; i++) {
    s = s * 1664525u + 1013904223u;
    noise[i] = (float)(s >> 8) / 16777216.0f; /* incompressible: ~256 KiB as float EXR */
  }
  fogmap map = {.width = w, .height = h, .density = noise};
  fog_error err;

  /* a folder that does not exist, and a "folder" that is a file */
  char *nowhere = in_folder("no/such/folder/out.exr");
  expect_write_failure(fogmap_save_exr(nowhere, &map, &err), &err, nowhere, "cannot create",
                       "No such file");
  char *png_nowhere = in_folder("missing/out.png");
  expect_write_failure(image_write_png(png_nowhere, w, h, 1, noise, &err), &err, png_nowhere,
                       "cannot create", "missing");
  write_bytes(in_folder("plain"), "x", 1);
  char *under_file = in_folder("plain/out.exr");
  expect_write_failure(fogmap_save_exr(under_file, &map, &err), &err, under_file,
                       "cannot create", "Not a directory");
  unlink(in_folder("plain"));
  check_listing("", "writes into missing folders");

  /* a full disk: RLIMIT_FSIZE makes writes past 16 KiB fail (EFBIG) like ENOSPC would */
  const char *old = "previous contents\n";
  char *exr = in_folder("target.exr"), *png = in_folder("target.png");
  write_bytes(exr, old, strlen(old));
  write_bytes(png, old, strlen(old));
  signal(SIGXFSZ, SIG_IGN);
  struct rlimit saved;
  getrlimit(RLIMIT_FSIZE, &saved);
  struct rlimit small = {.rlim_cur = 16384, .rlim_max = saved.rlim_max};
  CHECK(setrlimit(RLIMIT_FSIZE, &small) == 0, "setrlimit failed");
  int exr_status = fogmap_save_exr(exr, &map, &err);
  fog_error exr_err = err;
  int png_status = image_write_png(png, w, h, 3, noise, &err);
  fog_error png_err = err;
  image_channel two[2] = {{"R", noise, 1}, {"G", noise + w * h, 0}};
  int multi_status = image_write_exr(exr, w, h, two, 2, &err);
  fog_error multi_err = err;
  setrlimit(RLIMIT_FSIZE, &saved);
  signal(SIGXFSZ, SIG_DFL);
  expect_write_failure(exr_status, &exr_err, exr, "write failed", "File too large");
  expect_write_failure(png_status, &png_err, png, "write failed", "File too large");
  expect_write_failure(multi_status, &multi_err, exr, "write failed", "File too large");
  size_t n = 0;
  unsigned char *kept = read_bytes(exr, &n);
  CHECK(kept && n == strlen(old) && !memcmp(kept, old, n), "failed EXR write changed target");
  free(kept);
  kept = read_bytes(png, &n);
  CHECK(kept && n == strlen(old) && !memcmp(kept, old, n), "failed PNG write changed target");
  free(kept);
  check_listing("target.exr target.png", "writes to a full disk");

  /* the same writes with room succeed and replace the targets atomically */
  CHECK(fogmap_save_exr(exr, &map, &err) == 0, "%s", err.message);
  CHECK(image_write_png(png, w, h, 3, noise, &err) == 0, "%s", err.message);
  check_listing("target.exr target.png", "successful overwrites");
  fogmap back;
  CHECK(fogmap_load(exr, NULL, &back, &err) == 0, "%s", err.message);
  CHECK(back.density && !memcmp(back.density, noise, sizeof(float) * w * h),
        "overwritten EXR differs");
  fogmap_destroy(&back);

  /* invalid requests fail before touching the disk */
  expect_write_failure(image_write_png(png, w, h, 2, noise, &err), &err, png, "1 (grey)", NULL);
  expect_write_failure(image_write_exr(exr, 0, h, two, 1, &err), &err, exr, "positive", NULL);
  image_channel twice[2] = {{"R", noise, 0}, {"R", noise, 1}};
  expect_write_failure(image_write_exr(exr, w, h, twice, 2, &err), &err, exr, "twice", NULL);
  check_listing("target.exr target.png", "invalid write requests");
  unlink(exr);
  unlink(png);
  free(noise);
}

int main(void) {
  snprintf(folder, sizeof folder, "/tmp/fogmap_bad_input.XXXXXX");
  if (!test_scratch_folder(folder)) return 1;
  test_bad_files();
  test_failed_writes();
  CHECK(rmdir(folder) == 0, "temporary folder %s not empty afterwards", folder);
  return test_finish("test_fogmap_bad_input");
}
