/* fogpipe: the command-line entry point. It only dispatches to app/cmd_<name>.c. */
#include <stdbool.h>
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
          "usage: fogpipe <command> [options]\n"
          "       fogpipe help <command>   (or fogpipe <command> --help: its options)\n\n"
          "commands:\n");
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    fprintf(out, "  %-10s %s\n", commands[i].name, commands[i].summary);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    print_usage(stderr);
    return 2;
  }
  const bool help = !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") ||
                    !strcmp(argv[1], "help");
  /* `fogpipe help COMMAND` is `fogpipe COMMAND --help` (the command word was dropped) */
  if (help && argc == 3) {
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
      if (!strcmp(argv[2], commands[i].name))
        return commands[i].run(2, (char *[]){argv[2], "--help", NULL});
    fprintf(stderr, "fogpipe: help: unknown command '%s'\n\n", argv[2]);
    print_usage(stderr);
    return 2;
  }
  if (help && argc == 2) {
    print_usage(stdout);
    return 0;
  }
  if (help) {
    fprintf(stderr, "fogpipe: %s takes at most one command name\n\n", argv[1]);
    print_usage(stderr);
    return 2;
  }
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (!strcmp(argv[1], commands[i].name)) return commands[i].run(argc - 1, argv + 1);
  fprintf(stderr, "fogpipe: unknown command '%s'\n\n", argv[1]);
  print_usage(stderr);
  return 2;
}
