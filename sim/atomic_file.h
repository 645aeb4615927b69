/* Output files written whole or not at all: a temporary ".NAME.tmp.PID.N" in the target's
 * own folder (so rename(2) is atomic: same file system), renamed over the target only
 * once everything was written; any failure removes the temporary and leaves the target as
 * it was. fogpipe's outputs go through here: images, configs, the import sidecar, the
 * transform manifest, CSVs and charts (FFTW's wisdom cache and the recorder's write probe
 * are its own, private files).
 *
 * Permissions: a new file gets 0666 less the process umask, as any file a program
 * creates (the temporary is made with O_EXCL and that mode, so the kernel applies the
 * umask: thread-safe, where reading the umask is not); a regular file written over keeps
 * its own mode. */
#ifndef FOGPIPE_SIM_ATOMIC_FILE_H
#define FOGPIPE_SIM_ATOMIC_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "transform/fog_error.h"

typedef struct atomic_file {
  const char *path;     /* the target (not owned) */
  char temp_path[4096]; /* the temporary beside it */
  int fd;               /* -1 once closed */
  int write_errno;      /* first failed write's errno, 0 if none */
} atomic_file;

/* Creates the temporary; fails naming the target's folder and the reason. */
int atomic_file_open(atomic_file *file, const char *path, fog_error *err);
/* pwrite of all n bytes at offset; on failure remembers errno (the first one) and fails. */
int atomic_file_pwrite(atomic_file *file, const void *bytes, size_t n, uint64_t offset);
/* Closes, gives the temporary the replaced file's mode (if a regular file is replaced)
 * and renames it over the target; on failure (a remembered write error, close or rename
 * failing) removes the temporary and fails. */
int atomic_file_commit(atomic_file *file, fog_error *err);
/* Closes and removes the temporary (after a failure elsewhere). */
void atomic_file_abandon(atomic_file *file);

/* The whole file in one call: open, write size bytes, commit. */
int atomic_file_write(const char *path, const void *bytes, size_t size, fog_error *err);

#endif
