/* `fogpipe render` with a bad config: non-zero exit, the message names FILE:LINE: [section]
 * key, and no output file (nor a temporary) is left in the output folder. The same for a
 * fogmap that exists but is not an image (found only when rendering), and for a missing
 * config; --out naming the config's own fogmap is refused and leaves it as it was; and
 * --help lists every option. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_util.h"

static char dir[] = "/tmp/fogpipe_render_errors_XXXXXX";
static char text_of_own[2048];

static int files_in(const char *folder) {
  DIR *d = opendir(folder);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));)
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
  if (d) closedir(d);
  return n;
}

static void read_text(const char *path, char *text, size_t size) {
  FILE *f = fopen(path, "r");
  size_t n = f ? fread(text, 1, size - 1, f) : 0;
  text[n] = '\0';
  if (f) fclose(f);
}

static size_t read_bytes(const char *path, char *bytes, size_t size) {
  FILE *f = fopen(path, "rb");
  size_t n = f ? fread(bytes, 1, size, f) : 0;
  if (f) fclose(f);
  return n;
}

/* Runs fogpipe render on DIR/bad.ini holding `config`; checks exit != 0, stderr contains
 * `want` (with %s replaced by DIR), no file appeared in DIR/out. */
static void expect_failure(const char *bin, const char *config, const char *want_fmt) {
  char ini[256], outdir[256], err_path[256], command[1024], want[512], text[2048];
  snprintf(ini, sizeof ini, "%s/bad.ini", dir);
  snprintf(outdir, sizeof outdir, "%s/out", dir);
  snprintf(err_path, sizeof err_path, "%s/stderr.txt", dir);
  FILE *f = fopen(ini, "w");
  fputs(config, f);
  fclose(f);
  snprintf(command, sizeof command, "'%s' render '%s' --out '%s/x.exr' --size 32x18 2> '%s'",
           bin, ini, outdir, err_path);
  int status = system(command);
  read_text(err_path, text, sizeof text);
  snprintf(want, sizeof want, want_fmt, dir, dir); /* formats use %s once or twice */
  CHECK(status != 0, "exit status 0 for a bad config: %s", config);
  CHECK(strstr(text, want) != NULL, "stderr '%s' lacks '%s'", text, want);
  CHECK(files_in(outdir) == 0, "%d files left in the output folder", files_in(outdir));
}

