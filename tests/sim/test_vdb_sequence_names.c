/* How vdb_sequence_find reads its inputs' names (sim/vdb_import.h), on empty files in a
 * scratch folder (the finder lists names; it opens nothing):
 *   - a path that exists is itself: a folder or a file whose name holds '#' is not a
 *     frame pattern ("take#2/", "shot#48.vdb");
 *   - in a pattern, the frame number is the last run of '#' of the file name, never a
 *     '#' of a folder;
 *   - two different files of one frame number are refused, naming both (one would stand
 *     for the other); the same file given twice, however spelt ("d//f", "./d/f"), is one
 *     frame; a name without digits (numbered by its place) clashes with no frame. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "sim/vdb_import.h"
#include "test_util.h"

static char dir[] = "/tmp/fogpipe-vdbseq-XXXXXX";

static void touch(const char *name) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  CHECK(f != NULL, "cannot create %s", path);
  if (f) fclose(f);
}

/* The sequence of the inputs (names relative to dir): 0, or 1 with its error in err. */
static int find(const char *const *names, int count, vdb_sequence *seq, fog_error *err) {
  char paths[4][512];
  const char *inputs[4];
  for (int i = 0; i < count; i++) {
    snprintf(paths[i], sizeof paths[i], "%s/%s", dir, names[i]);
    inputs[i] = paths[i];
  }
  *err = (fog_error){0};
  return vdb_sequence_find(inputs, count, -1, -1, seq, err);
}

int main(void) {
  if (!test_scratch_folder(dir)) return 1;
  char folder[512];
  snprintf(folder, sizeof folder, "%s/take#2", dir);
  CHECK(mkdir(folder, 0755) == 0, "mkdir %s", folder);
  touch("take#2/fluid_0001.vdb");
  touch("take#2/fluid_0002.vdb");
  touch("take#2/fluid_0003.vdb");
  touch("shot#48.vdb");
  touch("other_0002.vdb");
  touch("fog.vdb");
  touch("a##_0007.vdb");
  vdb_sequence seq;
  fog_error err;

  const char *folder_input[] = {"take#2"};
  if (!find(folder_input, 1, &seq, &err)) {
    CHECK(seq.count == 3 && seq.frames[0] == 1 && seq.frames[2] == 3,
          "the folder take#2: %d frames", seq.count);
    vdb_sequence_destroy(&seq);
  } else {
    CHECK(0, "the folder take#2: %s", err.message);
  }
  const char *file_input[] = {"take#2/fluid_0002.vdb"};
  if (!find(file_input, 1, &seq, &err)) {
    CHECK(seq.count == 1 && seq.frames[0] == 2 && strstr(seq.paths[0], "take#2/fluid_0002"),
          "the file take#2/fluid_0002.vdb: %d frames", seq.count);
    vdb_sequence_destroy(&seq);
  } else {
    CHECK(0, "the file take#2/fluid_0002.vdb: %s", err.message);
  }
  const char *hash_name[] = {"shot#48.vdb"};
  if (!find(hash_name, 1, &seq, &err)) {
    CHECK(seq.count == 1 && strstr(seq.paths[0], "shot#48.vdb"), "shot#48.vdb: %d frames",
          seq.count);
    vdb_sequence_destroy(&seq);
  } else {
    CHECK(0, "the file shot#48.vdb: %s", err.message);
  }
  const char *pattern[] = {"take#2/fluid_####.vdb"};
  if (!find(pattern, 1, &seq, &err)) {
    CHECK(seq.count == 3 && seq.frames[1] == 2 && strstr(seq.paths[1], "take#2/fluid_0002.vdb"),
          "the pattern take#2/fluid_####.vdb: %d frames", seq.count);
    vdb_sequence_destroy(&seq);
  } else {
    CHECK(0, "the pattern take#2/fluid_####.vdb: %s", err.message);
  }
  const char *same_frame[] = {"take#2/fluid_0002.vdb", "other_0002.vdb"};
  int status = find(same_frame, 2, &seq, &err);
  CHECK(status != 0 && strstr(err.message, "frame 2 twice") &&
            strstr(err.message, "take#2/fluid_0002.vdb") && strstr(err.message, "other_0002.vdb"),
        "two files of frame 2: %s", status ? err.message : "accepted");
  if (!status) vdb_sequence_destroy(&seq);
  const char *same_file[] = {"take#2/fluid_0002.vdb", "take#2/fluid_0002.vdb"};
  if (!find(same_file, 2, &seq, &err)) {
    CHECK(seq.count == 1, "the same file twice: %d frames", seq.count);
    vdb_sequence_destroy(&seq);
  } else {
    CHECK(0, "the same file twice: %s", err.message);
  }
  const char *spellings[] = {"take#2//fluid_0002.vdb", "./take#2/fluid_0002.vdb"};
  if (!find(spellings, 2, &seq, &err)) {
    CHECK(seq.count == 1, "one file in two spellings: %d frames", seq.count);
    vdb_sequence_destroy(&seq);
  } else {
    CHECK(0, "one file in two spellings: %s", err.message);
  }
  const char *unnumbered[] = {"take#2/fluid_0001.vdb", "fog.vdb"};
  if (!find(unnumbered, 2, &seq, &err)) {
    CHECK(seq.count == 2, "a numbered file and fog.vdb: %d frames", seq.count);
    vdb_sequence_destroy(&seq);
  } else {
    CHECK(0, "a numbered file and fog.vdb (no digits): %s", err.message);
  }
  /* two runs of '#' in the name: the last is the frame number, the first is itself */
  const char *two_runs[] = {"a##_####.vdb"};
  if (!find(two_runs, 1, &seq, &err)) {
    CHECK(seq.count == 1 && seq.frames[0] == 7 && strstr(seq.paths[0], "a##_0007.vdb"),
          "a##_####.vdb: %d frames", seq.count);
    vdb_sequence_destroy(&seq);
  } else {
    CHECK(0, "a##_####.vdb: %s", err.message);
  }
  test_remove_tree(dir);
  return test_finish("test_vdb_sequence_names");
}
