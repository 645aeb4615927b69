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

#endif
