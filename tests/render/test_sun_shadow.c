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

#include "render/fog_light.h"
#include "render/fog_rbf_tiles.h"
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

/* RMS of interpolated - exact over random points of the fog's bounds, at resolution n (the
 * max over random points jumps with where they happen to fall). */
static double rbf_interpolation_error(const fog_model *m, const double sun[3], int n) {
  fog_sun_shadow s;
  fog_error err;
  CHECK(!fog_sun_shadow_create(&s, &(fog_sun_shadow_desc){.across = n, .along = n}, &err),
        "%s", err.message);
  CHECK(!fog_sun_shadow_compute(&s, m, sun, 2, &err), "%s", err.message);
  double lo[3], hi[3], sum = 0.0;
  fog_model_bounds(m, lo, hi);
  fog_test_rng = 0x1234567ull;
  const int count = 4000;
  for (int q = 0; q < count; q++) {
    double p[3];
    for (int a = 0; a < 3; a++) p[a] = fog_test_range(0.75 * lo[a] + 0.25 * hi[a], 0.25 * lo[a] + 0.75 * hi[a]);
    const double e = fog_sun_shadow_depth_at(&s, p) - rbf_exact(p, sun);
    sum += e * e;
  }
  fog_sun_shadow_destroy(&s);
  return sqrt(sum / count);
}

/* One Gaussian's volume spans its cull sphere on every axis of the sun's frame, whatever
 * the sun: 2 R wide, centred on it (the 6-radius box through its corners was wider). */
static void test_rbf_extent(void) {
  const double R = fog_rbf_cull_radius(&rbfs[0], 1);
  fog_model m = {.kind = FOG_MODEL_RBF, .rbfs = rbfs, .rbf_count = 1};
  for (int d = 0; d < 3; d++) {
    double sun[3];
    unit(sun_dirs[d], sun);
    fog_sun_shadow s;
    fog_error err;
    CHECK(!fog_sun_shadow_create(&s, &(fog_sun_shadow_desc){.across = 8, .along = 8}, &err) &&
              !fog_sun_shadow_compute(&s, &m, sun, 1, &err),
          "%s", err.message);
    for (int a = 0; a < 3; a++) {
      double centre = 0.0, origin = 0.0;
      for (int c = 0; c < 3; c++)
        centre += rbfs[0].centre[c] * s.axis[a][c], origin += s.origin[c] * s.axis[a][c];
      CHECK(fabs(s.extent[a] - 2.0 * R) <= 1e-9 * R && fabs(origin - (centre - R)) <= 1e-9 * R,
            "sun %d axis %d: extent %.9g from %.9g, expected %.9g from %.9g", d, a, s.extent[a],
            origin, 2.0 * R, centre - R);
    }
    fog_sun_shadow_destroy(&s);
  }
}

/* Small dense Gaussians far from the camera: the sun's mean at the product's 8 segments of
 * two nodes against the same mean converged (2048 segments), on rays through them. Spread
 * from the camera to the farthest Gaussian, 8 segments put one or two nodes in the fog (the
 * mean off by up to 0.44); over the stretch inside their cull spheres they follow it. A
 * fourth Gaussian behind the camera, on the rays' lines, must not pull the span back to it
 * (the GL's tile lists hold only what is in front). */
