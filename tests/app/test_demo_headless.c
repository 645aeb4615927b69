/* `fogpipe demo` without a display (DISPLAY and WAYLAND_DISPLAY unset) says so in ONE line,
 * records the scene headless into ./out/demo instead, exits 0, and prints where the frames
 * are; the frames it names exist and are readable. Run in a fresh temporary folder (the
 * recording goes to ./out/demo there). With --size, the recording has that size; with
 * --screenshot, the PNG holds the last frame's R, G, B encoded as sRGB and dithered, the
 * very codes of tests/reference/srgb8_dither_reference.h; a window-only option is named
 * as having no effect; a shorter run after a longer one leaves only its own frames; a scene
 * whose fogmap is one of out/demo's frames is refused before anything there is cleared; a
 * scene that fails leaves no out/demo behind. */
#include "tests/app/record_util.h"
#include "tests/app/child_util.h"
#include "tests/test_util.h"

#include <math.h>
#include <stdbool.h>

#include "sim/sim.h"
#include "tests/reference/srgb8_dither_reference.h"

enum { frames = 2 };

/* fogpipe demo ARGS... in root without a display, its output into log; the exit status. */
static int run_demo(const char *bin, const char *root, const char *log, char *const args[]) {
  pid_t pid = fork();
  if (pid == 0) {
    if (chdir(root) != 0) _exit(126);
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    execv(bin, args);
    _exit(127);
  }
  return record_wait(pid);
}

/* --size 96x54 --screenshot: the frames' size, and the PNG against the last frame. */
static void check_screenshot(const char *bin, const char *config, const char *root) {
  char log[700], folder[700], png[700], frame[800];
  snprintf(log, sizeof log, "%s/shot.log", root);
  snprintf(folder, sizeof folder, "%s/out/demo", root);
  snprintf(png, sizeof png, "%s/shot.png", root);
  test_remove_tree(folder);
  char *const args[] = {(char *)bin, "demo", (char *)config, "--frames", "2", "--size", "96x54",
                        "--screenshot", "shot.png", "--paused", NULL};
  int status = run_demo(bin, root, log, args);
  CHECK(status == 0, "demo --screenshot without a display exited with %d", status);
  CHECK(child_log_says(log, "--paused has no effect"), "--paused dropped without a word");
  int w = 0, h = 0;
  record_frame_path(folder, frames, frame, sizeof frame);
  CHECK(record_hash_frame(frame, &w, &h) != 0 && w == 96 && h == 54,
        "frame %s is %dx%d, expected --size 96x54", frame, w, h);
  static const char *const names[3] = {"R", "G", "B"};
  double worst = 0;
  for (int c = 0; c < 3; c++) {
    fogmap linear = {0}, encoded = {0};
    fog_error err = {0};
    if (fogmap_load(frame, &(fogmap_load_desc){.channel = names[c]}, &linear, &err) ||
        fogmap_load(png, &(fogmap_load_desc){.channel = names[c]}, &encoded, &err)) {
      CHECK(0, "channel %s: %s", names[c], err.message);
      fogmap_destroy(&linear);
      continue;
    }
    CHECK(encoded.width == 96 && encoded.height == 54, "shot.png is %dx%d", encoded.width,
          encoded.height);
    for (int i = 0; i < 96 * 54 && encoded.width == 96 && encoded.height == 54; i++) {
      const int expect = reference_srgb8_dithered(linear.density[i], i % 96, i / 96);
      worst = fmax(worst, fabs(255.0 * encoded.density[i] - expect));
    }
    fogmap_destroy(&linear);
    fogmap_destroy(&encoded);
  }
  CHECK(worst < 1e-3, "shot.png differs from the last frame, dithered, by %.3f levels", worst);
}

