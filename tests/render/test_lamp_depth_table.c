/* The lamps' table of optical depth from the camera ([light] lamp_depth_steps) belongs to
 * the fogmap, the volume and Perlin fog: the classic factors (linear, exp2) take their
 * depth in closed form, so the key changes neither their light (the CPU twin, bit for bit,
 * at 1 and 64 steps) nor the loop bound the fog pass checks against llvmpipe's cap (it
 * counted the table's 65 passes a pixel that the shader built and never read). The fogmap's
 * bound does grow with the key (the test can tell). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "render/render.h"
#include "test_util.h"

static fog_pass_params lamp_params(fog_model_kind model, int depth_steps) {
  fog_pass_params p = {.model = model, .model_fog_start = 10.0, .model_fog_end = 300.0,
                       .model_extinction = 0.01};
  p.sun.albedo = 0.8;
  p.lamps.count = 1;
  p.lamps.lamp[0] = (fog_lamp){.kind = FOG_LAMP_POINT, .position = {0, 5, -40},
                               .intensity = {100, 100, 100}, .radius = 0.5};
  p.lamps.method = (fog_lamp_method){.integral = FOG_LAMP_ANGLE, .angle_pieces = 8,
                                     .span_pieces = 8, .depth_steps = depth_steps,
                                     .shadow_steps = 8, .march_steps = 64};
  return p;
}

int main(void) {
  const fog_model_kind classic[] = {FOG_MODEL_LINEAR, FOG_MODEL_EXP2};
  for (int k = 0; k < 2; k++) {
    fog_pass_params one = lamp_params(classic[k], 1), many = lamp_params(classic[k], 64);
    const double b1 = fog_pass_lamp_loop_bound(&one), b64 = fog_pass_lamp_loop_bound(&many);
    printf("%s: lamp loop bound %g at 1 depth step, %g at 64\n",
           fog_model_table[classic[k]].name, b1, b64);
    CHECK(b1 == b64, "%s: the bound counts a depth table it does not build (%g and %g)",
          fog_model_table[classic[k]].name, b1, b64);
    /* the light itself: the CPU twin along a few rays */
    fog_model m = {.kind = classic[k], .extinction = 0.01, .fog_start = 10.0,
                   .fog_end = 300.0, .eye = {0, 2, 0}};
    for (int r = 0; r < 4; r++) {
      const double o[3] = {0, 2, 0}, len = sqrt(1.0 + 0.01 * r * r);
      const double d[3] = {0.1 * r / len, 0.05 / len, -1.0 / len};
      const double a = fog_lamp_inscatter_unit(&m, &one.lamps.lamp[0], &one.lamps.method,
                                               0.3, o, d, 200.0);
      const double b = fog_lamp_inscatter_unit(&m, &many.lamps.lamp[0], &many.lamps.method,
                                               0.3, o, d, 200.0);
      CHECK(a == b && a > 0, "%s ray %d: %.17g at 1 step, %.17g at 64",
            fog_model_table[classic[k]].name, r, a, b);
    }
  }
  fog_pass_params one = lamp_params(FOG_MODEL_FOGMAP, 1), many = lamp_params(FOG_MODEL_FOGMAP, 64);
  CHECK(fog_pass_lamp_loop_bound(&one) < fog_pass_lamp_loop_bound(&many),
        "the fogmap's bound does not count its depth table");
  return test_finish("test_lamp_depth_table");
}
