/* Private to the transform library: the plan's contents and the 2D passes. */
#ifndef FOGPIPE_TRANSFORM_PLAN_H
#define FOGPIPE_TRANSFORM_PLAN_H

#include <pthread.h>
#include <stdio.h>

#include "transform/lifting.h"

/* Columns are lifted in strips this many floats wide: a strip of a 1024-row level is
 * 128 KiB, so the lifting steps after the gather run in L2, and every inner loop runs
 * across the strip (contiguous, vectorised). */
#define TRANSFORM_STRIP 32

typedef struct transform_scratch {
  float *row;    /* one row's even and odd channels */
  float *strip;  /* one strip of columns, even then odd channel */
  float *ghost;  /* 2 * TRANSFORM_STRIP */
  float *ring;   /* the fused level's ring of rows (thread 0 only) */
  float *ring_ghost;
  float *level;  /* a level-sized output buffer for fused levels below J */
  float *level2; /* a second one (the inverse alternates between them) */
} transform_scratch;

/* One pass over rows or strips of columns, split between the threads. */
typedef struct transform_job {
  int columns, forward, top, bottom;
  const float *src;
  float *dst;
  size_t stride;
  int begin, end;
} transform_job;

struct transform_plan {
  transform_desc desc;
  int levels, threads;
  int *len_w, *len_h;             /* [0..J] */
  level_rules *rules_w, *rules_h; /* [0..J] */
  transform_scratch scratch[2];
  /* the second thread (desc.threads == 2) */
  pthread_t worker;
  pthread_mutex_t lock;
  pthread_cond_t wake, done;
  int worker_started, quit, pending;
  transform_job job;
};

void transform_rows(const transform_plan *p, int thread, int forward, int top, int bottom,
                    const float *src, float *dst, size_t stride, int r0, int r1);
void transform_columns(const transform_plan *p, int thread, int forward, int top,
                       int bottom, float *base, size_t stride, int c0, int c1);
/* Runs a job on [begin, end), halved between two threads when the plan has two. */
void transform_run_job(transform_plan *p, const transform_job *job);
int transform_workers_start(transform_plan *p);
void transform_workers_stop(transform_plan *p);

const char *transform_basis_name(transform_basis basis);

/* The single-pass forward level (transform_fused.c): symmetric, non-standard, >= 8 rows. */
int transform_fused_supported(const transform_plan *p, int l);
void transform_fused_forward_level(const transform_plan *p, int l, const float *src,
                                   size_t src_stride, float *dst, size_t dst_stride);
/* The single-pass inverse level (Haar, CDF 5/3): A_{l-1} from `low` (NULL: zero), the
 * bands from `coef` (Mallat layout), the w_l x h_l level to dst (not aliasing either). */
int transform_fused_inverse_supported(const transform_plan *p, int l);
void transform_fused_inverse_level(const transform_plan *p, int l, const float *low,
                                   size_t low_stride, const float *coef, size_t coef_stride,
                                   float *dst, size_t dst_stride);

#endif
