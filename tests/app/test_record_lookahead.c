/* The pipeline prepares the next frame while the current one is drawn: a failure of that
 * look-ahead (here the bake's frame 4, damaged) belongs to the next frame, not to the one
 * already prepared. `record bake.ini --frames 3` of a bake whose frame 4 is damaged writes
 * frames 1-3, exit 0 (it failed frame 3 naming frame 4's file, so a farm range ending
 * before a damaged file never finished); --frames 4 fails at frame 4, naming the file. */
#include "tests/app/record_util.h"
#include "tests/test_util.h"

int main(void) {
  char root[] = "/tmp/fogpipe-lookahead-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char bake[600], out[600], log[600], ini[700], last[700], command[3000];
  snprintf(bake, sizeof bake, "%s/bake", root);
  snprintf(out, sizeof out, "%s/out", root);
  snprintf(log, sizeof log, "%s/log.txt", root);
  snprintf(ini, sizeof ini, "%s/bake.ini", bake);
  snprintf(last, sizeof last, "%s/fog.0004.exr", bake);
  snprintf(command, sizeof command, "'%s' bake %s --frames 4 --out '%s'", record_bin(),
           RECORD_TEST_CONFIG, bake);
  CHECK(record_shell(command, log) == 0, "the bake failed");
  CHECK(truncate(last, 200) == 0, "cannot damage %s", last);
  for (int pass = 0; pass < 2; pass++) { /* threaded, then --synchronous */
    const char *mode = pass ? " --synchronous" : "";
    snprintf(command, sizeof command, "'%s' record '%s' --frames 3 --size %s --out '%s'%s",
             record_bin(), ini, RECORD_TEST_SIZE, out, mode);
    const int status = record_shell(command, log);
    if (status != 0) record_print_log(log);
    CHECK(status == 0, "record%s --frames 3 of a bake whose frame 4 is damaged: exit %d", mode,
          status);
    for (int f = 1; f <= 3; f++) {
      char frame[700];
      record_frame_path(out, f, frame, sizeof frame);
      CHECK(access(frame, F_OK) == 0, "record%s --frames 3: frame %d not written", mode, f);
    }
    snprintf(command, sizeof command,
             "'%s' record '%s' --frames 4 --size %s --out '%s-4%s'%s", record_bin(), ini,
             RECORD_TEST_SIZE, out, mode[0] ? "s" : "", mode);
    CHECK(record_shell(command, log) == 1 && record_log_contains(log, "frame 4") &&
              record_log_contains(log, "fog.0004.exr"),
          "record%s --frames 4 did not fail at frame 4 naming its file", mode);
    snprintf(command, sizeof command, "rm -rf '%s'", out);
    CHECK(system(command) == 0, "cannot remove %s", out);
  }
  test_remove_tree(root);
  return test_finish("test_record_lookahead");
}
