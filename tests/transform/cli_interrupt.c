/* `fogpipe transform` stopped by SIGTERM while it writes its levels (FOGPIPE_BIN): it exits
 * 130, removes its staging folder and the output folder it made, and leaves nothing behind.
 * It used to die with the signal and leave DIR/.transform.XXXXXX, 21 MB of partial levels
 * that no later run removed. The signal is sent once DIR exists (the levels are being
 * written then) on a 2048^2 map whose levels take a second or so to write. */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "sim/sim.h"
#include "test_util.h"

enum { SIDE = 2048 };

int main(void) {
  const char *bin = getenv("FOGPIPE_BIN");
  if (!bin) {
    fprintf(stderr, "FOGPIPE_BIN not set\n");
    return 1;
  }
  char root[] = "/tmp/fogpipe_transform_stop_XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char input[300], out[300];
  snprintf(input, sizeof input, "%s/big.exr", root);
  snprintf(out, sizeof out, "%s/levels", root);
  fogmap map;
  fog_error err = {0};
  CHECK(!fogmap_create(&map, SIDE, SIDE, &err), "%s", err.message);
  for (size_t i = 0; i < (size_t)SIDE * SIDE; i++) map.density[i] = (float)(i % 977) / 977.0f;
  CHECK(!fogmap_save_exr(input, &map, &err), "%s", err.message);
  fogmap_destroy(&map);

  const pid_t child = fork();
  if (child == 0) {
    freopen("/dev/null", "w", stdout);
    execl(bin, bin, "transform", input, "--levels", "2", "--basis", "haar", "--out", out,
          (char *)NULL);
    _exit(127);
  }
  /* wait for DIR (the run writes its levels then), then stop it */
  struct stat st;
  int waited = 0, status = 0;
  pid_t ended = 0; /* the child, reaped by the poll: its status is the one it left */
  while (stat(out, &st) != 0 && waited < 20000 &&
         (ended = waitpid(child, &status, WNOHANG)) == 0) {
    nanosleep(&(struct timespec){.tv_nsec = 1000000}, NULL);
    waited++;
  }
  if (ended != child) { /* (a poll that reaped it passed status 0 on: a failed run read as
                         * "finished before the signal") */
    kill(child, SIGTERM);
    waitpid(child, &status, 0);
  }
  const bool stopped = WIFEXITED(status) && WEXITSTATUS(status) == 130;
  const bool finished = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  CHECK(stopped || finished, "transform stopped by SIGTERM: %s %d",
        WIFSIGNALED(status) ? "killed by signal" : "exit", WIFSIGNALED(status) ? WTERMSIG(status)
                                                                            : WEXITSTATUS(status));
  if (finished) {
    printf("the transform finished before the signal: nothing tested\n");
  } else {
    CHECK(stat(out, &st) != 0, "%s is left after the stop (it made it)", out);
    const int left = test_folder_entries(root);
    CHECK(left == 1, "%d entries in %s besides the input", left - 1, root);
  }
  test_remove_tree(root);
  return test_finish("transform_cli_interrupt");
}
