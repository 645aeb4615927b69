/* `fogpipe record` stopped (SIGTERM) while it writes its last frame: the frame is finished
 * and kept, and the run exits 130 saying that every frame is complete. It exited 0, as if
 * no signal had come (docs/demo.md: Ctrl-C exits 130), so a script could not tell. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>

#include "child_util.h"
#include "test_bin.h"

int main(void) {
  char root[] = "/tmp/fogpipe_record_last_XXXXXX";
  const char *bin = test_bin_and_folder(root);
  if (!bin) return test_finish("test_record_last_frame_stop");
  char out[300], log[300], frame[400];
  snprintf(out, sizeof out, "%s/frames", root);
  snprintf(log, sizeof log, "%s.log", root);
  snprintf(frame, sizeof frame, "%s/frame.0001.exr", out);
  /* one frame large enough that its EXR takes a while to write */
  char *const argv[] = {(char *)bin, "record", "configs/default.ini", "--frames", "1",
                        "--size", "1280x720", "--out", out, NULL};
  const pid_t child = child_run(log, argv);
  /* the frame's temporary (atomic_file: .frame.0001.exr.tmp.PID.N): rendered, being written */
  bool writing = false, ended = false;
  for (long waited = 0; waited < 120000 && !writing && !ended; waited++) {
    writing = child_folder_has(out, ".frame.0001.exr.tmp");
    ended = waitpid(child, NULL, WNOHANG) != 0;
    if (!writing && !ended) nanosleep(&(struct timespec){.tv_nsec = 1000000}, NULL);
  }
  int status = 0;
  if (ended) {
    fprintf(stderr, "the run ended before its frame was seen being written\n");
  } else {
    kill(child, SIGTERM);
    waitpid(child, &status, 0);
  }
  CHECK(writing, "the frame's temporary never appeared (the run %s)", ended ? "ended" : "hung");
  if (writing) {
    CHECK(child_exit_code(status) == 130, "stopped during its last frame: exit %d, expected 130 "
          "(-1: killed by the signal)", child_exit_code(status));
    CHECK(child_log_says(log, "interrupted after the last frame") &&
              child_log_says(log, "every frame asked for is complete"),
          "the stop is not said");
    struct stat st;
    CHECK(stat(frame, &st) == 0 && st.st_size > 0, "the last frame %s is not kept", frame);
    CHECK(test_folder_entries(out) == 1, "%d entries in %s, expected the frame alone",
          test_folder_entries(out), out);
  }
  unlink(log);
  test_remove_tree(root);
  return test_finish("test_record_last_frame_stop");
}
