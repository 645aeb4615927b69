/* The exact optical depth of the 2.5D fogmap model along a ray, in double (the CPU
 * reference). Mirrored line by line by render/shaders/fog_integral.glsl: same function
 * names, same steps; see fog_field.h for the model, the knots and the exactness argument. */
#include <math.h>
#include <stdint.h>

#include "render/fog_field.h"
#include "render/fog_models.h"
#include "render/fog_occupancy.h"

/* Gauss-Legendre nodes and weights on [-1, 1] for 1..4 points (exact to degree 2m-1) and
 * for 8 points (the small-|a| exponential moments). */
static const double fog_gauss_nodes[5][4] = {
    {0},
    {0.0},
    {-0.57735026918962576, 0.57735026918962576},
    {-0.77459666924148338, 0.0, 0.77459666924148338},
    {-0.86113631159405258, -0.33998104358485626, 0.33998104358485626, 0.86113631159405258},
};
static const double fog_gauss_weights[5][4] = {
    {0},
    {2.0},
    {1.0, 1.0},
    {0.55555555555555556, 0.88888888888888889, 0.55555555555555556},
    {0.34785484513745386, 0.65214515486254614, 0.65214515486254614, 0.34785484513745386},
};
static const double fog_gauss8_nodes[8] = {
    -0.96028985649753623, -0.79666647741362674, -0.52553240991632899, -0.18343464249564980,
    0.18343464249564980,  0.52553240991632899,  0.79666647741362674,  0.96028985649753623};
static const double fog_gauss8_weights[8] = {
    0.10122853629037626, 0.22238103445337447, 0.31370664587788729, 0.36268378337836198,
    0.36268378337836198, 0.31370664587788729, 0.22238103445337447, 0.10122853629037626};

/* ---- the model's pieces ------------------------------------------------------------- */

void fog_profile_extent(const fog_profile *p, double *y_bottom, double *y_top) {
  if (p->kind == FOG_PROFILE_BSPLINE) {
    double half = 0.5 * (p->degree + 1);
    *y_bottom = p->origin - half * p->spacing;
    *y_top = p->origin + (p->count - 1 + half) * p->spacing;
  } else {
    *y_bottom = p->y_floor;
    *y_top = p->y_top;
  }
}

/* Physical quantities, taken as given: extinction 0 is no fog (never "0 means 1"). */
static double fog_cell_size(const fog_volume *v) { return v->cell_size; }
static double fog_extinction(const fog_volume *v) { return v->extinction; }

void fog_volume_box(const fog_volume *v, double box_min[3], double box_max[3]) {
  double h = fog_cell_size(v);
  box_min[0] = v->origin_x;
  box_max[0] = v->origin_x + v->map_width * h;
  box_min[2] = v->origin_z;
  box_max[2] = v->origin_z + v->map_height * h;
  fog_profile_extent(&v->profile, &box_min[1], &box_max[1]);
}

int fog_slab_entry_exit(const double lo[3], const double hi[3], const double dir[3],
                        double *t_enter, double *t_exit) {
  double t0 = -HUGE_VAL, t1 = HUGE_VAL;
  for (int a = 0; a < 3; a++) {
    if (dir[a] == 0.0) {
      if (lo[a] > 0.0 || hi[a] < 0.0) return 0;
      continue;
    }
    double ta = lo[a] / dir[a], tb = hi[a] / dir[a];
    if (ta > tb) {
      double s = ta;
      ta = tb;
      tb = s;
    }
    if (ta > t0) t0 = ta;
    if (tb < t1) t1 = tb;
  }
  *t_enter = t0;
  *t_exit = t1;
  return t0 <= t1;
}

int fog_box_entry_exit(const fog_volume *v, const double camera[3], const double dir[3],
                       double *t_enter, double *t_exit) {
  double lo[3], hi[3];
  fog_volume_box(v, lo, hi);
  for (int a = 0; a < 3; a++) { /* camera-relative first */
    lo[a] -= camera[a];
    hi[a] -= camera[a];
  }
  return fog_slab_entry_exit(lo, hi, dir, t_enter, t_exit);
}

/* The d+1 non-zero centred B-spline values at local coordinate s in [0, 1] of a knot cell
 * (uniform B-spline segments; w[k] belongs to coefficient c - d/2 + k). */
static void fog_cell_weights(int degree, double s, double w[4]) {
  double r = 1.0 - s;
  switch (degree) {
    case 0:
      w[0] = 1.0;
      break;
    case 1:
      w[0] = r;
      w[1] = s;
      break;
    case 2:
      w[0] = 0.5 * r * r;
      w[1] = 0.5 + s * r;
      w[2] = 0.5 * s * s;
      break;
    default:
      w[0] = r * r * r / 6.0;
      w[1] = (3.0 * s * s * s - 6.0 * s * s + 4.0) / 6.0;
      w[2] = (3.0 * r * r * r - 6.0 * r * r + 4.0) / 6.0;
      w[3] = s * s * s / 6.0;
      break;
  }
}

