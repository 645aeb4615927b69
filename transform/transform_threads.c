/* The optional second thread: one persistent worker made at plan creation, woken for
 * each pass, so that a run never creates threads or allocates. */
#include "transform/transform_plan.h"

static void run_part(const transform_plan *p, int thread, const transform_job *j, int b,
                     int e) {
  if (b >= e) return;
  if (j->columns)
    transform_columns(p, thread, j->forward, j->top, j->bottom, j->dst, j->stride, b, e);
  else
    transform_rows(p, thread, j->forward, j->top, j->bottom, j->src, j->dst, j->stride, b, e);
}

static int split_point(const transform_job *j) {
  int mid = j->begin + (j->end - j->begin) / 2;
  if (j->columns) /* keep strips whole */
    mid = j->begin + ((mid - j->begin + TRANSFORM_STRIP - 1) / TRANSFORM_STRIP) * TRANSFORM_STRIP;
  return mid < j->end ? mid : j->end;
}

static void *worker_main(void *arg) {
  transform_plan *p = arg;
  pthread_mutex_lock(&p->lock);
  for (;;) {
    while (!p->pending && !p->quit) pthread_cond_wait(&p->wake, &p->lock);
    if (p->quit) break;
    transform_job j = p->job;
    pthread_mutex_unlock(&p->lock);
    run_part(p, 1, &j, split_point(&j), j.end);
    pthread_mutex_lock(&p->lock);
    p->pending = 0;
    pthread_cond_signal(&p->done);
  }
  pthread_mutex_unlock(&p->lock);
  return NULL;
}

void transform_run_job(transform_plan *p, const transform_job *j) {
  /* small passes are not worth a wake-up */
  if (p->threads < 2 || (size_t)(j->end - j->begin) * (size_t)p->len_w[p->levels] < 16384) {
    run_part(p, 0, j, j->begin, j->end);
    return;
  }
  pthread_mutex_lock(&p->lock);
  p->job = *j;
  p->pending = 1;
  pthread_cond_signal(&p->wake);
  pthread_mutex_unlock(&p->lock);
  run_part(p, 0, j, j->begin, split_point(j));
  pthread_mutex_lock(&p->lock);
  while (p->pending) pthread_cond_wait(&p->done, &p->lock);
  pthread_mutex_unlock(&p->lock);
}

int transform_workers_start(transform_plan *p) {
  pthread_mutex_init(&p->lock, NULL);
  pthread_cond_init(&p->wake, NULL);
  pthread_cond_init(&p->done, NULL);
  if (pthread_create(&p->worker, NULL, worker_main, p)) return 1;
  p->worker_started = 1;
  return 0;
}

void transform_workers_stop(transform_plan *p) {
  if (!p->worker_started) return;
  pthread_mutex_lock(&p->lock);
  p->quit = 1;
  pthread_cond_signal(&p->wake);
  pthread_mutex_unlock(&p->lock);
  pthread_join(p->worker, NULL);
  pthread_mutex_destroy(&p->lock);
  pthread_cond_destroy(&p->wake);
  pthread_cond_destroy(&p->done);
  p->worker_started = 0;
}
