/* `fogpipe fit` on synthetic inputs with known answers (app/fit.h, docs/fit.md):
 *   a constant density picks homogeneous fog, its K the input's;
 *   an exponential column picks height fog with the input's scale height (to 1 %);
 *   OpenGL's linear and exp2 fog pick themselves, start, end and density recovered;
 *   a flat-bottomed ground fog (a fogmap over a slab) picks a fogmap;
 *   a hard-edged cylinder of fog (separable: a disc times a slab) gets fogmap rungs
 *   projected from its density, keeping the samples' mass (to float rounding); they err
 *   on average 10x less than every other approximation; the scratch folder goes with the
 *   result;
 *   two hard ellipsoids far apart: the bank of 2 ellipsoids finds both (centres within 2
 *   units, radii 8 % and densities 10 %: the test's 32 samples a side give the thinner axis
 *   two cells), its mean error 10x below the single ellipsoid's;
 *   a tilted uniform ellipsoid (a general quadric, rotated about two axes): the oriented
 *   ellipsoid rung (each cluster's full covariance) gives back its quadric (the shape matrix
 *   within 3 %, the density 5 %), erring 5x less than the axis-aligned ellipsoid, and its
 *   `general` config line reads back to the same volume;
 *   a single Gaussian picks one RBF, its centre, radius and density the input's (1 %), and
 *   lit (albedo 0.9) its in-scatter is within 1e-3 of the input's, the ellipsoid's not;
 *   a tall leaning plume of thin columns (a VDB written here) picks the volume at
 *   T = 0.01 and a fogmap at T = 0.5;
 *   over a sequence the worst frame decides (a blob that moves in its last frame: one
 *   still Gaussian for frames 1-2, the played fogmap for 1-3).
 * The views' errors are checked against the answers too: the rung that is the input has
 * error ~0 and the others are measured, not assumed; a ray whose tau is NaN makes the max
 * NaN (the ray after it overwrote the NaN and the larger errors before it: a rung with a
 * NaN ray could be chosen by its max). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/config.h"
#include "app/fit.h"
#include "app/fit_fogmap.h"
#include "app/fit_views.h"
#include "render/fog_sun_shadow.h"
#include "sim/sim.h"
#include "test_bin.h"

static const fit_desc quick = {.tolerance = 0.01, .rays_per_side = 16, .sample_side = 32,
                               .width = 160, .height = 90, .timed_frames = 3};

static const fit_rung *rung_named(const fit_result *r, const char *name) {
  for (int i = 0; i < r->count; i++)
    if (!strcmp(r->rungs[i].name, name)) return &r->rungs[i];
  return NULL;
}

/* The choice at `tolerance`, as far as it is not a measured time: a rung of family `want`
 * holds the fog within the tolerance, and fit_choose took a rung within it that no other
 * within it beats by more than the tie factor (1.25) in measured GL time. Which of several
 * rungs within the tolerance is fastest is a timing, not a property a test can hold on a
 * shared machine (a sanitizer run under load once timed "rbf 1" at 5.1 ms and "rbf 2" at
 * 0.5): when another family wins on time, it is said, not failed. */
static void check_choice(const fit_result *r, double tolerance, const char *want) {
  double best = HUGE_VAL;
  for (int i = 0; i < r->count; i++)
    if (!strcmp(r->rungs[i].family, want)) best = fmin(best, r->rungs[i].max_error);
  CHECK(best <= tolerance, "no %s rung within %g (best %g)", want, tolerance, best);
  const int c = fit_choose(r, tolerance, false);
  CHECK(c >= 0 && r->rungs[c].max_error <= tolerance, "at %g: chose %d", tolerance, c);
  if (c < 0) return;
  for (int i = 0; i < r->count; i++)
    if (r->rungs[i].max_error <= tolerance)
      CHECK(r->rungs[c].ms <= 1.25 * r->rungs[i].ms, "at %g: chose %s (%.2f ms), %s within "
            "it took %.2f", tolerance, r->rungs[c].name, r->rungs[c].ms, r->rungs[i].name,
            r->rungs[i].ms);
  if (strcmp(r->rungs[c].family, want))
    printf("note: at %g %s was measured faster than %s (within the tolerance too)\n",
           tolerance, r->rungs[c].name, want);
}

static void print_table(const char *title, const fit_result *r) {
  printf("%s: %d rays\n", title, r->rays);
  for (int i = 0; i < r->count; i++)
    printf("  %-24s max %.3e mean %.3e %7.2f ms light %.2e  %s\n", r->rungs[i].name,
           r->rungs[i].max_error, r->rungs[i].mean_error, r->rungs[i].ms,
           r->rungs[i].light_error, r->rungs[i].params);
}

