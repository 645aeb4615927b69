/* One option parser for every command: a command describes its options in a table (name,
 * value, help, where the value goes and its range), and cli_parse reads argv by it while
 * cli_print_help writes --help from the same rows, so the help cannot miss an option or
 * name one that does not exist. Values go through app/cli.h's parsers: one message style,
 * `fogpipe COMMAND: OPTION 'TEXT': expected ...`, exit status 2. */
#ifndef FOGPIPE_APP_CLI_OPTIONS_H
#define FOGPIPE_APP_CLI_OPTIONS_H

#include <stdbool.h>
#include <stdio.h>

typedef enum cli_kind {
  CLI_SECTION, /* not an option: a heading in --help ("placement:") */
  CLI_FLAG,    /* no value: *(bool *)target = true */
  CLI_INT,     /* *(int *)target, an integer in [min, max] */
  CLI_NUMBER,  /* *(double *)target, a finite number in [min, max] */
  CLI_FLOAT,   /* *(float *)target, the same */
  CLI_SIZE,    /* WIDTHxHEIGHT: ((int *)target)[0] and [1], each 1..CLI_MAX_SIZE */
  CLI_RANGE,   /* A or A-B in [min, max]: ((int *)target)[0] first, [1] last, [2] 1 for
                * A alone (first = last = A), 0 for A-B */
  CLI_TEXT,    /* *(const char **)target = the text (a path, a name) */
  CLI_OUTPUT,  /* *(const char **)target = a file name to write: it ends in one of
                * extensions (NULL-terminated: ".exr", ".png") and is no existing folder */
  CLI_CHOICE,  /* *(int *)target = the index of the text in choices (NULL-terminated) */
  CLI_CUSTOM,  /* parse(command, name, text, target): 0, or 2 with its message printed */
} cli_kind;

typedef struct cli_option {
  cli_kind kind;
  const char *name;  /* "--out"; CLI_SECTION: the heading */
  const char *value; /* the value's name in --help ("FILE", "WxH"); NULL for a flag */
  const char *help;  /* lines separated by '\n' */
  void *target;
  double min, max;                 /* CLI_INT, CLI_NUMBER, CLI_RANGE */
  const char *const *choices;      /* CLI_CHOICE */
  const char *const *extensions;   /* CLI_OUTPUT */
  int (*parse)(const char *command, const char *option, const char *text, void *target);
  bool *given; /* optional: set when the option was on the command line */
  bool required; /* cli_parse refuses a line without it: "--out DIR is required" */
  bool repeats;  /* may be given more than once (each value parsed in turn); any other
                    option with a value is refused the second time, not overwritten */
} cli_option;

/* The most rows (options and sections) one command's table may have. */
#define CLI_MAX_OPTIONS 128

typedef struct cli_spec {
  const char *command;  /* "render" */
  const char *usage;    /* after "usage: fogpipe COMMAND " */
  const char *about;    /* paragraphs of --help before the options */
  const char *operand;  /* the operands' name in messages ("CONFIG", "INPUT") */
  int min_operands, max_operands;
  const cli_option *options;
  int option_count;
  const char *footer; /* after the options (may be NULL) */
} cli_spec;

/* A spec's option rows from a table: `CLI_OPTIONS(options)` in its initialiser. */
#define CLI_OPTIONS(table) \
  .options = (table), .option_count = (int)(sizeof(table) / sizeof(*(table)))

/* A numeric macro as text, for defaults in help strings: "default " CLI_TEXT_OF(N). */
#define CLI_TEXT_OF_(x) #x
#define CLI_TEXT_OF(x) CLI_TEXT_OF_(x)

/* --help was asked for and printed: the command exits 0. */
#define CLI_HELP (-1)

/* Reads argv[1 .. argc) by spec: options (with `--name VALUE`), "--help"/"-h", and the
 * operands into operands[0 .. *count) (at most spec->max_operands; anything starting with
 * '-' is an option). Returns 0, CLI_HELP, or 2 with the message printed (an unknown option,
 * a missing or bad value, too few or too many operands, a required option not given, an
 * option with a value given twice). */
int cli_parse(const cli_spec *spec, int argc, char **argv, const char **operands, int *count);
/* cli_parse for a command with at most one operand: it goes to *operand (left as it was when
 * none is given; operand may be NULL when spec->max_operands is 0). */
int cli_parse_one(const cli_spec *spec, int argc, char **argv, const char **operand);

/* The --help text: usage, about, the options table by sections, the footer. */
void cli_print_help(const cli_spec *spec, FILE *out);

#endif
