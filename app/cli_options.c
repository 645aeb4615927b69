/* The option tables' parser and --help writer (app/cli_options.h). */
#include "app/cli_options.h"

#include <string.h>

#include "app/cli.h"

static const cli_option *find(const cli_spec *spec, const char *name) {
  for (int k = 0; k < spec->option_count; k++) {
    const cli_option *o = &spec->options[k];
    if (o->kind != CLI_SECTION && !strcmp(o->name, name)) return o;
  }
  return NULL;
}

/* "a, b or c" of a NULL-terminated list, into text. */
static void list_text(const char *const *items, char *text, size_t size) {
  size_t used = 0;
  text[0] = 0;
  for (int c = 0; items[c]; c++) {
    const char *sep = !c ? "" : items[c + 1] ? ", " : " or ";
    int n = snprintf(text + used, size - used, "%s%s", sep, items[c]);
    if (n < 0 || (size_t)n >= size - used) break;
    used += (size_t)n;
  }
}

static int choice_error(const cli_spec *spec, const cli_option *o, const char *text) {
  char expected[256];
  list_text(o->choices, expected, sizeof expected);
  return cli_usage_error(spec->command, "%s '%s': expected %s", o->name, text, expected);
}

/* An output file's name: one of the row's extensions, and not a folder. */
static int take_output(const cli_spec *spec, const cli_option *o, const char *text) {
  bool known = false;
  for (int e = 0; o->extensions[e] && !known; e++) known = cli_ends_with(text, o->extensions[e]);
  if (!known) {
    char expected[256];
    list_text(o->extensions, expected, sizeof expected);
    return cli_usage_error(spec->command, "%s '%s': expected a %s file name", o->name, text,
                           expected);
  }
  if (cli_output_file(spec->command, o->name, text) ||
      cli_output_in_folder(spec->command, o->name, text))
    return 2;
  *(const char **)o->target = text;
  return 0;
}

/* One option's value into its target: 0, or 2 with the message printed. */
static int take_value(const cli_spec *spec, const cli_option *o, const char *text) {
  const char *cmd = spec->command;
  int *ints = o->target;
  switch (o->kind) {
    case CLI_INT: return cli_int(cmd, o->name, text, (long)o->min, (long)o->max, ints);
    case CLI_NUMBER: return cli_number(cmd, o->name, text, o->min, o->max, o->target);
    case CLI_FLOAT: {
      double v;
      if (cli_number(cmd, o->name, text, o->min, o->max, &v)) return 2;
      *(float *)o->target = (float)v;
      return 0;
    }
    case CLI_SIZE: return cli_size(cmd, o->name, text, &ints[0], &ints[1]);
    case CLI_RANGE: {
      bool single;
      if (cli_range(cmd, o->name, text, (long)o->min, (long)o->max, &ints[0], &ints[1], &single))
        return 2;
      ints[2] = single;
      return 0;
    }
    case CLI_TEXT:
      if (!*text) return cli_usage_error(cmd, "%s: expected a value, got ''", o->name);
      *(const char **)o->target = text;
      return 0;
    case CLI_OUTPUT: return take_output(spec, o, text);
    case CLI_CHOICE:
      for (int c = 0; o->choices[c]; c++)
        if (!strcmp(text, o->choices[c])) return *ints = c, 0;
      return choice_error(spec, o, text);
    case CLI_CUSTOM: return o->parse(cmd, o->name, text, o->target);
    default: return 2;
  }
}

