/* Designed fog: density fields made from formulas rather than simulated or imported.
 * (Part of the sim library; include "sim/sim.h".)
 *
 *  - Perlin turbulence: Perlin's improved gradient noise (K. Perlin, "Improving Noise",
 *    SIGGRAPH 2002) summed over octaves as turbulence, T(p) = Σ_{o<octaves} |n(2^o p)| / 2^o
 *    (Perlin 1985), animated by translating the noise domain with a constant velocity
 *    (Zdrojewska, "Real time rendering of heterogenous fog based on the graphics hardware
 *    acceleration", CESCG 2004: fog density = turbulence(p - v t)).
 *  - Gaussian blobs: a sum of radial basis functions c·exp(-‖x - b‖² / (2σ²)) (the RBF fog
 *    of Zhou et al., "Fogshop", 2007, with a_i² = 1/(2σ_i²)), splatted into a fogmap.
 *
 * Coordinates are in fogmap cells: cell (x, z) sits at position (x, z), so a blob at
 * b = (10, 20) peaks exactly on cell (10, 20). Filling a fogmap never allocates, so both
 * can run per frame. */
#ifndef FOGPIPE_SIM_DESIGNED_FOG_H
#define FOGPIPE_SIM_DESIGNED_FOG_H

#include <signal.h>
#include <stdint.h>

#include "sim/fogmap.h"

/* The noise's permutation: P[i] for i in 0..511 (the 256-entry table repeated, so hashes
 * need no wrap-around). */
typedef struct perlin_noise {
  uint8_t perm[512];
} perlin_noise;

/* Seed 0 gives Perlin's reference permutation (the table in his 2002 Java code, so
 * perlin_noise3 matches ImprovedNoise.noise); other seeds a Fisher-Yates shuffle of 0..255
 * driven by splitmix64(seed): deterministic on every platform. */
void perlin_noise_init(perlin_noise *noise, uint64_t seed);

/* Improved noise n(x, y, z) (Perlin 2002): 0 at every integer lattice point, C2 smooth
 * (quintic fade 6t^5 - 15t^4 + 10t^3), |n| <= ~1.04, period 256 in each axis. */
double perlin_noise3(const perlin_noise *noise, double x, double y, double z);

/* Turbulence Σ_{o<octaves} |n(2^o p)| / 2^o (octaves < 1 counts as 1). */
double perlin_turbulence(const perlin_noise *noise, double x, double y, double z, int octaves);

/* Every field is a value (no "0 means default"): start from perlin_fog_desc_default(). */
typedef struct perlin_fog_desc {
  uint64_t seed;        /* permutation seed; 0: Perlin's reference table */
  int octaves;          /* 1 to 30 */
  float feature_size;   /* noise lattice spacing in cells (the largest eddies), > 0 */
  float velocity[2];    /* translation of the noise in cells per unit time (x, z) */
  float time;           /* animation time: samples turbulence(p - velocity * time) */
  float slice;          /* the noise's third coordinate (in lattice units) */
  float slice_rate;     /* slice change per unit time: the fog also evolves, not only drifts */
  float gain;           /* density = base + gain * turbulence, > 0 */
  float base;           /* constant density added everywhere (>= 0) */
  /* Set by the caller (its SIGINT/SIGTERM handler) to stop between rows: the call fails,
   * "stopped", the map part written (NULL: runs to the end). A 16384² map of 30 octaves
   * takes minutes. */
  const volatile sig_atomic_t *stop;
} perlin_fog_desc;

/* 4 octaves, eddies of 32 cells, gain 1, slice 1/3 (off every octave's lattice planes);
 * no base, still, seed 0. */
perlin_fog_desc perlin_fog_desc_default(void);

/* Overwrites every cell of map with base + gain * T((x - vx t) / s, (z - vz t) / s,
 * slice + slice_rate t). Fails (map untouched) on octaves outside 1..30, a feature size or
 * gain that is not positive, a negative base, non-finite parameters, or an empty map. */
int designed_fog_perlin(fogmap *map, const perlin_fog_desc *desc, fog_error *err);

/* One Gaussian: peak * exp(-((x - x0)² + (z - z0)²) / (2 sigma²)), in cells. */
typedef struct fog_blob {
  float x, z;   /* centre b */
  float sigma;  /* > 0 */
  float peak;   /* c >= 0 */
} fog_blob;

/* Every field is a value (no "0 means default"): start from blob_fog_desc_default(). */
typedef struct blob_fog_desc {
  const fog_blob *blobs;
  int blob_count;
  int add;       /* 0: the map is overwritten with the blob sum; 1: blobs are added to it */
  float cutoff;  /* > 0: each blob is evaluated within cutoff * sigma of its centre (beyond
                  * it exp(-cutoff²/2) is dropped); the default 6 drops a relative 1.5e-8 */
  const volatile sig_atomic_t *stop; /* as perlin_fog_desc's: looked at between rows */
} blob_fog_desc;

/* The cutoff that drops a relative 1.5e-8 of each blob. */
#define BLOB_FOG_CUTOFF 6.0f
/* No blobs, overwrite, cutoff BLOB_FOG_CUTOFF. */
blob_fog_desc blob_fog_desc_default(void);

/* Splats the blobs into map (point samples at cell positions). The total over an infinite
 * grid is 2πσ²c per blob up to an exp(-2π²σ²) aliasing term (Poisson summation), so mass
 * is conserved for sigma >= 1 cell. Fails (map untouched) on sigma <= 0, negative peak,
 * or non-finite values. */
int designed_fog_blobs(fogmap *map, const blob_fog_desc *desc, fog_error *err);

/* Multiplies map by other, cell by cell (same size): turbulence modulated by blobs. */
int designed_fog_multiply(fogmap *map, const fogmap *other, fog_error *err);

#endif
