/* [light] lamp and spot lines (docs/config.md): configs/night_lamps.ini parses into the
 * lamps it states, in file order; the default radius and method; scene_config_fog_lamps
 * makes spot axes unit and half-angles cosines; a config without lamps has none. */
#include <math.h>
#include <stdio.h>

#include "app/config.h"
#include "test_util.h"

int main(void) {
  scene_config cfg;
  fog_error err = {0};
  CHECK(scene_config_load("configs/night_lamps.ini", &cfg, &err) == 0, "night_lamps.ini: %s",
        err.message);
  CHECK(cfg.lamp_count == 9, "lamps: %d, expected 8 lamp lines and 1 spot", cfg.lamp_count);
  const scene_lamp_config *first = &cfg.lamps[0], *spot = &cfg.lamps[8];
  CHECK(!first->spot && first->position[0] == -100 && first->position[1] == 74 &&
            first->position[2] == 250 && first->colour[0] == 1800 && first->colour[2] == 450 &&
            first->radius == 0.5,
        "first lamp: (%g %g %g) colour %g radius %g", first->position[0], first->position[1],
        first->position[2], first->colour[0], first->radius);
  CHECK(spot->spot && spot->axis[1] == -127 && spot->inner == 8 && spot->outer == 16,
        "the spot: axis y %g, cone %g..%g", spot->axis[1], spot->inner, spot->outer);
  CHECK(cfg.lamp_method.angle_pieces == FOG_LAMP_ANGLE_PIECES &&
            cfg.lamp_method.span_pieces == FOG_LAMP_SPAN_PIECES &&
            cfg.lamp_method.depth_steps == FOG_LAMP_DEPTH_STEPS &&
            cfg.lamp_method.shadow_steps == FOG_LAMP_SHADOW_STEPS,
        "method defaults %d %d %d", cfg.lamp_method.angle_pieces, cfg.lamp_method.depth_steps,
        cfg.lamp_method.shadow_steps);
  fog_lamps lamps = scene_config_fog_lamps(&cfg);
  const fog_lamp *s = &lamps.lamp[8];
  double len = sqrt(s->axis[0] * s->axis[0] + s->axis[1] * s->axis[1] + s->axis[2] * s->axis[2]);
  double want_y = -127 / sqrt(50.0 * 50 + 127.0 * 127 + 170.0 * 170);
  CHECK(lamps.count == 9 && s->kind == FOG_LAMP_SPOT && fabs(len - 1) < 1e-15 &&
            fabs(s->axis[1] - want_y) < 1e-15,
        "spot axis (%.17g %.17g %.17g)", s->axis[0], s->axis[1], s->axis[2]);
  CHECK(fabs(s->cos_inner - cos(8 * 3.14159265358979323846 / 180)) < 1e-15 &&
            fabs(s->cos_outer - cos(16 * 3.14159265358979323846 / 180)) < 1e-15,
        "cone cosines %.17g %.17g", s->cos_inner, s->cos_outer);
  CHECK(lamps.lamp[0].kind == FOG_LAMP_POINT && lamps.lamp[0].intensity[1] == 1100,
        "first lamp as the fog sees it");
  CHECK(scene_config_load("configs/default.ini", &cfg, &err) == 0 && cfg.lamp_count == 0,
        "default.ini: %d lamps", cfg.lamp_count);
  return test_finish("test_config_lamps");
}
