/* The commands' error messages. */
#include "app/cli.h"

#include <stdarg.h>
#include <stdio.h>

static void print_message(const char *command, const char *format, va_list args) {
  fprintf(stderr, "fogpipe %s: ", command);
  vfprintf(stderr, format, args);
  fputc('\n', stderr);
}

int cli_fail(const char *command, const char *format, ...) {
  va_list args;
  va_start(args, format);
  print_message(command, format, args);
  va_end(args);
  return 1;
}

int cli_usage_error(const char *command, const char *format, ...) {
  va_list args;
  va_start(args, format);
  print_message(command, format, args);
  va_end(args);
  fprintf(stderr, "(fogpipe %s --help lists the options)\n", command);
  return 2;
}