static bool run(const char *title, scene_config *cfg, fit_result *r) {
  fit_desc d = quick;
  d.input = cfg;
  fog_error err;
  int status = fit_run(&d, r, &err);
  CHECK(status == 0, "%s: %s", title, err.message);
  if (status) return false;
  print_table(title, r);
  return true;
}

static void test_constant(void) {
  scene_config cfg;
  scene_config_init(&cfg);
  cfg.fog.model = FOG_MODEL_HOMOGENEOUS, cfg.fog.density_scale = 0.004;
  fit_result r;
  if (!run("constant", &cfg, &r)) return;
  const fit_rung *h = rung_named(&r, "homogeneous");
  CHECK(h && fabs(h->config->fog.density_scale - 0.004) < 1e-12, "K %.9g, want 0.004",
        h ? h->config->fog.density_scale : NAN);
  CHECK(h && h->max_error < 1e-9, "homogeneous error %g", h ? h->max_error : NAN);
  CHECK(!rung_named(&r, "height"), "a constant density has no height fog");
  CHECK(!r.lit && h && isnan(h->light_error), "unlit: no in-scatter error");
  check_choice(&r, 0.01, "homogeneous");
  fit_result_destroy(&r);
}

static void test_height(void) {
  scene_config cfg;
  scene_config_init(&cfg);
  cfg.fog.model = FOG_MODEL_HEIGHT, cfg.fog.density_scale = 0.01;
  cfg.fog.fog_height = 5.0, cfg.fog.scale_height = 12.0;
  fit_result r;
  if (!run("exponential column", &cfg, &r)) return;
  const fit_rung *h = rung_named(&r, "height");
  CHECK(h != NULL, "no height rung");
  if (h) {
    const scene_fog_config *f = &h->config->fog;
    double k_at_5 = f->density_scale * exp(-(5.0 - f->fog_height) / f->scale_height);
    CHECK(fabs(f->scale_height / 12.0 - 1.0) < 0.01, "H %.6g, want 12 (1 %%)", f->scale_height);
    CHECK(fabs(k_at_5 / 0.01 - 1.0) < 0.01, "K at y = 5: %.6g, want 0.01", k_at_5);
    CHECK(h->max_error < 1e-3, "height fog's error %g", h->max_error);
  }
  const fit_rung *k = rung_named(&r, "homogeneous");
  CHECK(k && k->max_error > 0.01, "homogeneous holds the column? error %g",
        k ? k->max_error : NAN);
  check_choice(&r, 0.01, "height");
  fit_result_destroy(&r);
}

/* The classic factors, fitted on the views (each view's camera their eye): OpenGL's linear
 * fog from 300 to 1400 and exp2 fog of density 0.00075 come back as themselves. */
static void test_classic(void) {
  for (int exp2 = 0; exp2 < 2; exp2++) {
    scene_config cfg;
    scene_config_init(&cfg);
    cfg.fog.model = exp2 ? FOG_MODEL_EXP2 : FOG_MODEL_LINEAR;
    cfg.fog.fog_start = 300, cfg.fog.fog_end = 1400, cfg.fog.density_scale = 0.00075;
    fit_result r;
    if (!run(exp2 ? "exp2 fog" : "linear fog", &cfg, &r)) continue;
    const fit_rung *g = rung_named(&r, exp2 ? "exp2" : "linear");
    CHECK(g != NULL, "no %s rung", exp2 ? "exp2" : "linear");
    if (g) {
      const scene_fog_config *f = &g->config->fog;
      if (exp2)
        CHECK(fabs(f->density_scale / 0.00075 - 1) < 1e-9, "exp2 density %.12g",
              f->density_scale);
      else
        CHECK(fabs(f->fog_start - 300) < 1e-6 && fabs(f->fog_end - 1400) < 1e-6,
              "linear from %.12g to %.12g", f->fog_start, f->fog_end);
      CHECK(g->max_error < 1e-6, "%s error %g", g->name, g->max_error);
    }
    check_choice(&r, 0.01, exp2 ? "exp2" : "linear");
    fit_result_destroy(&r);
  }
}

static void test_ground_fog(void) {
  scene_config cfg;
  scene_config_init(&cfg);
  cfg.fog.model = FOG_MODEL_FOGMAP;
  snprintf(cfg.fog.fogmap, sizeof cfg.fog.fogmap, "data/fogmap_sample.png");
  cfg.fog.density_scale = 0.02;
  cfg.box.origin[0] = -128, cfg.box.origin[1] = -128, cfg.box.cell_size = 1.0;
  cfg.box.floor = 0.0, cfg.box.top = 20.0; /* a slab: flat bottom, flat top */
  fit_result r;
  if (!run("ground fog", &cfg, &r)) return;
  const fit_rung *same = rung_named(&r, "fogmap linear mu 1"); /* the input's settings */
  CHECK(same && same->max_error < 1e-6, "the input's own fogmap: error %g",
        same ? same->max_error : NAN);
  check_choice(&r, 0.01, "fogmap");
  fit_result_destroy(&r);
}

