/* Reading one channel of a rendered EXR in the app tests, checking its size. */
#ifndef FOGPIPE_TEST_EXR_CHANNEL_UTIL_H
#define FOGPIPE_TEST_EXR_CHANNEL_UTIL_H

#include "sim/sim.h"
#include "test_util.h"

/* The channel's values (the caller frees them), or NULL after a failed CHECK. */
static inline float *load_exr_channel(const char *path, const char *channel, int width,
                                      int height) {
  fogmap map = {0};
  fog_error err;
  if (fogmap_load(path, &(fogmap_load_desc){.channel = channel}, &map, &err)) {
    CHECK(0, "%s channel %s: %s", path, channel, err.message);
    return NULL;
  }
  CHECK(map.width == width && map.height == height, "%s is %dx%d, expected %dx%d", path,
        map.width, map.height, width, height);
  return map.density;
}

#endif
