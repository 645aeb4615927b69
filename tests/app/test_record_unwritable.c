/* `fogpipe record` into a folder it cannot write fails before rendering anything: a clear
 * `fogpipe record: ...` message naming the folder, a non-zero exit status, and no frame.
 * Cases: the output path lies under a regular file (cannot be created), and a folder that
 * exists but refuses new files (a 0555 folder; as root, where permissions do not bind,
 * /proc, which refuses new files to everyone). */
#include "tests/app/record_util.h"
#include "tests/test_util.h"

static void expect_refused(const char *out, const char *log, const char *what) {
  int status = record_run(out, 3, NULL, log);
  CHECK(status != 0 && status != 130 && status < 128,
        "%s: record into %s exited with %d, expected an error status", what, out, status);
  CHECK(record_log_contains(log, "fogpipe record:"), "%s: no `fogpipe record:` message", what);
  CHECK(record_log_contains(log, out), "%s: the message does not name %s", what, out);
  char frame[600];
  record_frame_path(out, 1, frame, sizeof frame);
  struct stat st;
  CHECK(stat(frame, &st) != 0, "%s: a frame was written to %s", what, frame);
  if (status == 0) record_print_log(log);
}

int main(void) {
  char root[] = "/tmp/fogpipe-record-unwritable-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char log[600], file[600], under_file[700];
  snprintf(log, sizeof log, "%s/record.log", root);
  snprintf(file, sizeof file, "%s/a-file", root);
  FILE *f = fopen(file, "w");
  CHECK(f != NULL, "cannot create %s", file);
  if (f) fclose(f);
  snprintf(under_file, sizeof under_file, "%s/out", file);
  expect_refused(under_file, log, "output under a regular file");

  if (geteuid() != 0) {
    char locked[600];
    snprintf(locked, sizeof locked, "%s/locked", root);
    mkdir(locked, 0555);
    chmod(locked, 0555);
    expect_refused(locked, log, "read-only folder");
    chmod(locked, 0755);
  } else {
    expect_refused("/proc", log, "/proc (refuses new files)");
  }
  test_remove_tree(root);
  return test_finish("test_record_unwritable");
}
