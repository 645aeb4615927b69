/* An output path that is one of the files a scene config reads: refused before any work
 * (render --out, view and demo --screenshot), instead of replacing the scene's input. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "app/cli.h"
#include "app/config.h"
#include "sim/vdb_import.h"

/* Whether out names a file of the frame pattern (FOLDER/PREFIX###SUFFIX: the same folder,
 * however spelt, and PREFIX digits SUFFIX), existing or not. */
static bool in_sequence(const char *out, const char *pattern) {
  size_t start, length;
  if (!vdb_pattern_hash_run(pattern, &start, &length)) return cli_same_file(out, pattern);
  const char *pattern_slash = strrchr(pattern, '/');
  const char *out_slash = strrchr(out, '/');
  const size_t pattern_base = pattern_slash ? (size_t)(pattern_slash - pattern) + 1 : 0;
  const char *base = out_slash ? out_slash + 1 : out;
  /* the folders: compared by device and inode */
  char pattern_folder[SCENE_CONFIG_PATH_MAX], out_folder[SCENE_CONFIG_PATH_MAX];
  snprintf(pattern_folder, sizeof pattern_folder, "%.*s", pattern_slash ? (int)pattern_base : 2,
           pattern_slash ? pattern : "./");
  snprintf(out_folder, sizeof out_folder, "%.*s", out_slash ? (int)(base - out) : 2,
           out_slash ? out : "./");
  if (!cli_same_file(pattern_folder, out_folder)) return false;
  const char *prefix = pattern + pattern_base, *suffix = pattern + start + length;
  const size_t prefix_length = start - pattern_base;
  if (start < pattern_base || strncmp(base, prefix, prefix_length) != 0) return false;
  const char *digits = base + prefix_length;
  const size_t count = strspn(digits, "0123456789");
  return count >= 1 && strcmp(digits + count, suffix) == 0;
}

int cli_output_not_scene_input(const char *command, const char *option, const char *out,
                               const scene_config *cfg) {
  const struct {
    const char *path, *what;
  } inputs[] = {{cfg->path, "the config itself"},
                {cfg->fog.fogmap, "the config's [fog] fogmap"},
                {cfg->terrain.heightmap, "the config's [terrain] heightmap"},
                {cfg->fog.vdb, "a file of the config's [fog] vdb"}};
  for (size_t i = 0; i < sizeof inputs / sizeof *inputs; i++)
    if (cli_output_not_input(command, option, out, inputs[i].path, inputs[i].what)) return 2;
  if (cfg->fog.sequence[0] && in_sequence(out, cfg->fog.sequence))
    return cli_usage_error(command, "%s '%s' is a frame of the config's [fog] sequence (%s): "
                           "writing it would replace the input", option, out,
                           cfg->fog.sequence);
  return 0;
}
