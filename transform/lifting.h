/* Private to the transform library (not installed, not included by other folders):
 * boundary rules per level and the 1D lifting kernels on planar buffers. */
#ifndef FOGPIPE_TRANSFORM_LIFTING_H
#define FOGPIPE_TRANSFORM_LIFTING_H

#include "transform/transform.h"

/* A ghost coefficient as a linear functional of a level's stored coefficients:
 * ghost = sum weight[t] * c[index[t]]. At most 4 terms (first two and last two). */
typedef struct ghost_rule {
  int count;
  int index[4];
  double weight[4];
} ghost_rule;

/* The ghosts of one 1D level of length n: c[-1] = left(c), c[n] = right(c). */
typedef struct level_rules {
  ghost_rule left, right;
} level_rules;

/* Rules of the level J signal (the fogmap) for a basis and mode. */
level_rules ghost_rules_finest(transform_basis basis, transform_boundary boundary, int n);
/* Rules of the coarse level made from a fine level of length n with rules `fine`, such
 * that the coarse B-spline sum (ghosts included) equals the fine one (ghosts included)
 * on the fog box when the details are zero (the two-scale relation, Giroud & Biri eq. 6).
 * Returns non-zero if the 2x2 system is singular (never for the three bases). */
int ghost_rules_coarsen(transform_basis basis, transform_boundary boundary, int n,
                        const level_rules *fine, level_rules *coarse);

/* One split (analysis) or merge (synthesis) step of a 1D signal of length n = m + d
 * (m = ceil(n/2) even samples, d = floor(n/2) odd samples), stored planar with `lanes`
 * independent signals interleaved: e[k*lanes + i], o[k*lanes + i]. The kernels work on
 * the lifting channels (before scaling); `ghost` is scratch of 2*lanes floats. */
typedef struct lifting_step {
  transform_basis basis;
  int periodic;
  int n;
  const level_rules *fine;    /* rules of the length-n level (quadratic step 1) */
  const level_rules *coarse;  /* rules of the length-m level (predict at the right end) */
} lifting_step;

void lifting_forward(const lifting_step *step, float *restrict e, float *restrict o,
                     int lanes, float *restrict ghost);
void lifting_inverse(const lifting_step *step, float *restrict e, float *restrict o,
                     int lanes, float *restrict ghost);

/* Output scaling: c = lifting_scale_low * e, d = lifting_scale_high * o. */
float lifting_scale_low(transform_basis basis);
float lifting_scale_high(transform_basis basis);

#endif