/* Offset of the knot lines: cell c is [c + off, c + 1 + off] (half-integers for even d). */
static double fog_knot_offset(int degree) { return (degree % 2 == 0) ? -0.5 : 0.0; }

static double fog_grid_coefficient(const transform_grid *g, int i, int j) {
  if (i < 0 || j < 0 || i >= g->width || j >= g->height) return 0.0; /* ghosts materialised */
  return g->coefficients[(size_t)j * (size_t)g->width + (size_t)i];
}

/* f at grid coordinates (x, z) known to lie in knot cell (cx, cz): docs/integral.md, Knots: the basis,
 * f = sum c_ij phi_d(x - i) phi_d(z - j) with the cell's (d+1)^2 coefficients. */
static double fog_grid_value(const transform_grid *g, int cx, int cz, double x, double z) {
  int d = g->degree;
  double off = fog_knot_offset(d), wx[4], wz[4];
  fog_cell_weights(d, x - (cx + off), wx);
  fog_cell_weights(d, z - (cz + off), wz);
  int i0 = cx - d / 2, j0 = cz - d / 2;
  double sum = 0.0;
  for (int b = 0; b <= d; b++) {
    double row = 0.0;
    for (int a = 0; a <= d; a++) row += wx[a] * fog_grid_coefficient(g, i0 + a, j0 + b);
    sum += wz[b] * row;
  }
  return sum;
}

/* g of a B-spline profile at profile coordinate y in knot cell cy. */
static double fog_profile_bspline_value(const fog_profile *p, int cy, double y) {
  int d = p->degree;
  double w[4];
  fog_cell_weights(d, y - (cy + fog_knot_offset(d)), w);
  double sum = 0.0;
  for (int k = 0; k <= d; k++) {
    int i = cy - d / 2 + k;
    if (i >= 0 && i < p->count) sum += w[k] * p->coefficients[i];
  }
  return sum;
}

/* ---- exponential moments J_k = int_{-1}^{1} s^k e^{c0 + b s} ds ---------------------- */

void fog_exp_moments_closed(double c0, double b, int n, double m[]) {
  /* Integration by parts: J_k = [s^k e^{c0+bs}/b]_{-1}^{1} - (k/b) J_{k-1}; exp(c0 +- b)
   * are formed directly so a large |b| cannot overflow when c0 + |b| stays small. */
  double e_plus = exp(c0 + b), e_minus = exp(c0 - b);
  m[0] = (e_plus - e_minus) / b;
  for (int k = 1; k <= n; k++) {
    double boundary = e_plus - ((k % 2) ? -e_minus : e_minus);
    m[k] = (boundary - k * m[k - 1]) / b;
  }
}

void fog_exp_moments_quadrature(double c0, double b, int n, double m[]) {
  for (int k = 0; k <= n; k++) m[k] = 0.0;
  for (int i = 0; i < 8; i++) {
    double s = fog_gauss8_nodes[i], w = fog_gauss8_weights[i] * exp(c0 + b * s), sk = 1.0;
    for (int k = 0; k <= n; k++) {
      m[k] += w * sk;
      sk *= s;
    }
  }
}

void fog_exp_moments_series(double c0, double b, int n, double m[]) {
  /* e^{bs} = sum_j (bs)^j/j!, int_{-1}^{1} s^{k+j} ds = 2/(k+j+1) for even k+j: every term
   * of J_k has the sign of b^{k mod 2}, so nothing cancels; for |b| < 1 the 20th term is
   * below 1/20! ~ 4e-19 of the first. The terms fall as |b|^j / j!, so the sum stops once
   * one is below 1e-17 of the first (J_0 >= 2 e^{c0} / e: nothing it drops is resolved): a
   * sun column's short pieces (|b| ~ 0.1) need 10 terms, not 20. */
  const double first = exp(c0);
  double term = first; /* e^{c0} b^j / j! */
  for (int k = 0; k <= n; k++) m[k] = 0.0;
  for (int j = 0; j < 20; j++) {
    for (int k = (j % 2); k <= n; k += 2) m[k] += term * 2.0 / (k + j + 1);
    term *= b / (j + 1);
    if (!(fabs(term) > 1e-17 * first)) break;
  }
}

void fog_exp_moments(double c0, double b, int n, double m[]) {
  if (fabs(b) >= FOG_EXP_SWITCH)
    fog_exp_moments_closed(c0, b, n, m);
  else
    fog_exp_moments_series(c0, b, n, m);
}

