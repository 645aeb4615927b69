/* The lamps' in-scatter (render/fog_lamp.h: the CPU twin, which the GL pass matches pixel by
 * pixel in test_gpu_lamps) against the independent double-precision reference
 * (tests/render/lamp_reference.h: adaptive Gauss-Kronrod in t, nested tau and T), at the
 * product's default method, in the cases where lamp integrals break (Fogshop, Zhou et al.
 * 2007, Fig. 7, and the list), printing each error:
 * - Fogshop's halo: a bright lamp 0.5 radii from a Gaussian's centre, views sweeping past;
 *   Fogshop's approximation's error against ours;
 * - Fogshop's shaft: a dense tube of Gaussians with a hole, the lamp inside, in a thin base:
 *   the beam out of the hole; the approximation misses it (its base is unshadowed);
 * - the lamp inside dense fog with the camera in it, behind the camera, on the view ray
 *   (h = 0), 10 km away; the fogmap (tau table and march towards the lamp) and Perlin
 *   turbulence fog (the 3D volume is checked against the GL in test_gpu_lamps only).
 * Errors are relative to the largest reference value of each sweep of rays. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/render.h"
#include "fog_test_scene.h"
#include "lamp_reference.h"
#include "reference/perlin_reference.h"
#include "test_util.h"

static double model_k(const void *user, const double p[3]) {
  return fog_light_extinction_at((const fog_model *)user, p);
}

static const fog_lamp_method defaults = {.integral = FOG_LAMP_ANGLE,
                                         .angle_pieces = FOG_LAMP_ANGLE_PIECES,
                                         .span_pieces = FOG_LAMP_SPAN_PIECES,
                                         .depth_steps = FOG_LAMP_DEPTH_STEPS,
                                         .shadow_steps = FOG_LAMP_SHADOW_STEPS};

typedef struct sweep_error {
  double ours, fogshop; /* max |error| / max reference */
  double peak;
} sweep_error;

/* Rays from o towards targets[k] (n of them), each to t_end along its direction; the
 * reference's extinction from k (k_user), ours from m. */
static sweep_error sweep_with(const char *name, const fog_model *m, lamp_ref_extinction_fn k,
                              const void *k_user, const fog_lamp *lamp, double g,
                              double max_step, const double o[3], const double (*targets)[3],
                              int n, double t_end, bool with_fogshop) {
  lamp_ref_lamp ref_lamp = {.position = {lamp->position[0], lamp->position[1], lamp->position[2]},
                            .intensity = 1.0, .radius = lamp->radius,
                            .spot = lamp->kind == FOG_LAMP_SPOT,
                            .axis = {lamp->axis[0], lamp->axis[1], lamp->axis[2]},
                            .cos_inner = lamp->cos_inner, .cos_outer = lamp->cos_outer};
  lamp_ref_medium medium = {k, k_user, 1.0, g, max_step, 1e-9, NULL, NULL};
  double peak = 0.0, worst = 0.0, worst_fogshop = 0.0;
  double *want = malloc(sizeof(double) * n), *ours = malloc(sizeof(double) * n),
         *theirs = malloc(sizeof(double) * n);
  fog_lamp_method fogshop = defaults;
  fogshop.integral = FOG_LAMP_FOGSHOP;
  int unconverged = 0;
  for (int k = 0; k < n; k++) {
    double d[3] = {targets[k][0] - o[0], targets[k][1] - o[1], targets[k][2] - o[2]};
    fog_test_unit(d);
    lamp_ref_info info;
    want[k] = lamp_ref_inscatter_ex(&medium, &ref_lamp, o, d, t_end, &info);
    unconverged += !info.converged;
    ours[k] = fog_lamp_inscatter_unit(m, lamp, &defaults, g, o, d, t_end);
    theirs[k] = with_fogshop ? fog_lamp_inscatter_unit(m, lamp, &fogshop, g, o, d, t_end) : 0;
    peak = fmax(peak, want[k]);
  }
  for (int k = 0; k < n; k++) {
    worst = fmax(worst, fabs(ours[k] - want[k]));
    worst_fogshop = fmax(worst_fogshop, fabs(theirs[k] - want[k]));
  }
  CHECK(unconverged == 0, "%s: the reference did not converge on %d rays", name, unconverged);
  CHECK(peak > 0, "%s: no light", name);
  sweep_error e = {.ours = worst / peak, .fogshop = worst_fogshop / peak, .peak = peak};
  if (with_fogshop)
    printf("%-34s peak %.4e: ours max error %.2e of the peak, Fogshop's %.2e (%.0fx)\n", name,
           peak, e.ours, e.fogshop, e.fogshop / fmax(e.ours, 1e-300));
  else
    printf("%-34s peak %.4e: ours max error %.2e of the peak\n", name, peak, e.ours);
  free(want), free(ours), free(theirs);
  return e;
}

