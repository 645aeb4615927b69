/* libFuzzer harness: command-line options.
 *
 * fogpipe has no single option parser yet (each app/cmd_*.c parses its own argv; a later
 * refactor unifies them), so this fuzzes what is separable today without running a
 * command:
 *  - fogpipe import: parse_options (app/cmd_import.c), the whole argv stage of the
 *    command, into an import_options struct; nothing is read or written there.
 *  - fogpipe design: its value parsers (parse_numbers, parse_int with the bounds the
 *    command uses, the --out suffix test, the option table); its argv loop itself is
 *    fused with the work (it allocates up to 16384^2 fogmaps and writes --out), so only
 *    the helpers are called.
 * The commands are reached through fuzz_options_import.c and fuzz_options_design.c, which
 * #include the command's source file to call its static functions. Not fuzzed: the argv
 * loops of transform, render, view, demo, bench and record, which are fused with running
 * the command (they read and write the files named on the command line); record
 * (app/cmd_record.c) is also being rewritten. See docs/reliability.md.
 *
 * Input: byte 0 chooses the parser (even: import, odd: design); the rest is argv[1..],
 * split at NUL bytes (at most 64 arguments; argv[0] is the command name). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int fuzz_import_parse(int argc, char **argv);
void fuzz_design_parse(int argc, char **argv);

enum { max_args = 64 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1) return 0;
  const int design = data[0] & 1;
  /* Own, NUL-terminated copies: a parser may keep pointers into argv (import does). */
  char *text = malloc(size);
  if (!text) return 0;
  memcpy(text, data + 1, size - 1);
  text[size - 1] = '\0';
  char *argv[max_args + 2];
  int argc = 0;
  argv[argc++] = design ? "design" : "import";
  for (size_t i = 0; i < size - 1 && argc <= max_args;) {
    argv[argc++] = text + i;
    i += strlen(text + i) + 1;
  }
  argv[argc] = NULL;
  if (design)
    fuzz_design_parse(argc, argv);
  else
    fuzz_import_parse(argc, argv);
  free(text);
  return 0;
}
