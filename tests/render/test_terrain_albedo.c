/* terrain_albedo (render/terrain.h): snow caps the hills of a valley with relief, never the
 * bumps of a nearly flat field (the VDB scenes' 8 cm terrain once showed white streaks
 * along its far edge); grass stays grass low down, and the snow line fades in between 10
 * and 40 units of relief. */
#include <math.h>

#include "render/terrain.h"
#include "tests/test_util.h"

static double brightness(const float c[3]) { return (c[0] + c[1] + c[2]) / 3.0; }

int main(void) {
  float top_valley[3], top_field[3], low_valley[3], top_mid[3];
  terrain_albedo(0.95, 1.0, 160.0, top_valley); /* the default valley's summit */
  terrain_albedo(0.95, 1.0, 0.08, top_field);   /* the highest bump of an 8 cm field */
  terrain_albedo(0.10, 1.0, 160.0, low_valley);
  terrain_albedo(0.95, 1.0, 25.0, top_mid);
  CHECK(brightness(top_valley) > 0.8, "no snow on the valley's summit (%.3f)",
        brightness(top_valley));
  CHECK(brightness(top_field) < 0.3, "snow on a field 8 cm tall (%.3f)", brightness(top_field));
  CHECK(brightness(low_valley) < 0.2, "the valley floor is not grass (%.3f)",
        brightness(low_valley));
  CHECK(brightness(top_mid) > brightness(top_field) + 0.1 &&
            brightness(top_mid) < brightness(top_valley) - 0.1,
        "25 units of relief: %.3f, not between the field's %.3f and the valley's %.3f",
        brightness(top_mid), brightness(top_field), brightness(top_valley));
  return test_finish("test_terrain_albedo");
}
