/* The sun's optical-depth volume (render/fog_sun_shadow.h), on the CPU:
 *  - at its samples it holds the exact optical depth towards the sun: RBF fog against the
 *    Gaussians' closed form to infinity, the fogmap against one walk of its CPU twin from
 *    the sample (the volume sums a column segment by segment);
 *  - between samples the trilinear interpolation converges at second order (the error
 *    falls >= 3x for each doubling of the resolution) and its size is printed;
 *  - outside the box across the sunlight it is 0, beyond the far face the whole column;
 *  - which models get a volume, a closed form, or no sunlight at all. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "render/fog_sun_shadow.h"
#include "fog_test_scene.h"
#include "test_util.h"

static const double sun_dirs[3][3] = {{0.3, 0.8, -0.52}, {0.0, 1.0, 0.0}, {-0.9, 0.24, 0.36}};

static void unit(const double in[3], double out[3]) {
  for (int a = 0; a < 3; a++) out[a] = in[a];
  fog_test_unit(out);
}

/* Sample (i, j, k)'s world position. */
static void sample_position(const fog_sun_shadow *s, int i, int j, int k, double p[3]) {
  for (int c = 0; c < 3; c++)
    p[c] = s->origin[c] + s->extent[0] * i / (s->size[0] - 1) * s->axis[0][c] +
           s->extent[1] * j / (s->size[1] - 1) * s->axis[1][c] +
           s->extent[2] * k / (s->size[2] - 1) * s->axis[2][c];
}

static fog_rbf rbfs[3] = {{{10, 5, -4}, 3.0, 0.4}, {{14, 7, -2}, 2.0, 0.8}, {{7, 3, 1}, 4.0, 0.2}};

static double rbf_exact(const double p[3], const double sun[3]) {
  return fog_rbf_optical_depth(0.0, rbfs, 3, p, sun, HUGE_VAL);
}

/* The exact depth towards the sun from p, by the test's own reference. */
typedef double (*exact_depth)(const double p[3], const double sun[3], const void *user);

/* Makes *s, the across x across x along volume of m towards sun, and compares it at every
 * step[0]-th, step[1]-th, step[2]-th sample with exact: the largest |error| into *worst,
 * the largest exact depth into *peak. The caller destroys *s. */
static void sample_errors(fog_sun_shadow *s, const fog_model *m, const double sun[3],
                          int across, int along, const int step[3], exact_depth exact,
                          const void *user, double *worst, double *peak) {
  fog_error err;
  CHECK(!fog_sun_shadow_create(s, &(fog_sun_shadow_desc){.across = across, .along = along},
                               &err),
        "%s", err.message);
  CHECK(!fog_sun_shadow_compute(s, m, sun, 2, &err), "%s", err.message);
  *worst = 0.0, *peak = 0.0;
  for (int k = 0; k < along; k += step[2])
    for (int j = 0; j < across; j += step[1])
      for (int i = 0; i < across; i += step[0]) {
        double p[3];
        sample_position(s, i, j, k, p);
        double want = exact(p, sun, user);
        *peak = fmax(*peak, want);
        *worst = fmax(*worst, fabs(fog_sun_shadow_depth_at(s, p) - want));
      }
}

static double rbf_exact_of(const double p[3], const double sun[3], const void *user) {
  (void)user;
  return rbf_exact(p, sun);
}

/* Max |interpolated - exact| over random points of the fog's bounds, at resolution n. */
static double rbf_interpolation_error(const fog_model *m, const double sun[3], int n) {
  fog_sun_shadow s;
  fog_error err;
  CHECK(!fog_sun_shadow_create(&s, &(fog_sun_shadow_desc){.across = n, .along = n}, &err),
        "%s", err.message);
  CHECK(!fog_sun_shadow_compute(&s, m, sun, 2, &err), "%s", err.message);
  double lo[3], hi[3], worst = 0.0;
  fog_model_bounds(m, lo, hi);
  fog_test_rng = 0x1234567ull;
  for (int q = 0; q < 4000; q++) {
    double p[3];
    for (int a = 0; a < 3; a++) p[a] = fog_test_range(0.75 * lo[a] + 0.25 * hi[a], 0.25 * lo[a] + 0.75 * hi[a]);
    worst = fmax(worst, fabs(fog_sun_shadow_depth_at(&s, p) - rbf_exact(p, sun)));
  }
  fog_sun_shadow_destroy(&s);
  return worst;
}

