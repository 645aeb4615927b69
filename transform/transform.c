/* The 2D Mallat transform (forward, inverse; standard and non-standard), the
 * approximation pyramid, the deconstructed details (Giroud & Biri §4.4), per-band
 * energies and the renderable grids of every level. None of these allocate, but for
 * transform_density_pyramid's zero band, made once a plan (its first clamp). */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "transform/transform_plan.h"

static void rows_pass(transform_plan *p, int forward, int top, int bottom, const float *src,
                      float *dst, size_t stride, int rows) {
  transform_job j = {.kind = TRANSFORM_JOB_ROWS, .forward = forward, .top = top,
                     .bottom = bottom, .src = src, .dst = dst, .stride = stride, .begin = 0,
                     .end = rows, .samples = (size_t)rows * (size_t)p->len_w[top]};
  transform_run_job(p, &j);
}

static void columns_pass(transform_plan *p, int forward, int top, int bottom, float *base,
                         size_t stride, int columns) {
  transform_job j = {.kind = TRANSFORM_JOB_COLUMNS, .forward = forward, .top = top,
                     .bottom = bottom, .src = base, .dst = base, .stride = stride, .begin = 0,
                     .end = columns, .samples = (size_t)columns * (size_t)p->len_h[top]};
  transform_run_job(p, &j);
}

/* A job over the coarse rows k of level l (the single-pass levels and their copy back);
 * the caller sets what the job reads and writes. */
static transform_job level_job(const transform_plan *p, transform_job_kind kind, int l) {
  return (transform_job){.kind = kind, .level = l, .begin = 0, .end = (p->len_h[l] + 1) / 2,
                         .samples = (size_t)p->len_w[l] * (size_t)p->len_h[l]};
}

/* One single-pass level; the coarse rows k are split between the threads. */
static void fused_forward(transform_plan *p, int l, const float *src, size_t src_stride,
                          float *dst, size_t dst_stride) {
  transform_job j = level_job(p, TRANSFORM_JOB_FUSED_FORWARD, l);
  j.src = src, j.src_stride = src_stride, j.dst = dst, j.stride = dst_stride;
  transform_run_job(p, &j);
}

/* A level computed out of place back into the coefficients: each thread copies the rows
 * it computed, still in its own cache (on the 2-vCPU machines a copy of the other
 * core's rows ran 4x slower). */
static void copy_back(transform_plan *p, int l, const float *level, float *coefficients) {
  transform_job j = level_job(p, TRANSFORM_JOB_COPY_BACK, l);
  j.src = level, j.src_stride = (size_t)p->len_w[l];
  j.dst = coefficients, j.stride = (size_t)p->desc.width;
  transform_run_job(p, &j);
}

static void fused_inverse(transform_plan *p, int l, const float *low, size_t low_stride,
                          const float *coef, size_t coef_stride, float *dst,
                          size_t dst_stride) {
  transform_job j = level_job(p, TRANSFORM_JOB_FUSED_INVERSE, l);
  j.low = low, j.low_stride = low_stride, j.src = coef, j.src_stride = coef_stride;
  j.dst = dst, j.stride = dst_stride;
  transform_run_job(p, &j);
}

void transform_copy_block(float *dst, size_t dst_stride, const float *src,
                          size_t src_stride, int w, int h) {
  for (int y = 0; y < h; y++)
    memcpy(dst + (size_t)y * dst_stride, src + (size_t)y * src_stride, sizeof(float) * (size_t)w);
}

static void zero_block(float *dst, size_t stride, int w, int h) {
  for (int y = 0; y < h; y++) memset(dst + (size_t)y * stride, 0, sizeof(float) * (size_t)w);
}

int transform_forward(transform_plan *p, const float *fogmap, float *coefficients) {
  int J = p->levels, W = p->desc.width, H = p->desc.height;
  if (J == 0 || p->desc.decomposition == TRANSFORM_STANDARD) {
    rows_pass(p, 1, J, 0, fogmap, coefficients, (size_t)W, H);
    columns_pass(p, 1, J, 0, coefficients, (size_t)W, W);
    return 0;
  }
  for (int l = J; l >= 1; l--) {
    /* one streaming pass per level where possible (out of place) */
    if (transform_fused_supported(p, l) && (l < J || fogmap != coefficients)) {
      if (l == J) {
        fused_forward(p, l, fogmap, (size_t)W, coefficients, (size_t)W);
      } else {
        float *level = p->scratch[0].level;
        fused_forward(p, l, coefficients, (size_t)W, level, (size_t)p->len_w[l]);
        copy_back(p, l, level, coefficients);
      }
      continue;
    }
    rows_pass(p, 1, l, l - 1, l == J ? fogmap : coefficients, coefficients, (size_t)W,
              p->len_h[l]);
    columns_pass(p, 1, l, l - 1, coefficients, (size_t)W, p->len_w[l]);
  }
  return 0;
}

