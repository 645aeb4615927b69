/* The one error type (transform/fog_error.h): every code has its own text, a failure keeps
 * its code through each caller that wraps it, messages are cut at the buffer and never
 * overrun it, and a real failure of the library below (a transform plan) carries its code. */
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "transform/fog_error.h"
#include "transform/transform.h"

static void texts_are_distinct(void) {
  for (int a = 0; a < FOG_RESULT_COUNT; a++) {
    const char *ta = fog_result_text((fog_result)a);
    CHECK(ta && *ta && strcmp(ta, "unknown result"), "code %d has no text", a);
    for (int b = a + 1; b < FOG_RESULT_COUNT; b++)
      CHECK(strcmp(ta, fog_result_text((fog_result)b)), "codes %d and %d share '%s'", a, b, ta);
  }
  CHECK(!strcmp(fog_result_text(FOG_SUCCESS), "success"), "%s", fog_result_text(FOG_SUCCESS));
  CHECK(!strcmp(fog_result_text(FOG_RESULT_COUNT), "unknown result"), "past the enum");
  CHECK(!strcmp(fog_result_text((fog_result)-1), "unknown result"), "below the enum");
}

static void fail_sets_code_and_message(void) {
  fog_error err = {0};
  CHECK(fog_fail(&err, FOG_ERR_BAD_FILE, "%s: %d bytes", "a.vdb", 12) == 1, "status");
  CHECK(err.code == FOG_ERR_BAD_FILE && !strcmp(err.message, "a.vdb: 12 bytes"), "%d '%s'",
        err.code, err.message);
  CHECK(fog_fail(NULL, FOG_ERR_GRAPHICS, "nobody listens") == 1, "NULL error");
  /* a message longer than the buffer is cut, terminated, and nothing past it is written */
  struct {
    fog_error err;
    char guard[16];
  } boxed;
  memset(&boxed, 0x5a, sizeof boxed);
  char long_text[2000];
  memset(long_text, 'x', sizeof long_text - 1);
  long_text[sizeof long_text - 1] = '\0';
  fog_fail(&boxed.err, FOG_ERR_INVALID_ARGUMENT, "%s", long_text);
  CHECK(strlen(boxed.err.message) == sizeof boxed.err.message - 1, "cut at %zu",
        strlen(boxed.err.message));
  for (size_t i = 0; i < sizeof boxed.guard; i++)
    CHECK(boxed.guard[i] == 0x5a, "byte %zu past the message written", i);
}

static void wrap_keeps_the_cause(void) {
  fog_error cause = {0}, err = {0};
  fog_fail(&cause, FOG_ERR_FILE_ACCESS, "map.png: cannot open: No such file or directory");
  CHECK(fog_error_wrap(&err, &cause, "%s:%d: [fog] fogmap: ", "scene.ini", 7) == 1, "status");
  CHECK(err.code == FOG_ERR_FILE_ACCESS, "code %d", err.code);
  CHECK(!strcmp(err.message,
                "scene.ini:7: [fog] fogmap: map.png: cannot open: No such file or directory"),
        "'%s'", err.message);
  /* in place: the error is its own cause (a caller adding context to its own error) */
  fog_error_wrap(&err, &err, "record: ");
  CHECK(!strncmp(err.message, "record: scene.ini:7: ", 21) && err.code == FOG_ERR_FILE_ACCESS,
        "in place: '%s'", err.message);
  /* a cause that forgot its code still makes a failure */
  fog_error uncoded = {.message = "something"};
  fog_error_wrap(&err, &uncoded, "x: ");
  CHECK(err.code != FOG_SUCCESS && !strcmp(err.message, "x: something"), "uncoded cause");
  /* a context that fills the buffer leaves the cause out, terminated */
  char long_text[700];
  memset(long_text, 'c', sizeof long_text - 1);
  long_text[sizeof long_text - 1] = '\0';
  fog_error_wrap(&err, &cause, "%s", long_text);
  CHECK(strlen(err.message) == sizeof err.message - 1 && err.code == FOG_ERR_FILE_ACCESS,
        "long context: %zu", strlen(err.message));
  /* pass: the cause unchanged */
  fog_error passed = {0};
  CHECK(fog_error_pass(&passed, &cause) == 1 && passed.code == cause.code &&
            !strcmp(passed.message, cause.message),
        "pass");
  CHECK(fog_error_pass(NULL, &cause) == 1, "pass to NULL");
}

static void a_library_failure_carries_its_code(void) {
  transform_plan *plan = NULL;
  fog_error err = {0};
  int status = !(plan = transform_plan_create(&(transform_desc){.width = 6, .height = 6, .levels = 5, .basis = TRANSFORM_LINEAR},
      &err));
  CHECK(status != 0 && plan == NULL, "a 6x6 grid took 5 levels");
  CHECK(err.code == FOG_ERR_INVALID_ARGUMENT, "code %s: %s", fog_result_text(err.code),
        err.message);
  fog_error outer = {0};
  fog_error_wrap(&outer, &err, "transform: ");
  CHECK(outer.code == FOG_ERR_INVALID_ARGUMENT && strstr(outer.message, err.message), "wrapped: %s",
        outer.message);
}

int main(void) {
  texts_are_distinct();
  fail_sets_code_and_message();
  wrap_keeps_the_cause();
  a_library_failure_carries_its_code();
  return test_finish("test_fog_error");
}
