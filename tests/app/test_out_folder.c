/* app/out_folder.h: mkdir -p and its undo remove exactly the folders that were made. With
 * an empty folder that existed before (which the undo must keep: it is not ours), paths
 * through "..", ".", a trailing slash, a component that is a file (the failure removes what
 * was made before it), files left in a made folder (kept, and so are its parents), and a
 * name too long for the buffer (refused before anything is made). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/out_folder.h"
#include "tests/test_util.h"

static char root[] = "/tmp/fogpipe_out_folder_XXXXXX";

static bool is_folder(const char *relative) {
  char path[600];
  snprintf(path, sizeof path, "%s/%s", root, relative);
  struct stat st;
  return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

static int make(out_folder *f, const char *relative, fog_error *err) {
  char path[1200];
  snprintf(path, sizeof path, "%s/%s", root, relative);
  return out_folder_make(f, path, err);
}

int main(void) {
  if (!mkdtemp(root)) return 1;
  char path[600];
  snprintf(path, sizeof path, "%s/existing", root);
  CHECK(mkdir(path, 0777) == 0, "mkdir %s", path);
  snprintf(path, sizeof path, "%s/file", root);
  FILE *file = fopen(path, "w");
  CHECK(file != NULL, "%s", path);
  if (file) fclose(file);
  fog_error err = {0};
  out_folder f;

  /* through "..": new and existing/sub made; the undo keeps existing (it was there) */
  CHECK(make(&f, "new/../existing/sub", &err) == 0, "%s", err.message);
  CHECK(is_folder("new") && is_folder("existing/sub"), "new/../existing/sub not made");
  out_folder_undo(&f);
  CHECK(!is_folder("new") && !is_folder("existing/sub"), "the undo left new or existing/sub");
  CHECK(is_folder("existing"), "the undo removed existing, which was there before");

  /* "." and a trailing slash */
  CHECK(make(&f, "dot/.", &err) == 0 && make(&f, "dot/.", &err) == 0, "%s", err.message);
  CHECK(!f.any, "a second make of dot/. made something");
  CHECK(make(&f, "n2/.", &err) == 0 && is_folder("n2"), "%s", err.message);
  out_folder_undo(&f);
  CHECK(!is_folder("n2"), "the undo of n2/. left n2");
  CHECK(make(&f, "n3/a/", &err) == 0 && is_folder("n3/a"), "%s", err.message);
  out_folder_undo(&f);
  CHECK(!is_folder("n3"), "the undo of n3/a/ left n3 or n3/a");

  /* a file in the way: the failure removes what it made before it, and names the path */
  CHECK(make(&f, "n4/../file/sub", &err) != 0 && strstr(err.message, "file/sub"),
        "a path through a file: '%s'", err.message);
  CHECK(!is_folder("n4") && !f.any, "the failed make left n4");
  snprintf(path, sizeof path, "%s/file", root);
  struct stat st;
  CHECK(stat(path, &st) == 0 && S_ISREG(st.st_mode), "the file in the way was touched");

  /* a made folder that holds a file stays, with its parents */
  CHECK(make(&f, "n5/x", &err) == 0, "%s", err.message);
  snprintf(path, sizeof path, "%s/n5/x/keep", root);
  file = fopen(path, "w");
  if (file) fclose(file);
  out_folder_undo(&f);
  CHECK(is_folder("n5/x"), "the undo removed a folder holding a file");
  unlink(path);

  /* too long for the buffer: refused, nothing made */
  char longer[1100];
  memset(longer, 'y', sizeof longer - 1);
  longer[sizeof longer - 1] = '\0';
  memcpy(longer, "n6/", 3);
  CHECK(make(&f, longer, &err) != 0 && strstr(err.message, "bytes long"), "'%s'", err.message);
  CHECK(!is_folder("n6"), "a refused name made n6");

  char command[700];
  snprintf(command, sizeof command, "rm -rf '%s'", root);
  CHECK(system(command) == 0, "%s", command);
  return test_finish("test_out_folder");
}
