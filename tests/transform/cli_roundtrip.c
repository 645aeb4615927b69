/* `fogpipe transform` end to end (FOGPIPE_BIN): forward to a folder and --inverse back
 * reproduce the fogmap (<= 1e-6 relative) for every basis, both modes and both
 * decompositions; bad input (a missing file, too many levels, a folder missing a band, an
 * --inverse --out that is a file of its folder, a forward input that it would write) fails with a message naming the file, a
 * non-zero exit, and writes nothing; --out's parents are made, and a shallower transform
 * removes the deeper levels an earlier one left; an inverse of a map at the largest density
 * loads again; approx_J.exr is the input, bit for bit. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sim/image_io.h" /* exr_read_channel: a detail file read as it is, signed */
#include "sim/sim.h"
#include "tests/sim/exr_unchecked_writer.h" /* NaN and infinity, as a damaged file */
#include "test_util.h"

static char tmp[256];
static const char *bin;

static int run(const char *args, char *err_text, size_t err_size) {
  char cmd[2048], errfile[300];
  snprintf(errfile, sizeof errfile, "%s/stderr.txt", tmp);
  snprintf(cmd, sizeof cmd, "%s transform %s 2> %s", bin, args, errfile);
  int rc = system(cmd);
  FILE *f = fopen(errfile, "r");
  size_t n = f ? fread(err_text, 1, err_size - 1, f) : 0;
  err_text[n] = 0;
  if (f) fclose(f);
  return rc;
}

static int exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

/* fogpipe transform ARGS fails saying `why`, and leaves `kept` as it was (size and time). */
static void refused_and_kept(const char *args, const char *kept, const char *why) {
  struct stat before, after;
  char err[4096];
  CHECK(stat(kept, &before) == 0, "no %s", kept);
  int rc = run(args, err, sizeof err);
  CHECK(rc != 0 && strstr(err, why), "transform %s (%d): %s", args, rc, err);
  CHECK(stat(kept, &after) == 0 && after.st_size == before.st_size &&
            after.st_mtim.tv_sec == before.st_mtim.tv_sec &&
            after.st_mtim.tv_nsec == before.st_mtim.tv_nsec,
        "%s was rewritten", kept);
}

static void roundtrip(const char *options, const char *name) {
  char args[1024], err[4096], dir[300], out[300];
  snprintf(dir, sizeof dir, "%s/%s", tmp, name);
  snprintf(out, sizeof out, "%s/%s.exr", tmp, name);
  snprintf(args, sizeof args, "data/fogmap_sample.exr %s --out %s", options, dir);
  int rc = run(args, err, sizeof err);
  CHECK(rc == 0, "forward %s failed: %s", options, err);
  snprintf(args, sizeof args, "--inverse %s --out %s", dir, out);
  rc = run(args, err, sizeof err);
  CHECK(rc == 0, "inverse %s failed: %s", options, err);
  fogmap a, b;
  fog_error e;
  if (fogmap_load("data/fogmap_sample.exr", NULL, &a, &e)) {
    CHECK(0, "%s", e.message);
    return;
  }
  if (fogmap_load(out, NULL, &b, &e)) {
    CHECK(0, "%s", e.message);
    fogmap_destroy(&a);
    return;
  }
  CHECK(a.width == b.width && a.height == b.height, "%s: size changed", options);
  double worst = 0.0, scale = 0.0;
  for (size_t i = 0; a.width == b.width && i < (size_t)a.width * a.height; i++) {
    worst = fmax(worst, fabs((double)a.density[i] - b.density[i]));
    scale = fmax(scale, fabs((double)a.density[i]));
  }
  CHECK(worst <= 1e-6 * scale, "%s: round trip error %.3g (max density %.3g)", options, worst,
        scale);
  fogmap_destroy(&a);
  fogmap_destroy(&b);
}

/* The finest level, approx_J.exr, of a forward of `input` is the input itself: a fogmap,
 * bit for bit. It was the reconstruction, whose rounding took the ground fog's zeros to
 * -1e-9, which fogmap_load refuses. */
