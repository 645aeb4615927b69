/* libFuzzer harness: Blender/Mantaflow config_####.uni files (sim/vdb_config.c,
 * mantaflow_config_read: gzip, then a 204-byte little-endian struct). The input is the
 * file (a memfd path). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "sim/sim.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *path = fuzz_memfd_path(data, size);
  mantaflow_config cfg;
  fog_error err;
  memset(&err, 0x55, sizeof err);
  if (mantaflow_config_read(path, &cfg, &err) == 0) {
    for (int a = 0; a < 3; a++)
      if (cfg.res[a] <= 0 || cfg.base_res[a] <= 0 || !(cfg.p1[a] > cfg.p0[a])) abort();
    if (cfg.cache_version[4] != '\0') abort();
  } else if (!memchr(err.message, '\0', sizeof err.message)) {
    abort();
  }
  return 0;
}
