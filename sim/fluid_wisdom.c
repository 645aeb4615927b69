/* FFTW wisdom in the user's cache folder. Failing to read or write it only costs
 * planning time, so nothing here is an error for the caller. */
#define _POSIX_C_SOURCE 200809L
#include "sim/fluid_wisdom.h"

#include <errno.h>
#include <fftw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int cache_dir(char *dir, size_t size) {
  const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
  int n;
  if (xdg && xdg[0] == '/') /* the XDG spec ignores relative values */
    n = snprintf(dir, size, "%s/fogpipe", xdg);
  else if (home && home[0])
    n = snprintf(dir, size, "%s/.cache/fogpipe", home);
  else
    return 1;
  return n < 0 || (size_t)n >= size;
}

int fluid_wisdom_path(char *path, size_t size) {
  char dir[4096];
  if (cache_dir(dir, sizeof dir)) return 1;
  int n = snprintf(path, size, "%s/fftw3f.wisdom", dir);
  return n < 0 || (size_t)n >= size;
}

int fluid_wisdom_load(void) {
  char path[4200];
  if (fluid_wisdom_path(path, sizeof path)) return 1;
  return fftwf_import_wisdom_from_filename(path) ? 0 : 1;
}

/* mkdir -p for the cache folder (its parent ~/.cache may not exist yet). */
static int make_dirs(const char *dir) {
  char buf[4096];
  size_t len = strlen(dir);
  if (len >= sizeof buf) return 1;
  memcpy(buf, dir, len + 1);
  for (char *p = buf + 1; *p; p++) {
    if (*p != '/') continue;
    *p = 0;
    if (mkdir(buf, 0755) && errno != EEXIST) return 1;
    *p = '/';
  }
  return mkdir(buf, 0755) && errno != EEXIST;
}

int fluid_wisdom_save(void) {
  char dir[4096], path[4200], temp[4300];
  if (cache_dir(dir, sizeof dir) || make_dirs(dir)) return 1;
  snprintf(path, sizeof path, "%s/fftw3f.wisdom", dir);
  snprintf(temp, sizeof temp, "%s.tmp.%ld", path, (long)getpid());
  if (!fftwf_export_wisdom_to_filename(temp)) {
    remove(temp);
    return 1;
  }
  if (rename(temp, path)) {
    remove(temp);
    return 1;
  }
  return 0;
}
