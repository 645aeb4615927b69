/* A terrain desc's values are taken as given (render/terrain.h): height 0 is a flat
 * terrain at the origin's height, not a default height; a zero size, resolution, octave
 * count, frequency or persistence is refused with a message naming the value, not
 * replaced. */
#include <string.h>

#include "render/render.h"
#include "test_util.h"

static const terrain_desc hills = {.origin = {-50, 7, -20}, .size = {100, 40}, .height = 30,
                                   .resolution = 17, .octaves = 6, .frequency = 3,
                                   .persistence = 0.5, .seed = 2};

static void expect_refused(terrain_desc desc, const char *named, const char *what) {
  fog_error err = {0};
  terrain t;
  int status = terrain_create(&t, &desc, &err);
  CHECK(status != 0 && strstr(err.message, named), "%s: status %d, message '%s'", what, status,
        err.message);
  if (!status) terrain_destroy(&t);
}

int main(void) {
  fog_error err = {0};
  terrain t;
  terrain_desc flat = hills;
  flat.height = 0;
  CHECK(terrain_create(&t, &flat, &err) == 0, "flat terrain: %s", err.message);
  CHECK(t.min_y == 7 && t.max_y == 7, "height 0: heights span [%g, %g], not 7", t.min_y,
        t.max_y);
  CHECK(terrain_height_at(&t, 12.5, 3.25) == 7, "height 0: %g at (12.5, 3.25), not 7",
        terrain_height_at(&t, 12.5, 3.25));
  terrain_destroy(&t);
  CHECK(terrain_create(&t, &hills, &err) == 0, "hills: %s", err.message);
  CHECK(t.max_y - t.min_y > 1, "height 30: heights span only [%g, %g]", t.min_y, t.max_y);
  terrain_destroy(&t);

  terrain_desc d = hills;
  d.size[1] = 0;
  expect_refused(d, "size", "size 0");
  d = hills, d.height = -1;
  expect_refused(d, "height", "height -1");
  d = hills, d.resolution = 0;
  expect_refused(d, "resolution", "resolution 0");
  d = hills, d.octaves = 0;
  expect_refused(d, "octaves", "0 octaves");
  d = hills, d.frequency = 0;
  expect_refused(d, "frequency", "frequency 0");
  d = hills, d.persistence = 0;
  expect_refused(d, "persistence", "persistence 0");
  /* the finest noise the config allows (frequency 1e6, 16 octaves: lattice indices past
   * 2^31, which overflowed an int32 cast; the sanitizer pass catches the cast): heights
   * finite in [0, 1], varying */
  terrain_desc finest = hills;
  finest.frequency = 1e6, finest.octaves = 16, finest.resolution = 33;
  CHECK(terrain_create(&t, &finest, &err) == 0, "the finest terrain: %s", err.message);
  float lo = 1.0f, hi = 0.0f;
  int bad = 0;
  for (int k = 0; k < 33 * 33; k++) {
    const float h = t.h[k];
    if (!(h >= 0.0f && h <= 1.0f)) bad++;
    lo = h < lo ? h : lo, hi = h > hi ? h : hi;
  }
  CHECK(bad == 0 && hi - lo > 0.1f, "the finest terrain: %d heights outside [0, 1], range %g",
        bad, hi - lo);
  terrain_destroy(&t);
  return test_finish("test_terrain_desc");
}