int main(void) {
  const char *bin = getenv("FOGPIPE_BIN");
  CHECK(bin != NULL, "FOGPIPE_BIN is not set (run through ctest)");
  if (!bin) return test_finish("test_render_errors");
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  char outdir[256], path[256];
  snprintf(outdir, sizeof outdir, "%s/out", dir);
  {
    char command[512];
    snprintf(command, sizeof command, "mkdir -p '%s'", outdir);
    CHECK(system(command) == 0, "mkdir");
  }
  expect_failure(bin, "[render]\nwidth = 32\n\n[fog]\nbasis = wavelet\n",
                 "fogpipe render: %s/bad.ini:5: [fog] basis: expected one of haar|linear|quadratic");
  expect_failure(bin, "[camera]\nfov = wide\n", "fogpipe render: %s/bad.ini:2: [camera] fov: expected a number");
  expect_failure(bin, "[fog]\n; the map\nfogmap = missing.png\n",
                 "fogpipe render: %s/bad.ini:3: [fog] fogmap: cannot open '%s/missing.png'");
  /* A fogmap that opens but does not decode: found by the renderer, still file:line. */
  snprintf(path, sizeof path, "%s/notanimage.png", dir);
  FILE *f = fopen(path, "w");
  fputs("this is not a PNG\n", f);
  fclose(f);
  expect_failure(bin, "[fog]\n\nfogmap = notanimage.png\n", "fogpipe render: %s/bad.ini:3: [fog] fogmap: ");
  unlink(path);
  expect_failure(bin, "[terrain]\nsize = 100\n", "[terrain] size: expected two numbers");

  /* --out is the config's fogmap, spelt otherwise: refused, the fogmap's bytes unchanged */
  {
    char map[300], ini[300], command[1024], err_path[300];
    static char before[65536], after[65536];
    snprintf(map, sizeof map, "%s/map.exr", dir);
    snprintf(ini, sizeof ini, "%s/own.ini", dir);
    snprintf(err_path, sizeof err_path, "%s/own.txt", dir);
    snprintf(command, sizeof command, "'%s' design --perlin --size 16x16 --out '%s' > /dev/null",
             bin, map);
    CHECK(system(command) == 0, "design failed");
    FILE *g = fopen(ini, "w");
    fputs("[fog]\nfogmap = map.exr\n", g);
    fclose(g);
    size_t size_before = read_bytes(map, before, sizeof before);
    snprintf(command, sizeof command,
             "'%s' render '%s' --out '%s/out/../map.exr' --size 32x18 2> '%s'", bin, ini, dir,
             err_path);
    int status = system(command);
    read_text(err_path, text_of_own, sizeof text_of_own);
    size_t size_after = read_bytes(map, after, sizeof after);
    CHECK(status != 0 && strstr(text_of_own, "is the config's [fog] fogmap"),
          "render over its own fogmap: status %d, '%s'", status, text_of_own);
    CHECK(size_before > 0 && size_before == size_after && !memcmp(before, after, size_after),
          "the fogmap was rewritten (%zu bytes, now %zu)", size_before, size_after);
    unlink(map), unlink(ini), unlink(err_path);
  }

  /* Other outputs over a scene's inputs: render --out a frame of its [fog] sequence;
   * view --screenshot its heightmap; demo --screenshot its fogmap. Each refused (exit 2,
   * the key named) before any window or frame, and the file kept byte for byte. */
  {
    char frame[300], heightmap[300], fogmap[300], ini[300], command[1400], err_path[300];
    static char before[3][300000], after[300000];
    static char text[4096];
    snprintf(frame, sizeof frame, "%s/fog.0001.exr", dir);
    snprintf(heightmap, sizeof heightmap, "%s/hm.png", dir);
    snprintf(fogmap, sizeof fogmap, "%s/fm.png", dir);
    snprintf(ini, sizeof ini, "%s/inputs.ini", dir);
    snprintf(err_path, sizeof err_path, "%s/inputs.txt", dir);
    snprintf(command, sizeof command,
             "cp data/fogmap_sample.exr '%s' && cp data/heightmap.png '%s' && "
             "cp data/fogmap_sample.png '%s'", frame, heightmap, fogmap);
    CHECK(system(command) == 0, "%s", command);
    const char *kept[3] = {frame, heightmap, fogmap};
    size_t sizes[3];
    for (int i = 0; i < 3; i++) sizes[i] = read_bytes(kept[i], before[i], sizeof before[i]);
    const struct {
      const char *config, *args, *key;
      int file;
    } cases[] = {
        {"[fog]\nsequence = fog.####.exr\n", "render '%s' --size 32x18 --out '%s/out/../fog.0001.exr'",
         "is a frame of the config's [fog] sequence", 0},
        {"[terrain]\nheightmap = hm.png\n", "view '%s' --size 32x18 --screenshot '%s/./hm.png'",
         "is the config's [terrain] heightmap", 1},
        {"[fog]\nfogmap = fm.png\n", "demo '%s' --size 32x18 --frames 1 --screenshot '%s/fm.png'",
         "is the config's [fog] fogmap", 2},
    };
    for (int c = 0; c < 3; c++) {
      FILE *g = fopen(ini, "w");
      fputs(cases[c].config, g);
      fclose(g);
      char args[700];
      snprintf(args, sizeof args, cases[c].args, ini, dir);
      snprintf(command, sizeof command, "'%s' %s > /dev/null 2> '%s'", bin, args, err_path);
      int status = system(command);
      status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      read_text(err_path, text, sizeof text);
      size_t size_after = read_bytes(kept[cases[c].file], after, sizeof after);
      CHECK(status == 2 && strstr(text, cases[c].key), "%s: status %d, '%s'", args, status,
            text);
      CHECK(sizes[cases[c].file] > 0 && size_after == sizes[cases[c].file] &&
                !memcmp(before[cases[c].file], after, size_after),
            "%s rewrote %s", args, kept[cases[c].file]);
    }
    for (int i = 0; i < 3; i++) unlink(kept[i]);
    unlink(ini), unlink(err_path);
  }

  /* --help names every option. */
  char command[512], text[4096], out_path[256];
  snprintf(out_path, sizeof out_path, "%s/help.txt", dir);
  snprintf(command, sizeof command, "'%s' render --help > '%s'", bin, out_path);
  CHECK(system(command) == 0, "--help exit status");
  read_text(out_path, text, sizeof text);
  CHECK(strstr(text, "--out") && strstr(text, "--size") && strstr(text, "--help"), "help: %s", text);
  /* `fogpipe help render` is the same text (it printed the list of commands) */
  char same[4096];
  snprintf(command, sizeof command, "'%s' help render > '%s'", bin, out_path);
  CHECK(system(command) == 0, "help render: exit status");
  read_text(out_path, same, sizeof same);
  CHECK(!strcmp(text, same), "help render: %s", same);
  snprintf(command, sizeof command, "'%s' help nosuch > '%s' 2>&1", bin, out_path);
  const int unknown = system(command);
  read_text(out_path, same, sizeof same);
  CHECK(WIFEXITED(unknown) && WEXITSTATUS(unknown) == 2 &&
            strstr(same, "unknown command 'nosuch'"),
        "help nosuch: %s", same);
  unlink(out_path);
  snprintf(path, sizeof path, "%s/stderr.txt", dir);
  unlink(path);
  snprintf(path, sizeof path, "%s/bad.ini", dir);
  unlink(path);
  rmdir(outdir);
  rmdir(dir);
  return test_finish("test_render_errors");
}
