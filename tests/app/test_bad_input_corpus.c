/* The bad-input corpus (tests/bad_input/cases.txt): every case runs `fogpipe ARGS` and must
 * exit with its status, print its message fragment, and leave its output folder empty
 * (nothing half-written, no temporary). A case that hangs is killed after 120 s. */
#include "tests/app/record_util.h"

#include <ctype.h>

#include "tests/test_util.h"

#define CORPUS "tests/bad_input"

static char *trim(char *s) {
  while (isspace((unsigned char)*s)) s++;
  char *end = s + strlen(s);
  while (end > s && isspace((unsigned char)end[-1])) *--end = '\0';
  return s;
}

/* Copies text into out, replacing every @IN@ and @OUT@. */
static void substitute(const char *text, const char *out_dir, char *out, size_t size) {
  size_t n = 0;
  while (*text && n + 1 < size) {
    const char *with = NULL;
    size_t skip = 0;
    if (!strncmp(text, "@IN@", 4)) with = CORPUS, skip = 4;
    else if (!strncmp(text, "@OUT@", 5)) with = out_dir, skip = 5;
    if (with) {
      n += (size_t)snprintf(out + n, size - n, "%s", with);
      text += skip;
    } else {
      out[n++] = *text++;
    }
  }
  out[n < size ? n : size - 1] = '\0';
}

int main(void) {
  FILE *cases = fopen(CORPUS "/cases.txt", "r");
  CHECK(cases != NULL, "cannot open %s/cases.txt (run from the source folder)", CORPUS);
  if (!cases) return test_finish("test_bad_input_corpus");
  char root[] = "/tmp/fogpipe-bad-input-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char line[2048];
  int number = 0, run = 0;
  while (fgets(line, sizeof line, cases)) {
    number++;
    char *text = trim(line);
    if (!*text || *text == '#') continue;
    char *bar1 = strchr(text, '|'), *bar2 = bar1 ? strchr(bar1 + 1, '|') : NULL;
    CHECK(bar2 != NULL, "cases.txt:%d: expected EXIT | FRAGMENT | ARGUMENTS", number);
    if (!bar2) continue;
    *bar1 = *bar2 = '\0';
    int want = atoi(trim(text));
    char out_dir[700], fragment[1024], args[2048], log[800], command[4096];
    snprintf(out_dir, sizeof out_dir, "%s/case%d", root, number);
    mkdir(out_dir, 0755);
    substitute(trim(bar1 + 1), out_dir, fragment, sizeof fragment);
    substitute(trim(bar2 + 1), out_dir, args, sizeof args);
    snprintf(log, sizeof log, "%s/case%d.log", root, number);
    snprintf(command, sizeof command, "timeout 120 '%s' %s > '%s' 2>&1 < /dev/null",
             record_bin(), args, log);
    int status = system(command);
    int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    int left = test_folder_entries(out_dir);
    int found = record_log_contains(log, fragment);
    /* a sanitizer's report on the way out (make test-sanitize) is no expected error */
    const int sanitizer = record_log_contains(log, "Sanitizer") ||
                          record_log_contains(log, "runtime error:");
    CHECK(!sanitizer, "cases.txt:%d: a sanitizer reported on `fogpipe %s`", number, args);
    CHECK(code == want, "cases.txt:%d: `fogpipe %s` exited %d, expected %d", number, args,
          code, want);
    CHECK(found, "cases.txt:%d: the output lacks \"%s\"", number, fragment);
    CHECK(left == 0, "cases.txt:%d: %d entries left in the output folder", number, left);
    if (code != want || !found || left || sanitizer) record_print_log(log);
    printf("case %2d: exit %d, %s\n", number, code, found ? "message as expected" : "MESSAGE DIFFERS");
    run++;
  }
  fclose(cases);
  CHECK(run >= 20, "only %d cases ran", run);
  test_remove_tree(root);
  return test_finish("test_bad_input_corpus");
}