static void test_gaussian(void) {
  scene_config cfg;
  scene_config_init(&cfg);
  cfg.fog.model = FOG_MODEL_RBF;
  cfg.fog.rbfs[0] = (fog_rbf){.centre = {30, 40, -20}, .radius = 25, .density = 0.05};
  cfg.fog.rbf_count = 1;
  cfg.fog.albedo = 0.9; /* lit: the in-scatter is measured too */
  fit_result r;
  if (!run("one Gaussian", &cfg, &r)) return;
  const fit_rung *given = rung_named(&r, "rbf as given"), *ball = rung_named(&r, "ellipsoid");
  CHECK(r.lit && given && given->light_error == 0.0, "lit %d; the input's own in-scatter error %g",
        r.lit, given ? given->light_error : NAN);
  CHECK(ball && ball->light_error > 0.05, "the ellipsoid's in-scatter error %g",
        ball ? ball->light_error : NAN);
  const fit_rung *one = rung_named(&r, "rbf 1");
  CHECK(one && one->light_error < 1e-3, "one fitted Gaussian's in-scatter error %g",
        one ? one->light_error : NAN);
  const fit_rung *g = rung_named(&r, "rbf 1");
  CHECK(g != NULL, "no rbf 1 rung");
  if (g) {
    const fog_rbf *b = &g->config->fog.rbfs[0];
    double off = sqrt(pow(b->centre[0] - 30, 2) + pow(b->centre[1] - 40, 2) +
                      pow(b->centre[2] + 20, 2));
    CHECK(off < 0.01 * 25, "centre %g %g %g", b->centre[0], b->centre[1], b->centre[2]);
    CHECK(fabs(b->radius / 25 - 1) < 0.01, "radius %.6g, want 25", b->radius);
    CHECK(fabs(b->density / 0.05 - 1) < 0.01, "density %.6g, want 0.05", b->density);
  }
  check_choice(&r, 0.01, "rbf");
  CHECK(g && g->config->fog.rbf_count == 1 && g->max_error <= 0.01,
        "one Gaussian holds it? error %g", g ? g->max_error : NAN);
  fit_result_destroy(&r);
}

