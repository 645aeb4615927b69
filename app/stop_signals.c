/* SIGINT and SIGTERM into a flag (app/stop_signals.h). */
#define _POSIX_C_SOURCE 200809L
#include "app/stop_signals.h"

#include <stdatomic.h>
#include <stddef.h>

static volatile sig_atomic_t caught;
/* The handler runs on whichever thread the kernel picks, so the state it shares with the
 * holding thread is lock-free atomics (async-signal-safe, and no data race in C11). */
static atomic_int second_ends_process;
/* While held: a second signal is kept here for the release. The mask holds a signal on
 * the calling thread only, and a process-directed one goes to any thread that does not
 * block it (llvmpipe's, FFTW's, the pipeline's worker), so the handler holds it too. */
static atomic_int holding, held_second;

/* The default action of the signal: the process ends as the signal ends it (a shell sees
 * 130). sigaction and raise are async-signal-safe (POSIX.1-2008 §2.4.3). */
static void end_process(int signal_number) {
  struct sigaction default_action = {.sa_handler = SIG_DFL};
  sigemptyset(&default_action.sa_mask);
  sigaction(signal_number, &default_action, NULL);
  raise(signal_number);
}

static void on_stop(int signal_number) {
  if (caught && atomic_load(&second_ends_process)) {
    /* kept first, then the hold looked at: a release between the two reads it, or this
     * sees the hold gone; either way the process ends (never neither) */
    atomic_store(&held_second, signal_number);
    if (!atomic_load(&holding)) end_process(signal_number);
    return;
  }
  caught = signal_number;
}

void stop_signals_catch(stop_signals *s, bool second_ends) {
  /* The second signal is the handler's to act on, not SA_RESETHAND's: reset on the first
   * delivery, the default action would end the process on any thread while held. */
  struct sigaction action = {.sa_handler = on_stop, .sa_flags = SA_RESTART};
  sigemptyset(&action.sa_mask);
  s->old_second_ends = atomic_load(&second_ends_process) != 0; /* a catch inside another */
  atomic_store(&second_ends_process, second_ends);
  atomic_store(&holding, 0);
  atomic_store(&held_second, 0);
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
  atomic_store(&holding, 1);
  sigprocmask(SIG_BLOCK, &hold, &s->held_from);
}

void stop_signals_release(stop_signals *s) {
  atomic_store(&holding, 0);
  sigprocmask(SIG_SETMASK, &s->held_from, NULL); /* one held on this thread arrives now */
  const int second = atomic_exchange(&held_second, 0);
  if (second) end_process(second);
}

void stop_signals_restore(const stop_signals *s) {
  sigaction(SIGINT, &s->old_int, NULL);
  sigaction(SIGTERM, &s->old_term, NULL);
  atomic_store(&second_ends_process, s->old_second_ends);
}
