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

long fog_rbf_emitter_newest(const fog_rbf_emitter *e, double time) {
  /* k0 = count puffs are born before t = 0, so the stream is full from the start */
  return (long)floor(time * e->rate + 1e-9) + fog_rbf_emitter_count(e);
}

double fog_rbf_emitter_birth(const fog_rbf_emitter *e, long k) {
  return (double)(k - fog_rbf_emitter_count(e)) / e->rate;
}

void fog_rbf_emitter_start(const fog_rbf_emitter *e, long k, double start[3]) {
  uint64_t state = e->seed ^ mix((uint64_t)k);
  double offset[3], n2;
  do { /* a point in the unit ball, by rejection */
    for (int a = 0; a < 3; a++) offset[a] = 2.0 * unit(&state) - 1.0;
    n2 = offset[0] * offset[0] + offset[1] * offset[1] + offset[2] * offset[2];
  } while (n2 > 1.0);
  for (int a = 0; a < 3; a++) start[a] = e->position[a] + e->spread * offset[a];
}

void fog_rbf_emitter_shape(const fog_rbf_emitter *e, double age, fog_rbf *g) {
  g->radius = sqrt(e->radius * e->radius + 4.0 * e->diffusion * age);
  const double growth = e->radius / g->radius;
  double fade = (e->lifetime - age) / (0.2 * e->lifetime);
  fade = fade >= 1.0 ? 1.0 : fade <= 0.0 ? 0.0 : fade * fade * (3.0 - 2.0 * fade);
  g->density = e->density * growth * growth * growth * fade; /* mass: density r^3 */
}

int fog_rbf_emitter_puffs(const fog_rbf_emitter *e, double time, fog_rbf *out, int capacity) {
  const int count = fog_rbf_emitter_count(e);
  if (count > capacity) return -1;
  /* the puffs alive at time: born in (time - lifetime, time] */
  const long newest = fog_rbf_emitter_newest(e, time);
  for (int i = 0; i < count; i++) {
    const long k = newest - (count - 1) + i;
    const double age = time - fog_rbf_emitter_birth(e, k);
    fog_rbf *g = &out[i];
    fog_rbf_emitter_start(e, k, g->centre);
    for (int a = 0; a < 3; a++) g->centre[a] += e->wind[a] * age;
    fog_rbf_emitter_shape(e, age, g);
  }
  return count;
}