/* A quadric input has no fogmap: its rungs project the density (app/fit_fogmap.h). */
static void test_projected_fogmap(void) {
  scene_config cfg;
  scene_config_init(&cfg);
  cfg.fog.model = FOG_MODEL_QUADRIC;
  const double base[3] = {0, 0, 0}, radius = 60, height = 30, density = 0.03;
  cfg.fog.quadrics[0] = fog_quadric_cylinder(base, radius, height, density, 0.0);
  cfg.fog.quadric_count = 1;
  fit_result r;
  if (!run("a cylinder of fog", &cfg, &r)) return;
  const fit_rung *map = rung_named(&r, "fogmap linear mu 1");
  CHECK(map && map->config->fog.model == FOG_MODEL_FOGMAP && map->mean_error < 1e-2,
        "the projected fogmap's mean error %g", map ? map->mean_error : NAN);
  /* the cylinder rung holds it too: one cluster's moments are an upright uniform
   * cylinder's (a disc's R^2/4 across, a height's h^2/12 up) */
  const fit_rung *cyl = rung_named(&r, "cylinder");
  CHECK(cyl && cyl->config->fog.quadric_count == 1, "no cylinder rung");
  const fit_rung *ell = rung_named(&r, "ellipsoid");
  if (cyl && ell) {
    const fog_quadric *v = &cyl->config->fog.quadrics[0];
    const double r_fit = 0.5 * (v->hi[0] - v->lo[0]), h_fit = v->hi[1] - v->lo[1];
    printf("cylinder rung: r %.4g h %.4g K %.4g, mean |dtau| %.3g (the ellipsoid's %.3g)\n",
           r_fit, h_fit, v->density, cyl->mean_error, ell->mean_error);
    CHECK(fabs(r_fit / radius - 1) < 0.05 && fabs(h_fit / height - 1) < 0.08 &&
              fabs(v->density / density - 1) < 0.1,
          "cylinder r %g h %g K %g", r_fit, h_fit, v->density);
    CHECK(cyl->mean_error < 0.2 * ell->mean_error, "cylinder %.3g, ellipsoid %.3g",
          cyl->mean_error, ell->mean_error);
  }
  for (int i = 0; map && i < r.count; i++) {
    const char *family = r.rungs[i].family;
    if (strcmp(family, "fogmap") && strcmp(r.rungs[i].name, "quadric as given") &&
        strncmp(r.rungs[i].name, "cylinder", 8))
      CHECK(r.rungs[i].mean_error > 10 * map->mean_error,
            "%s errs %.3g on average, the fogmap %.3g", r.rungs[i].name, r.rungs[i].mean_error,
            map->mean_error);
  }
  /* the projection: the samples' mass to rounding, the cylinder's within the sampling */
  const fog_model model = {.kind = FOG_MODEL_QUADRIC, .quadrics = cfg.fog.quadrics,
                           .quadric_count = 1};
  fit_fogmap f;
  fog_error err;
  if (fit_fogmap_project(&model, r.lo, r.hi, 48, &f, &err) == 0) {
    double map_mass = 0.0;
    for (int i = 0; i < f.map.width * f.map.height; i++) map_mass += f.map.density[i];
    map_mass *= f.place.cell_size * f.place.cell_size * f.profile.thickness;
    fit_samples s;
    const int n[3] = {48, FIT_FOGMAP_LAYERS, 48};
    CHECK(fit_samples_create_grid(&s, &model, r.lo, r.hi, n, &err) == 0, "samples");
    double sample_mass = 0.0;
    for (int i = 0; i < n[0] * n[1] * n[2]; i++) sample_mass += s.k[i];
    sample_mass *= s.cell[0] * s.cell[1] * s.cell[2];
    fit_samples_destroy(&s);
    const double exact = density * 3.14159265358979323846 * radius * radius * height;
    printf("projected mass %.9g, samples %.9g, the cylinder %.9g\n", map_mass, sample_mass, exact);
    CHECK(fabs(map_mass / sample_mass - 1) < 1e-6 /* float cells */, "mass %.9g, the samples' %.9g", map_mass,
          sample_mass);
    CHECK(fabs(map_mass / exact - 1) < 0.02, "mass %.9g, the cylinder's %.9g", map_mass, exact);
    double peak = 0.0;
    for (int k = 0; k < f.profile.count; k++) peak = fmax(peak, f.profile.values[k]);
    CHECK(peak == 1.0, "the profile's peak %g", peak);
    fit_fogmap_destroy(&f);
  } else {
    CHECK(false, "projection: %s", err.message);
  }
  char scratch[sizeof r.scratch];
  snprintf(scratch, sizeof scratch, "%s", r.scratch);
  CHECK(scratch[0] && access(map ? map->config->fog.fogmap : "", R_OK) == 0,
        "the projected fogmap's file");
  fit_result_destroy(&r);
  CHECK(access(scratch, F_OK) != 0, "%s left behind", scratch);
}

/* Two hard ellipsoids far apart: the bank of 2 ellipsoids holds them (each cluster's
 * moments are a uniform ellipsoid's), the single ellipsoid spans both and does not
 * (measured: mean 3.1e-3 against 0.22). */
static void test_two_ellipsoids(void) {
  scene_config cfg;
  scene_config_init(&cfg);
  cfg.fog.model = FOG_MODEL_QUADRIC;
  const double a[3] = {-150, 40, -80}, ra[3] = {60, 25, 40};
  const double b[3] = {160, 50, 90}, rb[3] = {45, 30, 70};
  cfg.fog.quadrics[0] = fog_quadric_ellipsoid(a, ra, 0.02, 0.0);
  cfg.fog.quadrics[1] = fog_quadric_ellipsoid(b, rb, 0.03, 0.0);
  cfg.fog.quadric_count = 2;
  fit_result r;
  if (!run("two ellipsoids", &cfg, &r)) return;
  const fit_rung *one = rung_named(&r, "ellipsoid"), *two = rung_named(&r, "ellipsoids 2");
  CHECK(one && two && two->mean_error < 0.1 * one->mean_error && two->mean_error < 5e-3,
        "two ellipsoids' bank: mean %g, one ellipsoid %g", two ? two->mean_error : NAN,
        one ? one->mean_error : NAN);
  for (int q = 0; two && q < 2; q++) { /* each fitted volume is one of the input's */
    const fog_quadric *v = &two->config->fog.quadrics[q];
    double c[3], radius[3];
    for (int k = 0; k < 3; k++) c[k] = 0.5 * (v->lo[k] + v->hi[k]), radius[k] = 0.5 * (v->hi[k] - v->lo[k]);
    const bool is_a = fabs(c[0] - a[0]) < fabs(c[0] - b[0]);
    const double *want_c = is_a ? a : b, *want_r = is_a ? ra : rb;
    for (int k = 0; k < 3; k++)
      CHECK(fabs(c[k] - want_c[k]) < 2.0 && fabs(radius[k] / want_r[k] - 1) < 0.08,
            "ellipsoid %d axis %d: centre %g radius %g, want %g and %g", q, k, c[k], radius[k],
            want_c[k], want_r[k]);
    CHECK(fabs(v->density / (is_a ? 0.02 : 0.03) - 1) < 0.1, "ellipsoid %d: density %g", q,
          v->density);
  }
  fit_result_destroy(&r);
}