/* Monomial coefficients of a polynomial of degree n <= 4 on [-1, 1] from its values at
 * n+1 equispaced points s_i = -1 + 2i/n (inverse Vandermonde, exact rationals). */
static void fog_monomials_from_samples(int n, const double y[], double c[]) {
  switch (n) {
    case 0:
      c[0] = y[0];
      break;
    case 2:
      c[0] = y[1];
      c[1] = 0.5 * (y[2] - y[0]);
      c[2] = 0.5 * (y[2] + y[0]) - y[1];
      break;
    default: /* n = 4: points -1, -1/2, 0, 1/2, 1 */
      c[0] = y[2];
      c[1] = (y[0] - 8.0 * y[1] + 8.0 * y[3] - y[4]) / 6.0;
      c[2] = (-y[0] + 16.0 * y[1] - 30.0 * y[2] + 16.0 * y[3] - y[4]) / 6.0;
      c[3] = (-2.0 * y[0] + 4.0 * y[1] - 4.0 * y[3] + 2.0 * y[4]) / 3.0;
      c[4] = (2.0 * y[0] - 8.0 * y[1] + 12.0 * y[2] - 8.0 * y[3] + 2.0 * y[4]) / 3.0;
      break;
  }
}

/* ---- the walk ------------------------------------------------------------------------- */

/* One axis of the 2D DDA (Amanatides & Woo 1987) over knot lines: coordinate
 * x(t) = x0 + t * dx, knot cell `cell`, knot lines at integers + offset. The next crossing
 * is computed from the knot position (not accumulated), so long rays do not drift. */
typedef struct fog_axis {
  double x0, dx, inv_dx, offset; /* inv_dx: a multiply per step instead of a divide */
  int cell;
} fog_axis;

static void fog_axis_start(fog_axis *a, double x0, double dx, double offset, double t) {
  a->x0 = x0;
  a->dx = dx;
  a->inv_dx = (dx != 0.0) ? 1.0 / dx : 0.0;
  a->offset = offset;
  a->cell = (int)floor(x0 + t * dx - offset);
}

static double fog_axis_next(const fog_axis *a) {
  if (a->dx > 0.0) return (a->cell + 1 + a->offset - a->x0) * a->inv_dx;
  if (a->dx < 0.0) return (a->cell + a->offset - a->x0) * a->inv_dx;
  return HUGE_VAL;
}

static void fog_axis_step(fog_axis *a) { a->cell += (a->dx > 0.0) ? 1 : -1; }

/* The GLSL walk's last exponential break above y0, in half scale heights (FOG_EXP_TOP). */
#define FOG_EXP_BREAKS_TOP 210

/* The cell the DDA would be in after walking to t: every crossing at or before t stepped,
 * the next one after t. From the position's floor (which float rounding may put one cell
 * off at a knot line), then corrected with the crossings themselves, the same formula the
 * walk steps by: so a jump lands exactly where stepping would have (empty-space skipping
 * stays bit for bit). */
static void fog_axis_sync(fog_axis *a, double t) {
  if (a->dx == 0.0) return;
  const int step = (a->dx > 0.0) ? 1 : -1;
  a->cell = (int)floor(a->x0 + t * a->dx - a->offset);
  while (fog_axis_next(a) <= t) a->cell += step;
  for (;;) {
    fog_axis previous = *a;
    previous.cell -= step;
    if (!(fog_axis_next(&previous) > t)) break;
    a->cell = previous.cell;
  }
}

/* Where the axis leaves the current occupancy block: the crossing of the block's last knot
 * cell in the walk's direction (fog_occupancy.h: block bx holds texel columns
 * [bx B, bx B + B - 1], texel column = cell + shift). */
static double fog_axis_block_exit(const fog_axis *a, int shift) {
  if (a->dx == 0.0) return HUGE_VAL;
  const int b = FOG_OCCUPANCY_BLOCK, tx = a->cell + shift;
  const int bx = (tx >= 0) ? tx / b : -((-tx + b - 1) / b);
  fog_axis last = *a;
  last.cell = ((a->dx > 0.0) ? bx * b + b - 1 : bx * b) - shift;
  return fog_axis_next(&last);
}

/* The walk's state for one grid along one ray, camera-relative. block[a][b] holds the
 * coefficients c(i0 + a, j0 + b), a, b = 0..d, of the current knot cells (i0 = x.cell - d/2,
 * j0 = z.cell - d/2): a DDA step shifts it and reads the one column or row that entered, so
 * the walk reads each coefficient once (the GPU twin's reason; mirrored here). */
