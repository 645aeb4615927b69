/* `[fog] quadric = SHAPE ...` lines mean what docs/config.md says: each shape's surface (the
 * equation written out here, not through the render library's constructors) is where the
 * loaded volume's Q is 0, its core where Q = -1, its box the shape's bounds; `general` keeps
 * its ten coefficients and box as written; EDGE defaults to 0 (a hard edge), NOISE (after
 * EDGE) to 0; volumes stay in
 * file order; `scene_config_write` gives them back as the same scene. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/config.h"
#include "test_util.h"

static double q_at(const fog_quadric *v, double x, double y, double z) {
  const double *q = v->q;
  return q[0] * x * x + q[1] * y * y + q[2] * z * z + q[3] * x * y + q[4] * y * z +
         q[5] * x * z + q[6] * x + q[7] * y + q[8] * z + q[9];
}

static void near(double got, double want, double tol, const char *what) {
  CHECK(fabs(got - want) <= tol, "%s: %.17g, expected %.17g", what, got, want);
}

int main(void) {
  char dir[] = "/tmp/fogpipe_quadric_XXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  char path[256], copy[256];
  snprintf(path, sizeof path, "%s/q.ini", dir);
  snprintf(copy, sizeof copy, "%s/written.ini", dir);
  FILE *f = fopen(path, "w");
  fputs("[fog]\nmodel = quadric\ndensity_scale = 2\n"
        "quadric = sphere 10 20 30 5 0.1\n"
        "quadric = ellipsoid -10 0 5 4 2 8 0.2 0.25\n"
        "quadric = cylinder 100 -5 50 3 40 0.3 0.5\n"
        "quadric = cone -50 10 -60 12 30 0.4 1 0.35\n"
        "quadric = general 1 -2 3 0.5 -0.25 0.125 7 8 9 -10 -1 -2 -3 4 5 6 0.05 0.75\n", f);
  fclose(f);
  scene_config cfg;
  fog_error err = {0};
  if (scene_config_load(path, &cfg, &err)) {
    CHECK(0, "%s", err.message);
    return test_finish("test_config_quadric");
  }
  CHECK(cfg.fog.model == FOG_MODEL_QUADRIC && cfg.fog.quadric_count == 5, "model %d, %d volumes",
        cfg.fog.model, cfg.fog.quadric_count);
  const fog_quadric *s = &cfg.fog.quadrics[0], *e = &cfg.fog.quadrics[1];
  const fog_quadric *cy = &cfg.fog.quadrics[2], *co = &cfg.fog.quadrics[3];
  const fog_quadric *g = &cfg.fog.quadrics[4];
  /* sphere: |x - (10, 20, 30)| = 5; densities as written (density_scale applies at render) */
  near(q_at(s, 15, 20, 30), 0, 1e-13, "sphere surface +x");
  near(q_at(s, 10, 20 + 3, 30 + 4), 0, 1e-13, "sphere surface (0, 3, 4)");
  near(q_at(s, 10, 20, 30), -1, 1e-13, "sphere centre");
  near(s->lo[0], 5, 0, "sphere box"), near(s->hi[2], 35, 0, "sphere box");
  near(s->density, 0.1, 0, "sphere density"), near(s->edge, 0, 0, "default edge");
  near(s->noise, 0, 0, "default noise"), near(co->noise, 0.35, 0, "cone noise (after EDGE)");
  /* ellipsoid: ((x + 10)/4)^2 + (y/2)^2 + ((z - 5)/8)^2 = 1 */
  near(q_at(e, -6, 0, 5), 0, 1e-13, "ellipsoid x");
  near(q_at(e, -10, -2, 5), 0, 1e-13, "ellipsoid y");
  near(q_at(e, -10, 0, 13), 0, 1e-13, "ellipsoid z");
  near(q_at(e, -10, 0, 5), -1, 1e-13, "ellipsoid centre");
  near(e->lo[1], -2, 0, "ellipsoid box"), near(e->hi[2], 13, 0, "ellipsoid box");
  near(e->edge, 0.25, 0, "ellipsoid edge");
  /* cylinder: (x - 100)^2 + (z - 50)^2 = 9 for y in [-5, 35] */
  near(q_at(cy, 103, 0, 50), 0, 1e-12, "cylinder wall");
  near(q_at(cy, 100, 30, 47), 0, 1e-12, "cylinder wall");
  near(q_at(cy, 100, 12, 50), -1, 1e-12, "cylinder axis");
  near(cy->lo[1], -5, 0, "cylinder floor"), near(cy->hi[1], 35, 0, "cylinder top");
  /* cone: radius 12 (1 - (y - 10)/30) about (-50, -60), y in [10, 40], apex on top */
  near(q_at(co, -38, 10, -60), 0, 1e-12, "cone base rim");
  near(q_at(co, -50, 25, -54), 0, 1e-12, "cone wall half way (radius 6)");
  near(q_at(co, -50, 40, -60), 0, 1e-12, "cone apex");
  near(q_at(co, -50, 10, -60), -1, 1e-12, "cone base centre");
  near(co->lo[1], 10, 0, "cone base"), near(co->hi[1], 40, 0, "cone top");
  /* general: as written */
  static const double want_q[10] = {1, -2, 3, 0.5, -0.25, 0.125, 7, 8, 9, -10};
  for (int k = 0; k < 10; k++) near(g->q[k], want_q[k], 0, "general coefficient");
  near(g->lo[0], -1, 0, "general box"), near(g->hi[2], 6, 0, "general box");
  near(g->density, 0.05, 0, "general density"), near(g->edge, 0.75, 0, "general edge");
  /* written back: the same scene */
  CHECK(scene_config_write(&cfg, copy, &err) == 0, "scene_config_write: %s", err.message);
  scene_config again;
  if (scene_config_load(copy, &again, &err)) {
    CHECK(0, "written config: %s", err.message);
  } else {
    CHECK(scene_config_fingerprint(&again) == scene_config_fingerprint(&cfg),
          "written and loaded back, the volumes differ");
    CHECK(again.fog.quadric_count == 5 &&
              !memcmp(again.fog.quadrics, cfg.fog.quadrics, sizeof cfg.fog.quadrics[0] * 5),
          "written and loaded back, the volumes differ bit for bit");
  }
  /* A general quadric in full precision passes a config line's 199 bytes: it goes on over
   * indented lines (a comment between), is the same volume as the one-line form, written
   * back over three lines (six numbers a line), and a mistake in its second line names its
   * first. */
  {
    static const double q[17] = {8.264462809917356e-05, 3.086419753086420e-03,
                                 6.249999999999999e-04, -1.234567890123457e-04,
                                 2.345678901234568e-05, -3.456789012345679e-06,
                                 -4.567890123456789e-02, 5.678901234567890e-01,
                                 -6.789012345678901e-02, -9.876543210987654e-01,
                                 -1.110000000000001e+02, -3.330000000000001e+01,
                                 -5.550000000000001e+01, 1.110000000000001e+02,
                                 3.330000000000001e+01, 5.550000000000001e+01,
                                 1.963600000000001e-02};
    char line[1024] = "quadric = general";
    for (int k = 0; k < 17; k++) snprintf(line + strlen(line), sizeof line - strlen(line), " %.16e", q[k]);
    CHECK(strlen(line) > 199, "the one-line form is only %zu bytes", strlen(line));
    f = fopen(path, "w");
    fputs("[fog]\nmodel = quadric\nquadric = general", f);
    for (int k = 0; k < 17; k++) {
      if (k == 6) fputs("\n  ; the last coefficients, the box and the density\n ", f);
      if (k == 12) fputs("\n ", f);
      fprintf(f, " %.16e", q[k]);
    }
    fputs("\nquadric = sphere 0 0 0 5 0.1\n", f);
    fclose(f);
    scene_config split;
    if (scene_config_load(path, &split, &err)) {
      CHECK(0, "a general quadric over two lines: %s", err.message);
    } else {
      const fog_quadric *v = &split.fog.quadrics[0];
      bool same = split.fog.quadric_count == 2 && v->density == q[16];
      for (int k = 0; k < 10; k++) same = same && v->q[k] == q[k];
      for (int a = 0; a < 3; a++) same = same && v->lo[a] == q[10 + a] && v->hi[a] == q[13 + a];
      CHECK(same, "the two-line general quadric is not the one written (%d volumes)",
            split.fog.quadric_count);
      CHECK(scene_config_write(&split, copy, &err) == 0 &&
                scene_config_load(copy, &again, &err) == 0 &&
                !memcmp(again.fog.quadrics, split.fog.quadrics, 2 * sizeof split.fog.quadrics[0]),
            "written back over three lines and read: %s", err.message);
    }
    f = fopen(path, "w");
    fputs("[fog]\nmodel = quadric\nquadric = general 1 1 1 0 0 0 0 0 0 -1\n  -1 -1 -1 1 1\n"
          "density_scale = 1\n", f);
    fclose(f);
    CHECK(scene_config_load(path, &split, &err) != 0 && strstr(err.message, "q.ini:3: [fog] quadric: ") &&
              strstr(err.message, "16 numbers") == NULL && strstr(err.message, "17 to 19 numbers"),
          "a short two-line general quadric: %s", err.message);
  }
  unlink(copy), unlink(path), rmdir(dir);
  return test_finish("test_config_quadric");
}