/* A uniform ellipsoid of semi-axes `axes`, turned by 40 degrees about y then 25 about z,
 * as the ten coefficients: Q = (x - c)^T R diag(1/a^2) R^T (x - c) - 1, and its box. */
static fog_quadric tilted_ellipsoid(const double c[3], const double axes[3], double density,
                                    double P[3][3]) {
  const double ay = 40 * 3.14159265358979323846 / 180, az = 25 * 3.14159265358979323846 / 180;
  const double Ry[3][3] = {{cos(ay), 0, sin(ay)}, {0, 1, 0}, {-sin(ay), 0, cos(ay)}};
  const double Rz[3][3] = {{cos(az), -sin(az), 0}, {sin(az), cos(az), 0}, {0, 0, 1}};
  double R[3][3], S[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      R[i][j] = 0;
      for (int k = 0; k < 3; k++) R[i][j] += Rz[i][k] * Ry[k][j];
    }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      P[i][j] = S[i][j] = 0;
      for (int k = 0; k < 3; k++) {
        P[i][j] += R[i][k] * R[j][k] / (axes[k] * axes[k]);
        S[i][j] += R[i][k] * R[j][k] * axes[k] * axes[k];
      }
    }
  double Pc[3];
  for (int i = 0; i < 3; i++) Pc[i] = P[i][0] * c[0] + P[i][1] * c[1] + P[i][2] * c[2];
  fog_quadric v = {.q = {P[0][0], P[1][1], P[2][2], 2 * P[0][1], 2 * P[1][2], 2 * P[0][2],
                         -2 * Pc[0], -2 * Pc[1], -2 * Pc[2],
                         c[0] * Pc[0] + c[1] * Pc[1] + c[2] * Pc[2] - 1},
                   .density = density};
  for (int i = 0; i < 3; i++) v.lo[i] = c[i] - sqrt(S[i][i]), v.hi[i] = c[i] + sqrt(S[i][i]);
  return v;
}

