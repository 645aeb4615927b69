/* The optional second thread: one persistent worker made at plan creation, handed each
 * pass, so that a run never creates threads or allocates. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, sched_yield */

#include <sched.h>
#include <time.h>

#include "transform/transform_plan.h"

static void run_part(const transform_plan *p, int thread, const transform_job *j, int b,
                     int e) {
  if (b >= e) return;
  switch (j->kind) {
    case TRANSFORM_JOB_ROWS:
      transform_rows(p, thread, j->forward, j->top, j->bottom, j->src, j->dst, j->stride, b, e);
      break;
    case TRANSFORM_JOB_COLUMNS:
      transform_columns(p, thread, j->forward, j->top, j->bottom, j->dst, j->stride, b, e);
      break;
    case TRANSFORM_JOB_FUSED_FORWARD:
      transform_fused_forward_level(p, thread, j->level, j->src, j->src_stride, j->dst,
                                    j->stride, b, e);
      break;
    case TRANSFORM_JOB_FUSED_INVERSE:
      transform_fused_inverse_level(p, thread, j->level, j->low, j->low_stride, j->src,
                                    j->src_stride, j->dst, j->stride, b, e);
      break;
    case TRANSFORM_JOB_COPY_BACK: { /* low rows [b, e), high rows m + [b, e) below n */
      int n = p->len_h[j->level], m = (n + 1) / 2, w = p->len_w[j->level];
      int high_end = m + e < n ? m + e : n;
      transform_copy_block(j->dst + (size_t)b * j->stride, j->stride,
                           j->src + (size_t)b * j->src_stride, j->src_stride, w, e - b);
      if (m + b < high_end)
        transform_copy_block(j->dst + (size_t)(m + b) * j->stride, j->stride,
                             j->src + (size_t)(m + b) * j->src_stride, j->src_stride, w,
                             high_end - m - b);
      break;
    }
  }
}

static int split_point(const transform_job *j) {
  int mid = j->begin + (j->end - j->begin) / 2;
  if (j->kind == TRANSFORM_JOB_COLUMNS) /* keep strips whole */
    mid = j->begin + ((mid - j->begin + TRANSFORM_STRIP - 1) / TRANSFORM_STRIP) * TRANSFORM_STRIP;
  return mid < j->end ? mid : j->end;
}

/* Spins until *word differs from `from` or about SPIN_NS have passed; the value seen.
 * Passes follow each other within microseconds, and waking a thread that sleeps on a
 * condition variable costs far more than that on a virtual machine (the bench measured
 * 1024^2 3-level forwards of 1.3 ms with two threads against 0.28 ms with one). After
 * the first microseconds it yields the core at each turn, in case the other thread
 * waits for this very core. */
#define SPIN_NS 50000
static unsigned spin_while(atomic_uint *word, unsigned from, atomic_int *quit) {
  struct timespec t0, t;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  for (int i = 1;; i++) {
    unsigned v = atomic_load_explicit(word, memory_order_acquire);
    if (v != from || (quit && atomic_load_explicit(quit, memory_order_relaxed))) return v;
    if (i > 256) {
      sched_yield();
    } else {
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    }
    if (i % 64 == 0 || i > 256) {
      clock_gettime(CLOCK_MONOTONIC, &t);
      if ((t.tv_sec - t0.tv_sec) * 1000000000L + (t.tv_nsec - t0.tv_nsec) > SPIN_NS) return v;
    }
  }
}

static void *worker_main(void *arg) {
  transform_plan *p = arg;
  unsigned seen = 0;
  for (;;) {
    unsigned job = spin_while(&p->posted, seen, &p->quit);
    if (job == seen) {
      pthread_mutex_lock(&p->lock);
      p->worker_sleeps = 1;
      while ((job = atomic_load(&p->posted)) == seen && !atomic_load(&p->quit))
        pthread_cond_wait(&p->wake, &p->lock);
      p->worker_sleeps = 0;
      pthread_mutex_unlock(&p->lock);
    }
    if (atomic_load(&p->quit)) break;
    seen = job;
    transform_job j = p->job;
    run_part(p, 1, &j, split_point(&j), j.end);
    atomic_store_explicit(&p->finished, job, memory_order_release);
    pthread_mutex_lock(&p->lock);
    if (p->caller_sleeps) pthread_cond_signal(&p->done);
    pthread_mutex_unlock(&p->lock);
  }
  return NULL;
}

void transform_run_job(transform_plan *p, const transform_job *j) {
  /* small passes are not worth a wake-up */
  if (p->threads < 2 || j->samples < TRANSFORM_SPLIT_SAMPLES) {
    run_part(p, 0, j, j->begin, j->end);
    return;
  }
  p->job = *j;
  unsigned job = atomic_load(&p->posted) + 1;
  atomic_store_explicit(&p->posted, job, memory_order_release);
  pthread_mutex_lock(&p->lock);
  if (p->worker_sleeps) pthread_cond_signal(&p->wake);
  pthread_mutex_unlock(&p->lock);
  run_part(p, 0, j, j->begin, split_point(j));
  if (spin_while(&p->finished, job - 1, NULL) == job) return;
  pthread_mutex_lock(&p->lock);
  p->caller_sleeps = 1;
  while (atomic_load(&p->finished) != job) pthread_cond_wait(&p->done, &p->lock);
  p->caller_sleeps = 0;
  pthread_mutex_unlock(&p->lock);
}

int transform_workers_start(transform_plan *p) {
  pthread_mutex_init(&p->lock, NULL);
  pthread_cond_init(&p->wake, NULL);
  pthread_cond_init(&p->done, NULL);
  atomic_init(&p->posted, 0);
  atomic_init(&p->finished, 0);
  atomic_init(&p->quit, 0);
  if (pthread_create(&p->worker, NULL, worker_main, p)) return 1;
  p->worker_started = 1;
  return 0;
}

void transform_workers_stop(transform_plan *p) {
  if (!p->worker_started) return;
  pthread_mutex_lock(&p->lock);
  atomic_store(&p->quit, 1);
  pthread_cond_signal(&p->wake);
  pthread_mutex_unlock(&p->lock);
  pthread_join(p->worker, NULL);
  pthread_mutex_destroy(&p->lock);
  pthread_cond_destroy(&p->wake);
  pthread_cond_destroy(&p->done);
  p->worker_started = 0;
}
