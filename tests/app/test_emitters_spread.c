/* The simulation's three emitters sit across the whole map, x by its width and z by its
 * height: on a 256 x 32 map whose fog starts empty, five baked frames hold fog in each
 * quarter of the columns the emitters fall in (0.30, 0.55, 0.75 of the width), and under
 * half of it in the first quarter. Placed by the shorter side, all three sat in columns
 * 5..27 (FOGPIPE_BIN). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>

#include "sim/sim.h"
#include "test_bin.h"

enum { W = 256, H = 32 };

int main(void) {
  char dir[] = "/tmp/fogpipe_emitters_XXXXXX";
  const char *bin = test_bin_and_folder(dir);
  if (!bin) return test_finish("test_emitters_spread");
  char map_path[300], ini[300], out[300], frame[400], cmd[1400];
  snprintf(map_path, sizeof map_path, "%s/empty.exr", dir);
  snprintf(ini, sizeof ini, "%s/scene.ini", dir);
  snprintf(out, sizeof out, "%s/bake", dir);
  fogmap map;
  fog_error err;
  CHECK(!fogmap_create(&map, W, H, &err), "%s", err.message);
  for (int i = 0; i < W * H; i++) map.density[i] = 0.0f;
  CHECK(!fogmap_save_exr(map_path, &map, &err), "%s", err.message);
  fogmap_destroy(&map);
  test_write_text(ini, "[fog]\nfogmap = empty.exr\n[sim]\nemitter_rate = 1\n");
  snprintf(cmd, sizeof cmd, "'%s' bake '%s' --frames 5 --out '%s' > /dev/null", bin, ini, out);
  CHECK(system(cmd) == 0, "%s failed", cmd);
  snprintf(frame, sizeof frame, "%s/fog.0005.exr", out);
  CHECK(!fogmap_load(frame, NULL, &map, &err), "%s", err.message);
  double quarter[4] = {0, 0, 0, 0}, total = 0;
  for (int z = 0; map.density && z < map.height; z++)
    for (int x = 0; x < map.width; x++) {
      const double v = map.density[(size_t)z * map.width + x];
      quarter[4 * x / map.width] += v, total += v;
    }
  printf("baked %dx%d: mass by quarter of the columns %.4g %.4g %.4g %.4g\n", map.width,
         map.height, quarter[0], quarter[1], quarter[2], quarter[3]);
  CHECK(total > 0 && quarter[1] > 0.1 * total && quarter[2] > 0.1 * total &&
            quarter[3] > 0.1 * total && quarter[0] < 0.5 * total,
        "the emitters' fog by quarter: %g %g %g %g of %g", quarter[0], quarter[1], quarter[2],
        quarter[3], total);
  fogmap_destroy(&map);
  test_remove_tree(dir);
  return test_finish("test_emitters_spread");
}
