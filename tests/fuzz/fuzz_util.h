/* What the harnesses share: handing a fuzz input to a reader that takes a path. */
#ifndef FOGPIPE_FUZZ_UTIL_H
#define FOGPIPE_FUZZ_UTIL_H

#include <stddef.h>
#include <stdint.h>

/* The input as a file: one memfd per process (no file system, nothing left behind),
 * rewritten for each input; returns its path "/proc/self/fd/N". Aborts if the memfd
 * cannot be made or written (a harness fault, not a finding). */
const char *fuzz_memfd_path(const uint8_t *data, size_t size);

/* A scratch folder for readers that resolve names against the input's folder (the scene
 * config): $FOGPIPE_FUZZ_TMP if set (run.sh sets it and removes it afterwards), else a new
 * /dev/shm/fogpipe-fuzz.XXXXXX removed at exit. */
const char *fuzz_scratch_dir(void);

/* Writes data to DIR/name (truncating); returns the path (static storage). Aborts on
 * failure. */
const char *fuzz_write_file(const char *dir, const char *name, const uint8_t *data,
                            size_t size);

/* Makes DIR/name (and its folders) as an empty file, for names a parser only checks. */
void fuzz_touch(const char *dir, const char *name);

#endif