static void test_oriented_ellipsoid(const char *folder) {
  scene_config cfg;
  scene_config_init(&cfg);
  cfg.fog.model = FOG_MODEL_QUADRIC;
  const double c[3] = {20, 60, -30}, axes[3] = {110, 18, 40}, density = 0.02;
  double want[3][3];
  cfg.fog.quadrics[0] = tilted_ellipsoid(c, axes, density, want);
  cfg.fog.quadric_count = 1;
  fit_result r;
  if (!run("a tilted ellipsoid", &cfg, &r)) return;
  const fit_rung *turned = rung_named(&r, "oriented ellipsoid"), *upright = rung_named(&r, "ellipsoid");
  CHECK(turned && upright, "no oriented or upright ellipsoid rung");
  if (!turned || !upright) return fit_result_destroy(&r);
  const fog_quadric *v = &turned->config->fog.quadrics[0];
  double worst = 0, norm = 0;
  const double got[3][3] = {{v->q[0], v->q[3] / 2, v->q[5] / 2},
                            {v->q[3] / 2, v->q[1], v->q[4] / 2},
                            {v->q[5] / 2, v->q[4] / 2, v->q[2]}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      worst = fmax(worst, fabs(got[i][j] - want[i][j])), norm = fmax(norm, fabs(want[i][j]));
  const double centre_q = fog_quadric_value(v, c);
  printf("oriented ellipsoid: shape matrix off by %.3g of its largest entry, Q(centre) %.4f, "
         "K %.5g; mean |dtau| %.3g against the upright ellipsoid's %.3g\n",
         worst / norm, centre_q, v->density, turned->mean_error, upright->mean_error);
  CHECK(worst < 0.03 * norm, "shape matrix off by %.3g of %.3g", worst, norm);
  CHECK(fabs(centre_q + 1) < 0.02, "Q at the input's centre %g, expected -1", centre_q);
  CHECK(fabs(v->density / density - 1) < 0.05, "density %g, want %g", v->density, density);
  CHECK(turned->mean_error < 0.2 * upright->mean_error, "oriented %.3g, upright %.3g",
        turned->mean_error, upright->mean_error);
  /* its config line (general A..J box density) reads back to the same volume */
  char path[300];
  snprintf(path, sizeof path, "%s/oriented.ini", folder);
  fog_error err = {0};
  scene_config back;
  CHECK(scene_config_write(turned->config, path, &err) == 0 &&
            scene_config_load(path, &back, &err) == 0,
        "%s", err.message);
  double drift = 0;
  for (int k = 0; k < 10; k++)
    drift = fmax(drift, fabs(back.fog.quadrics[0].q[k] - v->q[k]));
  CHECK(back.fog.quadric_count == 1 && drift == 0 && back.fog.quadrics[0].density == v->density,
        "read back: %d volumes, coefficients off by %g", back.fog.quadric_count, drift);
  unlink(path);
  fit_result_destroy(&r);
}

/* Writes the grid as a VDB file and frees its values. */
static int write_grid(const char *path, vdb_dense_grid *g) {
  fog_error err = {0};
  int status = vdb_write_dense(path, g, &(vdb_write_desc){0}, &err);
  CHECK(status == 0, "%s", err.message);
  free(g->values);
  return status;
}

/* 2 x 4 x 2 m, Z-up as Blender writes it: 12 x 12 thin columns in a checkerboard, dense
 * ones 6 per metre, leaning by one voxel every 24 layers (a quarter column at the top):
 * too fine for 64 Gaussians, not quite a fogmap (the lean), exactly the volume. */
static int write_plume(const char *path) {
  enum { nx = 48, ny = 48, nz = 96 };
  vdb_dense_grid g = {.dim = {nx, ny, nz}, .index_min = {0, 0, 0},
                      .voxel_size = {2.0 / nx, 2.0 / ny, 4.0 / nz},
                      .translation = {-1.0 + 1.0 / nx, -1.0 + 1.0 / ny, 2.0 / nz}};
  g.values = calloc((size_t)nx * ny * nz, sizeof(float));
  if (!g.values) return 1;
  for (int k = 4; k < nz - 4; k++)
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        int shifted = i + k / 48;
        if ((((shifted / 4) + (j / 4)) & 1) == 0 && shifted < nx)
          g.values[((size_t)k * ny + j) * nx + i] = 4.0f;
      }
  return write_grid(path, &g);
}

static void test_plume(const char *folder) {
  char path[512];
  snprintf(path, sizeof path, "%s/plume_0001.vdb", folder);
  if (write_plume(path)) return;
  scene_config cfg;
  scene_config_init(&cfg);
  cfg.fog.model = FOG_MODEL_VOLUME;
  snprintf(cfg.fog.vdb, sizeof cfg.fog.vdb, "%s", path);
  snprintf(cfg.path, sizeof cfg.path, "%s", path);
  fog_error err;
  CHECK(fit_scene_for_volume(&cfg, NULL, 0, &err) == 0, "%s", err.message);
  fit_result r;
  if (!run("tall plume", &cfg, &r)) return;
  const fit_rung *v = rung_named(&r, "volume");
  CHECK(v && v->max_error < 1e-9, "the volume's own error %g", v ? v->max_error : NAN);
  check_choice(&r, 0.01, "volume");
  check_choice(&r, 0.5, "fogmap");
  fit_result_destroy(&r);
}

/* A 3-frame sequence on a 3 m cube of 64^3 voxels: one Gaussian blob (sigma 0.2 m, peak 8
 * per metre, 5 sigma clear of the grid's sides) at x = -0.5 in frames 1 and 2, moved to
 * x = +0.5 in frame 3. */
static int write_blob_frame(const char *folder, int number, double x0) {
  enum { n = 64 };
  vdb_dense_grid g = {.dim = {n, n, n}, .index_min = {0, 0, 0},
                      .voxel_size = {3.0 / n, 3.0 / n, 3.0 / n},
                      .translation = {-1.5 + 1.5 / n, -1.5 + 1.5 / n, 1.5 / n}};
  g.values = calloc((size_t)n * n * n, sizeof(float));
  if (!g.values) return 1;
  for (int k = 0; k < n; k++)
    for (int j = 0; j < n; j++)
      for (int i = 0; i < n; i++) {
        double x = g.translation[0] + i * g.voxel_size[0] - x0;
        double y = g.translation[1] + j * g.voxel_size[1];
        double z = g.translation[2] + k * g.voxel_size[2] - 1.5;
        g.values[((size_t)k * n + j) * n + i] =
            (float)(8.0 * exp(-(x * x + y * y + z * z) / (2 * 0.2 * 0.2)));
      }
  char path[512];
  snprintf(path, sizeof path, "%s/blob_%04d.vdb", folder, number);
  return write_grid(path, &g);
}