int main(void) {
  char root[] = "/tmp/fogpipe-demo-headless-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char source[1024], config[1200], log[600];
  if (!getcwd(source, sizeof source)) return 1;
  snprintf(config, sizeof config, "%s/configs/default.ini", source);
  snprintf(log, sizeof log, "%s/demo.log", root);
  const char *bin = record_bin();
  char bin_abs[1200];
  if (bin[0] == '/')
    snprintf(bin_abs, sizeof bin_abs, "%s", bin);
  else
    snprintf(bin_abs, sizeof bin_abs, "%s/%s", source, bin);

  char *const args[] = {bin_abs, "demo", config, "--frames", "2", NULL};
  int status = run_demo(bin_abs, root, log, args);
  CHECK(status == 0, "demo without a display exited with %d", status);

  /* Exactly one line about the missing display, and it names the output folder. */
  FILE *f = fopen(log, "r");
  int display_lines = 0, names_folder = 0;
  char line[2048];
  while (f && fgets(line, sizeof line, f)) {
    if (strstr(line, "display")) display_lines++;
    if (strstr(line, "out/demo")) names_folder++;
  }
  if (f) fclose(f);
  CHECK(display_lines == 1, "%d lines mention the display, expected exactly 1", display_lines);
  CHECK(names_folder >= 1, "the output does not say where the frames are");

  char out[700];
  snprintf(out, sizeof out, "%s/out/demo", root);
  int frame_files = 0;
  int others = record_count_files(out, &frame_files);
  CHECK(frame_files == frames && others == 0, "%d frames and %d other files in %s", frame_files,
        others, out);
  for (int i = 1; i <= frame_files; i++) {
    char path[800];
    int w = 0, h = 0;
    record_frame_path(out, i, path, sizeof path);
    CHECK(record_hash_frame(path, &w, &h) != 0 && w > 0 && h > 0, "frame %s unreadable", path);
  }
  if (status != 0 || display_lines != 1) record_print_log(log);
  /* A shorter run after it: out/demo holds its one frame, not the earlier run's frame 2
   * beside it (they were left), and says what it removed. */
  char *const again[] = {bin_abs, "demo", config, "--frames", "1", NULL};
  status = run_demo(bin_abs, root, log, again);
  CHECK(status == 0, "the second demo exited with %d", status);
  others = record_count_files(out, &frame_files);
  CHECK(frame_files == 1 && others == 0, "after a 1-frame run: %d frames and %d other files",
        frame_files, others);
  CHECK(child_log_says(log, "removed 2 frames of an earlier run"), "the clearing is not said");
  /* a scene that fails to load (its fogmap cut short) leaves the earlier frame in place:
   * the clearing waits until the scene has loaded (it used to come first) */
  {
    char cut[800], broken[800], cmd[2000];
    snprintf(cut, sizeof cut, "%s/cut.png", root);
    snprintf(broken, sizeof broken, "%s/broken.ini", root);
    snprintf(cmd, sizeof cmd, "head -c 500 data/fogmap_sample.png > '%s'", cut);
    CHECK(system(cmd) == 0, "%s", cmd);
    test_write_text(broken, "[fog]\nfogmap = cut.png\n");
    char *const fails[] = {bin_abs, "demo", broken, "--frames", "2", NULL};
    status = run_demo(bin_abs, root, log, fails);
    others = record_count_files(out, &frame_files);
    CHECK(status == 1 && child_log_says(log, "cut.png") && frame_files == 1 && others == 0,
          "a scene that fails to load: exit %d, %d frames left (expected the earlier 1)", status,
          frame_files);
  }
  check_screenshot(bin_abs, config, root);
  /* a scene whose fogmap is a frame of out/demo: refused before the earlier frames are
   * cleared (they were, the fogmap with them) */
  char map[800], scene[800];
  snprintf(map, sizeof map, "%s/out/demo/frame.0002.exr", root);
  snprintf(scene, sizeof scene, "%s/in_out.ini", root);
  char copy[2000];
  snprintf(copy, sizeof copy, "cp data/fogmap_sample.exr '%s'", map);
  CHECK(system(copy) == 0, "%s", copy);
  test_write_text(scene, "[fog]\nfogmap = out/demo/frame.0002.exr\n");
  char *const in_out[] = {bin_abs, "demo", scene, "--frames", "2", NULL};
  status = run_demo(bin_abs, root, log, in_out);
  CHECK(status == 2 && child_log_says(log, "would replace the input") && access(map, F_OK) == 0,
        "demo recording over its own fogmap: exit %d, the fogmap %s", status,
        access(map, F_OK) == 0 ? "kept" : "gone");
  /* frame.00002.exr is no name the demo writes, so it is neither refused nor cleared */
  char unpadded[800];
  snprintf(unpadded, sizeof unpadded, "%s/out/demo/frame.00002.exr", root);
  CHECK(rename(map, unpadded) == 0, "cannot rename %s", map);
  test_write_text(scene, "[fog]\nfogmap = out/demo/frame.00002.exr\n");
  status = run_demo(bin_abs, root, log, in_out);
  CHECK(status == 0 && access(unpadded, F_OK) == 0,
        "demo beside a fogmap frame.00002.exr: exit %d, the fogmap %s", status,
        access(unpadded, F_OK) == 0 ? "kept" : "gone");
  /* a scene that fails to load, in a folder without out/: exit 1 and no out/demo (nor out/)
   * left empty behind (the folder probe's were never taken away) */
  char fresh[700], broken[800], fresh_out[800];
  snprintf(fresh, sizeof fresh, "%s/fresh", root);
  snprintf(broken, sizeof broken, "%s/broken.ini", fresh);
  snprintf(fresh_out, sizeof fresh_out, "%s/out", fresh);
  CHECK(mkdir(fresh, 0755) == 0, "cannot make %s", fresh);
  char cut[800], cut_cmd[2000];
  snprintf(cut, sizeof cut, "%s/cut.exr", fresh);
  snprintf(cut_cmd, sizeof cut_cmd, "head -c 100 data/fogmap_sample.exr > '%s'", cut);
  CHECK(system(cut_cmd) == 0, "%s", cut_cmd);
  test_write_text(broken, "[fog]\nfogmap = cut.exr\n"); /* loads; its file fails to */
  char *const failing[] = {bin_abs, "demo", broken, "--frames", "1", "--size", "32x18", NULL};
  status = run_demo(bin_abs, fresh, log, failing);
  CHECK(status == 1 && access(fresh_out, F_OK) != 0,
        "demo of a scene that fails: exit %d, %s %s", status, fresh_out,
        access(fresh_out, F_OK) == 0 ? "left behind" : "gone");
  test_remove_tree(root);
  return test_finish("test_demo_headless");
}
