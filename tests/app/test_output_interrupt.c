/* Commands that write one output file, stopped by SIGTERM (FOGPIPE_BIN): `render`, `design`
 * and `transform --inverse`. While the file is written the signal waits until it is whole:
 * exit 0, the file there, no temporary beside it (they died with the signal and left
 * .OUT.tmp.PID.N, which no later run removes: 16 MB for a 2048x1152 render, 16 MB for a
 * 2048x2048 map). While the work before it runs: exit 130, saying nothing was written, and
 * nothing there; a long design stops between its rows, within seconds. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>

#include "child_util.h"
#include "test_bin.h"

/* argv run twice: stopped once its temporary `.NAME.tmp` appears in folder, then as soon as
 * it catches SIGTERM (before it writes). out: the file it writes, of at least min_size. */
static void stop_twice(const char *what, char *const argv[], const char *folder,
                       const char *out, const char *temp_prefix, long min_size,
                       const char *log) {
  struct stat st;
  /* 1. SIGTERM once the temporary file exists: the write finishes first */
  {
    const pid_t child = child_run(log, argv);
    bool seen = false;
    for (long waited = 0; waited < 120000 && !seen; waited++) {
      seen = child_folder_has(folder, temp_prefix);
      if (!seen && waitpid(child, NULL, WNOHANG) != 0) break;
      if (!seen) nanosleep(&(struct timespec){.tv_nsec = 500000}, NULL);
    }
    if (seen) kill(child, SIGTERM);
    int status = 0;
    waitpid(child, &status, 0);
    CHECK(seen, "%s: the temporary %s* never appeared (exit %d)", what, temp_prefix,
          child_exit_code(status));
    CHECK(child_exit_code(status) == 0, "%s: SIGTERM during the write: exit %d (-1: killed by "
          "the signal)", what, child_exit_code(status));
    CHECK(stat(out, &st) == 0 && st.st_size >= min_size, "%s: the output is not there whole",
          what);
    CHECK(!child_folder_has(folder, temp_prefix), "%s: a temporary file is left in %s", what,
          folder);
    unlink(out);
  }
  /* 2. SIGTERM as soon as it catches the signal (working then): nothing written */
  {
    const pid_t child = child_run(log, argv);
    bool ready = false;
    for (long waited = 0; waited < 120000 && !ready; waited++) {
      ready = child_catches_term(child);
      if (!ready && waitpid(child, NULL, WNOHANG) != 0) break;
      if (!ready) nanosleep(&(struct timespec){.tv_nsec = 500000}, NULL);
    }
    if (ready) kill(child, SIGTERM);
    int status = 0;
    waitpid(child, &status, 0);
    CHECK(ready, "%s: never caught SIGTERM (exit %d)", what, child_exit_code(status));
    CHECK(child_exit_code(status) == 130, "%s: SIGTERM while working: exit %d, expected 130",
          what, child_exit_code(status));
    CHECK(child_log_says(log, "interrupted: nothing written"), "%s: the stop is not said", what);
    CHECK(stat(out, &st) != 0, "%s: %s written after the stop", what, out);
    CHECK(!child_folder_has(folder, temp_prefix), "%s: a temporary file is left in %s", what,
          folder);
  }
}