/* Over a sequence the worst frame decides: frames 1-2 hold one still blob, which one
 * Gaussian fits; with frame 3 (the blob moved) no static rung holds them all, and a rung
 * that plays the frames (the fogmap, the volume) is picked. */
static void test_sequence(const char *folder) {
  if (write_blob_frame(folder, 1, -0.5) || write_blob_frame(folder, 2, -0.5) ||
      write_blob_frame(folder, 3, 0.5))
    return;
  scene_config cfg;
  scene_config_init(&cfg);
  cfg.fog.model = FOG_MODEL_VOLUME;
  snprintf(cfg.fog.vdb, sizeof cfg.fog.vdb, "%s/blob_####.vdb", folder);
  snprintf(cfg.path, sizeof cfg.path, "%s", cfg.fog.vdb);
  fog_error err;
  CHECK(fit_scene_for_volume(&cfg, NULL, 0, &err) == 0, "%s", err.message);
  const int still[] = {1, 2}, all[] = {1, 2, 3};
  fit_result r2, r3;
  fit_desc d = quick;
  d.input = &cfg, d.frames = still, d.frame_count = 2;
  int status = fit_run(&d, &r2, &err);
  CHECK(status == 0, "frames 1-2: %s", err.message);
  if (status) return;
  print_table("blob, frames 1-2", &r2);
  d.frames = all, d.frame_count = 3;
  status = fit_run(&d, &r3, &err);
  CHECK(status == 0, "frames 1-3: %s", err.message);
  if (status) {
    fit_result_destroy(&r2);
    return;
  }
  print_table("blob, frames 1-3", &r3);
  CHECK(r2.frame_count == 2 && r3.frame_count == 3, "frames measured %d, %d", r2.frame_count,
        r3.frame_count);
  const fit_rung *g2 = rung_named(&r2, "rbf 1"), *g3 = rung_named(&r3, "rbf 1");
  const fit_rung *v3 = rung_named(&r3, "volume");
  /* (the grid is the Gaussian trilinear at 1/4 sigma: within 0.05 of the analytic one) */
  CHECK(g2 && g2->max_error < 0.05, "frames 1-2: one Gaussian's error %g",
        g2 ? g2->max_error : NAN);
  check_choice(&r2, 0.05, "rbf");
  CHECK(g3 && g3->max_error > 0.3, "frames 1-3: one still Gaussian's error %g",
        g3 ? g3->max_error : NAN);
  CHECK(v3 && v3->max_error < 1e-9, "frames 1-3: the volume's error %g",
        v3 ? v3->max_error : NAN);
  /* A round blob is separable, f(x, z) g(y): the fogmap that plays the frames holds each
   * one exactly, and is cheaper than the volume. */
  const fit_rung *m3 = rung_named(&r3, "fogmap linear mu 1");
  CHECK(m3 && m3->max_error < 1e-4, "frames 1-3: the played fogmap's error %g",
        m3 ? m3->max_error : NAN);
  check_choice(&r3, 0.05, "fogmap");
  fit_result_destroy(&r2);
  fit_result_destroy(&r3);
}

/* The banks' amplitudes on the views' depths (fit_views_rbf_amplitudes): two Gaussians
 * whose centres and radii are right but amplitudes wrong come back to the reference's. */
static void test_amplitudes(void) {
  const fog_rbf truth[2] = {{.centre = {-20, 30, 0}, .radius = 25, .density = 0.02},
                            {.centre = {25, 35, 10}, .radius = 18, .density = 0.01}};
  fog_model reference = {.kind = FOG_MODEL_RBF, .rbfs = truth, .rbf_count = 2};
  double lo[3], hi[3];
  CHECK(fog_model_bounds(&reference, lo, hi), "bounds");
  fit_views views;
  fog_error err = {0};
  CHECK(fit_views_create(&views, &reference, lo, hi, 16, &err) == 0, "views: %s", err.message);
  fog_rbf guess[2] = {truth[0], truth[1]};
  guess[0].density = 0.05, guess[1].density = 0.002;
  CHECK(fit_views_rbf_amplitudes(&views, 1, guess, 2) == 0, "out of memory");
  for (int i = 0; i < 2; i++)
    CHECK(fabs(guess[i].density / truth[i].density - 1) < 1e-6, "amplitude %d: %.9g, want %g",
          i, guess[i].density, truth[i].density);
  fit_views_destroy(&views);
}

/* A fog floating far above the terrain (a cone of fog 1000 up, the terrain at 0): the height
 * rung's fitted H made a config whose fog, grown as e^{(y0-y)/H} down to the terrain, passed
 * float (the loader refuses it), and `fit --out` wrote it. Every rung now makes a scene
 * that passes the loader's model checks (scene_config_check); the height rung takes the
 * least H the scene holds. */