typedef struct fog_ray_walk {
  const transform_grid *grid;
  double block[3][3];
  const fog_profile *profile;
  fog_axis x, z, y;   /* y: B-spline profile knots only */
  double y_camera;    /* world height where the walk starts (t' = 0: the box entry) */
  double dir_y;
  double t_y0;        /* exponential profile: the parameter where y = y0 (or +-inf) */
  int above_y0_first; /* exponential: the ray starts above y0 */
  /* Empty-space skipping (NULL: none): blocks with bound <= skip_below are jumped. */
  const fog_occupancy *skip;
  float skip_below;
} fog_ray_walk;

static void fog_block_load(fog_ray_walk *w) {
  int d = w->grid->degree, i0 = w->x.cell - d / 2, j0 = w->z.cell - d / 2;
  for (int a = 0; a <= d; a++)
    for (int b = 0; b <= d; b++) w->block[a][b] = fog_grid_coefficient(w->grid, i0 + a, j0 + b);
}

/* After w->x stepped: shift the columns, read the one that entered. */
static void fog_block_step_x(fog_ray_walk *w) {
  int d = w->grid->degree, i0 = w->x.cell - d / 2, j0 = w->z.cell - d / 2;
  int entering = (w->x.dx > 0.0) ? d : 0;
  for (int b = 0; b <= d; b++) {
    if (w->x.dx > 0.0)
      for (int a = 0; a < d; a++) w->block[a][b] = w->block[a + 1][b];
    else
      for (int a = d; a > 0; a--) w->block[a][b] = w->block[a - 1][b];
    w->block[entering][b] = fog_grid_coefficient(w->grid, i0 + entering, j0 + b);
  }
}

/* After w->z stepped: shift every column's entries, read the row that entered. */
static void fog_block_step_z(fog_ray_walk *w) {
  int d = w->grid->degree, i0 = w->x.cell - d / 2, j0 = w->z.cell - d / 2;
  int entering = (w->z.dx > 0.0) ? d : 0;
  for (int a = 0; a <= d; a++) {
    if (w->z.dx > 0.0)
      for (int b = 0; b < d; b++) w->block[a][b] = w->block[a][b + 1];
    else
      for (int b = d; b > 0; b--) w->block[a][b] = w->block[a][b - 1];
    w->block[a][entering] = fog_grid_coefficient(w->grid, i0 + a, j0 + entering);
  }
}

/* f at parameter t of the current piece: the cell weights applied to the block. */
static double fog_walk_value(const fog_ray_walk *w, double t) {
  int d = w->grid->degree;
  double off = fog_knot_offset(d), wx[4], wz[4];
  double x = w->x.x0 + t * w->x.dx, z = w->z.x0 + t * w->z.dx;
  fog_cell_weights(d, x - (w->x.cell + off), wx);
  fog_cell_weights(d, z - (w->z.cell + off), wz);
  double sum = 0.0;
  for (int b = 0; b <= d; b++) {
    double row = 0.0;
    for (int a = 0; a <= d; a++) row += wx[a] * w->block[a][b];
    sum += wz[b] * row;
  }
  return sum;
}

/* Integral of f g over one piece [ta, tb] inside one knot cell of every axis. */
static double fog_piece_integral(const fog_ray_walk *w, double ta, double tb) {
  const transform_grid *g = w->grid;
  const fog_profile *p = w->profile;
  double half = 0.5 * (tb - ta), mid = 0.5 * (ta + tb);
  int d = g->degree;
  double tm = mid;
  if (p->kind == FOG_PROFILE_EXPONENTIAL && w->y_camera + tm * w->dir_y > p->y0) {
    /* f(t) e^{-(y(t) - y0)/H}: f is a polynomial of degree n = 2d in s = (t - mid)/half,
     * so int = half * sum_k c_k J_k(c0, b) with c0 = -(y(mid) - y0)/H, b = -dir_y half/H. */
    int n = 2 * d;
    double samples[5], c[5], moments[8];
    for (int i = 0; i <= n; i++) {
      double s = n ? -1.0 + 2.0 * i / n : 0.0, t = mid + half * s;
      samples[i] = fog_walk_value(w, t);
    }
    double c0 = -(w->y_camera + mid * w->dir_y - p->y0) / p->scale_height;
    double b = -w->dir_y * half / p->scale_height;
    fog_monomials_from_samples(n, samples, c);
    /* Closed form, or below the switch (where it cancels) the moments' series. */
    fog_exp_moments(c0, b, n, moments);
    double sum = 0.0;
    for (int k = 0; k <= n; k++) sum += c[k] * moments[k];
    return half * sum;
  }
  /* Polynomial piece: degree 2d + p in t, exact with m = d + p/2 + 1 Gauss nodes. */
  int pd = (p->kind == FOG_PROFILE_BSPLINE) ? p->degree : 0;
  int m = (2 * d + pd) / 2 + 1;
  double sum = 0.0;
  for (int i = 0; i < m; i++) {
    double t = mid + half * fog_gauss_nodes[m][i];
    double f = fog_walk_value(w, t);
    double gy = (p->kind == FOG_PROFILE_BSPLINE)
                    ? fog_profile_bspline_value(p, w->y.cell, w->y.x0 + t * w->y.dx)
                    : 1.0;
    sum += fog_gauss_weights[m][i] * f * gy;
  }
  return half * sum;
}

