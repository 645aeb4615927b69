/* libFuzzer harness: EXR fogmaps (sim/image_exr.c through OpenEXR Core), through the
 * public fogmap_load: magic detection (sim/fogmap_io.c), part 0's header, one channel of
 * a scanline or tiled image, every density checked. Input: byte 0 picks the channel
 * argument (none, "Y", "R", "G", "B", "A", "density" by byte 0 % 7), the rest is the file
 * (handed over as a memfd path). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "sim/sim.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const char *const channels[7] = {NULL, "Y", "R", "G", "B", "A", "density"};
  if (size < 1) return 0;
  fogmap_load_desc desc = {.channel = channels[data[0] % 7]};
  const char *path = fuzz_memfd_path(data + 1, size - 1);
  fogmap map;
  fog_error err;
  memset(&err, 0x55, sizeof err); /* a message that is not terminated shows up below */
  if (fogmap_load(path, &desc, &map, &err) == 0) {
    if (map.width <= 0 || map.height <= 0 || !map.density) abort();
    size_t count = (size_t)map.width * (size_t)map.height;
    for (size_t i = 0; i < count; i++)
      if (!(map.density[i] >= 0.0f && map.density[i] <= FOGMAP_MAX_DENSITY)) abort();
    fogmap_destroy(&map);
  } else if (!memchr(err.message, '\0', sizeof err.message)) {
    abort();
  }
  return 0;
}
