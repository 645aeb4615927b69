/* `fogpipe record` when writing a frame fails (the disk fills up): a file-size limit
 * (RLIMIT_FSIZE, with SIGXFSZ ignored so write() returns EFBIG as on a full disk) lets
 * the folder probe's 4 KiB through but not a frame. record must stop with a message
 * naming the frame, a non-zero status, and leave no frame and no temporary file (and not
 * the empty folder it made). Failing at frame 2 (a folder in the way of its file), it says
 * how to finish from the frame written, as a stop by Ctrl-C does. */
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
  CHECK(frame_files == 0 && others == -1,
        "%d frame files and %d other files left in %s (-1: the folder gone), expected the "
        "folder gone", frame_files, others,
        out);

  /* frame 1 written, frame 2 failing: the command that finishes the run */
  char blocker[700];
  snprintf(blocker, sizeof blocker, "%s/frame.0002.exr", out);
  CHECK(mkdir(out, 0755) == 0 && mkdir(blocker, 0755) == 0, "cannot make %s", blocker);
  char command[3000];
  snprintf(command, sizeof command, "'%s' record %s --frames 3 --out '%s' --size %s > '%s' 2>&1",
           record_bin(), RECORD_TEST_CONFIG, out, RECORD_TEST_SIZE, log);
  status = system(command);
  CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 1 &&
            record_log_contains(log, "cannot write frame 2") &&
            record_log_contains(log, "1 of 3 frames complete in") &&
            record_log_contains(log, "--resume"),
        "a write failing at frame 2: no command to finish from frame 1");
  if (!record_log_contains(log, "--resume")) record_print_log(log);
  test_remove_tree(root);
  return test_finish("test_record_write_fails");
}