/* The walk over [*t, t_end] (t_end a knot crossing or t1, so no piece is cut short): the
 * knot cells of x, z (2D DDA) and the profile's breaks, one exact piece at a time. */
static void fog_walk_cells(fog_ray_walk *w, double *t_io, double t_end, double t1,
                           double *sum) {
  double t = *t_io;
  /* Each iteration crosses one knot line or ends; the bound only guards against NaN. */
  for (long guard = 0; t < t_end && guard < 100000000L; guard++) {
    double tx = fog_axis_next(&w->x), tz = fog_axis_next(&w->z);
    double ty = (w->profile->kind == FOG_PROFILE_BSPLINE) ? fog_axis_next(&w->y) : HUGE_VAL;
    double t_next = t1;
    if (tx < t_next) t_next = tx;
    if (tz < t_next) t_next = tz;
    if (ty < t_next) t_next = ty;
    if (w->t_y0 > t && w->t_y0 < t_next) t_next = w->t_y0;
    if (t_next > t) *sum += fog_piece_integral(w, t, t_next);
    if (tx <= t_next) {
      fog_axis_step(&w->x);
      fog_block_step_x(w);
    }
    if (tz <= t_next) {
      fog_axis_step(&w->z);
      fog_block_step_z(w);
    }
    if (ty <= t_next) fog_axis_step(&w->y);
    if (t_next > t) t = t_next;
  }
  *t_io = t;
}

/* int_{t0}^{t1} f g dt for [t0, t1] inside the box. With skipping (w->skip) the ray goes
 * block by block of the occupancy map (fog_occupancy.h), as the GLSL twin does: an empty
 * block is jumped, every axis synced to where the ray leaves it; any other block is walked
 * cell by cell up to that exit, a knot crossing, so the pieces are the plain walk's. */
static double fog_walk_integral(fog_ray_walk *w, double t0, double t1) {
  double sum = 0.0, t = t0;
  if (!w->skip) {
    fog_walk_cells(w, &t, t1, t1, &sum);
    return sum;
  }
  const int shift = w->grid->degree - w->grid->degree / 2;
  /* Every crossing at the start stepped first (a walk starting on a block's edge, moving
   * back across it, has its block exit at t: no block was ever jumped); only zero-length
   * pieces go, so the sum is unchanged. */
  fog_axis_sync(&w->x, t);
  fog_axis_sync(&w->z, t);
  if (w->profile->kind == FOG_PROFILE_BSPLINE) fog_axis_sync(&w->y, t);
  fog_block_load(w);
  for (long guard = 0; t < t1 && guard < 100000000L; guard++) {
    double tb = fmin(t1, fmin(fog_axis_block_exit(&w->x, shift),
                              fog_axis_block_exit(&w->z, shift)));
    if (fog_occupancy_at(w->skip, w->x.cell, w->z.cell) <= w->skip_below && tb > t) {
      t = tb;
      fog_axis_sync(&w->x, t);
      fog_axis_sync(&w->z, t);
      if (w->profile->kind == FOG_PROFILE_BSPLINE) fog_axis_sync(&w->y, t);
      fog_block_load(w);
    } else {
      fog_walk_cells(w, &t, tb > t ? tb : t1, t1, &sum);
    }
  }
  return sum;
}

/* The walk set up at the box entry t0 >= t_start (false: the ray misses [t_start, t_stop]
 * inside the box); walk parameters are t - t0. */
