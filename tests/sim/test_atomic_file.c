/* sim/atomic_file.h: a new output file takes the process umask as any new file, a file
 * written over keeps its mode, and two writers never share a temporary; a failed write
 * leaves the target as it was and nothing beside it. Through the public writers
 * (image_write_png, atomic_file_write). */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sim/sim.h"
#include "test_util.h"

static unsigned mode_of(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 ? (unsigned)(st.st_mode & 07777) : 0u;
}

static char *read_all(const char *path, size_t *size) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  char *text = malloc(1 << 20);
  *size = text ? fread(text, 1, (1 << 20) - 1, f) : 0;
  if (text) text[*size] = '\0';
  fclose(f);
  return text;
}

typedef struct writer {
  const char *path;
  char byte;
  int failed;
} writer;

static void *write_many(void *arg) {
  writer *w = arg;
  char block[4096];
  memset(block, w->byte, sizeof block);
  for (int i = 0; i < 200; i++) {
    fog_error err = {0};
    w->failed |= atomic_file_write(w->path, block, sizeof block, &err);
  }
  return NULL;
}

int main(void) {
  char dir[] = "/tmp/fogpipe-atomic-XXXXXX";
  if (!test_scratch_folder(dir)) return 1;
  char png[600], text_path[600];
  snprintf(png, sizeof png, "%s/image.png", dir);
  snprintf(text_path, sizeof text_path, "%s/table.txt", dir);
  const float pixels[4] = {0, 0.25f, 0.5f, 1};
  fog_error err = {0};

  /* a new image under umask 027: 0640 (it was always 0644, whatever the umask) */
  const mode_t old_mask = umask(027);
  CHECK(image_write_png(png, 2, 2, 1, pixels, &err) == 0, "write %s: %s", png, err.message);
  umask(old_mask);
  CHECK(mode_of(png) == 0640, "a new PNG under umask 027: mode %o, expected 640", mode_of(png));
  /* written over, a 0600 file stays 0600 (it became 0644) */
  CHECK(chmod(png, 0600) == 0, "chmod %s", png);
  CHECK(image_write_png(png, 2, 2, 1, pixels, &err) == 0, "rewrite %s: %s", png, err.message);
  CHECK(mode_of(png) == 0600, "a 0600 PNG written over: mode %o, expected 600", mode_of(png));

  /* the whole-file call: the bytes as given */
  CHECK(atomic_file_write(text_path, "one\ntwo\n", 8, &err) == 0, "write %s: %s", text_path,
        err.message);
  size_t size = 0;
  char *back = read_all(text_path, &size);
  CHECK(back && size == 8 && !memcmp(back, "one\ntwo\n", 8), "%s holds '%s'", text_path,
        back ? back : "(nothing)");
  free(back);

  /* a failed write (onto a folder) leaves nothing beside it */
  char folder[600];
  snprintf(folder, sizeof folder, "%s/taken", dir);
  CHECK(mkdir(folder, 0755) == 0, "mkdir %s", folder);
  CHECK(atomic_file_write(folder, "x", 1, &err) != 0 && strstr(err.message, "taken"),
        "written onto a folder: %s", err.message);
  rmdir(folder);

  /* two threads writing one target: each file seen is one writer's whole block, never a
   * mix (a shared temporary would interleave them), and no temporary is left */
  char shared[600];
  snprintf(shared, sizeof shared, "%s/shared.bin", dir);
  writer a = {.path = shared, .byte = 'a'}, b = {.path = shared, .byte = 'b'};
  pthread_t ta, tb;
  CHECK(pthread_create(&ta, NULL, write_many, &a) == 0 &&
            pthread_create(&tb, NULL, write_many, &b) == 0,
        "pthread_create");
  pthread_join(ta, NULL);
  pthread_join(tb, NULL);
  CHECK(!a.failed && !b.failed, "a concurrent write failed");
  back = read_all(shared, &size);
  bool whole = back && size == 4096;
  for (size_t i = 1; whole && i < size; i++) whole = back[i] == back[0];
  CHECK(whole, "the shared target is not one writer's block (%zu bytes)", size);
  free(back);
  CHECK(test_folder_entries(dir) == 3, "%d entries in %s, expected the 3 targets",
        test_folder_entries(dir), dir);

  test_remove_tree(dir);
  return test_finish("test_atomic_file");
}
