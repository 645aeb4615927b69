/* libFuzzer harness: scene configs (app/config.c, scene_config_load; format in
 * docs/config.md). The input is the .ini file. It is written as scene.ini into a scratch
 * folder that also holds the files a config may name relatively (fogmaps, a heightmap,
 * VDB sequences, one with frames 1 and 2000000000; empty: the parser only checks that
 * they open or match), so the cross-key checks and the [fog] vdb sequence search
 * (vdb_sequence_find: patterns, globs, folders) are reached.
 *
 * Inputs that could leave the scratch folder are skipped: a value starting with '/', or
 * ".." anywhere, or a '.' before a glob character (".*" matches ".."). A glob of every
 * folder five levels below the root (vdb = "/" and "*" five times) lists the machine's
 * file tree, which takes as long as the tree is big (a 10 s timeout in the first runs): a
 * cost the user asked for, not the parser's; and a FIFO named as a fogmap would block.
 * Relative names are resolved against the scratch folder and stay inside it. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "fuzz_util.h"

static const char *dir;

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  dir = fuzz_scratch_dir();
  static const char *const names[] = {
      "fog.png", "fog.exr", "height.png", "vdb/fluid_data_0001.vdb",
      "vdb/fluid_data_0002.vdb", "vdb/fluid_data_0004.vdb", "cache/data/fluid_data_0010.vdb",
      "cache/config/config_0010.uni", "far/frame_1.vdb", "far/frame_2000000000.vdb"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) fuzz_touch(dir, names[i]);
  return 0;
}

/* A value that starts with '/' (after "=" or ":" and blanks as inih reads it, or as an
 * indented continuation line), or a '.' followed by '.' or by what glob reads as a pattern
 * ("*?[" or a '\\' escape). */
static int leaves_scratch(const uint8_t *data, size_t size) {
  for (size_t i = 0; i < size; i++) {
    if (data[i] == '.' && i + 1 < size && data[i + 1] && strchr(".*?[\\", data[i + 1]))
      return 1;
    if (data[i] != '=' && data[i] != ':' && data[i] != '\n' && i != 0) continue;
    size_t j = data[i] == '=' || data[i] == ':' || data[i] == '\n' ? i + 1 : i;
    while (j < size && data[j] && strchr(" \t\r\v\f", data[j])) j++;
    if (j < size && data[j] == '/') return 1;
  }
  return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (leaves_scratch(data, size)) return -1; /* -1: not added to the corpus */
  const char *path = fuzz_write_file(dir, "scene.ini", data, size);
  static scene_config cfg; /* 100 KB: not on the stack */
  fog_error err;
  memset(&err, 0x55, sizeof err); /* a message that is not terminated shows up below */
  if (scene_config_load(path, &cfg, &err) == 0) {
    /* What the commands do next with a loaded config. */
    camera cam;
    scene_config_camera(&cfg, &cam);
    static scene_desc desc;
    scene_config_scene_desc(&cfg, NULL, 0, 0, &desc);
    (void)scene_config_has_fog(&cfg);
  } else if (!memchr(err.message, '\0', sizeof err.message)) {
    abort(); /* a failure must leave a terminated message */
  }
  return 0;
}
