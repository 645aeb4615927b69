/* The commands that write a sequence of frames into a folder (bake: fog.####.exr and
 * bake.ini; record: frame.####.exr) refuse a folder where one of those files is a file the
 * scene reads, before any work, and leave it as it was: a fogmap named like a frame, or
 * the config itself named bake.ini. And a bake of one channel of a colour fogmap plays
 * back: its bake.ini names the frames (one channel, Y) without the input's [fog] channel.
 * A bake into a folder whose name a config cuts short is refused before it simulates. */
#define _POSIX_C_SOURCE 200809L
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "sim/image.h"
#include "test_bin.h"
#include "test_util.h"

static char dir[] = "/tmp/fogpipe_sequence_outputs_XXXXXX";

enum { N = 32 };

/* A 32 x 32 fogmap of value v at path (EXR channel Y, or a PNG of 3 channels whose G is
 * v and R, B zero). */
static int write_fogmap(const char *path, float v, bool png) {
  static float values[3 * N * N];
  fog_error err = {0};
  for (int i = 0; i < N * N; i++) values[3 * i] = 0, values[3 * i + 1] = v, values[3 * i + 2] = 0;
  if (png) return image_write_png(path, N, N, 3, values, &err);
  for (int i = 0; i < N * N; i++) values[i] = v;
  image_channel y = {.name = "Y", .pixels = values};
  return image_write_exr(path, N, N, &y, 1, &err);
}

/* The file's size and modification time, to see that a refused run left it alone. */
static bool same_stat(const char *path, const struct stat *before) {
  struct stat now;
  return stat(path, &now) == 0 && now.st_size == before->st_size &&
         now.st_mtim.tv_sec == before->st_mtim.tv_sec &&
         now.st_mtim.tv_nsec == before->st_mtim.tv_nsec;
}

static void expect_refused(const char *bin, const char *command, const char *args,
                           const char *input, const char *what) {
  struct stat before;
  CHECK(stat(input, &before) == 0, "%s is missing", input);
  char line[2048], output[4096];
  snprintf(line, sizeof line, "'%s' %s %s 2>&1", bin, command, args);
  int status = test_run_output(line, output, sizeof output);
  CHECK(status == 2 && strstr(output, "would replace the input") && strstr(output, what),
        "%s %s: exit %d, expected 2 naming %s: %s", command, args, status, what, output);
  CHECK(same_stat(input, &before), "%s %s changed %s", command, args, input);
}

static const char *const scene = "[render]\nwidth = 32\nheight = 18\n[terrain]\nresolution = 17\n";

/* `command CONFIG --frames N --out DIR` refused, where CONFIG (DIR/config) names the
 * fogmap DIR/map: one of the files the command would write (or remove). */
static void refused_fogmap(const char *bin, const char *command, const char *map,
                           const char *config, int frames) {
  char path[300], ini[300], text[600], args[1200];
  snprintf(path, sizeof path, "%s/%s", dir, map);
  CHECK(write_fogmap(path, 0.01f, false) == 0, "cannot write %s", path);
  snprintf(ini, sizeof ini, "%s/%s", dir, config);
  snprintf(text, sizeof text, "%s[fog]\nfogmap = %s\n", scene, map);
  test_write_text(ini, text);
  snprintf(args, sizeof args, "'%s' --frames %d --out '%s'", ini, frames, dir);
  expect_refused(bin, command, args, path, "[fog] fogmap");
}

