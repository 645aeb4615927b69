/* An indexed PNG's alpha comes from its tRNS chunk (sim/fogmap.h: indexed PNGs expand to
 * R, G, B, A): a 2 x 2 palette image whose entries 0 and 1 are transparent (alpha 0) and
 * half transparent (128), read with channel A, gives 0, 128/255 and 1, 1 (it read 1
 * everywhere: the decoder was not asked to apply tRNS). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <spng.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim/sim.h"
#include "test_util.h"

int main(void) {
  char dir[] = "/tmp/fogpipe_png_trns_XXXXXX";
  if (!test_scratch_folder(dir)) return 1;
  char path[300];
  snprintf(path, sizeof path, "%s/indexed.png", dir);
  spng_ctx *ctx = spng_ctx_new(SPNG_CTX_ENCODER);
  spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
  struct spng_ihdr ihdr = {.width = 2, .height = 2, .bit_depth = 8,
                           .color_type = SPNG_COLOR_TYPE_INDEXED};
  int e = spng_set_ihdr(ctx, &ihdr);
  struct spng_plte plte = {.n_entries = 4};
  for (int i = 0; i < 4; i++)
    plte.entries[i] = (struct spng_plte_entry){.red = (uint8_t)(60 * i), .green = 200,
                                               .blue = 10, .alpha = 255};
  if (!e) e = spng_set_plte(ctx, &plte);
  struct spng_trns trns = {.n_type3_entries = 2, .type3_alpha = {0, 128}};
  if (!e) e = spng_set_trns(ctx, &trns);
  const uint8_t indices[4] = {0, 1, 2, 3};
  if (!e) e = spng_encode_image(ctx, indices, sizeof indices, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
  size_t size = 0;
  void *png = e ? NULL : spng_get_png_buffer(ctx, &size, &e);
  spng_ctx_free(ctx);
  CHECK(png && !e, "encoding the test PNG: %s", spng_strerror(e));
  FILE *f = fopen(path, "wb");
  CHECK(f && png && fwrite(png, 1, size, f) == size, "writing %s", path);
  if (f) fclose(f);
  free(png);
  fogmap map = {0};
  fog_error err = {0};
  CHECK(!fogmap_load(path, &(fogmap_load_desc){.channel = "A"}, &map, &err), "%s", err.message);
  const float want[4] = {0.0f, 128.0f / 255.0f, 1.0f, 1.0f};
  for (int i = 0; map.density && i < 4; i++)
    CHECK(fabsf(map.density[i] - want[i]) <= 1e-6f, "pixel %d: alpha %g, expected %g", i,
          (double)map.density[i], (double)want[i]);
  fogmap_destroy(&map);
  CHECK(!fogmap_load(path, &(fogmap_load_desc){.channel = "R"}, &map, &err), "%s", err.message);
  for (int i = 0; map.density && i < 4; i++)
    CHECK(fabsf(map.density[i] - 60.0f * i / 255.0f) <= 1e-6f, "pixel %d: red %g", i,
          (double)map.density[i]);
  fogmap_destroy(&map);
  test_remove_tree(dir);
  return test_finish("test_png_indexed_alpha");
}
