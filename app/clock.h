/* The clocks the commands, the pipeline and the benchmarks time with (one definition). */
#ifndef FOGPIPE_APP_CLOCK_H
#define FOGPIPE_APP_CLOCK_H

/* Monotonic wall-clock time, seconds from an arbitrary start. */
double app_clock_seconds(void);

/* CPU time of the calling thread, seconds: what a piece of work costs, whether or not the
 * thread also waited for a core. */
double app_thread_cpu_seconds(void);

/* The median of n timings (n >= 1; for an even n the mean of the middle two), sorting
 * values in place: one definition for the pipeline, fit and the benchmarks. */
double app_median(double *values, int n);

#endif
