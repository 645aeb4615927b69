/* libFuzzer harness: PNG fogmaps (sim/image_png.c through libspng), decoded from memory as
 * fogmap_load decodes them after reading the file. Input: byte 0 picks the channel
 * argument (fogmap_load_desc.channel: none, "grey", "R", "G", "B", "A" by byte 0 % 6), the
 * rest is the PNG file. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sim/image_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static const char *const channels[6] = {NULL, "grey", "R", "G", "B", "A"};
  if (size < 1) return 0;
  const char *channel = channels[data[0] % 6];
  int width = 0, height = 0;
  float *pixels = NULL;
  fog_error err;
  memset(&err, 0x55, sizeof err); /* a message that is not terminated shows up below */
  if (png_read_channel("fuzz.png", data + 1, size - 1, channel, NULL, &width, &height, &pixels,
                       &err) == 0) {
    /* Every pixel must be there and be a sample / (2^depth - 1). */
    if (width <= 0 || height <= 0 || !pixels) abort();
    size_t count = (size_t)width * (size_t)height;
    for (size_t i = 0; i < count; i++)
      if (!(pixels[i] >= 0.0f && pixels[i] <= 1.0f)) abort();
    free(pixels);
  } else if (!memchr(err.message, '\0', sizeof err.message)) {
    abort();
  }
  return 0;
}
