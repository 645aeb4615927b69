/* Semi-Lagrangian advection on a periodic 2D grid: the density (and velocity) transport
 * of the fluid simulation. (Part of the sim library; include "sim/sim.h".)
 *
 * Grid convention: field[z * width + x], cell (x, z) sits at the integer point (x, z);
 * the domain is periodic with period width in x and height in z. Velocities are in cells
 * per second, dt in seconds.
 *
 * Every scheme traces the departure point of each cell back along the velocity with a
 * midpoint (RK2) step, x_d = x - dt u(x - dt/2 u(x)) (Stam 1999 "Stable Fluids" §2.2
 * traces with a single Euler step; RK2 is the usual improvement, Bridson 2015 §3.1), and
 * interpolates the old field there. All schemes are monotone in the sense that matters
 * here: the new value lies within the min/max of the old values around the departure
 * point, so fields never go below their old minimum (0 for density) nor above the old
 * maximum, at any CFL number. */
#ifndef FOGPIPE_SIM_ADVECT_H
#define FOGPIPE_SIM_ADVECT_H

typedef enum advect_scheme {
  /* Bilinear interpolation at the departure point (Stam 1999). First order, diffusive. */
  ADVECT_BILINEAR = 1,
  /* Tensor-product Catmull-Rom cubic clamped to the min/max of the 2x2 cell around the
   * departure point (the "clamp to the neighbourhood" limiter of Selle et al. 2008 §4
   * applied to the cubic): third order where smooth, no new extrema. */
  ADVECT_MONOTONE_CUBIC = 2,
  /* MacCormack form of BFECC (Selle, Fedkiw, Kim, Liu, Osher 2008, "An Unconditionally
   * Stable MacCormack Method", J. Sci. Comput. 35, eq. 5-7) over the clamped cubic: a
   * forward and a backward pass, phi = phi_hat + (phi - phi_bar)/2, clamped to the
   * min/max of the four old values around the departure point (their §4 limiter). The
   * most accurate scheme here; about twice the cost of ADVECT_MONOTONE_CUBIC. */
  ADVECT_MACCORMACK = 3,
  /* The same MacCormack correction over bilinear passes (Selle et al.'s own setting):
   * second order and cheaper, but on smooth fields less accurate than the limited cubic
   * (its remaining error is a phase lag; docs/simulation.md has the numbers). */
  ADVECT_MACCORMACK_BILINEAR = 4,
} advect_scheme;

/* The fixed inputs of one advection pass. */
typedef struct advect_pass {
  int width, height;              /* grid size, both >= 4 */
  const float *velocity_x;        /* width*height, cells per second */
  const float *velocity_z;
  float dt;                       /* seconds */
  advect_scheme scheme;
  /* The MacCormack schemes only: advect_scratch_floats(width, height, count) floats
   * (the forward results and the departure points). Unused (may be NULL) otherwise. */
  float *scratch;
  /* 1: the portable scalar loop even where the CPU has AVX2 (the clamped cubic's 8-cell
   * gather loop gives the same bits; tests compare the two). */
  int portable;
} advect_pass;

/* Padding between arrays that live in one block, in floats (17 cache lines). With
 * power-of-two grids, arrays exactly width*height apart map every access of a cell to
 * the same cache set (and 4K-alias on x86); a pass touching ~10 such arrays then thrashes
 * L1. Measured: bilinear 3-field advection at 512² 14.9 -> 11.2 ms with the padding. */
#define ADVECT_ARRAY_PAD 272

/* Floats of scratch the MacCormack schemes need for `count` fields. */
long advect_scratch_floats(int width, int height, int count);

/* Advects `count` fields (1..4) by the same velocity in one fused pass: the departure
 * point of each cell is traced once and every field is interpolated there.
 * sources[f] -> destinations[f]; a destination must not alias any source or the
 * velocity. Never allocates. */
void advect_fields(const advect_pass *pass, int count, const float *const *sources,
                   float *const *destinations);

/* The interpolators, exposed for tests: periodic bilinear and clamped cubic sample of a
 * field at the real-valued grid point (x, z) (any real x, z; wrapped periodically). */
float advect_sample_bilinear(const float *field, int width, int height, float x, float z);
float advect_sample_monotone_cubic(const float *field, int width, int height, float x,
                                   float z);

#endif