static void finest_is_input(const char *input, const char *options, int J, const char *name) {
  char args[1024], err[4096], dir[300], finest[400];
  snprintf(dir, sizeof dir, "%s/%s", tmp, name);
  snprintf(args, sizeof args, "%s %s --out %s", input, options, dir);
  CHECK(run(args, err, sizeof err) == 0, "forward %s failed: %s", options, err);
  snprintf(finest, sizeof finest, "%s/approx_%d.exr", dir, J);
  fogmap a, top;
  fog_error e;
  if (fogmap_load(input, NULL, &a, &e)) {
    CHECK(0, "%s", e.message);
    return;
  }
  if (fogmap_load(finest, NULL, &top, &e)) {
    CHECK(0, "%s: %s", options, e.message);
  } else {
    CHECK(top.width == a.width && top.height == a.height &&
              !memcmp(top.density, a.density, sizeof(float) * a.width * a.height),
          "%s: %s is not the input", options, finest);
    fogmap_destroy(&top);
  }
  fogmap_destroy(&a);
}

int main(void) {
  bin = getenv("FOGPIPE_BIN");
  if (!bin) {
    fprintf(stderr, "FOGPIPE_BIN not set\n");
    return 1;
  }
  snprintf(tmp, sizeof tmp, "/tmp/fogpipe_transform_cli_XXXXXX");
  CHECK(mkdtemp(tmp) != NULL, "mkdtemp");
  roundtrip("--basis haar --levels 3", "haar");
  roundtrip("--basis linear --levels 8", "linear_full");
  roundtrip("--basis quadratic --levels 4 --standard", "quadratic_standard");
  finest_is_input("data/fogmap_groundfog.exr", "--basis linear --levels 3", 3, "groundfog_linear");
  finest_is_input("data/fogmap_groundfog.exr", "--basis quadratic --levels 2", 2, "groundfog_quad");
  roundtrip("--basis linear --levels 5 --mode periodic --threads 2", "linear_periodic");

  char err[4096], args[1024], dir[300];
  /* a missing input file */
  snprintf(dir, sizeof dir, "%s/missing", tmp);
  snprintf(args, sizeof args, "data/no_such_fogmap.exr --levels 2 --out %s", dir);
  int rc = run(args, err, sizeof err);
  CHECK(rc != 0, "missing input accepted");
  CHECK(strstr(err, "fogpipe transform: data/no_such_fogmap.exr:") == err, "message: %s", err);
  CHECK(!exists(dir), "output folder created for a failed run");
  /* too many levels: the message names the largest J (256x256: 8) */
  snprintf(dir, sizeof dir, "%s/toodeep", tmp);
  snprintf(args, sizeof args, "data/fogmap_sample.exr --levels 12 --out %s", dir);
  rc = run(args, err, sizeof err);
  CHECK(rc != 0, "12 levels accepted for 256x256");
  CHECK(strstr(err, "fogpipe transform: data/fogmap_sample.exr:") == err &&
            strstr(err, "largest J that fits is 8"), "message: %s", err);
  CHECK(!exists(dir), "output folder created for a failed run");
  /* a folder missing one band */
  char band[400], out[300];
  snprintf(band, sizeof band, "%s/haar/detail_2_xy.exr", tmp);
  CHECK(unlink(band) == 0, "cannot remove %s", band);
  snprintf(out, sizeof out, "%s/broken.exr", tmp);
  snprintf(args, sizeof args, "--inverse %s/haar --out %s", tmp, out);
  rc = run(args, err, sizeof err);
  CHECK(rc != 0, "inverse of an incomplete folder accepted");
  CHECK(strstr(err, "detail_2_xy.exr") != NULL, "message does not name the file: %s", err);
  CHECK(!strstr(err, "EXR_ERR"), "OpenEXR's own message printed beside ours: %s", err);
  CHECK(!exists(out), "output written by a failed inverse");

  /* the folder with its parents; then a shallower transform into it: the deeper levels
   * an earlier run left are removed, not kept beside a transform.ini of fewer levels */
  snprintf(dir, sizeof dir, "%s/a/b/levels", tmp);
  snprintf(args, sizeof args, "data/fogmap_sample.exr --levels 3 --out %s", dir);
  rc = run(args, err, sizeof err);
  CHECK(rc == 0, "into a folder whose parents do not exist: %s", err);
  snprintf(args, sizeof args, "data/fogmap_sample.exr --levels 1 --out %s", dir);
  rc = run(args, err, sizeof err);
  CHECK(rc == 0, "the shallower transform: %s", err);
  static const char *const stale[] = {"approx_2.exr", "approx_3.exr", "deconstructed_2.exr",
                                      "detail_2_x.exr", "detail_3_xy.exr"};
  for (size_t k = 0; k < sizeof stale / sizeof stale[0]; k++) {
    char path[600];
    snprintf(path, sizeof path, "%s/%s", dir, stale[k]);
    CHECK(!exists(path), "%s of the 3-level transform left beside the 1-level one", stale[k]);
  }
  char kept[600];
  snprintf(kept, sizeof kept, "%s/detail_1_xy.exr", dir);
  CHECK(exists(kept), "the 1-level transform's own detail_1_xy.exr is missing");

  /* --inverse's --out a file of the folder it reads: refused before it replaces it */
  snprintf(out, sizeof out, "%s/linear_full/approx_0.exr", tmp);
  snprintf(args, sizeof args, "--inverse %s/linear_full --out %s", tmp, out);
  refused_and_kept(args, out, "a file of the --inverse folder");

  /* the forward input is a file the transform would write (the sample map copied in as
   * own/approx_0.exr): refused, the input kept */
  char own[400], copy[900];
  snprintf(own, sizeof own, "%s/own/approx_0.exr", tmp);
  snprintf(copy, sizeof copy, "mkdir -p '%s/own' && cp data/fogmap_sample.exr '%s'", tmp, own);
  CHECK(system(copy) == 0, "cannot make %s", own);
  snprintf(args, sizeof args, "%s --levels 1 --out %s/own", own, tmp);
  refused_and_kept(args, own, "is the input fogmap");

  /* a forward run that cannot finish (a folder where its detail_2_xy.exr goes) replaces
   * nothing of the transform in the folder: its manifest and levels as they were, and the
   * folder still inverts to its own input */
  {
    char folder[400], manifest[500], approx[500], blocker[1000], back[500];
    snprintf(folder, sizeof folder, "%s/linear_full", tmp);
    snprintf(manifest, sizeof manifest, "%s/transform.ini", folder);
    snprintf(approx, sizeof approx, "%s/approx_0.exr", folder);
    snprintf(blocker, sizeof blocker, "rm -f '%s/detail_2_xy.exr' && mkdir -p '%s/detail_2_xy.exr/x'",
             folder, folder);
    struct stat m0, a0, m1, a1;
    stat(manifest, &m0), stat(approx, &a0);
    CHECK(system(blocker) == 0, "%s", blocker);
    snprintf(args, sizeof args, "data/fogmap_sample.exr --basis haar --levels 3 --out %s",
             folder);
    rc = run(args, err, sizeof err);
    CHECK(rc != 0 && strstr(err, "detail_2_xy.exr"), "a folder in the way (%d): %s", rc, err);
    CHECK(stat(manifest, &m1) == 0 && stat(approx, &a1) == 0 && m1.st_ino == m0.st_ino &&
              m1.st_mtime == m0.st_mtime && a1.st_ino == a0.st_ino && a1.st_size == a0.st_size,
          "the failed forward replaced the folder's transform.ini or approx_0.exr");
    DIR *d = opendir(folder);
    int hidden = 0;
    for (struct dirent *e; d && (e = readdir(d));)
      hidden += e->d_name[0] == '.' && strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    if (d) closedir(d);
    CHECK(hidden == 0, "%d hidden files or folders left in %s", hidden, folder);
    snprintf(back, sizeof back, "rm -rf '%s/detail_2_xy.exr'", folder);
    CHECK(system(back) == 0, "%s", back);
    /* a hand-edited transform.ini read strictly by --inverse: a key twice (the last one
     * won), a degree against the basis, a line before any section, an unknown key, a
     * missing key named; each refused, no output written (they used to invert to
     * something else, exit 0) */
    static const struct {
      const char *edit, *says;
    } edits[] = {
        {"sed -i 's/^basis = .*/&\\nbasis = haar/'", "[transform] basis: given twice"},
        {"sed -i 's/^degree = .*/degree = 0/'", "degree = 0 contradicts basis"},
        {"sed -i '1i garbage'", ":1: expected a comment or '[transform]' first"},
        {"sed -i 's/^mode = /mood = /'", "[transform] mood: unknown key"},
        {"sed -i '/^levels = /d'", "(missing: levels)"},
        /* at most 60 (--levels' own limit): 1000000 stalled --inverse 25 s on its names */
        {"sed -i 's/^levels = .*/levels = 1000000/'", "bad value \"1000000\" for levels"},
    };
    char saved[400], edit[2400], inverse_out[400];
    snprintf(saved, sizeof saved, "%s/transform.ini.saved", tmp);
    snprintf(inverse_out, sizeof inverse_out, "%s/edited.exr", tmp);
    snprintf(edit, sizeof edit, "cp '%s' '%s'", manifest, saved);
    CHECK(system(edit) == 0, "%s", edit);
    for (int e = 0; e < (int)(sizeof edits / sizeof edits[0]); e++) {
      snprintf(edit, sizeof edit, "cp '%s' '%s' && %s '%s'", saved, manifest, edits[e].edit,
               manifest);
      CHECK(system(edit) == 0, "%s", edit);
      snprintf(args, sizeof args, "--inverse %s --out %s", folder, inverse_out);
      rc = run(args, err, sizeof err);
      CHECK(rc != 0 && strstr(err, edits[e].says) && !exists(inverse_out),
            "edit %d (%s): exit %d, stderr %s", e, edits[e].edit, rc, err);
    }
    snprintf(edit, sizeof edit, "mv '%s' '%s'", saved, manifest);
    CHECK(system(edit) == 0, "%s", edit);
  }

  /* a map at fogmap_load's largest density (1e12): the quadratic inverse's rounding came
   * back just above it (1.0000003e12), a file no command could load */
  char peak[400], peak_dir[400], peak_out[400], design[1200];
  snprintf(peak, sizeof peak, "%s/peak.exr", tmp);
  snprintf(peak_dir, sizeof peak_dir, "%s/peak", tmp);
  snprintf(peak_out, sizeof peak_out, "%s/peak_back.exr", tmp);
  snprintf(design, sizeof design, "'%s' design --blob 3,3,2,1e12 --size 16x16 --out '%s' > /dev/null",
           bin, peak);
  CHECK(system(design) == 0, "%s", design);
  snprintf(args, sizeof args, "%s --levels 3 --basis quadratic --out %s", peak, peak_dir);
  rc = run(args, err, sizeof err);
  CHECK(rc == 0, "forward of the 1e12 peak: %s", err);
  snprintf(args, sizeof args, "--inverse %s --out %s", peak_dir, peak_out);
  rc = run(args, err, sizeof err);
  CHECK(rc == 0, "inverse of the 1e12 peak: %s", err);
  fogmap back = {0};
  fog_error lerr = {0};
  CHECK(fogmap_load(peak_out, NULL, &back, &lerr) == 0, "the inverse does not load: %s",
        lerr.message);
  fogmap_destroy(&back);

  /* a coefficient file holding a NaN (or an infinity): refused naming the file and the
   * cell, nothing written; the inverse made the NaN 0 (a hole in the fog), exit 0 */
  const float bad_values[] = {NAN, INFINITY};
  for (int b = 0; b < 2; b++) {
    char detail[500], damaged_out[400];
    snprintf(detail, sizeof detail, "%s/detail_1_x.exr", peak_dir);
    snprintf(damaged_out, sizeof damaged_out, "%s/damaged_%d.exr", tmp, b);
    int w = 0, h = 0;
    float *values = NULL;
    CHECK(exr_read_channel(detail, "Y", NULL, &w, &h, &values, &lerr) == 0, "%s: %s", detail,
          lerr.message);
    if (!values) break;
    values[(size_t)w + 1] = bad_values[b]; /* x 1, y 1 */
    CHECK(exr_write_unchecked(detail, "Y", w, h, values) == 0, "cannot write %s", detail);
    free(values);
    snprintf(args, sizeof args, "--inverse %s --out %s", peak_dir, damaged_out);
    rc = run(args, err, sizeof err);
    CHECK(rc != 0 && strstr(err, "detail_1_x.exr") && strstr(err, "x 1, y 1") &&
              strstr(err, "finite"),
          "an inverse of a coefficient %g (%d): %s", bad_values[b], rc, err);
    CHECK(!exists(damaged_out), "output written by the inverse of a damaged folder");
  }

  /* an input named with a line break: the folder's transform.ini still reads back (the name
   * went raw into its comment line, and the line after it was refused) */
  {
    char odd[400], odd_dir[400], odd_out[400], copy_cmd[1200];
    snprintf(odd, sizeof odd, "%s/bad\nname.exr", tmp);
    snprintf(odd_dir, sizeof odd_dir, "%s/odd", tmp);
    snprintf(odd_out, sizeof odd_out, "%s/odd.exr", tmp);
    snprintf(copy_cmd, sizeof copy_cmd, "cp data/fogmap_sample.exr '%s'", odd);
    CHECK(system(copy_cmd) == 0, "cannot make %s", odd);
    snprintf(args, sizeof args, "'%s' --levels 1 --out %s", odd, odd_dir);
    CHECK(run(args, err, sizeof err) == 0, "forward of a name with a line break: %s", err);
    snprintf(args, sizeof args, "--inverse %s --out %s", odd_dir, odd_out);
    CHECK(run(args, err, sizeof err) == 0 && exists(odd_out),
          "inverse of the folder of a name with a line break: %s", err);
    /* a manifest naming a size past a fogmap's: refused before anything is made for it */
    char manifest[500];
    snprintf(manifest, sizeof manifest, "%s/transform.ini", odd_dir);
    FILE *m = fopen(manifest, "w");
    if (m) {
      fputs("[transform]\nbasis = linear\nlevels = 1\nwidth = 1000000\nheight = 20000\n", m);
      fclose(m);
    }
    snprintf(args, sizeof args, "--inverse %s --out %s/huge.exr", odd_dir, tmp);
    CHECK(run(args, err, sizeof err) != 0 && strstr(err, "more than a fogmap's"),
          "a manifest of 1000000 x 20000: %s", err);
  }

  /* an input path longer than the manifest reader's line was (512 bytes: the comment that
   * names the input split, and its rest was refused as a key line): the folder inverts, and
   * a shallower forward into it still removes the deeper levels (it read no manifest and
   * kept them) */
  {
    char long_in[700], long_dir[400], long_out[400], copy_cmd[800], stale_level[500];
    char long_args[1600];
    int n = snprintf(long_in, sizeof long_in, "%s/", tmp);
    for (int k = 0; k < 260; k++) n += snprintf(long_in + n, sizeof long_in - n, "./");
    snprintf(long_in + n, sizeof long_in - n, "long.exr");
    snprintf(long_dir, sizeof long_dir, "%s/long", tmp);
    snprintf(long_out, sizeof long_out, "%s/long_back.exr", tmp);
    snprintf(stale_level, sizeof stale_level, "%s/approx_2.exr", long_dir);
    snprintf(copy_cmd, sizeof copy_cmd, "cp data/fogmap_sample.exr '%s'", long_in);
    CHECK(system(copy_cmd) == 0, "cannot make %s", long_in);
    snprintf(long_args, sizeof long_args, "'%s' --levels 2 --out %s", long_in, long_dir);
    CHECK(run(long_args, err, sizeof err) == 0, "forward of a %zu-byte path: %s", strlen(long_in),
          err);
    snprintf(long_args, sizeof long_args, "'%s' --levels 1 --out %s", long_in, long_dir);
    CHECK(run(long_args, err, sizeof err) == 0 && !exists(stale_level),
          "a shallower forward of the long path left approx_2.exr (%s)", err);
    snprintf(long_args, sizeof long_args, "--inverse %s --out %s", long_dir, long_out);
    CHECK(run(long_args, err, sizeof err) == 0 && exists(long_out),
          "inverse of the folder of a %zu-byte path: %s", strlen(long_in), err);
  }

  char cmd[400];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
  if (system(cmd)) fprintf(stderr, "could not clean %s\n", tmp);
  return test_finish("transform_cli_roundtrip");
}
