/* Animated Perlin turbulence fog, per pixel (FOG_MODEL_PERLIN; Zdrojewska, "Real time
 * rendering of heterogenous fog based on the graphics hardware acceleration", CESCG 2004,
 * §2-3; docs/integral.md, Perlin turbulence fog).
 *
 * The density inside the fog's box [lo, hi] (0 outside) at time s:
 *   K(p, s) = extinction e^{-(y - y0)/H} T(p, s),   T(p, s) = sum_{i<octaves} 2^{-i} N_i(u_i)
 *   u_i = (p - wind_i s) 2^i texels_per_lattice / feature_size        (texel coordinates)
 * N_i is octave i's texture: |n_i| of Perlin's improved noise (Perlin 2002) with its own
 * permutation, periodic over `size` texels (size / FOG_PERLIN_TEXELS_PER_LATTICE lattice
 * cells), sampled at the texels and interpolated trilinearly. Each octave drifts with its
 * own wind (her animation: the octaves slide over one another).
 *
 * Because N_i is trilinear between texels, K along a ray is a cubic times an exponential
 * inside each texel cell of each octave: fog_perlin_optical_depth walks every octave's cells
 * (a 3D DDA) with 4 Gauss-Legendre nodes per piece, pieces cut so that the exponential
 * changes by at most e^{1/2} over one (its relative error then < 1e-7). The paper's
 * variant samples T once, at the ray's last point in the fog (the surface, or where the ray
 * leaves the box), and scales the height fog's closed form over the ray's stretch in the
 * box by it. */
#ifndef FOGPIPE_RENDER_FOG_PERLIN_H
#define FOGPIPE_RENDER_FOG_PERLIN_H

#include <stdbool.h>
#include <stdint.h>

#include "transform/fog_error.h"

#define FOG_PERLIN_MAX_OCTAVES 6
#define FOG_PERLIN_TEXELS_PER_LATTICE 4
#define FOG_PERLIN_MIN_SIZE 8
#define FOG_PERLIN_MAX_SIZE 128

typedef enum fog_perlin_integral {
  FOG_PERLIN_EXACT = 0, /* the ray integral, exact per texel cell */
  FOG_PERLIN_PAPER,     /* Zdrojewska: T sampled once, at the ray's last point in the fog */
} fog_perlin_integral;

/* Every field is a value: start from fog_perlin_desc_default(). */
typedef struct fog_perlin_desc {
  uint64_t seed;       /* octave i's permutation: splitmix64(seed + i) */
  int octaves;         /* 1..FOG_PERLIN_MAX_OCTAVES */
  int size;            /* texels a side, a power of two in FOG_PERLIN_MIN_SIZE..MAX_SIZE */
  double feature_size; /* world units of octave 0's lattice cell (its largest eddies), > 0 */
  double wind[FOG_PERLIN_MAX_OCTAVES][3]; /* octave i's drift, world units per second */
  double lo[3], hi[3]; /* the fog's box, lo < hi */
} fog_perlin_desc;

/* 3 octaves of 32^3 texels, eddies of 48 units, each octave its own wind; the box
 * [-128, 128] x [0, 24] x [-128, 128]. */
fog_perlin_desc fog_perlin_desc_default(void);

/* The octaves' textures: octave i's texel (x, y, z) at texels[((i size + z) size + y) size
 * + x] (the GL layout: one R32F 3D texture size x size x (size octaves)). */
typedef struct fog_perlin {
  fog_perlin_desc desc;
  float *texels;
  /* T's mean over the texture's period: sum_i 2^{-i} (the mean of octave i's texels; the
   * trilinear interpolant of periodic samples has their mean) */
  double mean_turbulence;
} fog_perlin;

/* Fills the textures. Fails naming the field on a bad descriptor (out-of-range octaves or
 * size, a feature size <= 0, an empty box, non-finite values). */
int fog_perlin_create(fog_perlin *perlin, const fog_perlin_desc *desc, fog_error *err);
void fog_perlin_destroy(fog_perlin *perlin);

/* Octave i's texel coordinates per world unit: 2^i TEXELS_PER_LATTICE / feature_size. */
double fog_perlin_octave_scale(const fog_perlin *perlin, int octave);
/* T(p, time): the turbulence in [0, ~2), without the height factor. */
double fog_perlin_turbulence(const fog_perlin *perlin, double time, const double p[3]);

/* The height fog over the turbulence: extinction, y0 and the scale height H > 0. */
typedef struct fog_perlin_medium {
  double extinction, y0, scale_height;
  double time;
  fog_perlin_integral integral;
} fog_perlin_medium;

/* K at p (0 outside the box). */
double fog_perlin_extinction_at(const fog_perlin *perlin, const fog_perlin_medium *medium,
                                const double p[3]);
/* The optical depth from o along unit d up to length (HUGE_VAL: through the box), by
 * medium->integral: exact per texel cell, or the paper's single sample. */
double fog_perlin_optical_depth(const fog_perlin *perlin, const fog_perlin_medium *medium,
                                const double o[3], const double d[3], double length);

/* The light a view ray gathers, per piece of the exact walk (docs/light.md, per-piece
 * light): S = int_0^L tau(u) K(u) f(u) du with f = light(user, point) in [0, 1] (T_s V),
 * every octave walked at once, so that the pieces lie between consecutive texel planes of
 * any octave (cut where the height exponent moves by 1/2), and `nodes` (1..4) Gauss-Legendre
 * nodes on each. tau at a node is e^{-(D + d)}: D the walk's running depth at the piece's
 * start, d the integral from there to the node of the polynomial through the piece's K at
 * its nodes. *depth receives the walk's optical depth over [0, length] (the nodes' sum: the
 * exact integral for nodes >= 2 up to the exponential's share, as the depth walk). The
 * walk stops past depth_limit. */
typedef double (*fog_point_light_fn)(const void *user, const double x[3]);
#define FOG_PIECE_MAX_NODES 4
/* The n-node Gauss-Legendre rule on [-1, 1] (n = 1..FOG_PIECE_MAX_NODES): nodes x, weights
 * w, and partial[j][k] = int_{-1}^{x_j} L_k(s) ds, L_k the Lagrange basis on the nodes: the
 * integral up to node j of the polynomial through values at the nodes is
 * sum_k partial[j][k] v_k. */
void fog_gauss_rule(int n, double x[FOG_PIECE_MAX_NODES], double w[FOG_PIECE_MAX_NODES],
                    double partial[FOG_PIECE_MAX_NODES][FOG_PIECE_MAX_NODES]);
/* One piece of a per-piece light walk (fog_gauss_rule's n nodes, half-length h, K[j] and the
 * light f[j] at the nodes): returns int tau K f over the piece as e^{-*depth}(1 - e^{-dD})
 * times f's mean weighted by tau K at the nodes (tau at node j e^{-h sum_q partial[j][q]
 * K[q]} within the piece), and adds the piece's depth dD (the nodes' sum) to *depth. */
double fog_piece_light(int n, const double w[FOG_PIECE_MAX_NODES],
                       const double partial[FOG_PIECE_MAX_NODES][FOG_PIECE_MAX_NODES], double h,
                       const double K[FOG_PIECE_MAX_NODES], const double f[FOG_PIECE_MAX_NODES],
                       double *depth);
double fog_perlin_light_integral(const fog_perlin *perlin, const fog_perlin_medium *medium,
                                 const double o[3], const double d[3], double length,
                                 int nodes, double depth_limit, fog_point_light_fn light,
                                 const void *user, double *depth);

#endif
