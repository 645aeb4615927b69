/* Messages of the fogpipe commands, one format for all: "fogpipe <command>: <message>"
 * on stderr. Libraries return their errors; only commands print. */
#ifndef FOGPIPE_APP_CLI_H
#define FOGPIPE_APP_CLI_H

/* Prints the message and returns 1 (the exit status of a failed run). */
int cli_fail(const char *command, const char *format, ...)
    __attribute__((format(printf, 2, 3)));

/* Prints the message and a pointer to --help; returns 2 (the status of a bad command line). */
int cli_usage_error(const char *command, const char *format, ...)
    __attribute__((format(printf, 2, 3)));

#endif
