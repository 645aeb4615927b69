/* Perlin improved noise (Perlin 2002) and turbulence fog: the reference value of Perlin's
 * own Java code, zero at every lattice point, continuity with a derived Lipschitz bound,
 * seed determinism, boundedness, and Zdrojewska's animation as an exact translation. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sim/designed_fog.h"
#include "sim/fogmap.h"
#include "test_util.h"

static uint64_t rng_state = 0x1234567u;
static double uniform(double lo, double hi) { /* xorshift64*, independent of the code */
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  uint64_t r = rng_state * 2685821657736338717ull;
  return lo + (hi - lo) * (double)(r >> 11) / 9007199254740992.0;
}

static void test_permutation(void) {
  uint64_t seeds[] = {0, 1, 2, 42, 0xdeadbeefull};
  for (size_t s = 0; s < sizeof seeds / sizeof seeds[0]; s++) {
    perlin_noise n;
    perlin_noise_init(&n, seeds[s]);
    int seen[256] = {0}, ok = 1;
    for (int i = 0; i < 256; i++) seen[n.perm[i]]++;
    for (int i = 0; i < 256; i++) ok &= seen[i] == 1 && n.perm[i + 256] == n.perm[i];
    CHECK(ok, "seed %llu: perm is not a permutation of 0..255 repeated",
          (unsigned long long)seeds[s]);
  }
}

static void test_reference_value(void) {
  /* ImprovedNoise.noise(3.14, 42, 7) with Perlin's table, the value his Java reference
   * implementation prints. */
  perlin_noise n;
  perlin_noise_init(&n, 0);
  double v = perlin_noise3(&n, 3.14, 42.0, 7.0);
  CHECK(fabs(v - 0.13691995878400012) < 1e-15, "noise(3.14, 42, 7) = %.17g", v);
}

static void test_zero_on_lattice(void) {
  uint64_t seeds[] = {0, 7, 12345};
  for (size_t s = 0; s < 3; s++) {
    perlin_noise n;
    perlin_noise_init(&n, seeds[s]);
    int nonzero = 0;
    for (int i = 0; i < 20000; i++) {
      double x = floor(uniform(-600, 600)), y = floor(uniform(-600, 600)),
             z = floor(uniform(-600, 600));
      if (perlin_noise3(&n, x, y, z) != 0.0) nonzero++;
    }
    CHECK(nonzero == 0, "seed %llu: %d lattice points are not 0", (unsigned long long)seeds[s],
          nonzero);
  }
}

static void test_continuity(void) {
  /* |dn/dx| <= max fade' (15/8) * max |g_b - g_a| (4) + Σ weights * |dg/dx| (1) = 8.5 */
  const double lipschitz = 8.5, h = 1e-7;
  perlin_noise n;
  perlin_noise_init(&n, 99);
  double worst = 0.0;
  for (int i = 0; i < 200000; i++) {
    double p[3] = {uniform(-300, 300), uniform(-300, 300), uniform(-300, 300)};
    if (i % 4 == 0) p[i / 4 % 3] = round(p[i / 4 % 3]) - h / 2; /* straddle a cell face */
    double v = perlin_noise3(&n, p[0], p[1], p[2]);
    for (int axis = 0; axis < 3; axis++) {
      double q[3] = {p[0], p[1], p[2]};
      q[axis] += h;
      double ratio = fabs(perlin_noise3(&n, q[0], q[1], q[2]) - v) / h;
      if (ratio > worst) worst = ratio;
    }
  }
  CHECK(worst <= lipschitz * 1.001, "difference quotient %g exceeds the bound %g", worst,
        lipschitz);
  CHECK(worst > 1.0, "difference quotients all tiny (%g): is the noise flat?", worst);
}

static void test_seed_determinism(void) {
  perlin_noise a, b, c;
  perlin_noise_init(&a, 2024);
  perlin_noise_init(&b, 2024);
  perlin_noise_init(&c, 2025);
  CHECK(!memcmp(a.perm, b.perm, sizeof a.perm), "same seed, different permutation");
  int same = 1, differ = 0;
  for (int i = 0; i < 1000; i++) {
    double x = uniform(-50, 50), y = uniform(-50, 50), z = uniform(-50, 50);
    if (perlin_noise3(&a, x, y, z) != perlin_noise3(&b, x, y, z)) same = 0;
    if (perlin_noise3(&a, x, y, z) != perlin_noise3(&c, x, y, z)) differ++;
  }
  CHECK(same, "same seed gave different noise");
  CHECK(differ > 900, "seeds 2024 and 2025 agree at %d of 1000 points", 1000 - differ);
}

