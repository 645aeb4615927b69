/* How vdb_sequence_find reads its inputs' names (sim/vdb_import.h), on empty files in a
 * scratch folder (the finder lists names; it opens nothing):
 *   - a path that exists is itself: a folder or a file whose name holds '#' is not a
 *     frame pattern ("take#2/", "shot#48.vdb"), nor one whose name holds '[', '*' or '?'
 *     a glob ("take[1]*?/"), and in a pattern below such a folder the frame number is
 *     read where the name has it ("shot[a]/fluid_####.vdb" finds 0047, 1047 and 1048);
 *   - in a pattern, the frame number is the last run of '#' of the file name, never a
 *     '#' of a folder;
 *   - two different files of one frame number are refused, naming both (one would stand
 *     for the other); the same file given twice, however spelt ("d//f", "./d/f"), is one
 *     frame; a name without digits takes its place in the list as its frame, and where a
 *     numbered file has that frame the refusal says so; a frame number past INT_MAX is
 *     refused;
 *   - a folder or wildcard matching a name without digits beside numbered names is refused,
 *     naming it (fog_preview.vdb beside fog_0000 and fog_0001 played as frame 2); where no
 *     name has digits they are numbered by place. */
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

/* One case: inputs (names relative to dir) and what the finder must give: `frames` files,
 * file `at` of frame `frame` whose path holds `path`; frames 0: refused, its message
 * holding `path`. */
typedef struct names_case {
  const char *label;
  const char *inputs[2];
  int frames, at, frame;
  const char *path;
} names_case;

static void check_case(const names_case *c) {
  char paths[2][512];
  const char *inputs[2];
  int count = 0;
  for (; count < 2 && c->inputs[count]; count++) {
    snprintf(paths[count], sizeof paths[count], "%s/%s", dir, c->inputs[count]);
    inputs[count] = paths[count];
  }
  vdb_sequence seq;
  fog_error err = {0};
  int status = vdb_sequence_find(inputs, count, -1, -1, &seq, &err);
  if (c->frames == 0) {
    CHECK(status != 0 && strstr(err.message, c->path), "%s: %s", c->label,
          status ? err.message : "accepted");
  } else {
    CHECK(status == 0 && seq.count == c->frames && seq.frames[c->at] == c->frame &&
              strstr(seq.paths[c->at], c->path),
          "%s: %s (%d frames)", c->label, status ? err.message : "other frames",
          status ? 0 : seq.count);
  }
  if (status == 0) vdb_sequence_destroy(&seq);
}

