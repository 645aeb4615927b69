/* The clocks (see clock.h). */
#define _POSIX_C_SOURCE 200809L
#include "app/clock.h"

#include <stdlib.h>
#include <time.h>

static double seconds_of(clockid_t id) {
  struct timespec ts;
  clock_gettime(id, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double app_clock_seconds(void) { return seconds_of(CLOCK_MONOTONIC); }

double app_thread_cpu_seconds(void) { return seconds_of(CLOCK_THREAD_CPUTIME_ID); }

static int compare_doubles(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

double app_median(double *values, int n) {
  qsort(values, (size_t)n, sizeof *values, compare_doubles);
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}
