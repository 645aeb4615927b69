/* The light at the edges of its settings, each against an exact value written here:
 * - light shafts over flat ground (a terrain of height 0) change nothing: no surface
 *   stands between the sun and fog above the ground, however far past the sun's shadow
 *   map the fog lies (rays up into a low sun and rays onto the ground: their in-scatter as
 *   with shafts off);
 * - height fog seen from far above its base (300 units over 2-unit scale heights):
 *   finite, and tau per pixel the closed form of the exponential's integral; Perlin fog's
 *   one-sample integral (the paper's) over it from 500 up, finite;
 * - a camera inside a box sees its inner faces lit as inner faces: the roof from below gets
 *   no sun (it faces away from it, and the roof shadows it), the back wall gets a lamp
 *   inside the box as the Lambertian formula says; its floor is the terrain (boxes have
 *   no bottom face, which fought flat ground for depth);
 * - a lamp of radius 0.001 at the camera, in height fog: every pixel finite;
 * - phase_g = 0.999 looking into the sun: the in-scatter is (L_amb + a L_sun p)(1 - tau)
 *   with Henyey-Greenstein's p in double, within 1e-4, at the peak too;
 * - a hard-edged sphere of density 10 to 1e4 over flat ground, lit from behind the camera,
 *   its self-shadow off: shafts on draw it as shafts off do (V = 1 everywhere), and its
 *   in-scatter is a L_sun p (1 - tau) (the two Gauss nodes' weights underflowed together
 *   in the shader's float in a segment ~90 deep: density 100 drew black with shafts on). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>

enum { W = 49, H = 27 };
#include "frame_util.h"
#include "render/fog_light.h"
#include "render/fog_models.h"
#include "test_util.h"

static const double pi = 3.14159265358979323846;
static char dir[] = "/tmp/fogpipe_light_edges_XXXXXX";

/* The config text loaded into cfg (1 on success, else a failed check). */
static int load(const char *text, scene_config *cfg) {
  char path[300];
  snprintf(path, sizeof path, "%s/scene.ini", dir);
  fog_error err = {0};
  if (!test_write_text(path, text)) return 0;
  const int loaded = scene_config_load(path, cfg, &err) == 0;
  CHECK(loaded, "%s", err.message);
  return loaded;
}

static bool all_finite(const frame *f) {
  for (int k = 0; k < W * H; k++) {
    if (!isfinite(f->tau[k])) return false;
    for (int c = 0; c < 3; c++)
      if (!isfinite(f->rgba[4 * k + c]) || !isfinite(f->inscatter[3 * k + c])) return false;
  }
  return true;
}

static void check_shafts_past_the_map(void) {
  static frame on, off;
  scene_config cfg;
  if (!load("[camera]\nposition = 0 50 900\npitch = 3\n[terrain]\nheight = 0\n"
            "[light]\nsun_elevation = 10\nsun_azimuth = 0\nfog_self_shadow = off\n"
            "[fog]\nmodel = homogeneous\ndensity_scale = 0.002\nalbedo = 1\nphase_g = 0\n"
            "colour = 0 0 0\n",
            &cfg))
    return;
  if (render(&cfg, &on, "shafts on")) return;
  cfg.shadow.shafts = 0;
  if (render(&cfg, &off, "shafts off")) return;
  camera cam;
  scene_config_camera(&cfg, &cam);
  double worst = 0, largest = 0;
  int up = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      /* the rays that stay above the ground: up into the sky, or down onto it (a ray down
       * past the terrain's edge goes on beneath it, where the terrain does shadow the fog) */
      double o[3], d[3];
      const double t = frame_pixel_ray(&off, &cam, px, py, o, d);
      if (d[1] < 0 && !isfinite(t)) continue;
      up += d[1] > 0;
      for (int c = 0; c < 3; c++) {
        const int k = 3 * (py * W + px) + c;
        worst = fmax(worst, fabs(on.inscatter[k] - off.inscatter[k]));
        largest = fmax(largest, off.inscatter[k]);
      }
    }
  printf("flat ground, a low sun: max |in-scatter with shafts - without| %.3e (largest %.3f, "
         "%d rays up)\n", worst, largest, up);
  CHECK(up > W * H / 4, "only %d rays up", up);
  CHECK(largest > 0.05, "too little in-scatter to test: %.3f", largest);
  CHECK(worst <= 1e-4 * largest, "the shafts darken fog nothing shadows by %.3e", worst);
}

