/* Atomic output files (sim/atomic_file.h). Not a power cut: nothing is fsynced before the
 * rename (a sync a frame costs more than it is worth here; after a power cut the name may
 * hold data never written to disk). */
#define _POSIX_C_SOURCE 200809L
#include "sim/atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int atomic_file_open(atomic_file *file, const char *path, fog_error *err) {
  *file = (atomic_file){.path = path, .fd = -1};
  if (!path || !*path) return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "no output file name given");
  /* ".NAME.tmp.PID.N" in the target's folder: the same file system, so rename is atomic;
   * hidden, so a folder listing during a long write is not confusing; the process and a
   * serial in it, so two writers (threads or processes) never share one, and O_EXCL, so
   * a stale temporary of a killed process or a user's file is never written through. */
  const char *slash = strrchr(path, '/');
  const int folder_len = slash ? (int)(slash - path) + 1 : 0;
  const char *name = path + folder_len;
  struct stat st;
  if (!*name || (stat(path, &st) == 0 && S_ISDIR(st.st_mode)))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: is a folder name, expected a file name",
                    path);
  static atomic_uint serial;
  int why = 0;
  for (int attempt = 0; attempt < 100 && file->fd < 0; attempt++) {
    /* the name cut to 200 bytes in the temporary's: the suffix on a legal 245-byte NAME
     * passed the file system's 255 ("File name too long" for a name that is not) */
    const int n = snprintf(file->temp_path, sizeof file->temp_path, "%.*s.%.200s.tmp.%ld.%u",
                           folder_len, path, name, (long)getpid(),
                           atomic_fetch_add(&serial, 1u));
    if (n < 0 || (size_t)n >= sizeof file->temp_path) {
      file->temp_path[0] = '\0';
      return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: file name too long", path);
    }
    /* 0666: the kernel takes the umask off, as for any new file */
    file->fd = open(file->temp_path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    why = file->fd < 0 ? errno : 0;
    if (file->fd < 0 && why != EEXIST) break;
  }
  if (file->fd < 0) {
    file->temp_path[0] = '\0';
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot create a file in folder '%.*s': %s", path,
                    folder_len ? folder_len : 1, folder_len ? path : ".", strerror(why));
  }
  return 0;
}

int atomic_file_pwrite(atomic_file *file, const void *bytes, size_t n, uint64_t offset) {
  const unsigned char *p = bytes;
  while (n > 0) {
    ssize_t written = pwrite(file->fd, p, n, (off_t)offset);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      /* A short write of 0 bytes with no errno is a full device in practice. */
      if (!file->write_errno) file->write_errno = written < 0 ? errno : ENOSPC;
      return 1;
    }
    p += written;
    n -= (size_t)written;
    offset += (uint64_t)written;
  }
  return 0;
}

void atomic_file_abandon(atomic_file *file) {
  if (file->fd >= 0) close(file->fd);
  file->fd = -1;
  if (file->temp_path[0]) unlink(file->temp_path);
  file->temp_path[0] = '\0';
}

int atomic_file_commit(atomic_file *file, fog_error *err) {
  if (file->write_errno) {
    int e = file->write_errno;
    atomic_file_abandon(file);
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: write failed: %s", file->path, strerror(e));
  }
  /* a file written over keeps its mode (a private 0600 config stays private) */
  struct stat target;
  if (stat(file->path, &target) == 0 && S_ISREG(target.st_mode))
    fchmod(file->fd, target.st_mode & 07777);
  int status = close(file->fd);
  file->fd = -1;
  if (status != 0) {
    int e = errno;
    atomic_file_abandon(file);
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: write failed on close: %s", file->path,
                    strerror(e));
  }
  if (rename(file->temp_path, file->path) != 0) {
    int e = errno;
    atomic_file_abandon(file);
    return fog_fail(err, FOG_ERR_FILE_ACCESS,
                    "%s: cannot rename the finished temporary file onto it: %s", file->path,
                    strerror(e));
  }
  file->temp_path[0] = '\0';
  return 0;
}

int atomic_file_write(const char *path, const void *bytes, size_t size, fog_error *err) {
  atomic_file file;
  if (atomic_file_open(&file, path, err)) return 1;
  atomic_file_pwrite(&file, bytes, size, 0); /* a failure is remembered for the commit */
  return atomic_file_commit(&file, err);
}
