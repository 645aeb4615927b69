/* The one error type: codes, default texts, filling and wrapping. */
#include "transform/fog_error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char *fog_result_text(fog_result code) {
  switch (code) {
    case FOG_SUCCESS:
      return "success";
    case FOG_ERR_OUT_OF_MEMORY:
      return "out of memory";
    case FOG_ERR_INVALID_ARGUMENT:
      return "invalid argument";
    case FOG_ERR_FILE_ACCESS:
      return "file access failed";
    case FOG_ERR_BAD_FILE:
      return "unexpected file contents";
    case FOG_ERR_BAD_CONFIG:
      return "bad scene config";
    case FOG_ERR_GRAPHICS:
      return "graphics error";
    case FOG_ERR_UNSUPPORTED:
      return "not supported";
    case FOG_ERR_NO_SUCH_CHANNEL:
      return "no such channel";
    case FOG_RESULT_COUNT:
      break;
  }
  return "unknown result";
}

int fog_fail(fog_error *err, fog_result code, const char *format, ...) {
  if (!err) return 1;
  err->code = code;
  va_list args;
  va_start(args, format);
  vsnprintf(err->message, sizeof err->message, format, args);
  va_end(args);
  return 1;
}

int fog_error_wrap(fog_error *err, const fog_error *cause, const char *format, ...) {
  if (!err) return 1;
  fog_error copy = *cause; /* err may be cause */
  va_list args;
  va_start(args, format);
  int n = vsnprintf(err->message, sizeof err->message, format, args);
  va_end(args);
  if (n < 0) n = 0;
  if ((size_t)n < sizeof err->message)
    snprintf(err->message + n, sizeof err->message - (size_t)n, "%s", copy.message);
  /* a cause that set no code still failed */
  err->code = copy.code != FOG_SUCCESS ? copy.code : FOG_ERR_INVALID_ARGUMENT;
  return 1;
}

int fog_error_pass(fog_error *err, const fog_error *cause) {
  return fog_error_wrap(err, cause, "%s", ""); /* no context: the same code rule */
}
