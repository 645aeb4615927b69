/* For the tests that run the fogpipe executable: its path (ctest passes FOGPIPE_BIN) and a
 * fresh temporary folder. Include after the feature-test macros (mkdtemp is POSIX). */
#ifndef FOGPIPE_TEST_BIN_H
#define FOGPIPE_TEST_BIN_H

#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>

#include "test_util.h"

/* The binary, with folder_template ("/tmp/NAME_XXXXXX") made into a new folder; NULL, with
 * a failed check, when either is missing. */
static inline const char *test_bin_and_folder(char *folder_template) {
  const char *bin = getenv("FOGPIPE_BIN");
  CHECK(bin != NULL, "FOGPIPE_BIN is not set (run through ctest)");
  if (!bin) return NULL;
  int made = mkdtemp(folder_template) != NULL;
  CHECK(made, "mkdtemp %s", folder_template);
  return made ? bin : NULL;
}

/* Runs the shell command line `command` (add 2>&1 to gather stderr too), its output into
 * output (size bytes, truncated, always terminated); the exit status, -1 when it did not
 * exit (a signal) or could not start. Needs <stdio.h> and <sys/wait.h>. */
static inline int test_run_output(const char *command, char *output, size_t size) {
  FILE *p = popen(command, "r");
  if (!p) return -1;
  size_t n = fread(output, 1, size - 1, p);
  output[n] = '\0';
  int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

#endif
