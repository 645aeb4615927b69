/* Messages of the fogpipe commands, one format for all: "fogpipe <command>: <message>"
 * on stderr. Libraries return their errors; only commands print. */
#ifndef FOGPIPE_APP_CLI_H
#define FOGPIPE_APP_CLI_H

/* Prints the message and returns 1 (the exit status of a failed run). */
int cli_fail(const char *command, const char *format, ...)
    __attribute__((format(printf, 2, 3)));

/* Prints the message and a pointer to --help; returns 2 (the status of a bad command line). */
int cli_usage_error(const char *command, const char *format, ...)
    __attribute__((format(printf, 2, 3)));

/* ---- option values: one parser and one message style for every command ----
 * Each takes the whole text (no trailing characters, no overflow) and the range allowed;
 * on a bad value it prints `fogpipe COMMAND: OPTION 'TEXT': expected ...` with the --help
 * pointer and returns 2 (the exit status of a bad command line), else stores and returns 0. */

#include <stdbool.h>
#include <stddef.h>

/* Images and windows: 1 to CLI_MAX_SIZE pixels a side. */
#define CLI_MAX_SIZE 16384

/* An output file's path that names an existing folder: refused with the usage message
 * (returns 2) before any work, not found out when the finished file is renamed onto it.
 * 0 otherwise. */
int cli_output_file(const char *command, const char *option, const char *path);
/* An output file's path whose folder is not there (for a command that makes no folders):
 * refused the same way, before any work. 0 otherwise. */
int cli_output_in_folder(const char *command, const char *option, const char *path);

/* Whether a and b name one existing file, however spelt (device and inode). */
bool cli_same_file(const char *a, const char *b);

/* An output file that is one of the command's inputs (the same file, however spelt):
 * refused with the usage message (returns 2) before any work, naming the input (`what`,
 * e.g. "the config's [fog] fogmap"), instead of replacing it. 0 otherwise, or when either
 * does not exist. */
int cli_output_not_input(const char *command, const char *option, const char *out,
                         const char *input, const char *what);

/* s as one POSIX shell word into out (size bytes): as it is when every character is plain
 * (letters, digits, _ . / : = @ % + , -), else in single quotes with a quote inside as
 * '\''. Returns out. For commands printed for a user to paste, or handed to sh -c. size
 * must be at least 4 strlen(s) + 3 (every character a quote), or the word is cut short. */
const char *cli_shell_word(const char *s, char *out, size_t size);

/* An output that is one of the files the scene config reads (the config, its fogmap,
 * heightmap or VDB file, a frame of its [fog] sequence, existing or not): refused with the
 * usage message (returns 2) before any work, naming the key. 0 otherwise. */
struct scene_config;
int cli_output_not_scene_input(const char *command, const char *option, const char *out,
                               const struct scene_config *cfg);
/* The same for a command that writes a sequence of files, out_pattern a #### pattern
 * (record's FOLDER/frame.####.exr, bake's FOLDER/fog.####.exr): refused when a file the
 * config reads is one of its files, or the config's own [fog] sequence or VDB pattern names
 * the same files (the same folder, prefix and suffix). option names where the folder came
 * from. */
int cli_sequence_not_scene_input(const char *command, const char *option, const char *out_pattern,
                                 const struct scene_config *cfg);

/* Whether a window could open: DISPLAY or WAYLAND_DISPLAY set (demo and view check it
 * before any work; without one demo records headless, view fails). */
bool cli_display_available(void);

/* Whether s ends with suffix, ignoring case (".EXR" is ".exr"). */
bool cli_ends_with(const char *s, const char *suffix);

/* The quiet cores (true on success), for values read from files too. */
bool cli_parse_long(const char *text, long min, long max, long *value);
bool cli_parse_double(const char *text, double min, double max, double *value);

int cli_int(const char *command, const char *option, const char *text, long min, long max,
            int *value);
/* A finite number in [min, max]. */
int cli_number(const char *command, const char *option, const char *text, double min,
               double max, double *value);
/* WIDTHxHEIGHT, each 1..CLI_MAX_SIZE. */
int cli_size(const char *command, const char *option, const char *text, int *width,
             int *height);
/* A or A-B with min <= A <= B <= max; *single tells which (A: first = last = A). */
int cli_range(const char *command, const char *option, const char *text, long min, long max,
              int *first, int *last, bool *single);

#endif
