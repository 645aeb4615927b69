#ifndef FOGPIPE_RENDER_ERROR_H
#define FOGPIPE_RENDER_ERROR_H

/* Errors are returned, never printed: a failing call fills message and returns non-zero. */
typedef struct render_error {
  char message[512];
} render_error;

#endif