static bool fog_walk_setup(const fog_volume *v, const transform_grid *g, const double camera[3],
                           const double dir[3], double t_start, double t_stop,
                           fog_ray_walk *w, double *t0_out, double *t1_out) {
  double t0, t1;
  if (!fog_box_entry_exit(v, camera, dir, &t0, &t1)) return false;
  if (t0 < t_start) t0 = t_start;
  if (t1 > t_stop) t1 = t_stop;
  if (!(t0 < t1)) return false;

  /* Camera-relative grid coordinates: u(t) = (t dir_x - (origin_x - camera_x))/h - 1/2,
   * x(t) = (u(t) - origin_u)/spacing = x0 + t dx. The walk then runs in t' = t - t0 from
   * the box entry, so piece lengths are differences of small numbers even on a 50 km ray
   * (in the float twin, whose ray set-up is double for the same reason: see
   * fog_optical_depth_inside in fog_integral.glsl). */
  double h = fog_cell_size(v);
  double rel_x = v->origin_x - camera[0], rel_z = v->origin_z - camera[2];
  double off = fog_knot_offset(g->degree);
  double x0 = (-rel_x / h - 0.5 - g->origin_u) / g->spacing, dx = dir[0] / (h * g->spacing);
  double z0 = (-rel_z / h - 0.5 - g->origin_v) / g->spacing, dz = dir[2] / (h * g->spacing);
  *w = (fog_ray_walk){.grid = g, .profile = &v->profile, .y_camera = camera[1] + t0 * dir[1],
                      .dir_y = dir[1], .t_y0 = HUGE_VAL};
  fog_axis_start(&w->x, x0 + t0 * dx, dx, off, 0.0);
  fog_axis_start(&w->z, z0 + t0 * dz, dz, off, 0.0);
  const fog_profile *p = &v->profile;
  if (p->kind == FOG_PROFILE_BSPLINE)
    fog_axis_start(&w->y, (w->y_camera - p->origin) / p->spacing, dir[1] / p->spacing,
                   fog_knot_offset(p->degree), 0.0);
  if (p->kind == FOG_PROFILE_EXPONENTIAL && dir[1] != 0.0)
    w->t_y0 = (p->y0 - w->y_camera) / dir[1];
  fog_block_load(w);
  *t0_out = t0, *t1_out = t1;
  return true;
}

double fog_optical_depth(const fog_volume *v, const transform_grid *g, const double camera[3],
                         const double dir[3], double t_start, double t_stop) {
  fog_ray_walk w;
  double t0, t1;
  if (!fog_walk_setup(v, g, camera, dir, t_start, t_stop, &w, &t0, &t1)) return 0.0;
  return fog_extinction(v) * fog_walk_integral(&w, 0.0, t1 - t0);
}

double fog_optical_depth_skipping(const fog_volume *v, const transform_grid *g,
                                  const fog_occupancy *occupancy, float skip_below,
                                  const double camera[3], const double dir[3], double t_start,
                                  double t_stop) {
  fog_ray_walk w;
  double t0, t1;
  if (!fog_walk_setup(v, g, camera, dir, t_start, t_stop, &w, &t0, &t1)) return 0.0;
  w.skip = occupancy;
  w.skip_below = skip_below;
  return fog_extinction(v) * fog_walk_integral(&w, 0.0, t1 - t0);
}

void fog_optical_depth_samples(const fog_volume *v, const transform_grid *g,
                               const double origin[3], const double dir[3], double step, int n,
                               double out[]) {
  fog_ray_walk w;
  double t0 = 0.0, t1 = 0.0, sum = 0.0;
  bool hit = n > 0 && fog_walk_setup(v, g, origin, dir, 0.0, step * (n - 1), &w, &t0, &t1);
  for (int k = 0; k < n; k++) {
    if (hit && k > 0) {
      /* [t_{k-1}, t_k] clipped to the box, in walk parameters: the walk carries on */
      double a = fmax(step * (k - 1), t0) - t0, b = fmin(step * k, t1) - t0;
      if (b > a) sum += fog_walk_integral(&w, a, b);
    }
    out[k] = fog_extinction(v) * sum;
  }
}

/* ---- the light a ray gathers, per piece of the walk (fog_fogmap_light_integral) --------- */

/* g at walk parameter t of the current piece. */
static double fog_walk_profile(const fog_ray_walk *w, double t) {
  const fog_profile *p = w->profile;
  if (p->kind == FOG_PROFILE_BSPLINE)
    return fog_profile_bspline_value(p, w->y.cell, w->y.x0 + t * w->y.dx);
  if (p->kind == FOG_PROFILE_EXPONENTIAL) {
    double y = w->y_camera + t * w->dir_y;
    return y > p->y0 ? exp(-(y - p->y0) / p->scale_height) : 1.0;
  }
  return 1.0;
}

