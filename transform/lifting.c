/* The 1D lifting kernels (Sweldens' lifting scheme, Daubechies & Sweldens 1998) for
 * the three B-spline bases, UNNORMALISED so that approximations are density-like.
 * The signal is split into even samples e and odd samples o (planar, `lanes` signals
 * side by side so that the same flat loops serve a row (lanes = 1: vectorised along
 * the row) and a strip of columns (lanes = strip width: vectorised across columns)).
 *
 * Forward steps (inverse: the same steps in reverse order with the opposite sign):
 *   Haar:      o -= e;                    e += o/2;               c = e,    d = -o/2
 *   CDF 5/3:   o[k] -= (e[k]+e[k+1])/2;   e[k] += (o[k-1]+o[k])/4; c = e,   d = -o/2
 *   bior3.3:   e[k] -= o[k-1]/3;          o[k] -= (9e[k]+3e[k+1])/8;
 *              e[k] += (3o[k-1] + 16o[k] - 3o[k+1])/36;           c = 3e/2, d = o/3
 * With the details zero the inverse gives the synthesis low-pass p_k (the B-spline
 * two-scale sequence, Giroud & Biri eq. 6): Haar x_2k = x_2k+1 = c_k; CDF 5/3
 * x_2k = c_k, x_2k+1 = (c_k + c_k+1)/2; bior3.3 x_2k = (c_k-1 + 3c_k)/4,
 * x_2k+1 = (3c_k + c_k+1)/4. In two-scale form (Giroud & Biri eq. 6 and 8), a coarse
 * coefficient c_n and a detail d_n contribute p_{k-2n} c_n + q_{k-2n} d_n to fine
 * coefficient k (fine units; k = 0 is the fine sample paired with coarse n = 0):
 *   Haar     p_0..1  = 1, 1                    q_0..1  = 1, -1
 *   CDF 5/3  p_-1..1 = 1/2, 1, 1/2             q_-1..3 = 1/4, 1/2, -3/2, 1/2, 1/4
 *   bior3.3  p_-1..2 = 1/4, 3/4, 3/4, 1/4      q_-3..4 = 3/32, 9/32, -7/32, -45/32,
 *                                                        45/32, 7/32, -9/32, -3/32
 * so phi_d(x/2) = sum_k p_k phi_d(x - k) (with the level's origin shift: the B-spline
 * two-scale relation) and psi(x/2) = sum_k q_k phi_d(x - k).
 * The detail scalings make PyWavelets' coefficients
 * exactly sqrt(2) times ours in every band (tests/transform/pywt_compare.py).
 *
 * Boundaries: a step that needs a sample outside the signal uses a ghost. Any rule
 * keeps the lifting invertible; the rules below make the inverse with zero details
 * equal the two-scale synthesis of the ghost-extended coarse level (ghost_rules.c),
 * which is what makes every exported grid exact on the fog box. */
#include <string.h>

#include "transform/lifting.h"

float lifting_scale_low(transform_basis basis) {
  return basis == TRANSFORM_QUADRATIC ? 1.5f : 1.0f;
}

float lifting_scale_high(transform_basis basis) {
  return basis == TRANSFORM_QUADRATIC ? (float)(1.0 / 3.0) : -0.5f;
}

/* out = rule applied to a channel holding coefficients of one level. */
static void ghost_from(const ghost_rule *r, const float *restrict c, int lanes,
                       float *restrict out) {
  for (int i = 0; i < lanes; i++) out[i] = 0.0f;
  for (int t = 0; t < r->count; t++) {
    const float *src = c + (size_t)r->index[t] * lanes;
    float w = (float)r->weight[t];
    for (int i = 0; i < lanes; i++) out[i] += w * src[i];
  }
}

/* The even-channel ghost e[m] at the right end: periodic wraps, symmetric applies the
 * coarse level's right rule (the even channel equals the coarse level up to scale). */
static const float *even_ghost_right(const lifting_step *s, const float *e, int lanes,
                                     float *ghost) {
  if (s->periodic) return e;
  ghost_from(&s->coarse->right, e, lanes, ghost);
  return ghost;
}

/* ---- Haar ---- */
static void haar_forward(const lifting_step *s, float *restrict e, float *restrict o,
                         int lanes) {
  size_t nd = (size_t)(s->n / 2) * lanes;
  for (size_t j = 0; j < nd; j++) o[j] -= e[j];
  for (size_t j = 0; j < nd; j++) e[j] += 0.5f * o[j];
  /* odd n: the last even sample pairs with its half-sample mirror; its detail is 0 */
}

