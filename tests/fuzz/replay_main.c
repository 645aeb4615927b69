/* libFuzzer's driver, replaced for the ordinary build (tests/fuzz/harnesses.cmake): runs a
 * harness's LLVMFuzzerTestOneInput once on each file named, or on each file of each folder
 * named, in name order, as `fuzz_TARGET FILE...` does under libFuzzer. A harness aborts on a
 * broken promise; this driver adds a non-zero exit for an unreadable argument, an empty
 * folder or an empty argument list, so a corpus that went missing does not pass as zero
 * inputs replayed, and counts the inputs the harness turned away unrun (its -1). */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
/* Defined by the harnesses that need set-up (fuzz_config.c); weak, as libFuzzer has it. */
__attribute__((weak)) int LLVMFuzzerInitialize(int *argc, char ***argv);

static int rejected; /* inputs the harness returned -1 for: not run */

static int replay_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    fprintf(stderr, "fuzz replay: cannot open %s\n", path);
    return 1;
  }
  size_t capacity = 4096, size = 0;
  uint8_t *data = malloc(capacity);
  for (size_t got; data && (got = fread(data + size, 1, capacity - size, f)) > 0;) {
    size += got;
    if (size == capacity) {
      uint8_t *grown = realloc(data, capacity *= 2);
      if (!grown) free(data);
      data = grown;
    }
  }
  const int failed = ferror(f) || !data;
  fclose(f);
  if (failed) {
    free(data);
    fprintf(stderr, "fuzz replay: cannot read %s\n", path);
    return 1;
  }
  /* A copy of exactly `size` bytes, so ASan sees a read past the input as libFuzzer would. */
  uint8_t *exact = malloc(size ? size : 1);
  if (!exact) abort();
  memcpy(exact, data, size);
  free(data);
  rejected += LLVMFuzzerTestOneInput(exact, size) == -1;
  free(exact);
  return 0;
}

static int compare_names(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Replays every regular file of FOLDER; returns the count, or -1 if it cannot be listed. */
static int replay_folder(const char *folder, int *failures) {
  DIR *dir = opendir(folder);
  if (!dir) return -1;
  char **names = NULL;
  int count = 0, capacity = 0;
  for (struct dirent *e; (e = readdir(dir));) {
    if (e->d_name[0] == '.') continue;
    if (count == capacity) {
      char **grown = realloc(names, sizeof *names * (capacity = capacity ? 2 * capacity : 64));
      if (!grown) abort();
      names = grown;
    }
    if (!(names[count++] = strdup(e->d_name))) abort();
  }
  closedir(dir);
  qsort(names, count, sizeof *names, compare_names);
  int replayed = 0;
  for (int i = 0; i < count; i++) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", folder, names[i]);
    struct stat st;
    if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) {
      *failures += replay_file(path);
      replayed++;
    }
    free(names[i]);
  }
  free(names);
  return replayed;
}

int main(int argc, char **argv) {
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  int inputs = 0, failures = 0;
  for (int i = 1; i < argc; i++) {
    struct stat st;
    if (stat(argv[i], &st) != 0) {
      fprintf(stderr, "fuzz replay: %s does not exist\n", argv[i]);
      failures++;
    } else if (S_ISDIR(st.st_mode)) {
      const int n = replay_folder(argv[i], &failures);
      if (n < 0) {
        fprintf(stderr, "fuzz replay: cannot list %s\n", argv[i]);
        failures++;
      } else if (n == 0) { /* a corpus or regressions folder emptied: nothing replayed */
        fprintf(stderr, "fuzz replay: %s holds no input\n", argv[i]);
        failures++;
      }
      inputs += n > 0 ? n : 0;
    } else {
      failures += replay_file(argv[i]);
      inputs++;
    }
  }
  printf("fuzz replay: %d inputs, %d turned away by the harness unrun, %d unreadable or "
         "missing\n", inputs, rejected, failures);
  return failures || inputs == 0;
}
