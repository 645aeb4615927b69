/* `fogpipe render` stopped by SIGTERM (FOGPIPE_BIN). While the file is written the signal
 * waits until it is whole: exit 0, the image there, no temporary beside it (it used to die
 * with the signal and leave .OUT.tmp.XXXXXX, which no later run removes). While the frame
 * is drawn: exit 130, saying nothing was written, and nothing there. A scene without fog
 * at 2048x1152 draws in about a second here and spends ~0.6 s writing its EXR. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdlib.h>

#include "child_util.h"
#include "test_bin.h"

/* Whether folder holds a file whose name starts with prefix. */
static bool folder_has(const char *folder, const char *prefix) {
  DIR *d = opendir(folder);
  bool found = false;
  for (struct dirent *e; d && !found && (e = readdir(d));)
    found = !strncmp(e->d_name, prefix, strlen(prefix));
  if (d) closedir(d);
  return found;
}

/* Whether the process catches SIGTERM (its SigCgt mask in /proc), i.e. past its set-up. */
static bool catches_term(pid_t pid) {
  char path[64], line[256];
  snprintf(path, sizeof path, "/proc/%d/status", (int)pid);
  FILE *f = fopen(path, "r");
  unsigned long long mask = 0;
  while (f && fgets(line, sizeof line, f))
    if (!strncmp(line, "SigCgt:", 7)) mask = strtoull(line + 7, NULL, 16);
  if (f) fclose(f);
  return mask & (1ULL << (SIGTERM - 1));
}

int main(void) {
  char root[] = "/tmp/fogpipe_render_stop_XXXXXX";
  const char *bin = test_bin_and_folder(root);
  if (!bin) return test_finish("test_render_interrupt");
  char config[300], out[300], log[300];
  snprintf(config, sizeof config, "%s/terrain.ini", root);
  snprintf(out, sizeof out, "%s/frame.exr", root);
  snprintf(log, sizeof log, "%s.log", root);
  test_write_text(config, "; the default terrain and boxes, no fog\n");
  char *const argv[] = {(char *)bin, "render", config, "--out", out, "--size", "2048x1152",
                        NULL};
  struct stat st;

  /* 1. SIGTERM once the temporary file exists: the write finishes first */
  {
    const pid_t child = child_run(log, argv);
    bool seen = false;
    for (long waited = 0; waited < 60000 && !seen; waited++) {
      seen = folder_has(root, ".frame.exr.tmp");
      if (!seen && waitpid(child, NULL, WNOHANG) != 0) break;
      if (!seen) nanosleep(&(struct timespec){.tv_nsec = 500000}, NULL);
    }
    if (seen) kill(child, SIGTERM);
    int status = 0;
    waitpid(child, &status, 0);
    CHECK(seen, "the temporary .frame.exr.tmp.* never appeared (exit %d)",
          child_exit_code(status));
    CHECK(child_exit_code(status) == 0, "SIGTERM during the write: exit %d (-1: killed by "
          "the signal)", child_exit_code(status));
    CHECK(stat(out, &st) == 0 && st.st_size > 1000000, "the image is not there whole");
    CHECK(!folder_has(root, ".frame.exr.tmp"), "a temporary file is left in %s", root);
    unlink(out);
  }

  /* 2. SIGTERM as soon as it catches the signal (it is drawing then): nothing written */
  {
    const pid_t child = child_run(log, argv);
    bool ready = false;
    for (long waited = 0; waited < 60000 && !ready; waited++) {
      ready = catches_term(child);
      if (!ready && waitpid(child, NULL, WNOHANG) != 0) break;
      if (!ready) nanosleep(&(struct timespec){.tv_nsec = 500000}, NULL);
    }
    if (ready) kill(child, SIGTERM);
    int status = 0;
    waitpid(child, &status, 0);
    CHECK(ready, "the render never caught SIGTERM (exit %d)", child_exit_code(status));
    CHECK(child_exit_code(status) == 130, "SIGTERM while drawing: exit %d, expected 130",
          child_exit_code(status));
    CHECK(child_log_says(log, "interrupted: nothing written"), "the stop is not said");
    CHECK(stat(out, &st) != 0, "%s written after the stop", out);
    CHECK(!folder_has(root, ".frame.exr.tmp"), "a temporary file is left in %s", root);
  }
  unlink(log);
  test_remove_tree(root);
  return test_finish("test_render_interrupt");
}
