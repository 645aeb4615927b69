/* Gaussian blob splats: total mass equals the analytic integral 2πσ²c (the grid sum of a
 * Gaussian with σ >= 1 cell differs from it only by an exp(-2π²σ²) aliasing term),
 * centroid equals the centre b, values equal the formula, blobs superpose, the cutoff
 * drops what it says, and bad blobs fail without touching the map. */
#include <math.h>
#include <string.h>

#include "sim/designed_fog.h"
#include "sim/fogmap.h"
#include "test_util.h"

/* The blobs at the default cutoff. */
#define BLOBS(b, n) (&(blob_fog_desc){.blobs = (b), .blob_count = (n), .cutoff = BLOB_FOG_CUTOFF})

static const double pi = 3.14159265358979323846;

static void moments(const fogmap *m, double *mass, double *cx, double *cz) {
  double s = 0, sx = 0, sz = 0;
  for (int z = 0; z < m->height; z++)
    for (int x = 0; x < m->width; x++) {
      double v = m->density[z * m->width + x];
      s += v;
      sx += v * x;
      sz += v * z;
    }
  *mass = s;
  *cx = sx / s;
  *cz = sz / s;
}

static void test_mass_and_centroid(void) {
  const fog_blob cases[] = {
      {.x = 64.0f, .z = 50.0f, .sigma = 1.5f, .peak = 0.8f},
      {.x = 63.37f, .z = 48.81f, .sigma = 3.0f, .peak = 2.0f},
      {.x = 60.5f, .z = 55.25f, .sigma = 7.3f, .peak = 1.0f},
      {.x = 70.9f, .z = 45.1f, .sigma = 1.0f, .peak = 5.0f},
  };
  fogmap map;
  fog_error err;
  CHECK(fogmap_create(&map, 140, 110, &err) == 0, "%s", err.message);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    const fog_blob *b = &cases[i];
    CHECK(designed_fog_blobs(&map, BLOBS(b, 1), &err) == 0,
          "%s", err.message);
    double mass, cx, cz;
    moments(&map, &mass, &cx, &cz);
    double analytic = 2.0 * pi * (double)b->sigma * b->sigma * b->peak;
    /* float values summed: relative 1e-6; aliasing at σ = 1: exp(-2π²) = 2.7e-9 */
    CHECK(fabs(mass - analytic) <= 2e-6 * analytic, "σ %g: mass %.9g, analytic %.9g",
          (double)b->sigma, mass, analytic);
    CHECK(fabs(cx - b->x) < 1e-4 && fabs(cz - b->z) < 1e-4,
          "σ %g: centroid (%.6f, %.6f), centre (%g, %g)", (double)b->sigma, cx, cz,
          (double)b->x, (double)b->z);
    /* the formula at a few cells */
    int probes[3][2] = {{(int)b->x, (int)b->z}, {(int)b->x + 2, (int)b->z - 1},
                        {(int)b->x - 3, (int)b->z + 2}};
    for (int p = 0; p < 3; p++) {
      double dx = probes[p][0] - (double)b->x, dz = probes[p][1] - (double)b->z;
      double expect = b->peak * exp(-(dx * dx + dz * dz) / (2.0 * b->sigma * b->sigma));
      double got = map.density[probes[p][1] * map.width + probes[p][0]];
      CHECK(fabs(got - expect) <= 1e-6 * b->peak, "value at (%d, %d) %g, expected %g",
            probes[p][0], probes[p][1], got, expect);
    }
  }
  fogmap_destroy(&map);
}

