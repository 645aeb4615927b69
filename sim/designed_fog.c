/* Designed fog: Perlin turbulence and Gaussian blobs (see designed_fog.h for the papers). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sim/designed_fog.h"

/* Perlin's reference permutation ("Improving Noise", 2002, ImprovedNoise.java). */
static const uint8_t reference_permutation[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,
    103, 30,  69,  142, 8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,
    0,   26,  197, 62,  94,  252, 219, 203, 117, 35,  11,  32,  57,  177, 33,  88,  237, 149,
    56,  87,  174, 20,  125, 136, 171, 168, 68,  175, 74,  165, 71,  134, 139, 48,  27,  166,
    77,  146, 158, 231, 83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,  55,  46,
    245, 40,  244, 102, 143, 54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187,
    208, 89,  18,  169, 200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186,
    3,   64,  52,  217, 226, 250, 124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212,
    207, 206, 59,  227, 47,  16,  58,  17,  182, 189, 28,  42,  223, 183, 170, 213, 119, 248,
    152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,   129, 22,  39,  253,
    19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,
    242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107,
    49,  192, 214, 31,  181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,
    150, 254, 138, 236, 205, 93,  222, 114, 67,  29,  24,  72,  243, 141, 128, 195, 78,  66,
    215, 61,  156, 180};

/* splitmix64 (Steele, Lea & Flood 2014): a well-mixed sequence from any seed. */
static uint64_t splitmix64(uint64_t *state) {
  uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

void perlin_noise_init(perlin_noise *noise, uint64_t seed) {
  uint8_t p[256];
  if (seed == 0) {
    memcpy(p, reference_permutation, sizeof p);
  } else {
    for (int i = 0; i < 256; i++) p[i] = (uint8_t)i;
    uint64_t state = seed;
    for (int i = 255; i > 0; i--) { /* Fisher-Yates */
      int j = (int)(splitmix64(&state) % (uint64_t)(i + 1));
      uint8_t t = p[i];
      p[i] = p[j];
      p[j] = t;
    }
  }
  for (int i = 0; i < 512; i++) noise->perm[i] = p[i & 255];
}

/* Perlin 2002: the quintic fade 6t^5 - 15t^4 + 10t^3 (zero 1st and 2nd derivatives at
 * t = 0, 1, so the noise is C2 across cells). */
static double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
static double lerp(double t, double a, double b) { return a + t * (b - a); }

/* Perlin 2002: the dot product with one of 12 cube-edge gradients (16 with 4 repeated),
 * chosen by the low 4 bits of the hash. */
static double grad(int hash, double x, double y, double z) {
  int h = hash & 15;
  double u = h < 8 ? x : y;
  double v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

double perlin_noise3(const perlin_noise *noise, double x, double y, double z) {
  const uint8_t *p = noise->perm;
  double fx = floor(x), fy = floor(y), fz = floor(z);
  int X = (int)((long long)fx & 255), Y = (int)((long long)fy & 255),
      Z = (int)((long long)fz & 255);
  x -= fx;
  y -= fy;
  z -= fz;
  double u = fade(x), v = fade(y), w = fade(z);
  int A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z;
  int B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z;
  return lerp(w,
              lerp(v, lerp(u, grad(p[AA], x, y, z), grad(p[BA], x - 1, y, z)),
                   lerp(u, grad(p[AB], x, y - 1, z), grad(p[BB], x - 1, y - 1, z))),
              lerp(v, lerp(u, grad(p[AA + 1], x, y, z - 1), grad(p[BA + 1], x - 1, y, z - 1)),
                   lerp(u, grad(p[AB + 1], x, y - 1, z - 1),
                        grad(p[BB + 1], x - 1, y - 1, z - 1))));
}

double perlin_turbulence(const perlin_noise *noise, double x, double y, double z, int octaves) {
  if (octaves < 1) octaves = 1;
  double sum = 0.0, frequency = 1.0;
  for (int o = 0; o < octaves; o++) {
    sum += fabs(perlin_noise3(noise, frequency * x, frequency * y, frequency * z)) / frequency;
    frequency *= 2.0;
  }
  return sum;
}

/* Slice 1/3: octave o samples the plane 2^o / 3, whose fraction is 1/3 or 2/3 for every o,
 * a third of a lattice cell from the lattice planes. On a plane (slice 0) improved noise is
 * 0 at every lattice point of every octave, so the turbulence was 0 on a regular grid
 * (one point every feature size), and the gradients without a z part drew straight ridges
 * along the axes there. */
perlin_fog_desc perlin_fog_desc_default(void) {
  return (perlin_fog_desc){.octaves = 4, .feature_size = 32.0f, .gain = 1.0f,
                           .slice = 1.0f / 3.0f};
}

int designed_fog_perlin(fogmap *map, const perlin_fog_desc *desc, fog_error *err) {
  const perlin_fog_desc d = *desc;
  const int octaves = d.octaves;
  const double size = d.feature_size, gain = d.gain;
  if (!map || !map->density || map->width <= 0 || map->height <= 0)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "Perlin fog: the fogmap is empty");
  if (octaves < 1 || octaves > 30)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "Perlin fog: octaves must be 1 to 30");
  if (!(size > 0.0) || !isfinite(size))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "Perlin fog: feature size must be positive and finite");
  if (!(gain > 0.0) || !isfinite(gain) || !(d.base >= 0.0f) || !isfinite(d.base))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "Perlin fog: gain must be positive and base >= 0, both finite");
  if (!isfinite(d.velocity[0]) || !isfinite(d.velocity[1]) || !isfinite(d.time) ||
      !isfinite(d.slice) || !isfinite(d.slice_rate))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "Perlin fog: velocity, time and slice must be finite");
  perlin_noise noise;
  perlin_noise_init(&noise, d.seed);
  /* Zdrojewska: the fog drifts by translating the noise domain, p - v t. The noise repeats
   * every 256 lattice units on each axis (the permutation is indexed & 255, and octave o's
   * 2^o · 256 is a multiple of 256), so the shift is taken modulo that period, exactly
   * (fmod): a drift of 1e30 cells rounded x - v t to one value for every column. */
  const double period = 256.0 * size;
  double shift_x = fmod((double)d.velocity[0] * d.time, period);
  double shift_z = fmod((double)d.velocity[1] * d.time, period);
  double slice = fmod((double)d.slice + fmod((double)d.slice_rate * d.time, 256.0), 256.0);
  for (int z = 0; z < map->height; z++) {
    if (d.stop && *d.stop)
      return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "Perlin fog: stopped at row %d of %d",
                      z, map->height);
    double pz = (z - shift_z) / size;
    float *row = map->density + (size_t)z * (size_t)map->width;
    for (int x = 0; x < map->width; x++) {
      double px = (x - shift_x) / size;
      row[x] = (float)(d.base + gain * perlin_turbulence(&noise, px, pz, slice, octaves));
    }
  }
  return 0;
}

