/* `fogpipe record` when writing a frame fails (the disk fills up): a file-size limit
 * (RLIMIT_FSIZE, with SIGXFSZ ignored so write() returns EFBIG as on a full disk) lets
 * the folder probe's 4 KiB through but not a frame. record must stop with a message
 * naming the frame, a non-zero status, and leave no frame and no temporary file (and not
 * the empty folder it made). */
#include "tests/app/record_util.h"

#include <sys/resource.h>

#include "tests/test_util.h"

int main(void) {
  char root[] = "/tmp/fogpipe-record-full-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char out[600], log[600];
  snprintf(out, sizeof out, "%s/frames", root);
  snprintf(log, sizeof log, "%s/record.log", root);
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit limit = {.rlim_cur = 8192, .rlim_max = 8192};
    setrlimit(RLIMIT_FSIZE, &limit);
    int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) dup2(fd, 1), dup2(fd, 2), close(fd);
    const char *argv[] = {record_bin(), "record", RECORD_TEST_CONFIG, "--frames", "3",
                          "--out", out, "--size", RECORD_TEST_SIZE, NULL};
    execv(argv[0], (char *const *)argv);
    _exit(127);
  }
  int status = record_wait(pid);
  CHECK(status != 0 && status < 128, "record exited with %d, expected an error status", status);
  CHECK(record_log_contains(log, "fogpipe record:") && record_log_contains(log, "frame 1"),
        "no `fogpipe record: ... frame 1` message");
  if (status == 0 || !record_log_contains(log, "frame 1")) record_print_log(log);
  int frame_files = 0;
  int others = record_count_files(out, &frame_files); /* -1: the folder record made is gone */
  CHECK(frame_files == 0 && others <= 0,
        "%d frame files and %d other files left in %s, expected none", frame_files, others,
        out);
  test_remove_tree(root);
  return test_finish("test_record_write_fails");
}
