/* Output folders (app/out_folder.h). */
#define _POSIX_C_SOURCE 200809L
#include "app/out_folder.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void out_folder_remove(const char *path, const char *created) {
  if (!created[0]) return;
  char folder[OUT_FOLDER_PATH_MAX];
  snprintf(folder, sizeof folder, "%s", path);
  const size_t root = strlen(created);
  /* rmdir refuses a folder that is not empty: frames and other files always stay */
  while (strlen(folder) >= root) {
    if (rmdir(folder) != 0 && errno != ENOENT) break;
    char *slash = strrchr(folder, '/');
    if (!slash || slash == folder) break;
    *slash = '\0';
  }
}

int out_folder_make(const char *path, char *created, size_t created_size, fog_error *err) {
  char partial[OUT_FOLDER_PATH_MAX];
  const size_t n = strlen(path);
  if (n == 0)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "the output folder's name is empty");
  if (n >= sizeof partial)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "the output folder's name is %zu bytes long, more than the %zu taken: %.60s...",
                    n, sizeof partial - 1, path);
  memcpy(partial, path, n + 1);
  char deepest[OUT_FOLDER_PATH_MAX] = ""; /* the innermost folder made so far */
  for (size_t i = 1; i <= n; i++) {
    if (partial[i] != '/' && partial[i] != '\0') continue;
    char saved = partial[i];
    partial[i] = '\0';
    if (mkdir(partial, 0777) == 0) {
      if (!created[0]) snprintf(created, created_size, "%s", partial);
      snprintf(deepest, sizeof deepest, "%s", partial);
    } else if (errno != EEXIST) {
      const int e = errno;
      fog_fail(err, FOG_ERR_FILE_ACCESS, "cannot create the output folder %s: %s", partial,
               strerror(e));
      out_folder_remove(deepest, created);
      created[0] = '\0';
      return 1;
    }
    partial[i] = saved;
  }
  struct stat st;
  if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "the output path %s exists and is not a folder", path);
    out_folder_remove(deepest, created);
    created[0] = '\0';
    return 1;
  }
  return 0;
}