double fog_fogmap_light_integral(const fog_volume *v, const transform_grid *g,
                                 const double camera[3], const double dir[3], double length,
                                 int nodes, double depth_limit, fog_point_light_fn light,
                                 const void *user, double *depth) {
  *depth = 0.0;
  fog_ray_walk w;
  double t0, t1;
  if (nodes < 1 || nodes > FOG_PIECE_MAX_NODES ||
      !fog_walk_setup(v, g, camera, dir, 0.0, length, &w, &t0, &t1))
    return 0.0;
  double gx[FOG_PIECE_MAX_NODES], gw[FOG_PIECE_MAX_NODES],
      partial[FOG_PIECE_MAX_NODES][FOG_PIECE_MAX_NODES];
  fog_gauss_rule(nodes, gx, gw, partial);
  const fog_profile *p = &v->profile;
  /* The exponential's breaks as the GLSL walk has them, y0 + k H/2 for k = 0..
   * FOG_EXP_BREAKS_TOP (cell -1 is all of the fog below y0, where g = 1; cell
   * FOG_EXP_BREAKS_TOP all above y0 + 105 H, where e^{-(y - y0)/H} is below float's least):
   * on a piece the exponent moves by at most 1/2, so a few nodes hold it. */
  fog_axis breaks = {0};
  const bool exponential = p->kind == FOG_PROFILE_EXPONENTIAL;
  if (exponential) {
    fog_axis_start(&breaks, (w.y_camera - p->y0) * 2.0 / p->scale_height,
                   dir[1] * 2.0 / p->scale_height, 0.0, 0.0);
    breaks.cell = breaks.cell < -1 ? -1 : breaks.cell > FOG_EXP_BREAKS_TOP ? FOG_EXP_BREAKS_TOP
                                                                           : breaks.cell;
  }
  const double scale = fog_extinction(v), len = t1 - t0;
  double t = 0.0, D = 0.0, S = 0.0;
  for (long guard = 0; t < len && D < depth_limit && guard < 100000000L; guard++) {
    double tx = fog_axis_next(&w.x), tz = fog_axis_next(&w.z);
    const bool capped = (breaks.cell <= -1 && breaks.dx < 0.0) ||
                        (breaks.cell >= FOG_EXP_BREAKS_TOP && breaks.dx > 0.0);
    double ty = p->kind == FOG_PROFILE_BSPLINE ? fog_axis_next(&w.y)
                : exponential && !capped       ? fog_axis_next(&breaks)
                                               : HUGE_VAL;
    double tn = fmin(len, fmin(tx, fmin(tz, ty)));
    if (tn > t) {
      double h = 0.5 * (tn - t), mid = 0.5 * (tn + t);
      double K[FOG_PIECE_MAX_NODES], f[FOG_PIECE_MAX_NODES];
      for (int j = 0; j < nodes; j++) {
        double tj = mid + h * gx[j], x[3];
        /* a negative K (a linear or quadratic map's ringing) weighs nothing, as in the
         * segments' mean (fog_sun_mean_light) */
        K[j] = fmax(scale * fog_walk_value(&w, tj) * fog_walk_profile(&w, tj), 0.0);
        for (int a = 0; a < 3; a++) x[a] = camera[a] + (t0 + tj) * dir[a];
        f[j] = light(user, x);
      }
      S += fog_piece_light(nodes, gw, partial, h, K, f, &D);
    }
    if (tx <= tn) {
      fog_axis_step(&w.x);
      fog_block_step_x(&w);
    }
    if (tz <= tn) {
      fog_axis_step(&w.z);
      fog_block_step_z(&w);
    }
    if (ty <= tn) fog_axis_step(p->kind == FOG_PROFILE_BSPLINE ? &w.y : &breaks);
    t = fmax(t, tn);
  }
  *depth = D;
  return S;
}

/* ---- uniform ray marching (the benchmark's alternative integrator) ---------------------- */

/* K / extinction at parameter t (inside the box): the cell from floor, then the same
 * pointwise formulas. */
static double fog_extinction_at(const fog_volume *v, const transform_grid *g,
                                const double camera[3], const double dir[3], double t) {
  double h = fog_cell_size(v), off = fog_knot_offset(g->degree);
  double x = ((-(v->origin_x - camera[0]) / h - 0.5 - g->origin_u) + t * dir[0] / h) / g->spacing;
  double z = ((-(v->origin_z - camera[2]) / h - 0.5 - g->origin_v) + t * dir[2] / h) / g->spacing;
  double f = fog_grid_value(g, (int)floor(x - off), (int)floor(z - off), x, z);
  const fog_profile *p = &v->profile;
  double y = camera[1] + t * dir[1];
  if (p->kind == FOG_PROFILE_EXPONENTIAL)
    return f * ((y > p->y0) ? exp(-(y - p->y0) / p->scale_height) : 1.0);
  if (p->kind == FOG_PROFILE_BSPLINE) {
    double yp = (y - p->origin) / p->spacing;
    return f * fog_profile_bspline_value(p, (int)floor(yp - fog_knot_offset(p->degree)), yp);
  }
  return f;
}

double fog_extinction_point(const fog_volume *v, const transform_grid *g, const double p[3]) {
  double lo[3], hi[3];
  fog_volume_box(v, lo, hi);
  for (int a = 0; a < 3; a++)
    if (!(p[a] >= lo[a] && p[a] <= hi[a])) return 0.0;
  static const double none[3] = {0, 0, 0};
  return fog_extinction(v) * fog_extinction_at(v, g, p, none, 0.0);
}