/* Inverse of levels 1..l of a len_w[l] x len_h[l] region, in place. */
static void inverse_region(transform_plan *p, float *buf, size_t stride, int l) {
  if (p->desc.decomposition == TRANSFORM_STANDARD) {
    columns_pass(p, 0, l, 0, buf, stride, p->len_w[l]);
    rows_pass(p, 0, l, 0, buf, buf, stride, p->len_h[l]);
    return;
  }
  for (int k = 1; k <= l; k++) {
    columns_pass(p, 0, k, k - 1, buf, stride, p->len_w[k]);
    rows_pass(p, 0, k, k - 1, buf, buf, stride, p->len_h[k]);
  }
}

/* One synthesis level of the non-standard transform: A_{l-1} from `low` (NULL: zero)
 * and band l from `coef` (Mallat layout, stride W) into the w_l x h_l block `dst`
 * (aliasing neither): one streaming pass where possible, else assemble + two passes. */
static void inverse_level(transform_plan *p, int l, const float *low, size_t low_stride,
                          const float *coef, float *dst, size_t dst_stride) {
  size_t W = (size_t)p->desc.width;
  if (transform_fused_inverse_supported(p, l)) {
    fused_inverse(p, l, low, low_stride, coef, W, dst, dst_stride);
    return;
  }
  int w = p->len_w[l], h = p->len_h[l], w0 = p->len_w[l - 1], h0 = p->len_h[l - 1];
  transform_copy_block(dst, dst_stride, coef, W, w, h);
  if (low)
    transform_copy_block(dst, dst_stride, low, low_stride, w0, h0);
  else
    zero_block(dst, dst_stride, w0, h0);
  columns_pass(p, 0, l, l - 1, dst, dst_stride, w);
  rows_pass(p, 0, l, l - 1, dst, dst, dst_stride, h);
}

int transform_inverse(transform_plan *p, const float *coefficients, float *fogmap) {
  size_t W = (size_t)p->desc.width, H = (size_t)p->desc.height;
  int J = p->levels;
  if (p->desc.decomposition == TRANSFORM_NONSTANDARD && J > 0 && coefficients != fogmap) {
    /* A_0 -> A_1 -> ... alternating between two scratch blocks, A_J into fogmap */
    const float *low = coefficients;
    size_t low_stride = W;
    for (int l = 1; l <= J; l++) {
      float *dst = l == J ? fogmap : (l % 2 ? p->scratch[0].level : p->scratch[0].level2);
      size_t dst_stride = l == J ? W : (size_t)p->len_w[l];
      inverse_level(p, l, low, low_stride, coefficients, dst, dst_stride);
      low = dst, low_stride = dst_stride;
    }
    return 0;
  }
  if (coefficients != fogmap) memcpy(fogmap, coefficients, sizeof(float) * W * H);
  inverse_region(p, fogmap, W, p->levels);
  return 0;
}

/* A_0 .. A_top of the non-standard decomposition, each one synthesis step from the last. */
static void incremental_approximations(transform_plan *p, const float *coefficients,
                                       float *const *approx, int top) {
  transform_copy_block(approx[0], (size_t)p->len_w[0], coefficients, (size_t)p->desc.width,
                       p->len_w[0], p->len_h[0]);
  for (int l = 1; l <= top; l++)
    inverse_level(p, l, approx[l - 1], (size_t)p->len_w[l - 1], coefficients, approx[l],
                  (size_t)p->len_w[l]);
}

int transform_pyramid(transform_plan *p, const float *coefficients, float *const *approx) {
  if (p->desc.decomposition != TRANSFORM_STANDARD) {
    incremental_approximations(p, coefficients, approx, p->levels);
    return 0;
  }
  size_t W = (size_t)p->desc.width;
  for (int l = 0; l <= p->levels; l++) { /* standard: each level's block synthesised alone */
    int w = p->len_w[l], h = p->len_h[l];
    transform_copy_block(approx[l], (size_t)w, coefficients, W, w, h);
    if (l > 0) inverse_region(p, approx[l], (size_t)w, l);
  }
  return 0;
}