static void haar_inverse(const lifting_step *s, float *restrict e, float *restrict o,
                         int lanes) {
  size_t nd = (size_t)(s->n / 2) * lanes;
  for (size_t j = 0; j < nd; j++) e[j] -= 0.5f * o[j];
  for (size_t j = 0; j < nd; j++) o[j] += e[j];
}

/* ---- CDF 5/3 ---- */
static void linear_predict(const lifting_step *s, float *restrict e, float *restrict o,
                           int lanes, float *restrict ghost, float sign) {
  int m = (s->n + 1) / 2, d = s->n / 2;
  int inner = d < m - 1 ? d : m - 1;
  float w = 0.5f * sign;
  size_t ni = (size_t)inner * lanes;
  for (size_t j = 0; j < ni; j++) o[j] -= w * (e[j] + e[j + lanes]);
  if (d == m) {
    const float *g = even_ghost_right(s, e, lanes, ghost);
    float *ol = o + (size_t)(d - 1) * lanes;
    const float *el = e + (size_t)(d - 1) * lanes;
    for (int i = 0; i < lanes; i++) ol[i] -= w * (el[i] + g[i]);
  }
}

static void linear_update(const lifting_step *s, float *restrict e, const float *restrict o,
                          int lanes, float sign) {
  int m = (s->n + 1) / 2, d = s->n / 2;
  float w = 0.25f * sign;
  /* k = 0: o[-1] is o[0] (whole-sample mirror) or o[d-1] (periodic) */
  const float *left = s->periodic ? o + (size_t)(d - 1) * lanes : o;
  for (int i = 0; i < lanes; i++) e[i] += w * (left[i] + o[i]);
  int inner = m < d ? m : d;
  for (size_t j = (size_t)lanes; j < (size_t)inner * lanes; j++) e[j] += w * (o[j - lanes] + o[j]);
  if (m > d) { /* odd n: o[m-1] mirrors to o[m-2] */
    float *el = e + (size_t)(m - 1) * lanes;
    const float *ol = o + (size_t)(m - 2) * lanes;
    for (int i = 0; i < lanes; i++) el[i] += w * 2.0f * ol[i];
  }
}

/* ---- bior3.3 ---- */
/* Value of fine sample k (k in [0, n)) of the current channels. */
static const float *fine_sample(const float *e, const float *o, int k, int lanes) {
  return (k % 2 == 0) ? e + (size_t)(k / 2) * lanes : o + (size_t)(k / 2) * lanes;
}

static void quadratic_step1_forward(const lifting_step *s, float *restrict e,
                                    const float *restrict o, int lanes,
                                    float *restrict ghost) {
  int m = (s->n + 1) / 2, d = s->n / 2;
  const float third = (float)(1.0 / 3.0);
  /* the ghost x[-1] from the untouched samples, before e changes */
  if (s->periodic) {
    memcpy(ghost, o + (size_t)(d - 1) * lanes, sizeof(float) * (size_t)lanes);
  } else {
    for (int i = 0; i < lanes; i++) ghost[i] = 0.0f;
    const ghost_rule *r = &s->fine->left;
    for (int t = 0; t < r->count; t++) {
      const float *src = fine_sample(e, o, r->index[t], lanes);
      float w = (float)r->weight[t];
      for (int i = 0; i < lanes; i++) ghost[i] += w * src[i];
    }
  }
  for (size_t j = (size_t)lanes; j < (size_t)m * lanes; j++) e[j] -= third * o[j - lanes];
  for (int i = 0; i < lanes; i++) e[i] -= third * ghost[i];
}

static void quadratic_step1_inverse(const lifting_step *s, float *restrict e,
                                    const float *restrict o, int lanes,
                                    float *restrict ghost) {
  int m = (s->n + 1) / 2, d = s->n / 2;
  const float third = (float)(1.0 / 3.0);
  for (size_t j = (size_t)lanes; j < (size_t)m * lanes; j++) e[j] += third * o[j - lanes];
  if (s->periodic) {
    const float *ol = o + (size_t)(d - 1) * lanes;
    for (int i = 0; i < lanes; i++) e[i] += third * ol[i];
    return;
  }
  /* e0' = x0 - (w0 x0 + rest)/3  =>  x0 = (e0' + rest/3) / (1 - w0/3) */
  const ghost_rule *r = &s->fine->left;
  double w0 = 0.0;
  for (int i = 0; i < lanes; i++) ghost[i] = 0.0f;
  for (int t = 0; t < r->count; t++) {
    if (r->index[t] == 0) {
      w0 += r->weight[t];
      continue;
    }
    const float *src = fine_sample(e, o, r->index[t], lanes);
    float w = (float)r->weight[t];
    for (int i = 0; i < lanes; i++) ghost[i] += w * src[i];
  }
  float inv = (float)(1.0 / (1.0 - w0 / 3.0));
  for (int i = 0; i < lanes; i++) e[i] = (e[i] + third * ghost[i]) * inv;
}

