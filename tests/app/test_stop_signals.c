/* stop_signals (app/stop_signals.h) in a process with a second thread, as every command
 * that draws has (llvmpipe's, FFTW's, the pipeline's worker). A held signal must wait for
 * the release on every thread: sigprocmask holds it on the calling thread only, and a
 * process-directed signal goes to any thread that does not block it. With second_ends, a
 * second signal while held used to reach the other thread after the first had reset the
 * handler (SA_RESETHAND): the default action ended the process in the middle of the write
 * the hold was there to finish. */
#define _POSIX_C_SOURCE 200809L
#include "app/stop_signals.h"
#include "test_util.h"

#include <pthread.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static void *idle_thread(void *unused) {
  (void)unused;
  for (;;) pause();
  return NULL;
}

static void sleep_ms(int ms) {
  struct timespec t = {.tv_sec = ms / 1000, .tv_nsec = (long)(ms % 1000) * 1000000L};
  while (nanosleep(&t, &t)) {
  }
}

/* Waits up to 3 s for the flag; 1 if it came. */
static int wait_caught(void) {
  for (int i = 0; i < 300; i++) {
    if (stop_signals_caught()) return 1;
    sleep_ms(10);
  }
  return 0;
}

/* The child: a second thread, the signals caught, held, `signals` SIGINTs sent to the
 * process, a byte 'H' written to the pipe while still held (the write that must finish),
 * then the release, then 'R' and exit 0. */
static void child(int fd, bool second_ends, bool hold, int signals) {
  pthread_t thread;
  if (pthread_create(&thread, NULL, idle_thread, NULL)) _exit(3);
  stop_signals stop;
  stop_signals_clear();
  stop_signals_catch(&stop, second_ends);
  if (hold) stop_signals_hold(&stop);
  for (int i = 0; i < signals; i++) {
    kill(getpid(), SIGINT);
    if (i == 0 && !wait_caught()) _exit(4); /* the first reaches the other thread's handler */
    sleep_ms(200);                           /* time for the second to act, if it does */
  }
  if (write(fd, "H", 1) != 1) _exit(5);
  if (hold) stop_signals_release(&stop);
  sleep_ms(200);
  if (!stop_signals_caught()) _exit(6);
  if (write(fd, "R", 1) != 1) _exit(5);
  _exit(0);
}

typedef struct outcome {
  char said[8];
  int exited, code, signalled, signal_number;
} outcome;

static outcome run_child(bool second_ends, bool hold, int signals) {
  outcome o = {.exited = 0};
  int fds[2];
  if (pipe(fds)) return o;
  fflush(NULL);
  pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    child(fds[1], second_ends, hold, signals);
  }
  close(fds[1]);
  size_t n = 0;
  ssize_t got;
  while (n < sizeof o.said - 1 && (got = read(fds[0], o.said + n, sizeof o.said - 1 - n)) > 0)
    n += (size_t)got;
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  o.exited = WIFEXITED(status);
  o.code = o.exited ? WEXITSTATUS(status) : -1;
  o.signalled = WIFSIGNALED(status);
  o.signal_number = o.signalled ? WTERMSIG(status) : 0;
  return o;
}

int main(void) {
  /* second_ends, two signals while held: the held write finishes ('H'), and the second
   * signal ends the process at the release (before 'R'), by SIGINT as a shell expects */
  outcome o = run_child(true, true, 2);
  printf("second_ends, held, 2 signals: said '%s', exit %d, signal %d\n", o.said, o.code,
         o.signal_number);
  CHECK(strcmp(o.said, "H") == 0, "said '%s'", o.said);
  CHECK(o.signalled && o.signal_number == SIGINT, "exit %d, signal %d", o.code, o.signal_number);

  /* second_ends, not held: the second signal ends the process at once (no 'H') */
  o = run_child(true, false, 2);
  printf("second_ends, not held, 2 signals: said '%s', signal %d\n", o.said, o.signal_number);
  CHECK(o.said[0] == 0, "said '%s'", o.said);
  CHECK(o.signalled && o.signal_number == SIGINT, "exit %d, signal %d", o.code, o.signal_number);

  /* one signal while held only sets the flag: the work goes on to the end */
  o = run_child(true, true, 1);
  printf("second_ends, held, 1 signal: said '%s', exit %d\n", o.said, o.code);
  CHECK(strcmp(o.said, "HR") == 0, "said '%s'", o.said);
  CHECK(o.exited && o.code == 0, "exit %d, signal %d", o.code, o.signal_number);

  /* without second_ends, signals only set the flag, held or not */
  o = run_child(false, true, 2);
  printf("flag only, held, 2 signals: said '%s', exit %d\n", o.said, o.code);
  CHECK(strcmp(o.said, "HR") == 0, "said '%s'", o.said);
  CHECK(o.exited && o.code == 0, "exit %d, signal %d", o.code, o.signal_number);
  o = run_child(false, false, 2);
  CHECK(strcmp(o.said, "HR") == 0, "said '%s'", o.said);
  CHECK(o.exited && o.code == 0, "exit %d, signal %d", o.code, o.signal_number);
  return test_finish("test_stop_signals");
}