int main(void) {
  if (!test_scratch_folder(dir)) return 1;
  char folder[512];
  snprintf(folder, sizeof folder, "%s/take#2", dir);
  CHECK(mkdir(folder, 0755) == 0, "mkdir %s", folder);
  snprintf(folder, sizeof folder, "%s/take[1]*?", dir);
  CHECK(mkdir(folder, 0755) == 0, "mkdir %s", folder);
  snprintf(folder, sizeof folder, "%s/shot[a]", dir);
  CHECK(mkdir(folder, 0755) == 0, "mkdir %s", folder);
  snprintf(folder, sizeof folder, "%s/mixed", dir);
  CHECK(mkdir(folder, 0755) == 0, "mkdir %s", folder);
  snprintf(folder, sizeof folder, "%s/plain", dir);
  CHECK(mkdir(folder, 0755) == 0, "mkdir %s", folder);
  static const char *const files[] = {"take#2/fluid_0001.vdb", "take#2/fluid_0002.vdb",
                                      "take#2/fluid_0003.vdb", "shot#48.vdb", "other_0002.vdb",
                                      "fog.vdb", "a##_0007.vdb", "take[1]*?/fluid_0004.vdb",
                                      "take[1]*?/fluid_0005.vdb", "big_4294967297.vdb",
                                      "shot[a]/fluid_0047.vdb", "shot[a]/fluid_1047.vdb",
                                      "shot[a]/fluid_1048.vdb", "shot[a]/smoke_9.vdb",
                                      "shot[a]/smoke_12.vdb", "mixed/fog_0000.vdb",
                                      "mixed/fog_0001.vdb", "mixed/fog_preview.vdb",
                                      "plain/a.vdb", "plain/b.vdb"};
  for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) touch(files[i]);
  static const names_case cases[] = {
      {"the folder take#2", {"take#2"}, 3, 2, 3, "take#2/fluid_0003.vdb"},
      {"the file take#2/fluid_0002.vdb", {"take#2/fluid_0002.vdb"}, 1, 0, 2,
       "take#2/fluid_0002.vdb"},
      {"the file shot#48.vdb", {"shot#48.vdb"}, 1, 0, 48, "shot#48.vdb"},
      {"the pattern take#2/fluid_####.vdb", {"take#2/fluid_####.vdb"}, 3, 1, 2,
       "take#2/fluid_0002.vdb"},
      /* two runs of '#' in the name: the last is the frame number, the first is itself */
      {"the pattern a##_####.vdb", {"a##_####.vdb"}, 1, 0, 7, "a##_0007.vdb"},
      /* glob's own characters in a folder's name are themselves ("take[1]" is no class) */
      {"the folder take[1]*?", {"take[1]*?"}, 2, 1, 5, "take[1]*?/fluid_0005.vdb"},
      {"the pattern take[1]*?/fluid_####.vdb", {"take[1]*?/fluid_####.vdb"}, 2, 0, 4,
       "take[1]*?/fluid_0004.vdb"},
      /* the digits found where the name has them, not where the glob's escapes put them
       * (frames without a leading 0 were dropped, an unpadded pattern matched nothing) */
      {"the pattern shot[a]/fluid_####.vdb", {"shot[a]/fluid_####.vdb"}, 3, 2, 1048,
       "shot[a]/fluid_1048.vdb"},
      {"the pattern shot[a]/smoke_%d.vdb", {"shot[a]/smoke_%d.vdb"}, 2, 1, 12,
       "shot[a]/smoke_12.vdb"},
      /* a frame number an int does not hold: refused, not wrapped to frame 1 */
      {"the file big_4294967297.vdb", {"big_4294967297.vdb"}, 0, 0, 0, "past 2147483647"},
      {"two files of frame 2", {"take#2/fluid_0002.vdb", "other_0002.vdb"}, 0, 0, 0,
       "frame 2 twice"},
      {"the same file twice", {"take#2/fluid_0002.vdb", "take#2/fluid_0002.vdb"}, 1, 0, 2,
       "fluid_0002.vdb"},
      {"one file in two spellings", {"take#2//fluid_0002.vdb", "./take#2/fluid_0002.vdb"}, 1, 0,
       2, "fluid_0002.vdb"},
      {"fog.vdb (no digits, place 1) and a file of frame 1", {"take#2/fluid_0001.vdb", "fog.vdb"},
       0, 0, 0, "a name without digits takes its place"},
      {"fog.vdb (no digits, place 0) and a file of frame 2", {"fog.vdb", "take#2/fluid_0002.vdb"},
       2, 0, 0, "fog.vdb"},
      {"the folder mixed (fog_preview.vdb beside numbered frames)", {"mixed"}, 0, 0, 0,
       "fog_preview.vdb: no frame number in its name"},
      {"the wildcard mixed/fog_*.vdb", {"mixed/fog_*.vdb"}, 0, 0, 0,
       "fog_preview.vdb: no frame number in its name"},
      {"the folder plain (no name with digits: by place)", {"plain"}, 2, 1, 1, "plain/b.vdb"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) check_case(&cases[i]);
  /* the refusal names both files */
  check_case(&(names_case){"two files of frame 2, the first named",
                           {"take#2/fluid_0002.vdb", "other_0002.vdb"}, 0, 0, 0,
                           "take#2/fluid_0002.vdb"});
  check_case(&(names_case){"two files of frame 2, the second named",
                           {"take#2/fluid_0002.vdb", "other_0002.vdb"}, 0, 0, 0,
                           "other_0002.vdb"});
  /* with a closed range, a frame number past INT_MAX is past its end: left out, as any */
  {
    char big[512], two[512];
    snprintf(big, sizeof big, "%s/big_4294967297.vdb", dir);
    snprintf(two, sizeof two, "%s/take#2/fluid_0002.vdb", dir);
    const char *inputs[2] = {big, two};
    vdb_sequence seq;
    fog_error err = {0};
    const int status = vdb_sequence_find(inputs, 2, 2, 2, &seq, &err);
    CHECK(status == 0 && seq.count == 1 && seq.frames[0] == 2,
          "frames 2-2 beside a frame past INT_MAX: %s", status ? err.message : "other frames");
    if (!status) vdb_sequence_destroy(&seq);
  }
  test_remove_tree(dir);
  return test_finish("test_vdb_sequence_names");
}
