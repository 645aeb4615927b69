/* `fogpipe record` of a late range stopped by SIGTERM while its simulation catches up to
 * the range's first frame (FOGPIPE_BIN): it exits 130, says how to resume, and removes the
 * folders it made. The handlers used to be set only once the frames began, so the catch-up
 * (thousands of frames on a farm's late range, where preemption sends SIGTERM) died with
 * the signal and left its empty folders. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>

#include "child_util.h"
#include "test_bin.h"

int main(void) {
  char root[] = "/tmp/fogpipe_record_stop_XXXXXX";
  const char *bin = test_bin_and_folder(root);
  if (!bin) return test_finish("test_record_range_stop");
  char out[300], log[300];
  snprintf(out, sizeof out, "%s/made/frames", root);
  snprintf(log, sizeof log, "%s.log", root);
  char *const argv[] = {(char *)bin, "record", "configs/default.ini", "--frames", "3000-3001",
                        "--size", "32x18", "--out", out, NULL};
  const pid_t child = child_run(log, argv);
  /* wait until the catch-up has begun, then stop it */
  child_wait_for(child, log, "re-running the simulation", NULL, 30.0);
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
  const bool stopped = child_exit_code(status) == 130;
  CHECK(stopped, "record stopped during its catch-up: exit %d (-1: killed by a signal)",
        child_exit_code(status));
  if (stopped) {
    CHECK(child_log_says(log, "interrupted before frame 3000") && child_log_says(log, "--resume"),
          "the stop and the command that resumes are not said");
    CHECK(test_folder_entries(root) == 0, "%d entries left in %s (its folders)",
          test_folder_entries(root), root);
  }
  unlink(log);
  test_remove_tree(root);
  return test_finish("test_record_range_stop");
}
