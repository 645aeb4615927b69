/* The simulation's random numbers: splitmix64 (Steele, Lea, Flood 2014, "Fast Splittable
 * Pseudorandom Number Generators", OOPSLA; constants from Vigna's reference code). Our
 * own generator, not rand(), so a seed gives the same sequence on every platform. */
#ifndef FOGPIPE_SIM_FLUID_RNG_H
#define FOGPIPE_SIM_FLUID_RNG_H

#include <stdint.h>

typedef struct fluid_rng {
  uint64_t state;
} fluid_rng;

static inline uint64_t fluid_rng_next(fluid_rng *rng) {
  uint64_t z = (rng->state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/* Uniform in [0, 1) with 53 random bits. */
static inline double fluid_rng_uniform(fluid_rng *rng) {
  return (double)(fluid_rng_next(rng) >> 11) * (1.0 / 9007199254740992.0);
}

#endif
