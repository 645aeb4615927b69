/* For the tests that run the fogpipe executable: its path (ctest passes FOGPIPE_BIN) and a
 * fresh temporary folder. Include after the feature-test macros (mkdtemp is POSIX). */
#ifndef FOGPIPE_TEST_BIN_H
#define FOGPIPE_TEST_BIN_H

#include <stdlib.h>

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

#endif
