/* The option tables (app/cli_options.h): cli_parse stores every kind of value where its row
 * says, refuses what the row does not allow with exit status 2 (unknown options, missing
 * values, numbers out of range or with trailing text, unknown choices, too many or too few
 * operands, a required option left out, a value given twice), answers --help with
 * CLI_HELP (even without the required option), and cli_print_help lists every row
 * (sections, options with their values and each line of their help). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "app/cli.h"
#include "app/cli_options.h"
#include "test_util.h"

typedef struct values {
  bool flag, given_number;
  int count, size[2], range[3], choice;
  double number;
  float ratio;
  const char *text, *custom, *out;
} values;

static int parse_upper(const char *command, const char *option, const char *text, void *target) {
  if (!(text[0] >= 'A' && text[0] <= 'Z'))
    return cli_usage_error(command, "%s '%s': expected a capital first", option, text);
  *(const char **)target = text;
  return 0;
}

static const char *const choices[] = {"red", "green", "blue", NULL};

static int run(values *v, const char **operands, int *count, const char *line) {
  *v = (values){.count = -1, .choice = -1};
  const cli_option options[] = {
      {.kind = CLI_SECTION, .name = "first:"},
      {.kind = CLI_FLAG, .name = "--flag", .target = &v->flag, .help = "a flag"},
      {.kind = CLI_INT, .name = "--count", .value = "N", .target = &v->count, .min = 1, .max = 9,
       .help = "a count\nover two lines"},
      {.kind = CLI_NUMBER, .name = "--number", .value = "X", .target = &v->number, .min = -1,
       .max = 1, .given = &v->given_number, .help = "a number"},
      {.kind = CLI_FLOAT, .name = "--ratio", .value = "R", .target = &v->ratio, .min = 0,
       .max = 2, .help = "a float"},
      {.kind = CLI_SECTION, .name = "second:"},
      {.kind = CLI_SIZE, .name = "--size", .value = "WxH", .target = v->size, .help = "a size"},
      {.kind = CLI_RANGE, .name = "--frames", .value = "A-B", .target = v->range, .min = 0,
       .max = 100, .help = "a range"},
      {.kind = CLI_TEXT, .name = "--text", .value = "TEXT", .target = &v->text, .help = "text"},
      {.kind = CLI_CHOICE, .name = "--colour", .value = "red|green|blue", .target = &v->choice,
       .choices = choices, .help = "a choice"},
      {.kind = CLI_CUSTOM, .name = "--name", .value = "NAME", .target = &v->custom,
       .parse = parse_upper, .help = "a custom value"},
      {.kind = CLI_TEXT, .name = "--out", .value = "DIR", .target = &v->out, .required = true,
       .help = "required"},
  };
  const cli_spec spec = {.command = "test", .usage = "FILE... [options]", .about = "About.",
                         .operand = "FILE", .min_operands = 1, .max_operands = 2,
                         CLI_OPTIONS(options),
                         .footer = "Footer."};
  char buffer[512], *argv[32];
  snprintf(buffer, sizeof buffer, "test %s", line);
  int argc = 0;
  for (char *w = strtok(buffer, " "); w && argc < 32; w = strtok(NULL, " ")) argv[argc++] = w;
  static char keep[32][64]; /* operands point into argv: keep the words */
  for (int i = 0; i < argc; i++) {
    snprintf(keep[i], sizeof keep[i], "%s", argv[i]);
    argv[i] = keep[i];
  }
  int status = cli_parse(&spec, argc, argv, operands, count);
  if (status == CLI_HELP) { /* the help again, into a string, to check its lines */
    char *text = NULL;
    size_t length = 0;
    FILE *f = open_memstream(&text, &length);
    cli_print_help(&spec, f);
    fclose(f);
    const char *lines[] = {"usage: fogpipe test FILE... [options]", "About.", "first:",
                           "  --flag ", "  --count N ", "a count\n", "over two lines\n",
                           "  --ratio R", "second:", "  --size WxH", "  --frames A-B",
                           "  --colour red|green|blue", "  --name NAME", "  --help", "Footer."};
    for (size_t k = 0; k < sizeof lines / sizeof lines[0]; k++)
      CHECK(strstr(text, lines[k]) != NULL, "help lacks '%s':\n%s", lines[k], text);
    free(text);
  }
  return status;
}

