/* Ghost coefficients per level: which linear combination of stored coefficients the
 * boundary extension puts just outside each end of a level.
 *
 * The fogmap (level J) uses the textbook extension: whole-sample symmetric for the
 * odd-length CDF 5/3 filters (x[-1] = x[1], x[n] = x[n-2]; samples sit at the
 * symmetry centres), half-sample symmetric for the even-length Haar and bior3.3
 * (x[-1] = x[0], x[n] = x[n-1]: mirrored about the fog box edge), or periodic.
 *
 * A coarser level's ghosts are then *derived*, not chosen: they are the values that
 * make the coarse B-spline sum equal the fine one on the fog box when the details are
 * zero. With the two-scale sequence p_k (Giroud & Biri eq. 6) the fine coefficients
 * of the coarse function are x_k = sum_j p_{k-2j} c_j, so requiring the fine ghosts
 * x_{-1}, x_n (the only ones whose support reaches into the box) to follow the fine
 * rule gives two linear equations for the coarse ghosts c_{-1}, c_m. For CDF 5/3 the
 * result stays whole-sample symmetric on the left and becomes half-sample symmetric on
 * the right after an even length; for bior3.3 an odd length turns the right end
 * whole-sample and the next even length gives c_m = (c_{m-2} + 2 c_{m-1})/3. Deriving
 * them keeps every level exact for any size, odd sizes included. */
#include <math.h>

#include "transform/lifting.h"

static ghost_rule rule_one(int index) {
  return (ghost_rule){.count = 1, .index = {index}, .weight = {1.0}};
}

static void rule_add(ghost_rule *r, int index, double weight) {
  for (int t = 0; t < r->count; t++)
    if (r->index[t] == index) {
      r->weight[t] += weight;
      return;
    }
  if (r->count < 4) {
    r->index[r->count] = index;
    r->weight[r->count] = weight;
    r->count++;
  }
}

static void rule_axpy(ghost_rule *r, double scale, const ghost_rule *x) {
  for (int t = 0; t < x->count; t++) rule_add(r, x->index[t], scale * x->weight[t]);
}

static void rule_clean(ghost_rule *r) {
  int k = 0;
  for (int t = 0; t < r->count; t++)
    if (fabs(r->weight[t]) > 1e-14) {
      r->index[k] = r->index[t];
      r->weight[k] = r->weight[t];
      k++;
    }
  r->count = k;
}

level_rules ghost_rules_finest(transform_basis basis, transform_boundary boundary, int n) {
  if (boundary == TRANSFORM_PERIODIC) return (level_rules){rule_one(n - 1), rule_one(0)};
  if (basis == TRANSFORM_LINEAR && n >= 2)
    return (level_rules){rule_one(1), rule_one(n - 2)};
  return (level_rules){rule_one(0), rule_one(n - 1)};
}

/* Fine coefficient k of the coarse function, as a*c[-1] + b*c[m] + v(c): the synthesis
 * low-pass p_k (linear: 1/2,1,1/2; quadratic: 1/4,3/4,3/4,1/4). */
typedef struct fine_functional {
  double a, b;
  ghost_rule v;
} fine_functional;

static fine_functional fine_at(transform_basis basis, int k, int m) {
  int idx[2];
  double w[2];
  int taps;
  int even = (k % 2 == 0);
  int half = (k >= 0) ? k / 2 : -((-k + 1) / 2); /* floor(k/2) */
  if (basis == TRANSFORM_LINEAR) {
    if (even) {
      taps = 1, idx[0] = half, w[0] = 1.0;
    } else {
      taps = 2, idx[0] = half, w[0] = 0.5, idx[1] = half + 1, w[1] = 0.5;
    }
  } else { /* quadratic: x_2j = (c_{j-1} + 3c_j)/4, x_{2j+1} = (3c_j + c_{j+1})/4 */
    taps = 2;
    if (even) {
      idx[0] = half - 1, w[0] = 0.25, idx[1] = half, w[1] = 0.75;
    } else {
      idx[0] = half, w[0] = 0.75, idx[1] = half + 1, w[1] = 0.25;
    }
  }
  fine_functional f = {0};
  for (int t = 0; t < taps; t++) {
    if (idx[t] == -1)
      f.a += w[t];
    else if (idx[t] == m)
      f.b += w[t];
    else
      rule_add(&f.v, idx[t], w[t]);
  }
  return f;
}

int ghost_rules_coarsen(transform_basis basis, transform_boundary boundary, int n,
                        const level_rules *fine, level_rules *coarse) {
  int m = (n + 1) / 2;
  if (boundary == TRANSFORM_PERIODIC || basis == TRANSFORM_HAAR) {
    /* Periodic stays periodic; Haar (degree 0) needs no ghosts inside the box. */
    *coarse = ghost_rules_finest(basis, boundary, m);
    return 0;
  }
  /* Equation for each end: x_ghost - rule(x_stored) = 0, written as
   * A_1 c[-1] + A_2 c[m] = rhs(c). */
  double A[2][2];
  ghost_rule rhs[2];
  for (int end = 0; end < 2; end++) {
    const ghost_rule *r = end == 0 ? &fine->left : &fine->right;
    fine_functional g = fine_at(basis, end == 0 ? -1 : n, m);
    A[end][0] = g.a;
    A[end][1] = g.b;
    rhs[end] = (ghost_rule){0};
    rule_axpy(&rhs[end], -1.0, &g.v);
    for (int t = 0; t < r->count; t++) {
      fine_functional s = fine_at(basis, r->index[t], m);
      A[end][0] -= r->weight[t] * s.a;
      A[end][1] -= r->weight[t] * s.b;
      rule_axpy(&rhs[end], r->weight[t], &s.v);
    }
  }
  double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
  if (fabs(det) < 1e-12) return 1;
  coarse->left = (ghost_rule){0};
  coarse->right = (ghost_rule){0};
  rule_axpy(&coarse->left, A[1][1] / det, &rhs[0]);
  rule_axpy(&coarse->left, -A[0][1] / det, &rhs[1]);
  rule_axpy(&coarse->right, A[0][0] / det, &rhs[1]);
  rule_axpy(&coarse->right, -A[1][0] / det, &rhs[0]);
  rule_clean(&coarse->left);
  rule_clean(&coarse->right);
  return 0;
}