static void check_height_fog_from_above(void) {
  static frame f;
  scene_config cfg;
  if (!load("[camera]\nposition = 0 300 0\npitch = -60\n[terrain]\nheight = 0.000001\n"
            "[fog]\nmodel = height\ndensity_scale = 0.01\nfog_height = 0\nscale_height = 2\n",
            &cfg) ||
      render(&cfg, &f, "height fog from above"))
    return;
  CHECK(all_finite(&f), "height fog seen from 300 units above its base: not finite");
  camera cam;
  scene_config_camera(&cfg, &cam);
  double worst = 0;
  int checked = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double o[3], d[3];
      const double t = frame_pixel_ray(&f, &cam, px, py, o, d);
      if (!isfinite(t) || d[1] >= 0) continue;
      /* int_0^t k e^{-(y(s) - y0)/H} ds = k H / -d_y (e^{-(y(t) - y0)/H} - e^{-(y(0) - y0)/H}) */
      const double k = 0.01, h = 2, y_end = o[1] + d[1] * t;
      const double depth = k * h / -d[1] * (exp(-y_end / h) - exp(-o[1] / h));
      worst = fmax(worst, fabs(f.tau[py * W + px] - exp(-depth)));
      checked++;
    }
  printf("height fog from above: %d pixels, max |tau - closed form| %.2e\n", checked, worst);
  CHECK(checked > W * H / 2, "only %d pixels on the ground", checked);
  CHECK(worst <= 1e-4, "tau off the closed form by %.3e", worst);
  /* the C twin, in double, from 2000 units up (e^{-1000} is 0 in double): a ray at -0.8
   * that ends on the base, 0.01 * 2 / 0.8 (1 - e^{-1000}) */
  const double twin = fog_height_optical_depth(0.01, 0, 2, 2000, -0.8, 2500);
  CHECK(fabs(twin - 0.025) <= 1e-15, "the C twin from 2000 up: %.17g, expected 0.025", twin);
}

/* Zdrojewska's one-sample Perlin integral (perlin_integral = paper) over the same height
 * fog, entering a tall box from above: finite too. */
static void check_perlin_paper_from_above(void) {
  static frame f;
  scene_config cfg;
  if (!load("[camera]\nposition = 0 500 0\npitch = -60\n[terrain]\nheight = 0.000001\n"
            "[box]\ntop = 200\n[fog]\nmodel = perlin\nperlin_integral = paper\n"
            "density_scale = 0.01\nfog_height = 0\nscale_height = 2\n",
            &cfg) ||
      render(&cfg, &f, "Perlin fog (paper) from above"))
    return;
  CHECK(all_finite(&f), "Perlin fog's paper integral from 500 units up: not finite");
}

