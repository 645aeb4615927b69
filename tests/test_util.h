/* Minimal test harness: CHECK records a failure with file:line and a message and
 * carries on, so one run reports every broken property; test_finish() prints a
 * summary and returns the process exit code. */
#ifndef FOGPIPE_TEST_UTIL_H
#define FOGPIPE_TEST_UTIL_H

#include <stdio.h>

static int test_checks_run;
static int test_checks_failed;

#define CHECK(cond, ...)                                                   \
  do {                                                                     \
    test_checks_run++;                                                     \
    if (!(cond)) {                                                         \
      test_checks_failed++;                                                \
      fprintf(stderr, "%s:%d: CHECK(%s) failed: ", __FILE__, __LINE__,     \
              #cond);                                                      \
      fprintf(stderr, __VA_ARGS__);                                        \
      fputc('\n', stderr);                                                 \
    }                                                                      \
  } while (0)

static inline int test_finish(const char *name) {
  printf("%s: %d checks, %d failed\n", name, test_checks_run, test_checks_failed);
  return test_checks_failed ? 1 : 0;
}

/* Writes text to path (a config or script a test needs), recording a failed check when it
 * cannot: 1 when written, else 0. */
static inline int test_write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  int written = f && fputs(text, f) >= 0;
  if (f && fclose(f) != 0) written = 0;
  CHECK(written, "cannot write %s", path);
  return written;
}

/* Scratch folders, for the tests that define _POSIX_C_SOURCE 200809L (mkdtemp, dirent). */
#if defined(_POSIX_C_SOURCE) && _POSIX_C_SOURCE >= 200809L
#include <dirent.h>
#include <stdlib.h>
#include <string.h>

/* mkdtemp on a "/tmp/NAME-XXXXXX" template (filled in place): 1, or 0 having said why. */
static inline int test_scratch_folder(char *template_path) {
  if (mkdtemp(template_path)) return 1;
  perror("mkdtemp");
  return 0;
}

/* Entries in a folder besides . and ..; -1 when it does not exist. */
static inline int test_folder_entries(const char *folder) {
  DIR *dir = opendir(folder);
  if (!dir) return -1;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(dir)))
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
  closedir(dir);
  return n;
}

/* rm -rf path (a scratch folder and what a test left in it). */
static inline void test_remove_tree(const char *path) {
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", path);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", path);
}
#endif

#endif
