/* fogpipe: the command-line entry point. It only dispatches to app/cmd_<name>.c. */
#include <stdio.h>
#include <string.h>

#include "app/commands.h"

typedef struct fog_command {
  const char *name;
  const char *summary;
  int (*run)(int argc, char **argv);
} fog_command;

static const fog_command commands[] = {
#define FOG_COMMAND(name, summary) {#name, summary, cmd_##name},
#include "app/commands.def"
#undef FOG_COMMAND
};

static void print_usage(FILE *out) {
  fprintf(out,
          "fogpipe: heterogeneous fog, simulated, imported or designed, wavelet-"
          "transformed\nand rendered with the exact extinction integral.\n\n"
          "usage: fogpipe <command> [options]   (fogpipe <command> --help for its options)\n\n"
          "commands:\n");
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    fprintf(out, "  %-10s %s\n", commands[i].name, commands[i].summary);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    print_usage(stderr);
    return 2;
  }
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
    print_usage(stdout);
    return 0;
  }
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (!strcmp(argv[1], commands[i].name)) return commands[i].run(argc - 1, argv + 1);
  fprintf(stderr, "fogpipe: unknown command '%s'\n\n", argv[1]);
  print_usage(stderr);
  return 2;
}