static void test_bounded(void) {
  perlin_noise n;
  perlin_noise_init(&n, 5);
  double max_abs = 0.0, max_turb = 0.0, min_turb = 1e9, sum = 0.0;
  const int samples = 400000;
  for (int i = 0; i < samples; i++) {
    double x = uniform(-256, 256), y = uniform(-256, 256), z = uniform(-256, 256);
    double v = perlin_noise3(&n, x, y, z);
    if (fabs(v) > max_abs) max_abs = fabs(v);
    sum += v;
    double t = perlin_turbulence(&n, x, y, z, 4);
    if (t > max_turb) max_turb = t;
    if (t < min_turb) min_turb = t;
  }
  /* each gradient term is |u| + |v| <= 2 and the weights sum to 1, so |n| <= 2; improved
   * noise in practice stays within about 1.04 */
  CHECK(max_abs <= 1.1, "max |noise| = %g", max_abs);
  CHECK(max_abs > 0.7, "max |noise| only %g: range too small", max_abs);
  CHECK(fabs(sum / samples) < 0.01, "noise mean %g is not ~0", sum / samples);
  CHECK(min_turb >= 0.0 && max_turb <= 1.1 * (1 + 0.5 + 0.25 + 0.125),
        "turbulence range [%g, %g]", min_turb, max_turb);
  /* turbulence is the documented sum */
  double x = 1.3, y = -7.77, z = 0.25;
  double expected = fabs(perlin_noise3(&n, x, y, z)) + fabs(perlin_noise3(&n, 2 * x, 2 * y, 2 * z)) / 2 +
                    fabs(perlin_noise3(&n, 4 * x, 4 * y, 4 * z)) / 4;
  CHECK(fabs(perlin_turbulence(&n, x, y, z, 3) - expected) < 1e-15, "turbulence formula");
}

static void test_fog_animation(void) {
  const int w = 48, h = 40;
  fogmap at0, at_t;
  fog_error err;
  CHECK(fogmap_create(&at0, w, h, &err) == 0 && fogmap_create(&at_t, w, h, &err) == 0, "%s",
        err.message);
  perlin_fog_desc desc = {.seed = 3, .octaves = 4, .feature_size = 12.5f,
                          .velocity = {2.0f, -1.5f}, .gain = 0.7f, .base = 0.05f};
  CHECK(designed_fog_perlin(&at0, &desc, &err) == 0, "%s", err.message);
  desc.time = 4.0f; /* shift (8, -6) cells: the same fog moved by exactly that */
  CHECK(designed_fog_perlin(&at_t, &desc, &err) == 0, "%s", err.message);
  int moved = 1;
  for (int z = 0; z < h - 6; z++)
    for (int x = 8; x < w; x++)
      if (at_t.density[z * w + x] != at0.density[(z + 6) * w + (x - 8)]) moved = 0;
  CHECK(moved, "fog at t = 4 is not the fog at t = 0 translated by velocity * t");

  /* a cell equals base + gain * turbulence at its position */
  perlin_noise n;
  perlin_noise_init(&n, 3);
  double expect = 0.05 + 0.7 * perlin_turbulence(&n, 17 / 12.5, 9 / 12.5, 0.0, 4);
  CHECK(fabs(at0.density[9 * w + 17] - expect) < 1e-6, "cell (17, 9) = %g, expected %g",
        at0.density[9 * w + 17], expect);
  float min = 1e9f;
  for (int i = 0; i < w * h; i++) min = fminf(min, at0.density[i]);
  CHECK(min >= 0.05f, "density below base: %g", min);

  /* bad parameters fail and leave the map alone */
  float before = at0.density[5];
  perlin_fog_desc bad = perlin_fog_desc_default();
  bad.base = -1.0f;
  CHECK(designed_fog_perlin(&at0, &bad, &err) != 0 && strstr(err.message, "base"),
        "negative base accepted: %s", err.message);
  bad = perlin_fog_desc_default();
  bad.feature_size = -2.0f;
  CHECK(designed_fog_perlin(&at0, &bad, &err) != 0 && strstr(err.message, "feature size"),
        "negative feature size accepted");
  /* no "0 means default": zero octaves, size or gain are refused, not replaced */
  bad = perlin_fog_desc_default();
  bad.octaves = 0;
  CHECK(designed_fog_perlin(&at0, &bad, &err) != 0 && strstr(err.message, "octaves"),
        "0 octaves accepted");
  bad = perlin_fog_desc_default();
  bad.gain = 0.0f;
  CHECK(designed_fog_perlin(&at0, &bad, &err) != 0 && strstr(err.message, "gain"),
        "gain 0 accepted");
  CHECK(at0.density[5] == before, "failed call changed the map");
  fogmap_destroy(&at0);
  fogmap_destroy(&at_t);
}