int transform_details(transform_plan *p, const float *coefficients, float *const *detail) {
  size_t W = (size_t)p->desc.width;
  for (int l = 1; l <= p->levels; l++) {
    int w = p->len_w[l], h = p->len_h[l];
    if (p->desc.decomposition == TRANSFORM_STANDARD) {
      /* the bands whose finer index is at most l sit inside the block: all levels */
      transform_copy_block(detail[l], (size_t)w, coefficients, W, w, h);
      zero_block(detail[l], (size_t)w, p->len_w[l - 1], p->len_h[l - 1]);
      inverse_region(p, detail[l], (size_t)w, l);
    } else {
      inverse_level(p, l, NULL, 0, coefficients, detail[l], (size_t)w);
    }
  }
  return 0;
}

/* The renderer's pyramid (transform.h). Clamping the B-spline coefficients clamps the
 * function: degree 0-2 B-splines are non-negative, so non-negative coefficients give fog
 * >= 0 everywhere. The levels are synthesised up to J - 1 only (A_J is the fogmap, and its
 * synthesis was 3/4 of the work). D_l is rewritten only next to a level that changed;
 * elsewhere the synthesis's D_l already equals A_l - refine(A_{l-1}). */
int transform_density_pyramid(transform_plan *p, const float *fogmap, const float *coefficients,
                              float *const *approx, float *const *detail, fog_error *err) {
  if (p->desc.decomposition != TRANSFORM_NONSTANDARD)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "transform: the density pyramid needs the non-standard decomposition");
  const int J = p->levels;
  const size_t W = (size_t)p->desc.width;
  incremental_approximations(p, coefficients, approx, J - 1);
  memcpy(approx[J], fogmap, sizeof(float) * W * (size_t)p->desc.height);
  if (detail && J > 0) transform_details(p, coefficients, detail);
  bool clamped_below = false; /* level l - 1 changed */
  for (int l = 0; l <= J; l++) {
    const size_t count = (size_t)p->len_w[l] * (size_t)p->len_h[l];
    bool clamped = false;
    for (size_t i = 0; l < J && i < count; i++)
      if (approx[l][i] < 0.0f) approx[l][i] = 0.0f, clamped = true;
    if (detail && l > 0 && (clamped || clamped_below)) {
      /* D_l = A_l - refine(A_{l-1}): one synthesis step of A_{l-1} with band l zero (the
       * plan's zero band, made on the first clamp and kept) */
      if (!p->zero_band) {
        if (!(p->zero_band = transform_alloc_floats(W * (size_t)p->desc.height)))
          return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "transform: out of memory for a "
                          "%dx%d zero band", p->desc.width, p->desc.height);
        memset(p->zero_band, 0, sizeof(float) * W * (size_t)p->desc.height);
      }
      inverse_level(p, l, approx[l - 1], (size_t)p->len_w[l - 1], p->zero_band, detail[l],
                    (size_t)p->len_w[l]);
      for (size_t i = 0; i < count; i++) detail[l][i] = approx[l][i] - detail[l][i];
    }
    clamped_below = clamped;
  }
  return 0;
}

void transform_detail_energy(const transform_plan *p, const float *coefficients,
                             double *energy) {
  size_t W = (size_t)p->desc.width;
  for (int o = 0; o < 3; o++) energy[o] = 0.0;
  for (int l = 1; l <= p->levels; l++)
    for (int o = 0; o < 3; o++) {
      int x, y, w, h;
      transform_band_rect(p, l, (transform_orientation)o, &x, &y, &w, &h);
      double sum = 0.0;
      for (int j = 0; j < h; j++) {
        const float *row = coefficients + (size_t)(y + j) * W + x;
        for (int i = 0; i < w; i++) sum += (double)row[i] * row[i];
      }
      energy[3 * l + o] = sum;
    }
}

/* ---- renderable grids ---- */

static int ghost_count(const transform_plan *p) {
  return transform_basis_degree(p->desc.basis) > 0 ? 1 : 0;
}

void transform_grid_size(const transform_plan *p, int level, int *width, int *height) {
  int g = ghost_count(p);
  *width = p->len_w[level] + 2 * g;
  *height = p->len_h[level] + 2 * g;
}