static void check_inside_a_box(void) {
  static frame f;
  scene_config cfg;
  const char *box = "[terrain]\nheight = 0.000001\n[objects]\nbox = 0 -50 40 40 40 1 1 1\n";
  char text[600];
  /* looking up at the roof from inside, the sun high above it */
  snprintf(text, sizeof text, "%s[camera]\nposition = 0 20 -50\npitch = 80\n"
           "[light]\nsun_elevation = 60\nambient = 0 0 0\n", box);
  if (load(text, &cfg) && !render(&cfg, &f, "inside a box, the roof")) {
    const float *c = &f.rgba[4 * ((H / 2) * W + W / 2)];
    CHECK(c[0] < 1e-6f && c[1] < 1e-6f && c[2] < 1e-6f,
          "the roof's inner face takes the sun: %g %g %g", c[0], c[1], c[2]);
  }
  /* looking down at the floor inside the white box, lit by the sky alone: the terrain,
   * green, and nowhere the box's own white bottom, which lay in the flat terrain's plane and
   * won the depth test in stripes */
  snprintf(text, sizeof text, "%s[camera]\nposition = 0 20 -50\npitch = -80\n"
           "[light]\nsun_elevation = -10\nambient = 1 1 1\n", box);
  if (load(text, &cfg) && !render(&cfg, &f, "inside a box, the floor")) {
    camera cam;
    scene_config_camera(&cfg, &cam);
    int grey = 0, floor = 0;
    for (int py = 0; py < H; py++)
      for (int px = 0; px < W; px++) {
        double o[3], d[3];
        const double t = frame_pixel_ray(&f, &cam, px, py, o, d);
        if (!(o[1] + t * d[1] < 0.01)) continue; /* a wall */
        const float *c = &f.rgba[4 * (py * W + px)];
        floor++;
        grey += fabsf(c[0] - c[2]) < 0.01f && fabsf(c[1] - c[2]) < 0.01f;
      }
    CHECK(floor > W * H / 2 && grey == 0,
          "%d of %d floor pixels are the box's white bottom, not the terrain", grey, floor);
  }
  /* a lamp inside, 20 units from the back wall on the camera's axis */
  snprintf(text, sizeof text, "%s[camera]\nposition = 0 20 -40\n"
           "[light]\nsun_elevation = -10\nambient = 0 0 0\nlamp = 0 20 -50 1000 1000 1000\n",
           box);
  if (load(text, &cfg) && !render(&cfg, &f, "inside a box, a lamp")) {
    /* E = I cos / (pi (d^2 + r^2)), Lambertian albedo 1: the default radius 0.5, cos 1 */
    const double want = 1000 / (pi * (20 * 20 + 0.5 * 0.5));
    const float got = f.rgba[4 * ((H / 2) * W + W / 2)];
    printf("inside a box: the back wall under the lamp %.6f, expected %.6f\n", got, want);
    CHECK(fabs(got - want) <= 1e-3 * want, "the back wall under a lamp inside the box: %.6f, "
          "expected %.6f", got, want);
  }
}

static void check_lamp_at_the_camera(void) {
  static frame f;
  scene_config cfg;
  if (!load("[camera]\nposition = 0 150 0\npitch = -10\n[terrain]\nheight = 0.000001\n"
            "[light]\nlamp = 0 150 0 1000 1000 1000 0.001\n"
            "[fog]\nmodel = height\ndensity_scale = 0.02\nfog_height = 40\nscale_height = 20\n"
            "albedo = 1\n",
            &cfg) ||
      render(&cfg, &f, "a lamp at the camera"))
    return;
  CHECK(all_finite(&f), "a lamp of radius 0.001 at the camera: not finite");
}

static void check_sharp_phase(void) {
  static frame f;
  scene_config cfg;
  if (!load("[camera]\nposition = 0 60 300\nyaw = 0\npitch = 20\n[terrain]\nresolution = 65\n"
            "[light]\nsun_azimuth = 0\nsun_elevation = 20\nfog_self_shadow = off\n"
            "shafts = off\n[fog]\nmodel = homogeneous\ndensity_scale = 0.004\nalbedo = 1\n"
            "phase_g = 0.999\n",
            &cfg) ||
      render(&cfg, &f, "phase_g 0.999"))
    return;
  camera cam;
  scene_config_camera(&cfg, &cam);
  const fog_sun sun = scene_config_fog_sun(&cfg);
  const double g = 0.999;
  double worst = 0, peak = 0;
  for (int py = 0; py < H; py++)
    for (int px = 0; px < W; px++) {
      double o[3], d[3];
      camera_ray(&cam, px, py, W, H, o, d);
      const double mu = d[0] * sun.direction[0] + d[1] * sun.direction[1] +
                        d[2] * sun.direction[2];
      const double p = (1 - g * g) / (4 * pi * pow(1 + g * g - 2 * g * mu, 1.5));
      const double t = f.tau[py * W + px];
      for (int c = 0; c < 3; c++) {
        const double want = (cfg.fog.colour[c] + sun.radiance[c] * p) * (1 - t);
        worst = fmax(worst, fabs(f.inscatter[3 * (py * W + px) + c] - want) / want);
        peak = fmax(peak, want);
      }
    }
  printf("phase_g 0.999 into the sun: max relative |in-scatter - (L_amb + a L_sun p)(1 - tau)| "
         "%.2e (peak %.4g)\n", worst, peak);
  CHECK(peak > 1e3, "the sun is not in view: peak in-scatter %.4g", peak);
  CHECK(worst <= 1e-4, "the sharp phase function is off by %.3e relative", worst);
}

