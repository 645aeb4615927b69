/* `fogpipe record` of a late range stopped by SIGTERM while its simulation catches up to
 * the range's first frame (FOGPIPE_BIN): it exits 130, says how to resume, and removes the
 * folders it made. The handlers used to be set only once the frames began, so the catch-up
 * (thousands of frames on a farm's late range, where preemption sends SIGTERM) died with
 * the signal and left its empty folders. */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "test_util.h"

static bool file_says(const char *path, const char *text) {
  FILE *f = fopen(path, "r");
  char line[4096];
  bool found = false;
  while (f && fgets(line, sizeof line, f)) found = found || strstr(line, text);
  if (f) fclose(f);
  return found;
}

int main(void) {
  const char *bin = getenv("FOGPIPE_BIN");
  if (!bin) {
    fprintf(stderr, "FOGPIPE_BIN not set (run through ctest)\n");
    return 1;
  }
  char root[] = "/tmp/fogpipe_record_stop_XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char out[300], log[300];
  snprintf(out, sizeof out, "%s/made/frames", root);
  snprintf(log, sizeof log, "%s.log", root);
  const pid_t child = fork();
  if (child == 0) {
    if (!freopen(log, "w", stdout) || dup2(fileno(stdout), 2) < 0) _exit(126);
    execl(bin, bin, "record", "configs/default.ini", "--frames", "3000-3001", "--size", "32x18",
          "--out", out, (char *)NULL);
    _exit(127);
  }
  /* wait until the catch-up has begun, then stop it */
  int waited = 0;
  while (!file_says(log, "re-running the simulation") && waited < 30000 &&
         waitpid(child, NULL, WNOHANG) == 0) {
    nanosleep(&(struct timespec){.tv_nsec = 1000000}, NULL);
    waited++;
  }
  nanosleep(&(struct timespec){.tv_nsec = 200000000}, NULL);
  kill(child, SIGTERM);
  struct timespec sent, ended;
  clock_gettime(CLOCK_MONOTONIC, &sent);
  int status = 0;
  waitpid(child, &status, 0);
  clock_gettime(CLOCK_MONOTONIC, &ended);
  /* within parts of the catch-up (8 frames), not after all 2999 of them (~10 s and more) */
  const double seconds =
      (double)(ended.tv_sec - sent.tv_sec) + 1e-9 * (double)(ended.tv_nsec - sent.tv_nsec);
  CHECK(seconds < 2.0, "the stop took %.2f s after the signal", seconds);
  const bool stopped = WIFEXITED(status) && WEXITSTATUS(status) == 130;
  CHECK(stopped, "record stopped during its catch-up: %s %d",
        WIFSIGNALED(status) ? "killed by signal" : "exit",
        WIFSIGNALED(status) ? WTERMSIG(status) : WEXITSTATUS(status));
  if (stopped) {
    CHECK(file_says(log, "interrupted before frame 3000") && file_says(log, "--resume"),
          "the stop and the command that resumes are not said");
    CHECK(test_folder_entries(root) == 0, "%d entries left in %s (its folders)",
          test_folder_entries(root), root);
  }
  unlink(log);
  test_remove_tree(root);
  return test_finish("test_record_range_stop");
}