static float apply_rule(const ghost_rule *r, const float *c, size_t step) {
  double v = 0.0;
  for (int t = 0; t < r->count; t++) v += r->weight[t] * c[(size_t)r->index[t] * step];
  return (float)v;
}

int transform_grid_export(const transform_plan *p, int level, const float *stored,
                          transform_grid *grid, fog_error *err) {
  if (level < 0 || level > p->levels)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "grid level %d: expected 0..%d", level,
                    p->levels);
  int gw, gh;
  transform_grid_size(p, level, &gw, &gh); /* reads level's sizes: checked above */
  if (!grid->coefficients)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "grid for level %d has no coefficients",
                    level);
  if (grid->width != gw || grid->height != gh) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "grid for level %d must be %dx%d (transform_grid_size), got %dx%d", level, gw, gh,
             grid->width, grid->height);
    return 1;
  }
  int g = ghost_count(p), w = p->len_w[level], h = p->len_h[level];
  int degree = transform_basis_degree(p->desc.basis);
  double spacing = ldexp(1.0, p->levels - level);
  /* where stored coefficient (0,0) sits: CDF 5/3 keeps the even samples (position 0);
   * Haar and bior3.3 average pairs, so level l sits at (2^(J-l) - 1)/2 */
  double first = degree == 1 ? 0.0 : 0.5 * (spacing - 1.0);
  float *c = grid->coefficients;
  for (int j = 0; j < h; j++) {
    float *row = c + (size_t)(j + g) * gw + g;
    memcpy(row, stored + (size_t)j * w, sizeof(float) * (size_t)w);
    if (g) {
      row[-1] = apply_rule(&p->rules_w[level].left, row, 1);
      row[w] = apply_rule(&p->rules_w[level].right, row, 1);
    }
  }
  if (g) { /* ghost rows from the extended rows: corners are the tensor product */
    const float *first_row = c + (size_t)g * gw;
    for (int i = 0; i < gw; i++) {
      c[i] = apply_rule(&p->rules_h[level].left, first_row + i, (size_t)gw);
      c[(size_t)(gh - 1) * gw + i] = apply_rule(&p->rules_h[level].right, first_row + i, (size_t)gw);
    }
  }
  grid->origin_u = first - g * spacing;
  grid->origin_v = first - g * spacing;
  grid->spacing = spacing;
  grid->degree = degree;
  return 0;
}

int transform_grid_create_level(const transform_plan *p, int level, const float *stored,
                                transform_grid *grid, fog_error *err) {
  int gw, gh;
  if (level < 0 || level > p->levels) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "level %d outside 0..%d", level, p->levels);
    return 1;
  }
  transform_grid_size(p, level, &gw, &gh);
  if (transform_grid_create(grid, gw, gh, err)) return 1;
  if (transform_grid_export(p, level, stored, grid, err)) {
    transform_grid_destroy(grid);
    return 1;
  }
  return 0;
}

/* ---- the atlas for GPU upload ---- */

void transform_atlas_offset(const transform_plan *p, int level, int *x, int *y) {
  int J = p->levels, gw, gh;
  *x = 0, *y = 0;
  if (level == J) return;
  transform_grid_size(p, J, &gw, &gh);
  *x = gw;
  for (int k = level + 1; k < J; k++) {
    transform_grid_size(p, k, &gw, &gh);
    *y += gh;
  }
}

void transform_atlas_size(const transform_plan *p, int *width, int *height) {
  int J = p->levels, gw, gh;
  transform_grid_size(p, J, width, height);
  if (J == 0) return;
  int column = 0;
  transform_grid_size(p, J - 1, &gw, &gh);
  *width += gw;
  for (int k = 0; k < J; k++) {
    transform_grid_size(p, k, &gw, &gh);
    column += gh;
  }
  if (column > *height) *height = column;
}

void transform_atlas_pack(const transform_plan *p, const transform_grid *grids, float *atlas) {
  int aw, ah;
  transform_atlas_size(p, &aw, &ah);
  memset(atlas, 0, sizeof(float) * (size_t)aw * (size_t)ah);
  for (int l = 0; l <= p->levels; l++) {
    const transform_grid *g = &grids[l];
    if (!g->coefficients) continue;
    int x, y;
    transform_atlas_offset(p, l, &x, &y);
    transform_copy_block(atlas + (size_t)y * aw + x, (size_t)aw, g->coefficients, (size_t)g->width,
               g->width, g->height);
  }
}