/* Height fog as dense near-homogeneous haze (scale height 1e7, K = 100): every ray is
 * opaque within a fraction of a unit and the sun's way out is e^{-1e9}: the in-scatter is the
 * ambient colour alone. The span of the sun's mean, -H/d_y ln(1 - q) with q = 20 d_y/(K H)
 * ~ 1e-8, was ln(1) = 0 in float: empty, so its mean was 1 and the sun shone through. */
static void check_near_homogeneous_height_fog(void) {
  static frame f;
  scene_config cfg;
  if (!load("[camera]\nposition = 0 300 0\nlook_at = 0 300 -100\nfov = 55\n"
            "[light]\nsun_elevation = 20\n[fog]\nmodel = height\ndensity_scale = 100\n"
            "fog_height = 0\nscale_height = 1e7\nalbedo = 0.9\n",
            &cfg) ||
      render(&cfg, &f, "near-homogeneous height fog"))
    return;
  double worst = 0;
  for (int k = 0; k < W * H; k++)
    for (int c = 0; c < 3; c++)
      worst = fmax(worst, fabs(f.inscatter[3 * k + c] - cfg.fog.colour[c]));
  printf("height fog of scale height 1e7: max |in-scatter - the ambient colour| %.2e\n", worst);
  CHECK(worst <= 1e-5, "the sun shines through opaque fog: in-scatter off by %.3e", worst);
}

static void check_dense_sphere_shafts(void) {
  static frame on, off;
  for (double density = 10.0; density <= 1e4; density *= 10.0) {
    char text[600];
    snprintf(text, sizeof text,
             "[camera]\nposition = 0 100 200\nlook_at = 0 100 0\n[terrain]\nheight = 0\n"
             "[light]\nsun_elevation = 30\nsun_azimuth = 180\nfog_self_shadow = off\n"
             "[fog]\nmodel = quadric\nquadric = sphere 0 100 0 30 %g 0\nalbedo = 0.9\n"
             "phase_g = 0\ncolour = 0 0 0\n", density);
    scene_config cfg;
    if (!load(text, &cfg)) return;
    if (render(&cfg, &on, "dense sphere, shafts on")) return;
    cfg.shadow.shafts = 0;
    if (render(&cfg, &off, "dense sphere, shafts off")) return;
    /* isotropic: p = 1/(4 pi), whatever the angle */
    const fog_sun fs = scene_config_fog_sun(&cfg);
    CHECK(fs.albedo == 0.9 && fs.direction[1] > 0.4, "the sun: albedo %g, up %g", fs.albedo,
          fs.direction[1]);
    double worst = 0.0, worst_exact = 0.0, largest = 0.0;
    for (int k = 0; k < W * H; k++)
      for (int c = 0; c < 3; c++) {
        const double exact = 0.9 * fs.radiance[c] / (4.0 * pi) * (1.0 - off.tau[k]);
        worst = fmax(worst, fabs(on.inscatter[3 * k + c] - off.inscatter[3 * k + c]));
        worst_exact = fmax(worst_exact, fabs(on.inscatter[3 * k + c] - exact));
        largest = fmax(largest, exact);
      }
    printf("sphere of density %g: max |shafts on - off| %.3e, |on - a L p (1 - tau)| %.3e "
           "(largest %.3f)\n", density, worst, worst_exact, largest);
    CHECK(largest > 0.1, "density %g: too little in-scatter to test: %.3f", density, largest);
    CHECK(worst <= 1e-4 * largest, "density %g: the shafts change unshadowed fog by %.3e",
          density, worst);
    CHECK(worst_exact <= 1e-3 * largest, "density %g: in-scatter off by %.3e", density,
          worst_exact);
  }
}

int main(void) {
  if (!test_scratch_folder(dir)) return test_finish("test_light_edges");
  check_dense_sphere_shafts();
  check_shafts_past_the_map();
  check_height_fog_from_above();
  check_perlin_paper_from_above();
  check_inside_a_box();
  check_lamp_at_the_camera();
  check_sharp_phase();
  check_near_homogeneous_height_fog();
  test_remove_tree(dir);
  return test_finish("test_light_edges");
}
