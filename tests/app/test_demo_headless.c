/* `fogpipe demo` without a display (DISPLAY and WAYLAND_DISPLAY unset) says so in ONE line,
 * records the scene headless into ./out/demo instead, exits 0, and prints where the frames
 * are; the frames it names exist and are readable. Run in a fresh temporary folder (the
 * recording goes to ./out/demo there). */
#include "tests/app/record_util.h"
#include "tests/test_util.h"

enum { frames = 2 };

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

  pid_t pid = fork();
  if (pid == 0) {
    if (chdir(root) != 0) _exit(126);
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    execl(bin_abs, bin_abs, "demo", config, "--frames", "2", (char *)NULL);
    _exit(127);
  }
  int status = record_wait(pid);
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
  test_remove_tree(root);
  return test_finish("test_demo_headless");
}