static void test_rbf(void) {
  fog_model m = {.kind = FOG_MODEL_RBF, .rbfs = rbfs, .rbf_count = 3};
  for (int d = 0; d < 3; d++) {
    double sun[3];
    unit(sun_dirs[d], sun);
    fog_sun_shadow s;
    double worst, peak;
    sample_errors(&s, &m, sun, 24, 20, (const int[3]){2, 5, 3}, rbf_exact_of, NULL, &worst,
                  &peak);
    printf("rbf sun %d: at the samples max |error| %.3g of a peak depth %.3g\n", d, worst, peak);
    CHECK(peak > 0.2 && worst <= 2e-6 * peak, "sun %d: sample error %g, peak %g", d, worst, peak);
    /* Across the sunlight outside the box: no fog on that line; beyond the far face: the
     * whole column (the sample there). */
    double p[3], q[3];
    sample_position(&s, 12, 12, 19, p);
    for (int c = 0; c < 3; c++) q[c] = p[c] + 50.0 * s.axis[2][c];
    CHECK(fabs(fog_sun_shadow_depth_at(&s, q) - fog_sun_shadow_depth_at(&s, p)) <= 1e-6,
          "beyond the far face: %g vs the last sample %g", fog_sun_shadow_depth_at(&s, q),
          fog_sun_shadow_depth_at(&s, p));
    sample_position(&s, 23, 12, 10, p);
    for (int c = 0; c < 3; c++) q[c] = p[c] + (s.extent[0] / 23.0 * 1.01) * s.axis[0][c];
    CHECK(fog_sun_shadow_depth_at(&s, q) == 0.0, "outside across: %g", fog_sun_shadow_depth_at(&s, q));
    fog_sun_shadow_destroy(&s);
    /* Second order between the samples. */
    double e32 = rbf_interpolation_error(&m, sun, 32), e64 = rbf_interpolation_error(&m, sun, 64),
           e128 = rbf_interpolation_error(&m, sun, 128);
    printf("rbf sun %d: between samples max |error| %.3g (32^3), %.3g (64^3), %.3g (128^3)\n", d,
           e32, e64, e128);
    CHECK(e32 > 3.0 * e64 && e64 > 3.0 * e128, "sun %d: not second order: %g %g %g", d, e32, e64,
          e128);
  }
}

typedef struct fogmap_fog {
  const fog_volume *volume;
  const transform_grid *grid;
} fogmap_fog;
static double fogmap_exact(const double p[3], const double sun[3], const void *user) {
  const fogmap_fog *f = user;
  return fog_optical_depth(f->volume, f->grid, p, sun, 0.0, HUGE_VAL);
}

static void test_fogmap(void) {
  fog_test_rng = 0xABCDEFull;
  for (int pk = 0; pk < 3; pk++) {
    fog_volume v = fog_test_volume((fog_profile_kind)pk);
    transform_grid g = fog_test_grid(pk == 1 ? 2 : 1, 1.0, 0.0);
    fog_lod lod = {.levels = 0, .approx = &g, .mu = 1.0};
    fog_model m = {.kind = FOG_MODEL_FOGMAP, .volume = &v, .lod = &lod};
    double sun[3];
    unit(sun_dirs[pk], sun);
    CHECK(fog_sun_shadow_kind_of(&m, sun) == FOG_SUN_SHADOW_VOLUME, "fogmap: a volume");
    fog_sun_shadow s;
    double worst, peak;
    sample_errors(&s, &m, sun, 20, 33, (const int[3]){3, 3, 4}, fogmap_exact,
                  &(fogmap_fog){&v, &g}, &worst, &peak);
    printf("fogmap profile %d: at the samples max |error| %.3g of a peak depth %.3g\n", pk, worst,
           peak);
    CHECK(peak > 0.2 && worst <= 2e-6 * peak, "profile %d: %g of %g", pk, worst, peak);
    fog_sun_shadow_destroy(&s);
    transform_grid_destroy(&g);
  }
}

static void test_kinds(void) {
  const double up[3] = {0, 1, 0}, down[3] = {0, -1, 0};
  fog_model homogeneous = {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = 0.01};
  fog_model height = {.kind = FOG_MODEL_HEIGHT, .extinction = 0.01, .scale_height = 10};
  fog_model rbf_base = {.kind = FOG_MODEL_RBF, .extinction = 0.01, .rbfs = rbfs, .rbf_count = 3};
  fog_model none = {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = 0.0};
  CHECK(fog_sun_shadow_kind_of(&homogeneous, up) == FOG_SUN_SHADOW_OPAQUE, "homogeneous");
  CHECK(fog_sun_shadow_kind_of(&height, up) == FOG_SUN_SHADOW_HEIGHT, "height, sun up");
  CHECK(fog_sun_shadow_kind_of(&height, down) == FOG_SUN_SHADOW_OPAQUE, "height, sun down");
  CHECK(fog_sun_shadow_kind_of(&rbf_base, up) == FOG_SUN_SHADOW_OPAQUE, "rbf over a base");
  CHECK(fog_sun_shadow_kind_of(&none, up) == FOG_SUN_SHADOW_NONE, "no fog");
  fog_sun_shadow s;
  fog_error err;
  CHECK(fog_sun_shadow_create(&s, &(fog_sun_shadow_desc){.across = 1, .along = 8}, &err) != 0 &&
            strstr(err.message, "expected 2.."),
        "a 1-column volume is refused: %s", err.message);
}

int main(void) {
  test_rbf();
  test_fogmap();
  test_kinds();
  return test_finish("test_sun_shadow");
}
