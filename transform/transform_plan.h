/* Private to the transform library: the plan's contents and the 2D passes. */
#ifndef FOGPIPE_TRANSFORM_PLAN_H
#define FOGPIPE_TRANSFORM_PLAN_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>

#include "transform/lifting.h"

/* Columns are lifted in strips this many floats wide: a strip of a 1024-row level is
 * 128 KiB, so the lifting steps after the gather run in L2, and every inner loop runs
 * across the strip (contiguous, vectorised). */
#define TRANSFORM_STRIP 32

/* Passes smaller than this many samples run on one thread: waking the worker costs
 * more than half of such a pass. */
#define TRANSFORM_SPLIT_SAMPLES 16384

typedef struct transform_scratch {
  float *row;    /* one row's even and odd channels */
  float *strip;  /* one strip of columns, even then odd channel */
  float *ghost;  /* 2 * TRANSFORM_STRIP */
  float *ring;   /* the fused level's ring of rows */
  float *ring_ghost;
  float *level;  /* a level-sized output buffer for fused levels below J */
  float *level2; /* a second one (the inverse alternates between them) */
} transform_scratch;

/* One pass, split between the threads: over rows [begin, end), strips of columns, or
 * the coarse rows k in [begin, end) of a single-pass level (forward: low row k and
 * high row m+k; inverse: fine rows 2k and 2k+1). */
typedef enum transform_job_kind {
  TRANSFORM_JOB_ROWS,
  TRANSFORM_JOB_COLUMNS,
  TRANSFORM_JOB_FUSED_FORWARD,
  TRANSFORM_JOB_FUSED_INVERSE,
  TRANSFORM_JOB_COPY_BACK /* a forward level's rows k and m+k, src -> dst */
} transform_job_kind;

typedef struct transform_job {
  transform_job_kind kind;
  int forward, top, bottom; /* rows, columns */
  const float *src;
  float *dst;
  size_t stride;
  int level;                /* fused: l */
  const float *low;         /* fused inverse: A_{l-1} (NULL: zero) */
  size_t src_stride, low_stride;
  int begin, end;
  size_t samples;           /* the whole pass's size, to decide whether to split it */
} transform_job;

struct transform_plan {
  transform_desc desc;
  int levels, threads;
  int *len_w, *len_h;             /* [0..J] */
  level_rules *rules_w, *rules_h; /* [0..J] */
  transform_scratch scratch[2];
  float *zero_band; /* width x height zeros (transform_density_pyramid), NULL until needed */
  /* the second thread (desc.threads == 2): job number `posted` is the worker's to run
   * once it differs from what it last ran; `finished` is the last one it completed.
   * Either side spins a few tens of microseconds before sleeping on a condition
   * variable; *_sleeps (under lock) says who needs a signal. */
  pthread_t worker;
  pthread_mutex_t lock;
  pthread_cond_t wake, done;
  int worker_started, worker_sleeps, caller_sleeps;
  atomic_int quit;
  atomic_uint posted, finished;
  transform_job job;
};

void transform_rows(const transform_plan *p, int thread, int forward, int top, int bottom,
                    const float *src, float *dst, size_t stride, int r0, int r1);
void transform_columns(const transform_plan *p, int thread, int forward, int top,
                       int bottom, float *base, size_t stride, int c0, int c1);
/* h rows of w floats from src to dst (transform.c). */
void transform_copy_block(float *dst, size_t dst_stride, const float *src,
                          size_t src_stride, int w, int h);
/* Runs a job on [begin, end), halved between two threads when the plan has two. */
void transform_run_job(transform_plan *p, const transform_job *job);
int transform_workers_start(transform_plan *p);
void transform_workers_stop(transform_plan *p);

const char *transform_basis_name(transform_basis basis);

/* The single-pass forward level (transform_fused.c): symmetric, non-standard, >= 8 rows,
 * not disabled by desc.two_pass. Output rows k in [k0, k1) of each half (k < (h_l+1)/2):
 * a thread given a range starting past 0 re-lifts the few input rows before it, so the
 * ranges are independent and the result has the same bits however it is split. */
int transform_fused_supported(const transform_plan *p, int l);
void transform_fused_forward_level(const transform_plan *p, int thread, int l,
                                   const float *src, size_t src_stride, float *dst,
                                   size_t dst_stride, int k0, int k1);
/* The single-pass inverse level (Haar, CDF 5/3): A_{l-1} from `low` (NULL: zero), the
 * bands from `coef` (Mallat layout), the w_l x h_l level to dst (not aliasing either);
 * fine rows 2k and 2k+1 for k in [k0, k1). */
int transform_fused_inverse_supported(const transform_plan *p, int l);
void transform_fused_inverse_level(const transform_plan *p, int thread, int l,
                                   const float *low, size_t low_stride, const float *coef,
                                   size_t coef_stride, float *dst, size_t dst_stride, int k0,
                                   int k1);

#endif