int main(void) {
  char root[] = "/tmp/fogpipe_output_stop_XXXXXX";
  const char *bin = test_bin_and_folder(root);
  if (!bin) return test_finish("test_output_interrupt");
  char config[300], out[300], log[300], map[300], pyramid[300], back[300], command[1200];
  snprintf(config, sizeof config, "%s/terrain.ini", root);
  snprintf(out, sizeof out, "%s/frame.exr", root);
  snprintf(log, sizeof log, "%s.log", root);
  snprintf(map, sizeof map, "%s/map.exr", root);
  snprintf(pyramid, sizeof pyramid, "%s/pyramid", root);
  snprintf(back, sizeof back, "%s/back.exr", root);

  /* render: a scene without fog at 2048x1152 draws in about a second here and spends
   * ~0.6 s writing its EXR */
  test_write_text(config, "; the default terrain and boxes, no fog\n");
  char *const render[] = {(char *)bin, "render", config, "--out", out, "--size", "2048x1152",
                          NULL};
  stop_twice("render", render, root, out, ".frame.exr.tmp", 1000000, log);

  /* design: 2048x2048 of Perlin turbulence (~1 s), its 16 MB EXR (incompressible) */
  char *const design[] = {(char *)bin, "design", "--perlin", "--size", "2048x2048", "--out",
                          map, NULL};
  stop_twice("design", design, root, map, ".map.exr.tmp", 10000000, log);

  /* a design of ~20 s (4096x4096, 30 octaves) stops between its rows: exit 130 within
   * seconds of the signal (it looked at the signal only once all of it was computed) */
  {
    char *const slow[] = {(char *)bin, "design", "--perlin", "--octaves", "30", "--size",
                          "4096x4096", "--out", map, NULL};
    const pid_t child = child_run(log, slow);
    bool ready = false;
    for (long waited = 0; waited < 120000 && !ready; waited++) {
      ready = child_catches_term(child);
      if (!ready && waitpid(child, NULL, WNOHANG) != 0) break;
      if (!ready) nanosleep(&(struct timespec){.tv_nsec = 500000}, NULL);
    }
    nanosleep(&(struct timespec){.tv_nsec = 200000000}, NULL); /* into the rows */
    struct timespec sent, ended;
    clock_gettime(CLOCK_MONOTONIC, &sent);
    if (ready) kill(child, SIGTERM);
    int status = 0;
    waitpid(child, &status, 0);
    clock_gettime(CLOCK_MONOTONIC, &ended);
    const double seconds =
        (double)(ended.tv_sec - sent.tv_sec) + 1e-9 * (double)(ended.tv_nsec - sent.tv_nsec);
    printf("design of 4096x4096, 30 octaves: stopped %.3f s after the signal\n", seconds);
    fflush(stdout); /* not again by the next child's freopen */
    CHECK(ready && child_exit_code(status) == 130 && seconds < 5.0,
          "a long design stopped: exit %d, %.2f s after the signal", child_exit_code(status),
          seconds);
    CHECK(stat(map, &(struct stat){0}) != 0, "the stopped design wrote %s", map);
  }

  /* transform --inverse of that map's pyramid: reads 13 files, writes 16 MB */
  snprintf(command, sizeof command,
           "'%s' design --perlin --size 2048x2048 --out '%s' > /dev/null && '%s' transform "
           "'%s' --levels 3 --out '%s' > /dev/null",
           bin, map, bin, map, pyramid);
  CHECK(system(command) == 0, "%s", command);
  char *const inverse[] = {(char *)bin, "transform", "--inverse", pyramid, "--out", back, NULL};
  stop_twice("transform --inverse", inverse, root, back, ".back.exr.tmp", 10000000, log);

  /* record: two SIGTERMs 10 ms apart while a frame's file is written (the second ends the
   * process): the frame is whole first, no temporary left beside it (one died mid-write
   * and left a partial .frame.0001.exr.tmp.PID.N; two sent together merge into one) */
  {
    char frames[300];
    snprintf(frames, sizeof frames, "%s/frames", root);
    char *const record[] = {(char *)bin, "record", config, "--out", frames, "--frames", "2",
                            "--size", "1920x1080", NULL};
    const pid_t child = child_run(log, record);
    bool seen = false;
    for (long waited = 0; waited < 240000 && !seen; waited++) {
      seen = child_folder_has(frames, ".frame.0001.exr.tmp");
      if (!seen && waitpid(child, NULL, WNOHANG) != 0) break;
      if (!seen) nanosleep(&(struct timespec){.tv_nsec = 250000}, NULL);
    }
    if (seen) {
      kill(child, SIGTERM);
      nanosleep(&(struct timespec){.tv_nsec = 10000000}, NULL);
      kill(child, SIGTERM);
    }
    int status = 0;
    waitpid(child, &status, 0);
    char whole[400];
    snprintf(whole, sizeof whole, "%s/frame.0001.exr", frames);
    struct stat st;
    CHECK(seen, "record: the frame's temporary never appeared (exit %d)",
          child_exit_code(status));
    CHECK(!child_folder_has(frames, ".frame.0001.exr.tmp"), "record: two signals during the "
          "write left a temporary in %s (exit %d)", frames, child_exit_code(status));
    CHECK(stat(whole, &st) == 0 && st.st_size > 1000000, "record: frame 1 is not there whole "
          "(exit %d)", child_exit_code(status));
  }

  unlink(log);
  test_remove_tree(root);
  return test_finish("test_output_interrupt");
}
