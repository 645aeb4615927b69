/* `fogpipe record` is deterministic: the same config recorded twice gives bit-identical
 * EXR pixels in every channel (R, G, B, A, transmittance, depth), frame by frame, and so
 * does a third run with the CPU stages on the rendering thread (--synchronous) instead of
 * the worker thread: the double buffering changes when a step is computed, never which
 * step a frame shows. The frames are not all the same image (the fog moves), so equality
 * is not trivially met. */
#include "tests/app/record_util.h"
#include "tests/test_util.h"

enum { frames = 5 };

int main(void) {
  char root[] = "/tmp/fogpipe-record-det-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  enum { runs = 3 };
  char out[runs][512], log[runs][512];
  uint64_t hashes[runs][frames] = {{0}};
  for (int run = 0; run < runs; run++) {
    snprintf(out[run], sizeof out[run], "%s/run%d", root, run);
    snprintf(log[run], sizeof log[run], "%s/run%d.log", root, run);
    int status = record_run(out[run], frames, run == 2 ? "--synchronous" : NULL, log[run]);
    CHECK(status == 0, "record run %d exited with %d", run, status);
    if (status != 0) record_print_log(log[run]);
    int frame_files = 0;
    int others = record_count_files(out[run], &frame_files);
    CHECK(frame_files == frames && others == 0,
          "run %d: %d frame files (expected %d) and %d other files", run, frame_files, frames,
          others);
    for (int f = 0; f < frames; f++) {
      char path[600];
      record_frame_path(out[run], f + 1, path, sizeof path);
      int w = 0, h = 0;
      hashes[run][f] = record_hash_frame(path, &w, &h);
      CHECK(hashes[run][f] != 0, "run %d frame %d unreadable", run, f + 1);
      CHECK(w == 64 && h == 36, "frame %s is %dx%d, expected 64x36", path, w, h);
    }
  }
  for (int f = 0; f < frames; f++) {
    CHECK(hashes[0][f] == hashes[1][f], "frame %d differs between two identical runs", f + 1);
    CHECK(hashes[0][f] == hashes[2][f],
          "frame %d differs between the worker-thread and the synchronous pipeline", f + 1);
  }
  int distinct = 0;
  for (int f = 1; f < frames; f++) distinct += hashes[0][f] != hashes[0][0];
  CHECK(distinct > 0, "all %d frames are identical: the fog does not move", frames);
  test_remove_tree(root);
  return test_finish("test_record_deterministic");
}