static void test_superposition_and_cutoff(void) {
  fogmap one, two, both;
  fog_error err;
  fogmap_create(&one, 64, 64, &err);
  fogmap_create(&two, 64, 64, &err);
  fogmap_create(&both, 64, 64, &err);
  fog_blob blobs[2] = {{.x = 20, .z = 30, .sigma = 4, .peak = 1},
                       {.x = 26.5f, .z = 33, .sigma = 2.5f, .peak = 0.5f}};
  designed_fog_blobs(&one, BLOBS(&blobs[0], 1), &err);
  designed_fog_blobs(&two, BLOBS(&blobs[1], 1), &err);
  CHECK(designed_fog_blobs(&both, BLOBS(blobs, 2), &err) == 0,
        "%s", err.message);
  int sum_ok = 1;
  for (int i = 0; i < 64 * 64; i++)
    if (fabsf(both.density[i] - (one.density[i] + two.density[i])) > 1e-7f) sum_ok = 0;
  CHECK(sum_ok, "two blobs are not the sum of each");
  /* add mode: onto what is there */
  designed_fog_blobs(&one,
                     &(blob_fog_desc){.blobs = &blobs[1], .blob_count = 1, .add = 1,
                                      .cutoff = BLOB_FOG_CUTOFF},
                     &err);
  CHECK(!memcmp(one.density, both.density, sizeof(float) * 64 * 64),
        "add mode differs from splatting both");

  /* cutoff 2σ: zero beyond, and the dropped mass is the Gaussian's tail exp(-2) */
  fog_blob wide = {.x = 32, .z = 32, .sigma = 5, .peak = 1};
  designed_fog_blobs(&one, &(blob_fog_desc){.blobs = &wide, .blob_count = 1, .cutoff = 2},
                     &err);
  int outside_zero = 1;
  double mass = 0;
  for (int z = 0; z < 64; z++)
    for (int x = 0; x < 64; x++) {
      double r = hypot(x - 32.0, z - 32.0);
      if (r > 10.0 + 1e-9 && one.density[z * 64 + x] != 0.0f) outside_zero = 0;
      mass += one.density[z * 64 + x];
    }
  CHECK(outside_zero, "values beyond the cutoff");
  double kept = mass / (2 * pi * 25.0);
  CHECK(fabs(kept - (1 - exp(-2.0))) < 0.03, "cutoff 2σ kept %g of the mass, expected ~%g",
        kept, 1 - exp(-2.0));
  fogmap_destroy(&one);
  fogmap_destroy(&two);
  fogmap_destroy(&both);
}

static void test_bad_blobs(void) {
  fogmap map;
  fog_error err;
  fogmap_create(&map, 16, 16, &err);
  map.density[3] = 7.0f;
  fog_blob bad[2] = {{.x = 5, .z = 5, .sigma = 1, .peak = 1}, {.x = 5, .z = 5, .sigma = 0}};
  CHECK(designed_fog_blobs(&map, BLOBS(bad, 2), &err) != 0 &&
            strstr(err.message, "blob 1") && strstr(err.message, "sigma"),
        "sigma 0 accepted: %s", err.message);
  /* a cutoff of 0 is refused (it meant 6: no physical value means "default") */
  CHECK(designed_fog_blobs(&map, &(blob_fog_desc){.blobs = bad, .blob_count = 1}, &err) != 0 &&
            strstr(err.message, "cutoff"),
        "cutoff 0 accepted: %s", err.message);
  bad[1] = (fog_blob){.x = 5, .z = 5, .sigma = 1, .peak = -1};
  CHECK(designed_fog_blobs(&map, BLOBS(bad, 2), &err) != 0 &&
            strstr(err.message, "peak"),
        "negative peak accepted");
  CHECK(map.density[3] == 7.0f && map.density[5 * 16 + 5] == 0.0f, "failed call changed the map");
  /* blobs far away (or huge) do nothing and do not overflow the index arithmetic */
  fog_blob far[2] = {{.x = 1e30f, .z = -1e30f, .sigma = 1, .peak = 1},
                     {.x = -500, .z = 8, .sigma = 3, .peak = 1}};
  CHECK(designed_fog_blobs(&map, BLOBS(far, 2), &err) == 0,
        "%s", err.message);
  int zero = 1;
  for (int i = 0; i < 256; i++) zero &= map.density[i] == 0.0f;
  CHECK(zero, "far-away blobs left density");
  fogmap_destroy(&map);
}

int main(void) {
  test_mass_and_centroid();
  test_superposition_and_cutoff();
  test_bad_blobs();
  return test_finish("test_designed_blobs");
}