int main(void) {
  values v;
  const char *operands[2];
  int count;
  int status = run(&v, operands, &count,
                   "a.ini --flag --count 7 --number -0.5 --ratio 1.5 --size 640x360 "
                   "--frames 3-9 --text hello --colour blue --name Fog b.ini --out o");
  CHECK(status == 0, "a full line: status %d", status);
  CHECK(count == 2 && !strcmp(operands[0], "a.ini") && !strcmp(operands[1], "b.ini"),
        "operands");
  CHECK(v.flag && v.count == 7 && v.number == -0.5 && v.ratio == 1.5f && v.given_number,
        "flag, int, number, float");
  CHECK(v.size[0] == 640 && v.size[1] == 360, "size %dx%d", v.size[0], v.size[1]);
  CHECK(v.range[0] == 3 && v.range[1] == 9 && v.range[2] == 0, "range %d-%d", v.range[0],
        v.range[1]);
  CHECK(!strcmp(v.text, "hello") && v.choice == 2 && !strcmp(v.custom, "Fog"),
        "text, choice, custom");
  CHECK(run(&v, operands, &count, "a.ini --frames 5 --out o") == 0 && v.range[0] == 5 &&
            v.range[1] == 5 && v.range[2] == 1,
        "a single frame");
  CHECK(run(&v, operands, &count, "a.ini --out o") == 0 && !v.given_number && v.count == -1,
        "untouched without the options");
  CHECK(run(&v, operands, &count, "a.ini --flag --flag --out o") == 0 && v.flag,
        "a flag twice is still the flag");
  CHECK(run(&v, operands, &count, "--help") == CLI_HELP, "--help");
  CHECK(run(&v, operands, &count, "a.ini -h") == CLI_HELP, "-h");

  const char *bad[] = {
      "a.ini --bogus --out o",        /* unknown */
      "a.ini --count",                /* no value */
      "a.ini --count 10 --out o",     /* out of range */
      "a.ini --count 3x --out o",     /* trailing text */
      "a.ini --number nan --out o",   /* not finite */
      "a.ini --ratio 2.5 --out o",    /* float out of range */
      "a.ini --size 0x10 --out o",    /* size */
      "a.ini --frames 9-3 --out o",   /* range backwards */
      "a.ini --colour purple --out o", /* unknown choice */
      "a.ini --name fog --out o",     /* custom refusal */
      "a.ini b.ini c.ini --out o",    /* too many operands */
      "--flag --out o",               /* too few */
      "a.ini --flag",                 /* no --out */
      "a.ini --text --out",           /* --out only as --text's value */
      "a.ini --count 2 --count 3 --out o", /* twice */
  };
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
    CHECK(run(&v, operands, &count, bad[k]) == 2, "'%s' was not refused with 2", bad[k]);

  /* cli_parse_one: the one operand where asked, the caller's default kept without one */
  bool flag = false;
  const cli_option one_options[] = {{.kind = CLI_FLAG, .name = "--flag", .target = &flag}};
  const cli_spec one = {.command = "one", .operand = "CONFIG", .max_operands = 1,
                        CLI_OPTIONS(one_options)};
  CHECK(one.option_count == 1, "CLI_OPTIONS counts %d rows", one.option_count);
  char *with[] = {"one", "--flag", "a.ini"}, *without[] = {"one", "--flag"};
  char *two[] = {"one", "a.ini", "b.ini"};
  const char *config = "default.ini";
  CHECK(cli_parse_one(&one, 2, without, &config) == 0 && !strcmp(config, "default.ini") && flag,
        "no operand: '%s' kept", config);
  CHECK(cli_parse_one(&one, 3, with, &config) == 0 && !strcmp(config, "a.ini"), "operand '%s'",
        config);
  CHECK(cli_parse_one(&one, 3, two, &config) == 2, "two operands refused");
  const cli_spec none = {.command = "none", CLI_OPTIONS(one_options)};
  CHECK(cli_parse_one(&none, 2, without, NULL) == 0 && cli_parse_one(&none, 3, with, NULL) == 2,
        "no operands taken: NULL target, an operand refused");

  /* CLI_OUTPUT: a file name with one of the row's extensions (any case), no existing folder */
  const char *image = NULL;
  const cli_option out_rows[] = {{.kind = CLI_OUTPUT, .name = "--out", .value = "FILE",
                                  .target = &image,
                                  .extensions = (const char *const[]){".exr", ".png", NULL}}};
  const cli_spec out_spec = {.command = "out", CLI_OPTIONS(out_rows)};
  char *good[] = {"out", "--out", "/tmp/fogpipe-cli-image.PNG"};
  char *wrong[] = {"out", "--out", "/tmp/fogpipe-cli-image.jpg"};
  char scratch[] = "/tmp/fogpipe-cli-options-XXXXXX", dir_exr[64];
  CHECK(test_scratch_folder(scratch), "scratch folder");
  snprintf(dir_exr, sizeof dir_exr, "%s/d.exr", scratch);
  CHECK(mkdir(dir_exr, 0700) == 0, "mkdir %s", dir_exr);
  char *folder[] = {"out", "--out", dir_exr};
  CHECK(cli_parse_one(&out_spec, 3, good, NULL) == 0 && image == good[2], "a .PNG name: '%s'",
        image ? image : "(none)");
  CHECK(cli_parse_one(&out_spec, 3, wrong, NULL) == 2, "a .jpg name was taken");
  CHECK(cli_parse_one(&out_spec, 3, folder, NULL) == 2, "a folder d.exr was taken as a file");
  test_remove_tree(scratch);
  return test_finish("test_cli_options");
}
