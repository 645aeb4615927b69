/* Output folders (app/out_folder.h). */
#define _POSIX_C_SOURCE 200809L
#include "app/out_folder.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void out_folder_undo(const out_folder *folder) {
  if (!folder->any) return;
  char prefix[OUT_FOLDER_PATH_MAX];
  for (size_t end = strlen(folder->path); end > 0; end--) {
    if (!folder->made[end]) continue;
    memcpy(prefix, folder->path, end);
    prefix[end] = '\0';
    rmdir(prefix); /* refused while not empty: what a failed run wrote stays */
  }
}

int out_folder_make(out_folder *folder, const char *path, fog_error *err) {
  memset(folder, 0, sizeof *folder);
  const size_t n = strlen(path);
  if (n == 0)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "the output folder's name is empty");
  if (n >= sizeof folder->path)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "the output folder's name is %zu bytes long, more than the %zu taken: "
                    "%.60s...", n, sizeof folder->path - 1, path);
  memcpy(folder->path, path, n + 1);
  char partial[OUT_FOLDER_PATH_MAX];
  memcpy(partial, path, n + 1);
  for (size_t i = 1; i <= n; i++) {
    if (partial[i] != '/' && partial[i] != '\0') continue;
    char saved = partial[i];
    partial[i] = '\0';
    if (mkdir(partial, 0777) == 0) {
      folder->made[i] = folder->any = true;
    } else if (errno != EEXIST) {
      const int e = errno;
      fog_fail(err, FOG_ERR_FILE_ACCESS, "cannot create the output folder %s: %s", partial,
               strerror(e));
      out_folder_undo(folder);
      memset(folder, 0, sizeof *folder);
      return 1;
    }
    partial[i] = saved;
  }
  struct stat st;
  if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "the output path %s exists and is not a folder", path);
    out_folder_undo(folder);
    memset(folder, 0, sizeof *folder);
    return 1;
  }
  return 0;
}