/* The default design's turbulence has no grid of zeros: on a lattice plane (slice 0)
 * every octave's noise is 0 at every lattice point, so the fog was exactly `base` at one
 * point every feature size; the default slice (1/3) lies off every octave's planes. */
static void test_default_slice_off_lattice(void) {
  const int size = 257, feature = 32;
  fogmap map;
  fog_error err;
  CHECK(fogmap_create(&map, size, size, &err) == 0, "%s", err.message);
  perlin_fog_desc desc = perlin_fog_desc_default();
  CHECK(designed_fog_perlin(&map, &desc, &err) == 0, "%s", err.message);
  double all = 0.0, lattice = 0.0;
  int lattice_points = 0, zeros = 0;
  for (int z = 0; z < size; z++)
    for (int x = 0; x < size; x++) {
      double v = map.density[(size_t)z * size + x];
      all += v;
      if (x % feature == 0 && z % feature == 0) {
        lattice += v;
        lattice_points++;
        if (v < 1e-3) zeros++;
      }
    }
  all /= (double)size * size;
  lattice /= lattice_points;
  CHECK(zeros <= lattice_points / 20, "%d of %d lattice points hold no fog", zeros,
        lattice_points);
  CHECK(lattice > 0.4 * all, "mean at the lattice points %g against %g over the map", lattice,
        all);
  /* slice 0 is still there for who asks: zero at every lattice point */
  desc.slice = 0.0f;
  CHECK(designed_fog_perlin(&map, &desc, &err) == 0, "%s", err.message);
  for (int z = 0; z < size; z += feature)
    for (int x = 0; x < size; x += feature)
      CHECK(map.density[(size_t)z * size + x] == 0.0f, "slice 0: (%d, %d) = %g", x, z,
            map.density[(size_t)z * size + x]);
  fogmap_destroy(&map);
}

/* A drift far past the noise's period (256 lattice units an axis) is the drift modulo it:
 * 2^100 cells with feature size 16 (period 4096 = 2^12 cells) is no drift at all, bit for
 * bit; and any long drift is still turbulence across a row (x - v t rounded to one value
 * for every column, a map of constant rows). */
static void test_long_drift(void) {
  const int w = 40, h = 24;
  fogmap still, far;
  fog_error err;
  CHECK(fogmap_create(&still, w, h, &err) == 0 && fogmap_create(&far, w, h, &err) == 0, "%s",
        err.message);
  perlin_fog_desc desc = perlin_fog_desc_default();
  desc.feature_size = 16.0f;
  CHECK(designed_fog_perlin(&still, &desc, &err) == 0, "%s", err.message);
  desc.velocity[0] = 0x1p100f, desc.velocity[1] = -0x1p90f, desc.slice_rate = 0x1p80f;
  desc.time = 1.0f;
  CHECK(designed_fog_perlin(&far, &desc, &err) == 0, "%s", err.message);
  CHECK(memcmp(still.density, far.density, sizeof(float) * (size_t)w * h) == 0,
        "a drift of whole periods changed the fog");
  desc.velocity[0] = 1e30f, desc.velocity[1] = 3e25f, desc.slice_rate = 0.0f;
  CHECK(designed_fog_perlin(&far, &desc, &err) == 0, "%s", err.message);
  int flat_rows = 0;
  for (int z = 0; z < h; z++) {
    float lo = far.density[z * w], hi = lo;
    for (int x = 1; x < w; x++)
      lo = fminf(lo, far.density[z * w + x]), hi = fmaxf(hi, far.density[z * w + x]);
    if (hi - lo < 0.05f) flat_rows++;
  }
  CHECK(flat_rows == 0, "a drift of 1e30 cells: %d of %d rows flat", flat_rows, h);
  fogmap_destroy(&still);
  fogmap_destroy(&far);
}

int main(void) {
  test_long_drift();
  test_permutation();
  test_reference_value();
  test_zero_on_lattice();
  test_continuity();
  test_seed_determinism();
  test_bounded();
  test_fog_animation();
  test_default_slice_off_lattice();
  return test_finish("test_designed_perlin");
}
