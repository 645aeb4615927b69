/* A frame brighter than half-float holds (a lamp of 1e9 seen through fog: its glow passes
 * 65504) is written, not refused after the whole render (app/frame_exr.h):
 *   - frame_exr_channels keeps R G B A half up to 65504 and a non-finite value (the writer
 *     refuses that one, naming the pixel), and makes them float past it;
 *   - `fogpipe render --out x.exr` exits 0, says so on stderr, and the file's R holds the
 *     bright value as float (its largest read back equals the float written: > 65504);
 *   - `fogpipe record` writes every frame and says how many went as float, and which first. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/frame_exr.h"
#include "exr_channel_util.h"
#include "record_util.h"
#include "test_bin.h"

enum { W = 64, H = 36 };

static void channels_rule(void) {
  static float rgba[4 * 4], one[4], scratch[FRAME_EXR_PLANES * 4];
  const float cases[3] = {FRAME_EXR_HALF_MAX, 65600.0f, NAN};
  const bool want[3] = {false, true, false};
  for (int k = 0; k < 3; k++) {
    for (int i = 0; i < 16; i++) rgba[i] = 0.5f;
    rgba[9] = cases[k];
    image_channel channels[FRAME_EXR_CHANNELS];
    const camera cam = {.fov_y = 1.0, .near_plane = CAMERA_DEFAULT_NEAR,
                        .far_plane = CAMERA_DEFAULT_FAR};
    const bool as_float = frame_exr_channels(rgba, one, one, rgba, &cam, 2, 2, false, scratch,
                                             channels);
    CHECK(as_float == want[k], "a value of %g: as float %d, expected %d", (double)cases[k],
          as_float, want[k]);
    for (int c = 0; c < 4; c++)
      CHECK(channels[c].as_half == !want[k], "a value of %g: channel %s as_half %d",
            (double)cases[k], channels[c].name, channels[c].as_half);
  }
}

/* Runs `fogpipe ARGS 2>&1`, returning its exit status and output. */
static int run(const char *args, char *output, size_t size) {
  char command[2048];
  snprintf(command, sizeof command, "%s %s 2>&1", record_bin(), args);
  return test_run_output(command, output, size);
}

static double largest(const float *v) {
  double m = 0.0;
  for (int i = 0; i < W * H; i++) m = fmax(m, v[i]);
  return m;
}

int main(void) {
  channels_rule();
  char dir[] = "/tmp/fogpipe_hot_XXXXXX";
  if (!mkdtemp(dir)) {
    CHECK(0, "mkdtemp");
    return test_finish("test_exr_beyond_half");
  }
  char config[256], exr[256], frames[256], args[1024];
  static char output[16384];
  snprintf(config, sizeof config, "%s/hot.ini", dir);
  snprintf(exr, sizeof exr, "%s/hot.exr", dir);
  snprintf(frames, sizeof frames, "%s/frames", dir);
  if (!test_write_text(config, "[camera]\nposition = 0 20 100\nlook_at = 0 10 0\n"
                               "[light]\nlamp = 0 10 60 1e9 1e9 1e9 0.5\n"
                               "[fog]\nmodel = homogeneous\ndensity_scale = 0.01\nalbedo = 0.9\n"))
    return test_finish("test_exr_beyond_half");

  snprintf(args, sizeof args, "render %s --out %s --size %dx%d", config, exr, W, H);
  int status = run(args, output, sizeof output);
  CHECK(status == 0, "render: exit %d: %s", status, output);
  CHECK(strstr(output, "written as 32-bit float") != NULL, "render: no word of float: %s",
        output);
  float *r = load_exr_channel(exr, "R", W, H);
  if (r) {
    printf("render: R's largest %.1f\n", largest(r));
    CHECK(largest(r) > FRAME_EXR_HALF_MAX && isfinite(largest(r)), "R's largest %g",
          largest(r));
    free(r);
  }

  snprintf(args, sizeof args, "record %s --frames 2 --out %s --size %dx%d", config,
           frames, W, H);
  status = run(args, output, sizeof output);
  CHECK(status == 0, "record: exit %d: %s", status, output);
  CHECK(strstr(output, "2 frames (the first: 1) written with R G B A as 32-bit float"),
        "record: %s", output);
  for (int n = 1; n <= 2; n++) {
    char path[512];
    snprintf(path, sizeof path, "%s/frame.%04d.exr", frames, n);
    float *g = load_exr_channel(path, "G", W, H);
    if (g) {
      CHECK(largest(g) > FRAME_EXR_HALF_MAX, "frame %d: G's largest %g", n, largest(g));
      free(g);
    }
    unlink(path);
  }
  rmdir(frames);
  unlink(exr);
  unlink(config);
  rmdir(dir);
  return test_finish("test_exr_beyond_half");
}
