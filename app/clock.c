/* The clocks (see clock.h). */
#define _POSIX_C_SOURCE 200809L
#include "app/clock.h"

#include <time.h>

static double seconds_of(clockid_t id) {
  struct timespec ts;
  clock_gettime(id, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double app_clock_seconds(void) { return seconds_of(CLOCK_MONOTONIC); }

double app_thread_cpu_seconds(void) { return seconds_of(CLOCK_THREAD_CPUTIME_ID); }
