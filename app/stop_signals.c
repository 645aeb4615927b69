/* SIGINT and SIGTERM into a flag (app/stop_signals.h). */
#define _POSIX_C_SOURCE 200809L
#include "app/stop_signals.h"

#include <stddef.h>

static volatile sig_atomic_t caught;

static void on_stop(int signal_number) { caught = signal_number; }

void stop_signals_catch(stop_signals *s, bool second_ends) {
  struct sigaction action = {.sa_handler = on_stop,
                             .sa_flags = SA_RESTART | (second_ends ? SA_RESETHAND : 0)};
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, NULL, &s->old_int);
  sigaction(SIGTERM, NULL, &s->old_term);
  if (s->old_int.sa_handler != SIG_IGN) sigaction(SIGINT, &action, NULL);
  if (s->old_term.sa_handler != SIG_IGN) sigaction(SIGTERM, &action, NULL);
}

int stop_signals_caught(void) { return caught; }

void stop_signals_clear(void) { caught = 0; }

volatile sig_atomic_t *stop_signals_flag(void) { return &caught; }

void stop_signals_hold(stop_signals *s) {
  sigset_t hold;
  sigemptyset(&hold);
  sigaddset(&hold, SIGINT);
  sigaddset(&hold, SIGTERM);
  sigprocmask(SIG_BLOCK, &hold, &s->held_from);
}

void stop_signals_release(stop_signals *s) { sigprocmask(SIG_SETMASK, &s->held_from, NULL); }

void stop_signals_restore(const stop_signals *s) {
  sigaction(SIGINT, &s->old_int, NULL);
  sigaction(SIGTERM, &s->old_term, NULL);
}
