/* Every EXR fogpipe writes reads back exactly (sim/image.h): small images of every size
 * 1..12 x 1..12 whose content ranges from constant to incompressible (values drawn from 2
 * up to 2^24 levels), as 32-bit float and as half, written and read back value for value.
 * Some of these ZIP chunks deflate to exactly their raw length; OpenEXR Core 3.1.5 wrote the
 * stream anyway and every reader took it for raw bytes (a 6x6 wavelet band read back
 * 5e29), so image_write_exr keeps the raw bytes there. Every channel is marked pLinear 0
 * (scene-linear light, which B44 and DWA compress in a log space), as OpenEXR's default. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <openexr.h>

#include "sim/sim.h"
#include "test_util.h"

/* The number of channels of the file at path marked perceptually linear (pLinear 1); -1
 * when it cannot be read. */
static int perceptually_linear_channels(const char *path) {
  exr_context_t ctxt;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  if (exr_start_read(&ctxt, path, &init) != EXR_ERR_SUCCESS) return -1;
  const exr_attr_chlist_t *channels = NULL;
  int marked = -1;
  if (exr_get_channels(ctxt, 0, &channels) == EXR_ERR_SUCCESS) {
    marked = 0;
    for (int c = 0; c < channels->num_channels; c++) marked += channels->entries[c].p_linear != 0;
  }
  exr_finish(&ctxt);
  return marked;
}

static uint64_t state = 0x9e3779b97f4a7c15ull;
static uint32_t next_random(void) {
  state ^= state << 13, state ^= state >> 7, state ^= state << 17;
  return (uint32_t)(state >> 11);
}

int main(void) {
  char dir[] = "/tmp/fogpipe_exr_sizes_XXXXXX";
  if (!mkdtemp(dir)) {
    CHECK(0, "mkdtemp");
    return test_finish("test_exr_round_trip_sizes");
  }
  char path[128];
  snprintf(path, sizeof path, "%s/x.exr", dir);
  static float pixels[12 * 12];
  const uint32_t levels[5] = {2, 16, 256, 65536, 1u << 24};
  int files = 0, wrong = 0;
  for (int half = 0; half <= 1; half++)
    for (int l = 0; l < 5; l++)
      for (int w = 1; w <= 12; w++)
        for (int h = 1; h <= 12; h++) {
          for (int i = 0; i < w * h; i++) {
            /* half: values a half holds exactly (1 + 10 mantissa bits, exponents -4..3),
             * so equal means read back right */
            const uint32_t k = next_random() % levels[l];
            pixels[i] = half ? ldexpf((float)(1024 + k % 1024), (int)(k / 1024 % 8) - 14)
                             : (float)k * 1.0e-3f + 0.5f;
          }
          const image_channel y = {.name = "Y", .pixels = pixels, .as_half = half};
          fog_error err = {0};
          if (image_write_exr(path, w, h, &y, 1, &err)) {
            CHECK(0, "%dx%d: %s", w, h, err.message);
            continue;
          }
          fogmap map = {0};
          if (fogmap_load(path, &(fogmap_load_desc){.channel = "Y"}, &map, &err)) {
            CHECK(0, "%dx%d read: %s", w, h, err.message);
            continue;
          }
          files++;
          bool same = map.width == w && map.height == h;
          for (int i = 0; same && i < w * h; i++) same = map.density[i] == pixels[i];
          if (!same && wrong++ < 5)
            printf("%s %dx%d, %u levels: not read back as written\n", half ? "half" : "float",
                   w, h, levels[l]);
          fogmap_destroy(&map);
        }
  /* three channels, half and float */
  const image_channel rgb[3] = {{.name = "R", .pixels = pixels, .as_half = 1},
                                {.name = "G", .pixels = pixels, .as_half = 1},
                                {.name = "depth", .pixels = pixels}};
  fog_error err = {0};
  CHECK(image_write_exr(path, 4, 4, rgb, 3, &err) == 0, "%s", err.message);
  const int marked = perceptually_linear_channels(path);
  CHECK(marked == 0, "%d of 3 channels marked perceptually linear (pLinear 1)", marked);
  unlink(path);
  rmdir(dir);
  printf("%d EXRs of 1..12 x 1..12, float and half: %d not read back as written\n", files,
         wrong);
  CHECK(files == 2 * 5 * 144, "%d of %d written and read", files, 2 * 5 * 144);
  CHECK(wrong == 0, "%d EXRs came back different", wrong);
  return test_finish("test_exr_round_trip_sizes");
}
