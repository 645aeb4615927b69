/* libFuzzer harness: command-line options.
 *
 * Every command reads its argv with the one table parser (app/cli_options.c: cli_parse,
 * cli_parse_one) and its own rows. This fuzzes two commands whose argv stage is a function
 * of its own, run without running the command:
 *  - fogpipe import: parse_options (app/cmd_import.c), into an import_options struct;
 *  - fogpipe design: parse_design_options (app/cmd_design.c), into a design_options
 *    struct, plus the value parsers its rows use on every argument;
 * each checked against what it promises the command on success. Nothing is read or
 * written there (an output row only stats its path). The commands are reached through
 * fuzz_options_import.c and fuzz_options_design.c, which #include the command's source
 * file to call its static functions. See docs/reliability.md.
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
