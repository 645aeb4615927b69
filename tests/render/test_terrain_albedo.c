/* terrain_albedo (render/terrain.h): snow caps the hills of a valley with relief, never the
 * bumps of a nearly flat field (the VDB scenes' 8 cm terrain once showed white streaks
 * along its far edge); grass stays grass low down, and the snow line fades in between 10
 * and 40 units of relief. Flat ground (`height = 0`) and a field of bumps are one grass
 * whatever their hidden noise: the dry patches that follow h on hills once coloured a flat
 * plane in blotches no one could see the cause of (0.11 to 0.20 red). */
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
  for (int field = 0; field < 2; field++) {
    const double relief = field ? 0.08 : 0.0;
    float low[3], high[3];
    terrain_albedo(0.2, 1.0, relief, low);
    terrain_albedo(0.7, 1.0, relief, high);
    CHECK(low[0] == high[0] && low[1] == high[1] && low[2] == high[2],
          "relief %g: h 0.2 gives %.3f %.3f %.3f, h 0.7 %.3f %.3f %.3f (flat ground in patches)",
          relief, low[0], low[1], low[2], high[0], high[1], high[2]);
  }
  float dry_hill[3], green_hill[3];
  terrain_albedo(0.7, 1.0, 160.0, dry_hill);
  terrain_albedo(0.2, 1.0, 160.0, green_hill);
  CHECK(dry_hill[0] > green_hill[0] + 0.05, "the valley's upper slopes are not drier (%.3f, "
        "%.3f)", dry_hill[0], green_hill[0]);
  return test_finish("test_terrain_albedo");
}
