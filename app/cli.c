/* The commands' error messages. */
#include "app/cli.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <strings.h>

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

/* strtol and strtod skip leading white space; an option's value has none. */
static bool starts_with_space(const char *text) { return isspace((unsigned char)text[0]); }

bool cli_parse_long(const char *text, long min, long max, long *value) {
  if (starts_with_space(text)) return false;
  char *end;
  errno = 0;
  long v = strtol(text, &end, 10);
  if (errno || end == text || *end || v < min || v > max) return false;
  *value = v;
  return true;
}

bool cli_parse_double(const char *text, double min, double max, double *value) {
  if (starts_with_space(text)) return false;
  char *end;
  double v = strtod(text, &end); /* overflow: infinite, refused; underflow: the nearest */
  if (end == text || *end || !isfinite(v) || !(v >= min && v <= max)) return false;
  if (strpbrk(text, "xX")) return false; /* strtod reads hexadecimal too: decimal only */
  *value = v;
  return true;
}

int cli_int(const char *command, const char *option, const char *text, long min, long max,
            int *value) {
  long v;
  if (!cli_parse_long(text, min, max, &v))
    return cli_usage_error(command, "%s '%s': expected a whole number from %ld to %ld", option,
                           text, min, max);
  *value = (int)v;
  return 0;
}

int cli_number(const char *command, const char *option, const char *text, double min,
               double max, double *value) {
  if (!cli_parse_double(text, min, max, value))
    return cli_usage_error(command, "%s '%s': expected a number from %g to %g", option, text,
                           min, max);
  return 0;
}

int cli_size(const char *command, const char *option, const char *text, int *width,
             int *height) {
  const char *x = strpbrk(text, "xX");
  char w[32];
  long a, b;
  if (x && x > text && (size_t)(x - text) < sizeof w) {
    memcpy(w, text, (size_t)(x - text));
    w[x - text] = '\0';
    if (cli_parse_long(w, 1, CLI_MAX_SIZE, &a) && cli_parse_long(x + 1, 1, CLI_MAX_SIZE, &b)) {
      *width = (int)a, *height = (int)b;
      return 0;
    }
  }
  return cli_usage_error(command, "%s '%s': expected WIDTHxHEIGHT, each 1 to %d (e.g. 640x360)",
                         option, text, CLI_MAX_SIZE);
}

int cli_range(const char *command, const char *option, const char *text, long min, long max,
              int *first, int *last, bool *single) {
  const char *dash = text[0] ? strchr(text + 1, '-') : NULL;
  char a_text[32];
  long a = 0, b = 0;
  bool ok;
  if (dash && (size_t)(dash - text) < sizeof a_text) {
    memcpy(a_text, text, (size_t)(dash - text));
    a_text[dash - text] = '\0';
    ok = cli_parse_long(a_text, min, max, &a) && cli_parse_long(dash + 1, min, max, &b) && a <= b;
  } else {
    ok = !dash && cli_parse_long(text, min, max, &a);
    b = a;
  }
  if (!ok)
    return cli_usage_error(command, "%s '%s': expected A or A-B, whole numbers with %ld <= A <= "
                           "B <= %ld", option, text, min, max);
  *first = (int)a, *last = (int)b, *single = !dash;
  return 0;
}

bool cli_ends_with(const char *s, const char *suffix) {
  size_t n = strlen(s), m = strlen(suffix);
  return n >= m && strcasecmp(s + n - m, suffix) == 0;
}

bool cli_same_file(const char *a, const char *b) {
  struct stat sa, sb;
  return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

int cli_output_not_input(const char *command, const char *option, const char *out,
                         const char *input, const char *what) {
  if (!input || !*input || !cli_same_file(out, input)) return 0;
  return cli_usage_error(command, "%s '%s' is %s (%s): writing it would replace the input",
                         option, out, what, input);
}

int cli_output_file(const char *command, const char *option, const char *path) {
  struct stat st;
  if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
    return cli_usage_error(command, "%s '%s': a folder of that name is there; expected a file "
                           "name", option, path);
  return 0;
}

int cli_output_in_folder(const char *command, const char *option, const char *path) {
  /* its folder must be there: found now, not when the file is written after the work */
  struct stat st;
  const char *slash = strrchr(path, '/');
  if (slash && slash > path) {
    char folder[4096];
    snprintf(folder, sizeof folder, "%.*s", (int)(slash - path), path);
    if (stat(folder, &st) != 0 || !S_ISDIR(st.st_mode))
      return cli_usage_error(command, "%s '%s': there is no folder '%s' to write it in", option,
                             path, folder);
  }
  return 0;
}

bool cli_display_available(void) {
  const char *display = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
  return (display && *display) || (wayland && *wayland);
}

const char *cli_shell_word(const char *s, char *out, size_t size) {
  const char *plain = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./:=@%+,-";
  if (*s && strspn(s, plain) == strlen(s)) {
    snprintf(out, size, "%s", s);
    return out;
  }
  size_t used = 0;
  out[used++] = '\'';
  for (; *s && used + 6 < size; s++) {
    if (*s == '\'') {
      memcpy(out + used, "'\\''", 4);
      used += 4;
    } else {
      out[used++] = *s;
    }
  }
  out[used++] = '\'';
  out[used] = '\0';
  return out;
}