/* The same with the model's own extinction in the reference (fog_light_extinction_at). */
static sweep_error sweep(const char *name, const fog_model *m, const fog_lamp *lamp, double g,
                         double max_step, const double o[3], const double (*targets)[3], int n,
                         double t_end, bool with_fogshop) {
  return sweep_with(name, m, model_k, m, lamp, g, max_step, o, targets, n, t_end,
                    with_fogshop);
}

/* Perlin fog's extinction from the independent reference (tests/reference/perlin_reference.h:
 * the texels read and interpolated there, the height factor, 0 outside the box). */
static double perlin_ref_k(const void *user, const double p[3]) {
  const light_ref_medium *medium = user;
  return medium->density(medium, p);
}

int main(void) {
  enum { N = 17 };
  double targets[N][3];
  fog_lamp point = {.kind = FOG_LAMP_POINT, .intensity = {1, 1, 1}, .radius = 0.05};

  /* Fogshop's halo: a Gaussian of radius 2 at the origin, the lamp 1 unit (0.5 radii) off
   * its centre, the camera 20 away; views sweep across the lamp. */
  {
    fog_rbf g = {.centre = {0, 0, 0}, .radius = 2.0, .density = 0.6};
    fog_model m = {.kind = FOG_MODEL_RBF, .rbfs = &g, .rbf_count = 1};
    point.position[0] = 1.0, point.position[1] = 0, point.position[2] = 0;
    const double o[3] = {0.3, 0.2, 20.0};
    for (int k = 0; k < N; k++)
      targets[k][0] = -4.0 + 8.0 * k / (N - 1), targets[k][1] = 0.05, targets[k][2] = 0.0;
    for (int gi = 0; gi < 2; gi++) {
      double phase = gi ? 0.7 : 0.0;
      sweep_error e = sweep(gi ? "halo (g 0.7)" : "halo (isotropic)", &m, &point, phase, 0.1, o,
                            (const double(*)[3])targets, N, 40.0, true);
      /* measured at the defaults (8 + 8 pieces): 4.4e-5 isotropic, 1.4e-3 at g 0.7 (the ray
       * 0.05 from the lamp: the phase function's turn there and the Gaussian's extent are two
       * scales; 12 + 12 pieces: 9e-5) */
      CHECK(e.ours <= (gi ? 2e-3 : 1e-4), "halo g %g: our error %.3e of the peak", phase, e.ours);
      CHECK(e.fogshop >= 20 * e.ours && e.fogshop > 0.05,
            "halo g %g: Fogshop's approximation %.3e, ours %.3e: expected it >= 20x ours",
            phase, e.fogshop, e.ours);
    }
  }

  /* Fogshop's shaft: 8 rings of 12 Gaussians on a cylinder of radius 3 round the y axis, one
   * missing (the hole, towards +x), in a thin base; the lamp at the centre. Views from the
   * side sweep across the beam that leaves the hole. */
  {
    fog_rbf tube[96];
    int count = 0;
    for (int ring = 0; ring < 8; ring++)
      for (int a = 0; a < 12; a++) {
        if (ring == 4 && a == 0) continue; /* the hole, at angle 0 (+x), y = 0.5 */
        double angle = 2 * 3.14159265358979 * a / 12;
        tube[count++] = (fog_rbf){.centre = {3 * cos(angle), -3.5 + ring, 3 * sin(angle)},
                                  .radius = 0.9, .density = 3.0};
      }
    fog_model m = {.kind = FOG_MODEL_RBF, .extinction = 0.02, .rbfs = tube, .rbf_count = count};
    fog_lamp lamp = point;
    lamp.position[0] = 0, lamp.position[1] = 0.5, lamp.position[2] = 0;
    const double o[3] = {12.0, 0.5, 25.0};
    /* rays across the beam outside the tube, x from 4 to 14 at y 0.5, z 0 */
    for (int k = 0; k < N; k++)
      targets[k][0] = 4.0 + 10.0 * k / (N - 1), targets[k][1] = 0.5, targets[k][2] = 0.0;
    sweep_error e = sweep("shaft through a hole", &m, &lamp, 0.3, 0.2, o,
                          (const double(*)[3])targets, N, 30.0, true);
    CHECK(e.ours <= 1e-3, "shaft: our error %.3e of the peak", e.ours);
    CHECK(e.fogshop >= 20 * e.ours, "shaft: Fogshop's %.3e, ours %.3e", e.fogshop, e.ours);
  }

  /* A narrow spot (inner 1, outer 2 degrees; 3 and 5) shining along +x in thin homogeneous
   * fog, the views sweeping across its beam: the pieces cut at the ray's crossings of the
   * cones (a beam narrower than a piece's nodes fell between them: 0 to 3.65x the light) */
  {
    fog_model thin = {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = 0.01};
    const double o[3] = {0, 10, 60};
    for (int k = 0; k < N; k++)
      targets[k][0] = -30.0 + 60.0 * k / (N - 1), targets[k][1] = 10.0, targets[k][2] = 0.0;
    const double pi = 3.14159265358979323846, cones[2][2] = {{1, 2}, {3, 5}};
    for (int c = 0; c < 2; c++) {
      fog_lamp spot = {.kind = FOG_LAMP_SPOT, .position = {-40, 10, 0}, .intensity = {1, 1, 1},
                       .radius = 0.05, .axis = {1, 0, 0}, .cos_inner = cos(cones[c][0] * pi / 180),
                       .cos_outer = cos(cones[c][1] * pi / 180)};
      sweep_error e = sweep(c ? "spot 3/5 degrees across its beam" : "spot 1/2 degrees across "
                            "its beam", &thin, &spot, 0.3, 0, o, (const double(*)[3])targets, N,
                            200.0, false);
      CHECK(e.ours <= 1e-4, "a narrow spot (%g/%g degrees): our error %.3e of the peak",
            cones[c][0], cones[c][1], e.ours);
    }
  }

  /* Homogeneous fog: the lamp inside dense fog with the camera in it; behind the camera; on
   * the view ray (h = 0 at the sweep's middle ray); 10 km away in thin fog. */
  {
    fog_model dense = {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = 0.2};
    fog_lamp lamp = point;
    lamp.radius = 0.2;
    const double o[3] = {0, 0, 0};
    lamp.position[0] = 2, lamp.position[1] = 0.5, lamp.position[2] = -5;
    for (int k = 0; k < N; k++)
      targets[k][0] = -10 + 20.0 * k / (N - 1), targets[k][1] = 0.5, targets[k][2] = -10;
    sweep_error e = sweep("inside dense fog (K 0.2)", &dense, &lamp, 0.6, 0, o,
                          (const double(*)[3])targets, N, 60.0, false);
    CHECK(e.ours <= 1e-4, "inside dense fog: %.3e", e.ours);
    lamp.position[2] = 6; /* behind the camera */
    e = sweep("behind the camera", &dense, &lamp, 0.6, 0, o, (const double(*)[3])targets, N,
              60.0, false);
    CHECK(e.ours <= 1e-4, "behind the camera: %.3e", e.ours);
    /* on the ray: target k = N/2 passes through the lamp */
    lamp.position[0] = 0, lamp.position[1] = 0.25, lamp.position[2] = -5;
    e = sweep("on the view ray (h = 0)", &dense, &lamp, 0.6, 0, o, (const double(*)[3])targets,
              N, 60.0, false);
    CHECK(e.ours <= 1e-4, "on the ray: %.3e", e.ours);
    fog_model thin = {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = 1e-4};
    lamp.position[0] = 300, lamp.position[1] = 50, lamp.position[2] = -10000;
    lamp.radius = 0.5;
    for (int k = 0; k < N; k++)
      targets[k][0] = 200 + 200.0 * k / (N - 1), targets[k][1] = 50, targets[k][2] = -10000;
    e = sweep("10 km away (K 1e-4)", &thin, &lamp, 0.6, 0, o, (const double(*)[3])targets, N,
              2e4, false);
    CHECK(e.ours <= 1e-4, "10 km away: %.3e", e.ours);
  }

  /* The fogmap (tau from the table, T by the march): the test box with the exponential
   * profile, a lamp inside it, the camera inside too. */
  {
    fog_volume v = fog_test_volume(FOG_PROFILE_EXPONENTIAL);
    v.extinction = 0.1;
    transform_grid grid = fog_test_grid(1, 1.0, 0.0);
    fog_lod lod = {.levels = 0, .approx = &grid};
    fog_model m = {.kind = FOG_MODEL_FOGMAP, .volume = &v, .lod = &lod,
                   .lod_method = FOG_LOD_SWITCH};
    fog_lamp lamp = point;
    lamp.radius = 0.3;
    lamp.position[0] = 125, lamp.position[1] = 3, lamp.position[2] = -30;
    const double o[3] = {104, 4, -28};
    for (int k = 0; k < N; k++)
      targets[k][0] = 150, targets[k][1] = 3, targets[k][2] = -45 + 30.0 * k / (N - 1);
    sweep_error e = sweep("fogmap, lamp and camera inside", &m, &lamp, 0.6, 0.5, o,
                          (const double(*)[3])targets, N, 60.0, false);
    /* measured at the defaults: 1.85e-2 (the knot cells' kinks inside the pieces; 8 + 16
     * pieces with 64 depth and 16 shadow steps: 1.9e-3, 16 + 32: 7e-4) */
    CHECK(e.ours <= 2.5e-2, "fogmap: %.3e", e.ours);
    transform_grid_destroy(&grid);
  }
  /* Perlin turbulence fog (its octaves drifted to a time), the lamp and the camera inside */
  {
    fog_perlin_desc pd = fog_perlin_desc_default();
    pd.octaves = 3, pd.feature_size = 12.0;
    pd.lo[0] = 80.0, pd.hi[0] = 180.0, pd.lo[1] = 0.0, pd.hi[1] = 20.0;
    pd.lo[2] = -80.0, pd.hi[2] = 20.0;
    fog_perlin perlin;
    fog_error err = {0};
    if (fog_perlin_create(&perlin, &pd, &err)) {
      CHECK(0, "perlin: %s", err.message);
      return test_finish("test_lamp_accuracy");
    }
    fog_model m = {.kind = FOG_MODEL_PERLIN, .extinction = 0.08, .y0 = 2.0,
                   .scale_height = 6.0, .perlin = &perlin, .time = 7.5};
    fog_lamp lamp = point;
    lamp.radius = 0.3;
    lamp.position[0] = 125, lamp.position[1] = 3, lamp.position[2] = -30;
    const double o[3] = {104, 4, -28};
    /* three rays, past the lamp and either side (the reference's nested quadrature through
     * the noise costs ~10 s for the three); its density the independent one */
    enum { RAYS = 3 };
    for (int k = 0; k < RAYS; k++)
      targets[k][0] = 150, targets[k][1] = 3, targets[k][2] = -36 + 6.0 * k;
    const fog_perlin_medium pm = {.extinction = m.extinction, .y0 = m.y0,
                                  .scale_height = m.scale_height, .time = m.time,
                                  .integral = FOG_PERLIN_EXACT};
    const light_ref_medium density = light_ref_perlin_medium(&perlin, &pm);
    sweep_error e = sweep_with("perlin, lamp and camera inside", &m, perlin_ref_k, &density,
                               &lamp, 0.6, 0.5, o, (const double(*)[3])targets, RAYS, 40.0,
                               false);
    /* measured at the defaults: 5.6e-3 (T's 8-step walk through the eddies) */
    CHECK(e.ours <= 8e-3, "perlin: %.3e", e.ours);
    fog_perlin_destroy(&perlin);
  }
  return test_finish("test_lamp_accuracy");
}