int cli_parse(const cli_spec *spec, int argc, char **argv, const char **operands, int *count) {
  *count = 0;
  bool seen[CLI_MAX_OPTIONS] = {false}; /* by row: for the required ones */
  if (spec->option_count > CLI_MAX_OPTIONS)
    return cli_fail(spec->command, "%d option rows: at most %d (CLI_MAX_OPTIONS)",
                    spec->option_count, CLI_MAX_OPTIONS);
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      cli_print_help(spec, stdout);
      return CLI_HELP;
    }
    if (a[0] != '-' || !a[1]) { /* an operand ("-" alone is one too) */
      if (*count == spec->max_operands)
        return spec->max_operands == 0
                   ? cli_usage_error(spec->command, "unexpected argument '%s' (options only)", a)
               : spec->max_operands == 1
                   ? cli_usage_error(spec->command, "one %s only, got '%s' and '%s'",
                                     spec->operand, operands[0], a)
                   : cli_usage_error(spec->command, "at most %d %s operands, got '%s' too",
                                     spec->max_operands, spec->operand, a);
      operands[(*count)++] = a;
      continue;
    }
    const cli_option *o = find(spec, a);
    if (!o) return cli_usage_error(spec->command, "unknown option '%s'", a);
    if (seen[o - spec->options] && o->kind != CLI_FLAG && !o->repeats)
      return cli_usage_error(spec->command, "%s given twice (which value was meant?)", a);
    seen[o - spec->options] = true;
    if (o->given) *o->given = true;
    if (o->kind == CLI_FLAG) {
      *(bool *)o->target = true;
      continue;
    }
    if (i + 1 >= argc)
      return cli_usage_error(spec->command, "%s needs a value (%s)", a, o->value);
    /* `--out --synchronous` (a value left out) took the next option as a folder's name,
     * ran without it and exited 0; a number, size or range refuses such a value itself */
    const char *value = argv[++i];
    if ((o->kind == CLI_TEXT || o->kind == CLI_OUTPUT) && !strncmp(value, "--", 2)) {
      /* a path may be written ./--x; a grid's or channel's name has no such way */
      const bool path = o->kind == CLI_OUTPUT || (o->value && (strstr(o->value, "DIR") ||
                                                               strstr(o->value, "FILE")));
      char hint[300] = "";
      if (path) snprintf(hint, sizeof hint, " (a file that starts with '--' is ./%.200s)", value);
      return cli_usage_error(spec->command, "%s needs a value (%s), got the option '%s'%s", a,
                             o->value, value, hint);
    }
    if (take_value(spec, o, value)) return 2;
  }
  if (*count < spec->min_operands)
    return cli_usage_error(spec->command, "no %s given", spec->operand);
  for (int k = 0; k < spec->option_count; k++) {
    const cli_option *o = &spec->options[k];
    if (o->required && !seen[k])
      return cli_usage_error(spec->command, "%s%s%s is required", o->name, o->value ? " " : "",
                             o->value ? o->value : "");
  }
  return 0;
}

/* Help lines: the option and its value in a column of 24, the text beside, continued. */
enum { HELP_COLUMN = 24 };

static void print_help_lines(FILE *out, const char *help, int column) {
  for (const char *line = help; line && *line;) {
    const char *end = strchr(line, '\n');
    int n = end ? (int)(end - line) : (int)strlen(line);
    fprintf(out, "%.*s\n", n, line);
    if (!end) break;
    line = end + 1;
    if (*line) fprintf(out, "%*s", column, "");
  }
}

void cli_print_help(const cli_spec *spec, FILE *out) {
  fprintf(out, "usage: fogpipe %s %s\n\n", spec->command, spec->usage);
  if (spec->about) fprintf(out, "%s\n\n", spec->about);
  bool headed = spec->option_count > 0 && spec->options[0].kind == CLI_SECTION;
  if (!headed) fprintf(out, "options:\n");
  for (int k = 0; k < spec->option_count; k++) {
    const cli_option *o = &spec->options[k];
    if (o->kind == CLI_SECTION) {
      fprintf(out, "%s%s\n", k ? "\n" : "", o->name);
      continue;
    }
    char left[64];
    int n = snprintf(left, sizeof left, "  %s%s%s", o->name, o->value ? " " : "",
                     o->value ? o->value : "");
    if (n >= HELP_COLUMN - 1)
      fprintf(out, "%s\n%*s", left, HELP_COLUMN, "");
    else
      fprintf(out, "%-*s", HELP_COLUMN, left);
    print_help_lines(out, o->help, HELP_COLUMN);
  }
  fprintf(out, "  %-*s%s\n", HELP_COLUMN - 2, "--help", "this text");
  if (spec->footer) fprintf(out, "\n%s\n", spec->footer);
}

int cli_parse_one(const cli_spec *spec, int argc, char **argv, const char **operand) {
  const char *given = NULL;
  int count = 0, parsed = cli_parse(spec, argc, argv, &given, &count);
  if (!parsed && count) *operand = given;
  return parsed;
}