blob_fog_desc blob_fog_desc_default(void) {
  return (blob_fog_desc){.blobs = NULL, .blob_count = 0, .add = 0, .cutoff = BLOB_FOG_CUTOFF};
}

int designed_fog_blobs(fogmap *map, const blob_fog_desc *desc, fog_error *err) {
  const blob_fog_desc d = desc ? *desc : blob_fog_desc_default();
  const double cutoff = d.cutoff;
  if (!map || !map->density || map->width <= 0 || map->height <= 0)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "Gaussian blobs: the fogmap is empty");
  if (d.blob_count < 0 || (d.blob_count > 0 && !d.blobs))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "Gaussian blobs: no blob array given");
  if (!(cutoff > 0.0) || !isfinite(cutoff))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "Gaussian blobs: cutoff must be positive and finite");
  for (int i = 0; i < d.blob_count; i++) {
    const fog_blob *b = &d.blobs[i];
    if (!(b->sigma > 0.0f) || !isfinite(b->sigma) || !(b->peak >= 0.0f) ||
        !isfinite(b->peak) || !isfinite(b->x) || !isfinite(b->z)) {
      if (err)
        fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                 "Gaussian blob %d: sigma must be > 0, peak >= 0, all finite (got centre "
                 "(%g, %g), sigma %g, peak %g)",
                 i, (double)b->x, (double)b->z, (double)b->sigma, (double)b->peak);
      return 1;
    }
  }
  if (!d.add)
    memset(map->density, 0, sizeof(float) * (size_t)map->width * (size_t)map->height);
  for (int i = 0; i < d.blob_count; i++) {
    const fog_blob *b = &d.blobs[i];
    /* Fogshop's RBF c·exp(-a²‖x-b‖²) with a² = 1/(2σ²), within cutoff·σ of b. */
    double inv_two_sigma2 = 1.0 / (2.0 * (double)b->sigma * b->sigma);
    double reach = cutoff * b->sigma, reach2 = reach * reach; /* a disc of radius reach */
    /* the cells within reach, clipped to the map (decided in double: no int overflow) */
    double lo_x = fmax(0.0, ceil(b->x - reach)), hi_x = fmin(map->width - 1.0, floor(b->x + reach));
    double lo_z = fmax(0.0, ceil(b->z - reach)), hi_z = fmin(map->height - 1.0, floor(b->z + reach));
    if (lo_x > hi_x || lo_z > hi_z) continue;
    int x0 = (int)lo_x, x1 = (int)hi_x, z0 = (int)lo_z, z1 = (int)hi_z;
    for (int z = z0; z <= z1; z++) {
      if (d.stop && *d.stop)
        return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "Gaussian blobs: stopped at blob %d",
                        i);
      double dz = z - (double)b->z;
      float *row = map->density + (size_t)z * (size_t)map->width;
      for (int x = x0; x <= x1; x++) {
        double dx = x - (double)b->x, r2 = dx * dx + dz * dz;
        if (r2 <= reach2) row[x] += (float)(b->peak * exp(-r2 * inv_two_sigma2));
      }
    }
  }
  return 0;
}

int designed_fog_multiply(fogmap *map, const fogmap *other, fog_error *err) {
  if (!map || !other || !map->density || !other->density || map->width != other->width ||
      map->height != other->height)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "fogmap multiply: both fogmaps must exist and have the same size");
  size_t count = (size_t)map->width * (size_t)map->height;
  for (size_t i = 0; i < count; i++) map->density[i] *= other->density[i];
  return 0;
}
