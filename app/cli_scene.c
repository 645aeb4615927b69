/* An output path that is one of the files a scene config reads: refused before any work
 * (render --out, view and demo --screenshot, record's and bake's frames), instead of
 * replacing the scene's input. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "app/cli.h"
#include "app/config.h"
#include "sim/vdb_import.h"

/* Splits a #### pattern into its folder ("./" when it has none), the file name's prefix
 * before the run of '#', the run's length and the suffix after it. False when the file
 * name has no run. */
static bool pattern_parts(const char *pattern, char *folder, size_t folder_size,
                          const char **prefix, size_t *prefix_length, size_t *run_length,
                          const char **suffix) {
  size_t start, length;
  if (!vdb_pattern_hash_run(pattern, &start, &length)) return false;
  const char *slash = strrchr(pattern, '/');
  const size_t base = slash ? (size_t)(slash - pattern) + 1 : 0;
  snprintf(folder, folder_size, "%.*s", slash ? (int)base : 2, slash ? pattern : "./");
  *prefix = pattern + base, *prefix_length = start - base, *suffix = pattern + start + length;
  *run_length = length;
  return true;
}

/* Whether out names a file of the frame pattern (FOLDER/PREFIX###SUFFIX: the same folder,
 * however spelt, and PREFIX digits SUFFIX, the digits as the pattern writes a number:
 * padded with zeros to the run's length, no more), existing or not. */
static bool in_sequence(const char *out, const char *pattern) {
  char pattern_folder[SCENE_CONFIG_PATH_MAX], out_folder[SCENE_CONFIG_PATH_MAX];
  const char *prefix, *suffix;
  size_t prefix_length, length;
  if (!pattern_parts(pattern, pattern_folder, sizeof pattern_folder, &prefix, &prefix_length,
                     &length, &suffix))
    return cli_same_file(out, pattern);
  /* the folders: compared by device and inode */
  const char *out_slash = strrchr(out, '/');
  const char *base = out_slash ? out_slash + 1 : out;
  snprintf(out_folder, sizeof out_folder, "%.*s", out_slash ? (int)(base - out) : 2,
           out_slash ? out : "./");
  if (!cli_same_file(pattern_folder, out_folder)) return false;
  if (strncmp(base, prefix, prefix_length) != 0) return false;
  const char *digits = base + prefix_length;
  const size_t count = strspn(digits, "0123456789");
  if (count < 1 || count > 18 || strcmp(digits + count, suffix) != 0) return false;
  char written[32]; /* frame.2.exr and frame.00002.exr are no frames of frame.####.exr */
  snprintf(written, sizeof written, "%0*lld", (int)length, strtoll(digits, NULL, 10));
  return strlen(written) == count && strncmp(written, digits, count) == 0;
}

/* The files a scene config reads, each with the words that name it in a refusal; the
 * [fog] sequence (a #### pattern) last. */
typedef struct scene_input {
  const char *path, *what;
} scene_input;
enum { SCENE_INPUTS = 5 };
static void scene_inputs(const scene_config *cfg, scene_input inputs[SCENE_INPUTS]) {
  inputs[0] = (scene_input){cfg->path, "the config itself"};
  inputs[1] = (scene_input){cfg->fog.fogmap, "the config's [fog] fogmap"};
  inputs[2] = (scene_input){cfg->terrain.heightmap, "the config's [terrain] heightmap"};
  inputs[3] = (scene_input){cfg->fog.vdb, "a file of the config's [fog] vdb"};
  inputs[4] = (scene_input){cfg->fog.sequence, "the config's [fog] sequence"};
}

int cli_output_not_scene_input(const char *command, const char *option, const char *out,
                               const scene_config *cfg) {
  scene_input inputs[SCENE_INPUTS];
  scene_inputs(cfg, inputs);
  for (int i = 0; i < SCENE_INPUTS - 1; i++)
    if (cli_output_not_input(command, option, out, inputs[i].path, inputs[i].what)) return 2;
  if (cfg->fog.sequence[0] && in_sequence(out, cfg->fog.sequence))
    return cli_usage_error(command, "%s '%s' is a frame of the config's [fog] sequence (%s): "
                           "writing it would replace the input", option, out,
                           cfg->fog.sequence);
  return 0;
}

/* Whether two #### patterns name the same files: the same folder (by device and inode),
 * prefix and suffix, whatever the number of '#'. */
static bool same_sequence(const char *a, const char *b) {
  char folder_a[SCENE_CONFIG_PATH_MAX], folder_b[SCENE_CONFIG_PATH_MAX];
  const char *prefix_a, *prefix_b, *suffix_a, *suffix_b;
  size_t length_a, length_b, run_a, run_b;
  return pattern_parts(a, folder_a, sizeof folder_a, &prefix_a, &length_a, &run_a, &suffix_a) &&
         pattern_parts(b, folder_b, sizeof folder_b, &prefix_b, &length_b, &run_b, &suffix_b) &&
         length_a == length_b && !strncmp(prefix_a, prefix_b, length_a) &&
         !strcmp(suffix_a, suffix_b) && cli_same_file(folder_a, folder_b);
}

int cli_sequence_not_scene_input(const char *command, const char *option, const char *out_pattern,
                                 const scene_config *cfg) {
  scene_input inputs[SCENE_INPUTS];
  scene_inputs(cfg, inputs);
  for (int i = 0; i < SCENE_INPUTS; i++) {
    const char *input = inputs[i].path;
    if (!input[0]) continue;
    size_t start, length;
    const bool is_pattern = vdb_pattern_hash_run(input, &start, &length);
    if (is_pattern ? same_sequence(input, out_pattern) : in_sequence(input, out_pattern))
      return cli_usage_error(command, "%s: the files %s would be written include %s (%s): "
                             "writing them would replace the input; choose another folder",
                             option, out_pattern, inputs[i].what, input);
  }
  return 0;
}
