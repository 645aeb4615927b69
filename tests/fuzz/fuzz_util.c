/* fuzz_util.h. */
#define _GNU_SOURCE
#include "fuzz_util.h"

#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

static void die(const char *what) {
  fprintf(stderr, "fuzz harness: %s: %s\n", what, strerror(errno));
  abort();
}

static void write_all(int fd, const uint8_t *data, size_t size) {
  if (ftruncate(fd, 0) != 0) die("ftruncate");
  size_t done = 0;
  while (done < size) {
    ssize_t n = pwrite(fd, data + done, size - done, (off_t)done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) die("pwrite");
    done += (size_t)n;
  }
}

const char *fuzz_memfd_path(const uint8_t *data, size_t size) {
  static int fd = -1;
  static char path[64];
  if (fd < 0) {
    fd = memfd_create("fogpipe-fuzz", MFD_CLOEXEC);
    if (fd < 0) die("memfd_create");
    snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
  }
  write_all(fd, data, size);
  return path;
}

static char scratch[4096];
static int scratch_owned;

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw) {
  return remove(path);
}

static void remove_scratch(void) {
  if (scratch_owned) nftw(scratch, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

const char *fuzz_scratch_dir(void) {
  if (scratch[0]) return scratch;
  const char *given = getenv("FOGPIPE_FUZZ_TMP");
  if (given && *given) {
    snprintf(scratch, sizeof scratch, "%s", given);
    if (mkdir(scratch, 0700) != 0 && errno != EEXIST) die(scratch);
  } else {
    snprintf(scratch, sizeof scratch, "/dev/shm/fogpipe-fuzz.XXXXXX");
    if (!mkdtemp(scratch)) die("mkdtemp");
    scratch_owned = 1;
    atexit(remove_scratch);
  }
  return scratch;
}

const char *fuzz_write_file(const char *dir, const char *name, const uint8_t *data,
                            size_t size) {
  static char path[4200];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  int fd = open(path, O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) die(path);
  write_all(fd, data, size);
  close(fd);
  return path;
}

void fuzz_touch(const char *dir, const char *name) {
  char path[4200];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  for (char *p = path + strlen(dir) + 1; *p; p++)
    if (*p == '/') {
      *p = '\0';
      if (mkdir(path, 0700) != 0 && errno != EEXIST) die(path);
      *p = '/';
    }
  int fd = open(path, O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) die(path);
  close(fd);
}
