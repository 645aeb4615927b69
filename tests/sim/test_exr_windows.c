/* How fogmap_load reads an EXR's windows and channels (sim/image_exr.c), on files written
 * here through OpenEXR Core directly:
 * - the image is the display window, the data window placed in it at its offset, zero
 *   where there is no data, cropped where it reaches past (a file cropped to its non-empty
 *   pixels was read as the data window alone, stretched over the fog box);
 * - a file with any subsampled channel is refused, naming it (OpenEXR Core 3.1 decoded a
 *   luminance/chroma file's full-resolution Y as 1, 0.5, 0, ... for a constant 0.5, and
 *   read past its buffer). */
#define _POSIX_C_SOURCE 200809L
#include <openexr.h>
#include <stdio.h>
#include <string.h>

#include "sim/sim.h"
#include "test_util.h"

static exr_attr_box2i_t box(int x0, int y0, int x1, int y1) {
  exr_attr_box2i_t b;
  b.min.x = x0, b.min.y = y0, b.max.x = x1, b.max.y = y1;
  return b;
}

/* One scanline part, uncompressed, every channel float and the value v everywhere. */
static int write_exr(const char *path, int count, const char *const *names, const int *sampling,
                     exr_attr_box2i_t display, exr_attr_box2i_t data, float v) {
  exr_context_t ctxt = NULL;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  int part = 0;
  exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
  if (!rv) rv = exr_add_part(ctxt, "test", EXR_STORAGE_SCANLINE, &part);
  exr_attr_v2f_t centre;
  centre.x = centre.y = 0.0f;
  if (!rv)
    rv = exr_initialize_required_attr(ctxt, part, &display, &data, 1.0f, &centre, 1.0f,
                                      EXR_LINEORDER_INCREASING_Y, EXR_COMPRESSION_NONE);
  for (int c = 0; !rv && c < count; c++)
    rv = exr_add_channel(ctxt, part, names[c], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR,
                         sampling[c], sampling[c]);
  if (!rv) rv = exr_write_header(ctxt);
  float row[256];
  for (int i = 0; i < 256; i++) row[i] = v;
  exr_encode_pipeline_t encode = EXR_ENCODE_PIPELINE_INITIALIZER;
  int initialised = 0;
  for (int y = data.min.y; !rv && y <= data.max.y; y++) {
    exr_chunk_info_t chunk;
    rv = exr_write_scanline_chunk_info(ctxt, part, y, &chunk);
    if (!rv)
      rv = initialised ? exr_encoding_update(ctxt, part, &chunk, &encode)
                       : exr_encoding_initialize(ctxt, part, &chunk, &encode);
    initialised = !rv || initialised;
    for (int c = 0; !rv && c < encode.channel_count; c++) {
      exr_coding_channel_info_t *info = &encode.channels[c];
      info->encode_from_ptr = (const uint8_t *)row;
      info->user_pixel_stride = 4;
      info->user_line_stride = 4 * info->width;
      info->user_bytes_per_element = 4;
      info->user_data_type = EXR_PIXEL_FLOAT;
    }
    if (!rv) rv = exr_encoding_choose_default_routines(ctxt, part, &encode);
    if (!rv) rv = exr_encoding_run(ctxt, part, &encode);
  }
  if (initialised) exr_encoding_destroy(ctxt, &encode);
  exr_finish(&ctxt);
  return rv;
}

/* f is display-sized, v inside the data window [x0, x1] x [y0, y1] (display coordinates
 * from the display's corner), 0 outside. */
static void check_placed(const char *what, const fogmap *f, int w, int h, int x0, int y0, int x1,
                         int y1, float v) {
  CHECK(f->width == w && f->height == h, "%s: %dx%d, expected the display window's %dx%d",
        what, f->width, f->height, w, h);
  if (f->width != w || f->height != h) return;
  int wrong = 0;
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++) {
      const float want = x >= x0 && x <= x1 && y >= y0 && y <= y1 ? v : 0.0f;
      wrong += f->density[y * w + x] != want;
    }
  CHECK(wrong == 0, "%s: %d pixels not where the data window puts them", what, wrong);
}

/* A Y channel of v on data inside display, loaded: v on `placed` (display coordinates from
 * its corner), 0 elsewhere. */
static void windowed(const char *dir, const char *name, exr_attr_box2i_t display,
                     exr_attr_box2i_t data, float v, exr_attr_box2i_t placed) {
  char path[400];
  snprintf(path, sizeof path, "%s/%s.exr", dir, name);
  const char *y_only[1] = {"Y"};
  const int full[1] = {1};
  CHECK(write_exr(path, 1, y_only, full, display, data, v) == 0, "cannot write %s", path);
  fogmap f;
  fog_error err = {0};
  CHECK(fogmap_load(path, NULL, &f, &err) == 0, "%s: %s", name, err.message);
  if (err.code) return;
  check_placed(name, &f, display.max.x - display.min.x + 1, display.max.y - display.min.y + 1,
               placed.min.x, placed.min.y, placed.max.x, placed.max.y, v);
  fogmap_destroy(&f);
}

int main(void) {
  char dir[] = "/tmp/fogpipe-exr-windows-XXXXXX";
  if (!test_scratch_folder(dir)) return 1;
  char path[300];
  fogmap f;
  fog_error err = {0};
  /* the data window inside the display window, off its corner; then both off the origin,
   * the data window reaching past the display on two sides */
  windowed(dir, "inside", box(0, 0, 9, 9), box(2, 3, 5, 7), 2.0f, box(2, 3, 5, 7));
  windowed(dir, "past", box(10, 20, 17, 25), box(14, 18, 21, 22), 3.0f, box(4, 0, 7, 2));
  /* a subsampled chroma channel beside a full one: refused, naming it */
  snprintf(path, sizeof path, "%s/chroma.exr", dir);
  const char *yca[3] = {"A", "BY", "Y"};
  const int sampling[3] = {1, 2, 1};
  CHECK(write_exr(path, 3, yca, sampling, box(0, 0, 7, 5), box(0, 0, 7, 5), 0.5f) == 0,
        "cannot write %s", path);
  const int status = fogmap_load(path, &(fogmap_load_desc){.channel = "Y"}, &f, &err);
  CHECK(status != 0 && strstr(err.message, "\"BY\" is subsampled (2 x 2)"),
        "a file with a subsampled channel: %s", status ? err.message : "loaded");
  if (!status) fogmap_destroy(&f);
  test_remove_tree(dir);
  return test_finish("test_exr_windows");
}
