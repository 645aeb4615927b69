/* Every command that writes files, when the disk fills up (issue: a failed write inside
 * the EXR header used to hang the process for ever, in OpenEXR Core's context lock, and
 * leave hidden temporaries behind). A file-size limit (RLIMIT_FSIZE, with SIGXFSZ ignored
 * so write() returns EFBIG as on a full disk) stands in for the full disk: 100 bytes fails
 * the first header write, 3000 bytes fails later in the pixels. Each command must end
 * within a minute with an error status, a message naming what it was writing, and leave
 * nothing in its output folder. */
#include "tests/app/record_util.h"

#include <sys/resource.h>

#include "tests/test_util.h"

#define VDB_FRAME FOGPIPE_SOURCE_DIR "/../shared/data/vdb/groundfog/data/fluid_data_0010.vdb"

/* Runs argv (argv[0] is replaced by the fogpipe binary) under a file-size limit; returns
 * the exit status, 128 + signal, or -2 when it had to be killed after 60 s. */
static int run_limited(const char *const *args, long fsize_limit, const char *log) {
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit limit = {.rlim_cur = (rlim_t)fsize_limit, .rlim_max = (rlim_t)fsize_limit};
    int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644); /* before the limit bites */
    if (fd >= 0) dup2(fd, 1), dup2(fd, 2), close(fd);
    setrlimit(RLIMIT_FSIZE, &limit);
    const char *argv[16] = {record_bin()};
    for (int i = 1; args[i] && i < 15; i++) argv[i] = args[i];
    execv(argv[0], (char *const *)argv);
    _exit(127);
  }
  for (int waited_ms = 0; waited_ms < 60000; waited_ms += 20) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    record_sleep_ms(20);
  }
  kill(pid, SIGKILL);
  waitpid(pid, NULL, 0);
  return -2;
}

static void check_command(const char *root, const char *name, const char *const *args,
                          const char *folder, long limit) {
  char log[700];
  snprintf(log, sizeof log, "%s/%s-%ld.log", root, name, limit);
  int status = run_limited(args, limit, log);
  CHECK(status != -2, "%s with a %ld-byte file limit hung (killed after 60 s)", name, limit);
  CHECK(status > 0 && status < 128, "%s with a %ld-byte file limit exited with %d", name,
        limit, status);
  CHECK(record_log_contains(log, folder), "%s: the message does not name %s", name, folder);
  int left = test_folder_entries(folder);
  if (left < 0) left = 0; /* never made: nothing left */
  CHECK(left == 0, "%s with a %ld-byte limit left %d entries in %s", name, limit, left,
        folder);
  if (status <= 0 || status >= 128 || left) record_print_log(log);
  char cmd[800];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", folder);
  if (system(cmd)) fprintf(stderr, "cannot clean %s\n", folder);
}

int main(void) {
  char root[] = "/tmp/fogpipe-full-disk-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char render_dir[600], render_out[700], transform_dir[600], import_dir[600];
  snprintf(render_dir, sizeof render_dir, "%s/render", root);
  snprintf(render_out, sizeof render_out, "%s/frame.exr", render_dir);
  snprintf(transform_dir, sizeof transform_dir, "%s/transform", root);
  snprintf(import_dir, sizeof import_dir, "%s/import", root);

  const long limits[] = {100, 3000};
  for (int i = 0; i < 2; i++) {
    mkdir(render_dir, 0755);
    const char *render[] = {"", "render", RECORD_TEST_CONFIG, "--size", RECORD_TEST_SIZE,
                            "--out", render_out, NULL};
    check_command(root, "render", render, render_dir, limits[i]);
    const char *transform[] = {"", "transform", "data/fogmap_sample.png", "--levels", "3",
                               "--out", transform_dir, NULL};
    check_command(root, "transform", transform, transform_dir, limits[i]);
    const char *import[] = {"", "import", VDB_FRAME, "--out", import_dir, NULL};
    check_command(root, "import", import, import_dir, limits[i]);
  }
  test_remove_tree(root);
  return test_finish("test_full_disk_every_writer");
}
