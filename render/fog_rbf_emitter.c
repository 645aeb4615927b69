/* Puffs of Gaussian fog from an emitter (render/fog_rbf_emitter.h). */
#include "render/fog_rbf_emitter.h"

#include <math.h>

int fog_rbf_emitter_count(const fog_rbf_emitter *e) {
  return (int)ceil(e->rate * e->lifetime - 1e-9);
}

/* splitmix64: puff k's own random numbers, whatever order puffs are asked for in. */
static uint64_t mix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

static double unit(uint64_t *state) { /* [0, 1) */
  *state = mix(*state);
  return (double)(*state >> 11) / 9007199254740992.0;
}

int fog_rbf_emitter_puffs(const fog_rbf_emitter *e, double time, fog_rbf *out, int capacity) {
  const int count = fog_rbf_emitter_count(e);
  if (count > capacity) return -1;
  const long k0 = count; /* puff k is born at (k - k0) / rate: k0 of them before t = 0 */
  /* the puffs alive at time: born in (time - lifetime, time] */
  const long newest = (long)floor(time * e->rate + 1e-9) + k0;
  for (int i = 0; i < count; i++) {
    const long k = newest - (count - 1) + i;
    const double born = (double)(k - k0) / e->rate, age = time - born;
    uint64_t state = e->seed ^ mix((uint64_t)k);
    double offset[3], n2;
    do { /* a point in the unit ball, by rejection */
      for (int a = 0; a < 3; a++) offset[a] = 2.0 * unit(&state) - 1.0;
      n2 = offset[0] * offset[0] + offset[1] * offset[1] + offset[2] * offset[2];
    } while (n2 > 1.0);
    fog_rbf *g = &out[i];
    for (int a = 0; a < 3; a++)
      g->centre[a] = e->position[a] + e->spread * offset[a] + e->wind[a] * age;
    g->radius = sqrt(e->radius * e->radius + 4.0 * e->diffusion * age);
    const double growth = e->radius / g->radius;
    double fade = (e->lifetime - age) / (0.2 * e->lifetime);
    fade = fade >= 1.0 ? 1.0 : fade <= 0.0 ? 0.0 : fade * fade * (3.0 - 2.0 * fade);
    g->density = e->density * growth * growth * growth * fade; /* mass: density r^3 */
  }
  return count;
}
