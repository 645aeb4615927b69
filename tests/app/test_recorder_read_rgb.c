/* recorder_read_rgb (what `record --preview` and the headless demo's screenshot read back)
 * returns a frame's R, G, B as written, whatever light a pixel holds: a lamp-lit pixel of
 * 1.07e13 was refused as "too large ... densities must be ... at most 1e+12" (the frames
 * were read as fogmaps), after the whole recording. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app/recorder.h"
#include "test_util.h"

enum { W = 4, H = 3 };

int main(void) {
  char root[] = "/tmp/fogpipe-read-rgb-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  recorder rec;
  fog_error err = {0};
  CHECK(!recorder_open(&rec, &(recorder_desc){.folder = root, .width = W, .height = H}, &err),
        "recorder_open: %s", err.message);
  float rgba[W * H * 4], transmittance[W * H], depth[W * H], inscatter[W * H * 3];
  for (int i = 0; i < W * H; i++) {
    rgba[4 * i + 0] = i == 5 ? 1.07e13f : 0.25f * i;
    rgba[4 * i + 1] = 1.5f;
    rgba[4 * i + 2] = i == 7 ? 7e4f : 0.0f; /* past half's 65504: written as float */
    rgba[4 * i + 3] = 1.0f;
    transmittance[i] = 0.5f, depth[i] = 10.0f;
    for (int c = 0; c < 3; c++) inscatter[3 * i + c] = rgba[4 * i + c];
  }
  recorder_frame frame = {.rgba = rgba, .transmittance = transmittance, .depth = depth,
                          .inscatter = inscatter};
  float *scratch = malloc(sizeof(float) * RECORDER_PLANES * W * H);
  CHECK(scratch && !recorder_write_frame(&rec, 1, &frame, scratch, NULL, &err),
        "recorder_write_frame: %s", err.message);
  float rgb[W * H * 3];
  CHECK(!recorder_read_rgb(&rec, 1, rgb, &err), "recorder_read_rgb: %s", err.message);
  for (int i = 0; i < W * H; i++)
    for (int c = 0; c < 3; c++)
      CHECK(rgb[3 * i + c] == rgba[4 * i + c], "pixel %d channel %d: read %.9g, wrote %.9g", i,
            c, rgb[3 * i + c], rgba[4 * i + c]);
  free(scratch);
  test_remove_tree(root);
  return test_finish("test_recorder_read_rgb");
}