double fog_optical_depth_march(const fog_volume *v, const transform_grid *g,
                               const double camera[3], const double dir[3], double t_start,
                               double t_stop, int steps, double jitter) {
  double t0, t1;
  if (!fog_box_entry_exit(v, camera, dir, &t0, &t1)) return 0.0;
  if (t0 < t_start) t0 = t_start;
  if (t1 > t_stop) t1 = t_stop;
  if (!(t0 < t1) || steps < 1) return 0.0;
  double dt = (t1 - t0) / steps, sum = 0.0;
  for (int i = 0; i < steps; i++) sum += fog_extinction_at(v, g, camera, dir, t0 + (i + jitter) * dt);
  return fog_extinction(v) * sum * dt;
}

double fog_march_jitter(unsigned px, unsigned py_gl, unsigned frame) {
  /* Integer hash (the shader's fog_hash): same bits on CPU and GPU. */
  uint32_t h = px * 1973u + py_gl * 9277u + frame * 26699u;
  h = (h ^ (h >> 16)) * 0x7feb352du;
  h = (h ^ (h >> 15)) * 0x846ca68bu;
  h ^= h >> 16;
  return (double)(h >> 8) * (1.0 / 16777216.0);
}

/* ---- LOD by distance (docs/integral.md) -------------------------------------------------------- */

double fog_lod_ray_length(const fog_volume *v, const double camera[3], const double dir[3],
                          double t_surface) {
  double t0, t1;
  if (!fog_box_entry_exit(v, camera, dir, &t0, &t1) || t1 <= 0.0) return 0.0;
  return t1 < t_surface ? t1 : t_surface;
}

/* One grid over [t_start, t_stop]: the exact walk (steps == 0) or the marcher. */
static double fog_grid_integral(const fog_volume *v, const transform_grid *g,
                                const double camera[3], const double dir[3], double t_start,
                                double t_stop, int steps, double jitter) {
  if (steps > 0) return fog_optical_depth_march(v, g, camera, dir, t_start, t_stop, steps, jitter);
  return fog_optical_depth(v, g, camera, dir, t_start, t_stop);
}

static double fog_lod_integral(const fog_volume *v, const fog_lod *lod, fog_lod_method method,
                               const double camera[3], const double dir[3], double t_surface,
                               int steps, double jitter) {
  double op = fog_lod_ray_length(v, camera, dir, t_surface);
  if (op <= 0.0) return 0.0;
  int J = lod->levels;
  if (method == FOG_LOD_SUM_OF_DETAILS) {
    /* Giroud & Biri §4.4: A_0 over the whole ray, detail band l up to d_l = ||OP|| mu^l. */
    double sum = fog_grid_integral(v, &lod->approx[0], camera, dir, 0.0, op, steps, jitter);
    double d_l = op;
    for (int l = 1; l <= J; l++) {
      d_l *= lod->mu;
      if (d_l <= 0.0) break;
      sum += fog_grid_integral(v, &lod->detail[l - 1], camera, dir, 0.0, d_l, steps, jitter);
    }
    return sum;
  }
  /* Approximation switching: segment (d_{l+1}, d_l] sees A_l; A_0 beyond d_1, A_J before d_J. */
  double sum = 0.0, far = op, d_l = op;
  for (int l = 0; l < J; l++) {
    double near = d_l * lod->mu; /* d_{l+1} */
    if (far > near)
      sum += fog_grid_integral(v, &lod->approx[l], camera, dir, near, far, steps, jitter);
    far = near;
    d_l = near;
  }
  if (far > 0.0) sum += fog_grid_integral(v, &lod->approx[J], camera, dir, 0.0, far, steps, jitter);
  return sum;
}

double fog_optical_depth_lod(const fog_volume *v, const fog_lod *lod, fog_lod_method method,
                             const double camera[3], const double dir[3], double t_surface) {
  return fog_lod_integral(v, lod, method, camera, dir, t_surface, 0, 0.0);
}

double fog_optical_depth_lod_march(const fog_volume *v, const fog_lod *lod,
                                   fog_lod_method method, const double camera[3],
                                   const double dir[3], double t_surface, int steps,
                                   double jitter) {
  return fog_lod_integral(v, lod, method, camera, dir, t_surface, steps < 1 ? 1 : steps, jitter);
}

/* Extinction is never negative: an optical depth below 0 (signed detail bands summed,
 * ringing) is no fog, not light made (the GL pass takes the same). */
double fog_transmittance(double optical_depth) { return exp(-fmax(optical_depth, 0.0)); }

void fog_blend(double tau, const double surface[3], const double fog_colour[3], double out[3]) {
  /* Giroud & Biri eq. 4: L(O) = tau(O,P) L(P) + L_fog (1 - tau(O,P)). */
  for (int c = 0; c < 3; c++) out[c] = tau * surface[c] + fog_colour[c] * (1.0 - tau);
}