/* The fit of a config written as `text` into folder/name (false: a failed check). */
static bool run_text(const char *folder, const char *name, const char *text, fit_result *r) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", folder, name);
  test_write_text(path, text);
  static scene_config cfg; /* the rungs' configs are copies: it may be reused */
  fog_error err;
  const int loaded = scene_config_load(path, &cfg, &err);
  CHECK(loaded == 0, "%s", err.message);
  return !loaded && run(name, &cfg, r);
}

static void test_floating_fog(const char *folder) {
  fit_result r;
  if (!run_text(folder, "floating.ini",
                "[fog]\nmodel = quadric\nquadric = cone 0 1000 0 40 20 0.05\n"
                "[camera]\nposition = 0 1010 100\n[terrain]\norigin = -500 0 -500\n",
                &r))
    return;
  fog_error err;
  const fit_rung *h = rung_named(&r, "height");
  CHECK(h != NULL, "the cone's layers decay: a height rung");
  if (h) {
    const double least = scene_config_min_scale_height(h->config);
    CHECK(least > 1.0 && h->config->fog.scale_height >= least,
          "height rung H %g below the least the scene holds, %g", h->config->fog.scale_height,
          least);
  }
  for (int i = 0; i < r.count; i++)
    CHECK(scene_config_check(r.rungs[i].config, &err) == 0, "rung %s: %s", r.rungs[i].name,
          err.message);
  fit_result_destroy(&r);
}

/* Gaussian fog lit by a lamp with Fogshop's integral (for Gaussians alone): every other
 * rung lights it with ours; they kept fogshop, which the pass and the loader refuse beside
 * any other model, and the fit ended with an error. */
static void test_fogshop_input(const char *folder) {
  fit_result r;
  if (!run_text(folder, "fogshop.ini",
                "[fog]\nmodel = rbf\nrbf = 0 20 0 15 0.02\nalbedo = 0.8\n"
                "[light]\nlamp = 5 20 5 300 300 300\nlamp_integral = fogshop\n"
                "[camera]\nposition = 0 30 120\nlook_at = 0 20 0\n",
                &r))
    return;
  fog_error err;
  for (int i = 0; i < r.count; i++) {
    const scene_config *c = r.rungs[i].config;
    CHECK(scene_config_check(c, &err) == 0, "rung %s: %s", r.rungs[i].name, err.message);
    if (c->fog.model == FOG_MODEL_RBF && c->fog.quadric_count == 0)
      CHECK(c->lamp_method.integral == FOG_LAMP_FOGSHOP, "rung %s lost fogshop",
            r.rungs[i].name);
  }
  fit_result_destroy(&r);
}

/* Three rays through homogeneous fog of K 0.1 (tau e^{-1} along 10 units); the second's
 * length NaN. References 0 (error 0.37), e^{-1} and e^{-1} (error 0 on the third). */
static void test_nan_ray(void) {
  double origin[3][3] = {{0, 0, 0}, {0, 1, 0}, {0, 2, 0}}, dir[3][3] = {{1, 0, 0}, {1, 0, 0},
                                                                         {1, 0, 0}};
  double length[3] = {10.0, NAN, 10.0}, reference[3] = {0.0, exp(-1.0), exp(-1.0)};
  const fit_views v = {.count = 3, .origin = origin, .dir = dir, .length = length,
                       .reference = reference};
  const fog_model rung = {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = 0.1};
  double max_error, mean_error;
  fit_views_measure(&v, &rung, &max_error, &mean_error);
  printf("a NaN ray among errors 0.37 and 0: max %g, mean %g\n", max_error, mean_error);
  CHECK(isnan(max_error) && isnan(mean_error), "a NaN ray: max %g, mean %g (expected NaN: the "
        "rung measured nothing there)", max_error, mean_error);
}

int main(void) {
  char folder[] = "/tmp/fogpipe_fit_XXXXXX";
  test_nan_ray();
  CHECK(mkdtemp(folder) != NULL, "mkdtemp");
  test_constant();
  test_amplitudes();
  test_height();
  test_classic();
  test_ground_fog();
  test_gaussian();
  test_projected_fogmap();
  test_two_ellipsoids();
  test_oriented_ellipsoid(folder);
  test_plume(folder);
  test_sequence(folder);
  test_floating_fog(folder);
  test_fogshop_input(folder);
  char command[256];
  snprintf(command, sizeof command, "rm -rf '%s'", folder);
  if (system(command)) fprintf(stderr, "could not remove %s\n", folder);
  return test_finish("test_fit");
}
