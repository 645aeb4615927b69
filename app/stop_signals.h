/* Ctrl-C and SIGTERM while a command writes its outputs (record, bake, fit, transform,
 * import, render, design): caught into a flag the command polls between units of work, so that it
 * can remove what it half-made and exit 130 instead of dying with a staging folder or a
 * partial file left.
 * A signal the parent set to be ignored (nohup, a farm's scheduler) stays ignored. */
#ifndef FOGPIPE_APP_STOP_SIGNALS_H
#define FOGPIPE_APP_STOP_SIGNALS_H

#include <signal.h>
#include <stdbool.h>

typedef struct stop_signals {
  struct sigaction old_int, old_term;
  sigset_t held_from; /* the mask before stop_signals_hold */
  bool old_second_ends; /* an outer catch's second_ends, put back by stop_signals_restore */
} stop_signals;

/* Catches SIGINT and SIGTERM from now on into the flag (not cleared: a signal during a
 * recording's frames still stops its preview after a second catch). second_ends: a second
 * signal ends the process at once (for work that polls seldom, such as fit's rungs), or at
 * the release when it comes while held. */
void stop_signals_catch(stop_signals *s, bool second_ends);
/* The signal caught, or 0; and the flag back to 0. */
int stop_signals_caught(void);
void stop_signals_clear(void);
/* The flag itself, for a library that polls a volatile (fit_desc.stop). */
volatile sig_atomic_t *stop_signals_flag(void);
/* SIGINT and SIGTERM held (acted on at release) around writes and renames that must
 * finish, whichever of the process's threads the kernel hands them to. */
void stop_signals_hold(stop_signals *s);
void stop_signals_release(stop_signals *s);
/* The handlers as they were before stop_signals_catch. */
void stop_signals_restore(const stop_signals *s);

#endif