int main(void) {
  const char *bin = test_bin_and_folder(dir);
  if (!bin) return test_finish("test_sequence_outputs");
  char path[300], ini[300], args[1200], line[2048], output[4096];

  /* a fogmap named as bake's second frame, in the folder the bake is to fill; and a frame
   * past the bake's end, which a bake removes as a longer bake's leftover */
  refused_fogmap(bin, "bake", "fog.0002.exr", "frame_named.ini", 2);
  refused_fogmap(bin, "bake", "fog.0002.exr", "frame_named.ini", 1);

  /* the config itself as the bake's bake.ini (its fogmap in another folder) */
  snprintf(path, sizeof path, "%s/maps", dir);
  CHECK(mkdir(path, 0777) == 0, "cannot make %s", path);
  snprintf(path, sizeof path, "%s/maps/m.exr", dir);
  CHECK(write_fogmap(path, 0.01f, false) == 0, "cannot write %s", path);
  snprintf(ini, sizeof ini, "%s/bake.ini", dir);
  char text[600];
  snprintf(text, sizeof text, "%s[fog]\nfogmap = maps/m.exr\n", scene);
  test_write_text(ini, text);
  snprintf(args, sizeof args, "'%s' --frames 1 --out '%s'", ini, dir);
  expect_refused(bin, "bake", args, ini, "the config itself");

  /* record: a fogmap named as its frame 2 */
  refused_fogmap(bin, "record", "frame.0002.exr", "record_named.ini", 2);
  snprintf(path, sizeof path, "%s/frame.0001.exr", dir);
  struct stat st;
  CHECK(stat(path, &st) != 0, "the refused record wrote %s", path);
  /* a fogmap named frame.2.exr is none of record's frames (frame.0002.exr is): it runs */
  snprintf(ini, sizeof ini, "%s/record_unpadded.ini", dir);
  snprintf(line, sizeof line, "'%s' record '%s' --frames 2 --out '%s/beside' 2>&1", bin, ini,
           dir);
  char beside[300];
  snprintf(beside, sizeof beside, "%s/beside", dir);
  CHECK(mkdir(beside, 0777) == 0, "cannot make %s", beside);
  snprintf(path, sizeof path, "%s/beside/frame.2.exr", dir);
  CHECK(write_fogmap(path, 0.01f, false) == 0, "cannot write %s", path);
  snprintf(text, sizeof text, "%s[fog]\nfogmap = beside/frame.2.exr\n", scene);
  test_write_text(ini, text);
  CHECK(test_run_output(line, output, sizeof output) == 0,
        "record beside a fogmap frame.2.exr (not frame.0002.exr) refused: %s", output);

  /* one channel of a colour PNG, baked and played back */
  snprintf(path, sizeof path, "%s/colour.png", dir);
  CHECK(write_fogmap(path, 0.5f, true) == 0, "cannot write %s", path);
  snprintf(ini, sizeof ini, "%s/channel.ini", dir);
  snprintf(text, sizeof text, "%s[fog]\nfogmap = colour.png\nchannel = G\ndensity_scale = 0.02\n",
           scene);
  test_write_text(ini, text);
  snprintf(line, sizeof line, "'%s' bake '%s' --frames 2 --out '%s/bake_g' 2>&1", bin, ini, dir);
  CHECK(test_run_output(line, output, sizeof output) == 0, "bake of channel G: %s", output);
  snprintf(line, sizeof line, "'%s' render '%s/bake_g/bake.ini' --out '%s/g.exr' 2>&1", bin, dir,
           dir);
  CHECK(test_run_output(line, output, sizeof output) == 0 && strstr(output, "scene + fog"),
        "the bake of channel G does not render: %s", output);

  /* a folder whose name a config would cut short ("x ;y": ';' after a blank starts a
   * comment): refused before the simulation, the folder it made removed */
  snprintf(line, sizeof line, "'%s' bake '%s' --frames 2 --out '%s/x ;y' 2>&1", bin, ini, dir);
  int status = test_run_output(line, output, sizeof output);
  snprintf(path, sizeof path, "%s/x ;y", dir);
  CHECK(status == 1 && strstr(output, "' ;'") && !strstr(output, "frame") &&
            stat(path, &st) != 0,
        "bake --out 'x ;y': exit %d, %s", status, output);

  test_remove_tree(dir);
  return test_finish("test_sequence_outputs");
}
