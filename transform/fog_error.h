#ifndef FOGPIPE_FOG_ERROR_H
#define FOGPIPE_FOG_ERROR_H

/* The one error type of every fogpipe library: a result code a caller can act on, and a
 * message a person can (naming the file, line or key and what was expected). Modelled on
 * OpenEXR Core's exr_result_t with its default messages.
 *
 * Libraries never print: a failing call fills its fog_error and returns non-zero (a create
 * of an opaque object: NULL). A caller
 * that fails because a callee did passes the callee's code on with fog_error_wrap, adding
 * its own context in front of the message. It lives in transform/, the library at the
 * bottom of the arrows, so that every other library can return it. */

#ifdef __cplusplus
extern "C" {
#endif

typedef enum fog_result {
  FOG_SUCCESS = 0,
  FOG_ERR_OUT_OF_MEMORY, /* an allocation failed */
  FOG_ERR_INVALID_ARGUMENT, /* a value, size or combination the call does not accept */
  FOG_ERR_FILE_ACCESS, /* a file or folder could not be opened, read, written or renamed */
  FOG_ERR_BAD_FILE, /* a file's contents are not what was expected (format, damage) */
  FOG_ERR_BAD_CONFIG, /* a scene config's line or key is wrong (the message names it) */
  FOG_ERR_GRAPHICS, /* the GL, EGL or GLFW refused (context, shader, framebuffer) */
  FOG_ERR_UNSUPPORTED, /* built without the feature, or a feature not available here */
  FOG_ERR_NO_SUCH_CHANNEL, /* an image has no channel of the name asked for (it may have
                            * others: a caller can try another name) */
  FOG_RESULT_COUNT
} fog_result;

typedef struct fog_error {
  fog_result code;
  char message[600];
} fog_error;

/* The generic text of a code ("out of memory", ...); "unknown result" past the enum. */
const char *fog_result_text(fog_result code);

/* Sets code and the printf-formatted message (when err is not NULL); returns 1, the failing
 * status, for `return fog_fail(...)`. */
int fog_fail(fog_error *err, fog_result code, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Fails because cause did: keeps cause's code (FOG_ERR_INVALID_ARGUMENT where a cause
 * set none), and the message becomes the formatted context followed by cause's message
 * ("transform: " + "levels must be ..."). err may be cause itself. Returns 1. */
int fog_error_wrap(fog_error *err, const fog_error *cause, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Fails with cause's code and message unchanged (err may be NULL; a cause without a code
 * gets FOG_ERR_INVALID_ARGUMENT). Returns 1. */
int fog_error_pass(fog_error *err, const fog_error *cause);

#ifdef __cplusplus
}
#endif

#endif
