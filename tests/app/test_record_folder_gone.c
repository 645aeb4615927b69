/* Ranges of one recording share its folder (docs/farm.md): a range that fails or stops
 * before its first frame removes the empty folders it made, while another range may still
 * be catching up to its own first frame. That one makes the folder again when it writes:
 * here the folder is removed while `record --frames 3000-3001` re-runs the simulation to
 * frame 2999, and the range still writes both frames, exit 0 (it failed: "cannot create a
 * file in folder", FOGPIPE_BIN). */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>

#include "child_util.h"
#include "test_bin.h"

int main(void) {
  char root[] = "/tmp/fogpipe_record_gone_XXXXXX";
  const char *bin = test_bin_and_folder(root);
  if (!bin) return test_finish("test_record_folder_gone");
  char out[300], log[300], frame[400];
  snprintf(out, sizeof out, "%s/shot/frames", root);
  snprintf(log, sizeof log, "%s.log", root);
  char *const argv[] = {(char *)bin, "record", "configs/default.ini", "--frames", "3000-3001",
                        "--size", "32x18", "--out", out, NULL};
  const pid_t child = child_run(log, argv);
  child_wait_for(child, log, "re-running the simulation", NULL, 30.0);
  char shot[300];
  snprintf(shot, sizeof shot, "%s/shot", root);
  const bool removed = rmdir(out) == 0 && rmdir(shot) == 0; /* as another range's undo does */
  int status = 0;
  waitpid(child, &status, 0);
  CHECK(removed, "the folders were not there to remove during the catch-up");
  snprintf(frame, sizeof frame, "%s/frame.3001.exr", out);
  struct stat st;
  const int code = child_exit_code(status);
  CHECK(code == 0 && stat(frame, &st) == 0, "the range after its folder went: exit %d, %s %s",
        code, frame, stat(frame, &st) == 0 ? "written" : "missing");
  unlink(log);
  test_remove_tree(root);
  return test_finish("test_record_folder_gone");
}