static void test_rbf_light_span(void) {
  static const fog_rbf far[4] = {{{690, 30, 40}, 8.0, 0.3}, {{720, 45, -30}, 12.0, 0.2},
                                 {{705, 20, 0}, 10.0, 0.25}, {{-300, 25, 0}, 10.0, 0.3}};
  fog_model m = {.kind = FOG_MODEL_RBF, .rbfs = far, .rbf_count = 4};
  double sun[3];
  unit((const double[3]){-0.5, 0.45, 0.3}, sun);
  fog_sun_shadow s;
  fog_error err;
  CHECK(!fog_sun_shadow_create(&s, &(fog_sun_shadow_desc){.across = 48, .along = 48}, &err) &&
            !fog_sun_shadow_compute(&s, &m, sun, 2, &err),
        "%s", err.message);
  const double o[3] = {0, 25, 0};
  double worst = 0.0;
  for (int q = 0; q < 3; q++)
    for (int k = -8; k <= 8; k++) {
      double d[3];
      for (int c = 0; c < 3; c++) d[c] = far[q].centre[c] - o[c];
      d[1] += 1.2 * k, d[2] += 0.9 * k; /* across the Gaussian, within ~1.5 radii */
      fog_test_unit(d);
      const double coarse = fog_sun_mean_transmittance(
          &m, FOG_SUN_SHADOW_VOLUME, &s, (fog_light_rule){.steps = 8, .nodes = 2}, 1e30, o, d,
          1e30);
      const double fine = fog_sun_mean_transmittance(
          &m, FOG_SUN_SHADOW_VOLUME, &s, (fog_light_rule){.steps = 2048, .nodes = 2}, 1e30, o, d,
          1e30);
      worst = fmax(worst, fabs(coarse - fine));
    }
  printf("rbf far from the camera: 8 segments against 2048, max |mean difference| %.3g\n", worst);
  CHECK(worst <= 0.05, "the sun's mean over far Gaussians: 8 segments off by %g", worst);
  fog_sun_shadow_destroy(&s);
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
    double e48 = rbf_interpolation_error(&m, sun, 48), e96 = rbf_interpolation_error(&m, sun, 96),
           e192 = rbf_interpolation_error(&m, sun, 192);
    printf("rbf sun %d: between samples RMS error %.3g (48^3), %.3g (96^3), %.3g (192^3)\n", d,
           e48, e96, e192);
    CHECK(e48 > 3.0 * e96 && e96 > 3.0 * e192, "sun %d: not second order: %g %g %g", d, e48, e96,
          e192);
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
  /* the sun's disc half under the horizon still lights (fog_sun_above_horizon 0.5): the
   * height fog towards it, along the ground, is opaque */
  const double setting[3] = {1, 0, 0};
  CHECK(fog_sun_above_horizon(setting) == 0.5, "half the disc: %g", fog_sun_above_horizon(setting));
  CHECK(fog_sun_shadow_kind_of(&height, setting) == FOG_SUN_SHADOW_OPAQUE, "height, sun setting");
  CHECK(fog_sun_shadow_kind_of(&rbf_base, up) == FOG_SUN_SHADOW_OPAQUE, "rbf over a base");
  CHECK(fog_sun_shadow_kind_of(&none, up) == FOG_SUN_SHADOW_NONE, "no fog");
  /* A sun wholly below the horizon lights nothing: no T_s for any model, so no volume is
   * computed and no walk towards it is drawn (the same image: its light is 0). */
  const double s5 = sin(5.0 * 3.14159265358979323846 / 180.0);
  const double below[3] = {sqrt(1 - s5 * s5), -s5, 0};
  const double just_below[3] = {1, -1.01 * sin(FOG_SUN_ANGULAR_RADIUS), 0};
  fog_model bounded = {.kind = FOG_MODEL_RBF, .rbfs = rbfs, .rbf_count = 3};
  CHECK(fog_sun_shadow_kind_of(&bounded, up) == FOG_SUN_SHADOW_VOLUME, "rbf: a volume");
  const fog_model *models[] = {&homogeneous, &height, &rbf_base, &bounded};
  for (int i = 0; i < 4; i++) {
    CHECK(fog_sun_shadow_kind_of(models[i], down) == FOG_SUN_SHADOW_NONE, "model %d, sun down", i);
    CHECK(fog_sun_shadow_kind_of(models[i], below) == FOG_SUN_SHADOW_NONE, "model %d, -5 deg", i);
    CHECK(fog_sun_shadow_kind_of(models[i], just_below) == FOG_SUN_SHADOW_NONE,
          "model %d, the disc just under", i);
  }
  fog_sun_shadow s;
  fog_error err;
  CHECK(fog_sun_shadow_create(&s, &(fog_sun_shadow_desc){.across = 1, .along = 8}, &err) != 0 &&
            strstr(err.message, "expected 2.."),
        "a 1-column volume is refused: %s", err.message);
}

int main(void) {
  test_rbf_extent();
  test_rbf_light_span();
  test_rbf();
  test_fogmap();
  test_kinds();
  return test_finish("test_sun_shadow");
}