static void quadratic_step2(const lifting_step *s, const float *restrict e, float *restrict o,
                            int lanes, float *restrict ghost, float sign) {
  int m = (s->n + 1) / 2, d = s->n / 2;
  int inner = d < m - 1 ? d : m - 1;
  float a = 1.125f * sign, b = 0.375f * sign;
  for (size_t j = 0; j < (size_t)inner * lanes; j++) o[j] -= a * e[j] + b * e[j + lanes];
  if (d == m) {
    const float *g = even_ghost_right(s, e, lanes, ghost);
    float *ol = o + (size_t)(d - 1) * lanes;
    const float *el = e + (size_t)(d - 1) * lanes;
    for (int i = 0; i < lanes; i++) ol[i] -= a * el[i] + b * g[i];
  }
}

/* o[k] for the third step: outside the signal it is 0 (symmetric) or wraps. */
static const float *odd_at(const lifting_step *s, const float *o, int k, int lanes,
                           const float *zeros) {
  int d = s->n / 2;
  if (k >= 0 && k < d) return o + (size_t)k * lanes;
  if (s->periodic) return o + (size_t)((k % d + d) % d) * lanes;
  return zeros;
}

static void quadratic_step3(const lifting_step *s, float *restrict e, const float *restrict o,
                            int lanes, float *restrict ghost, float sign) {
  int m = (s->n + 1) / 2, d = s->n / 2;
  float a = (float)(3.0 / 36.0) * sign, b = (float)(16.0 / 36.0) * sign;
  float *zeros = ghost + lanes;
  for (int i = 0; i < lanes; i++) zeros[i] = 0.0f;
  int end = m < d - 1 ? m : d - 1; /* interior: o[k-1], o[k], o[k+1] all stored */
  if (end > 1)
    for (size_t j = (size_t)lanes; j < (size_t)end * lanes; j++)
      e[j] += a * (o[j - lanes] - o[j + lanes]) + b * o[j];
  int tail = end > 1 ? end : 1; /* boundary elements: k = 0 and k >= tail */
  for (int k = 0; k < m; k = (k == 0 ? tail : k + 1)) {
    const float *om = odd_at(s, o, k - 1, lanes, zeros);
    const float *o0 = odd_at(s, o, k, lanes, zeros);
    const float *op = odd_at(s, o, k + 1, lanes, zeros);
    float *ek = e + (size_t)k * lanes;
    for (int i = 0; i < lanes; i++) ek[i] += a * (om[i] - op[i]) + b * o0[i];
  }
}

void lifting_forward(const lifting_step *s, float *restrict e, float *restrict o, int lanes,
                     float *restrict ghost) {
  switch (s->basis) {
    case TRANSFORM_HAAR:
      haar_forward(s, e, o, lanes);
      break;
    case TRANSFORM_LINEAR:
      linear_predict(s, e, o, lanes, ghost, 1.0f);
      linear_update(s, e, o, lanes, 1.0f);
      break;
    case TRANSFORM_QUADRATIC:
      quadratic_step1_forward(s, e, o, lanes, ghost);
      quadratic_step2(s, e, o, lanes, ghost, 1.0f);
      quadratic_step3(s, e, o, lanes, ghost, 1.0f);
      break;
  }
}

void lifting_inverse(const lifting_step *s, float *restrict e, float *restrict o, int lanes,
                     float *restrict ghost) {
  switch (s->basis) {
    case TRANSFORM_HAAR:
      haar_inverse(s, e, o, lanes);
      break;
    case TRANSFORM_LINEAR:
      linear_update(s, e, o, lanes, -1.0f);
      linear_predict(s, e, o, lanes, ghost, -1.0f);
      break;
    case TRANSFORM_QUADRATIC:
      quadratic_step3(s, e, o, lanes, ghost, -1.0f);
      quadratic_step2(s, e, o, lanes, ghost, -1.0f);
      quadratic_step1_inverse(s, e, o, lanes, ghost);
      break;
  }
}
