/* `fogpipe record` of a [fog] vdb config: the sequence is played, not simulated. 3 tiny
 * frames; recorded frame n (1-based) shows time (n-1)/fps, the VDB frame at 24 fps there,
 * so its transmittance must match `fogpipe render --vdb-frame` of that frame, and the frames
 * must differ from each other (the fog moves). Two configs:
 *   - configs/vdb_groundfog.ini at --fps 12 (VDB frames 1, 3, 5), the 2.5D fogmaps through
 *     the pipeline (render takes a separate code path, app/render_fog.c: within 0.02);
 *   - configs/vdb_plume_volume.ini at --fps 1 (VDB frames 1, 25 and, past the last, 48),
 *     model = volume: the frames' 3D grids through a render session, as render draws one
 *     (the same pixels: within 1e-6).
 * And between frames: recorded at --fps 48, the plume's frame 2 is half-way between VDB
 * frames 1 and 2, two grids of different boxes blended voxel by voxel; the exact integral is linear in the density, so its optical depth must be the mean
 * of the two frames' rendered separately (to float rounding). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sim/sim.h"
#include "exr_channel_util.h"
#include "test_bin.h"

#define W 48
#define H 27

static void check_recording(const char *bin, const char *dir, const char *config, int fps,
                            const int vdb_frames[3], double tolerance) {
  char command[1200];
  snprintf(command, sizeof command,
           "rm -rf '%s/rec' && '%s' record %s --frames 3 --fps %d --size %dx%d --out '%s/rec' > "
           "'%s/log' 2>&1",
           dir, bin, config, fps, W, H, dir, dir);
  int status = system(command);
  CHECK(status == 0, "%s: record failed (%d)", config, status);
  float *rec[3] = {0};
  for (int n = 1; n <= 3; n++) {
    char path[400], still[400];
    snprintf(path, sizeof path, "%s/rec/frame.%04d.exr", dir, n);
    snprintf(still, sizeof still, "%s/still%d.exr", dir, n);
    snprintf(command, sizeof command,
             "'%s' render %s --vdb-frame %d --size %dx%d --out '%s' > /dev/null", bin, config,
             vdb_frames[n - 1], W, H, still);
    CHECK(system(command) == 0, "%s: render --vdb-frame %d failed", config, vdb_frames[n - 1]);
    rec[n - 1] = load_exr_channel(path, "transmittance", W, H);
    float *want = load_exr_channel(still, "transmittance", W, H);
    if (rec[n - 1] && want) {
      double worst = 0;
      int foggy = 0;
      for (int k = 0; k < W * H; k++) {
        worst = fmax(worst, fabs((double)rec[n - 1][k] - want[k]));
        foggy += rec[n - 1][k] < 0.95f;
      }
      printf("%s frame %d: %d foggy pixels, max |record - render| = %.3g\n", config, n, foggy,
             worst);
      CHECK(foggy > 0, "%s frame %d has no fog", config, n);
      CHECK(worst <= tolerance, "%s frame %d: record differs from render --vdb-frame %d by %g",
            config, n, vdb_frames[n - 1], worst);
    }
    free(want);
    unlink(still);
  }
  if (rec[0] && rec[2]) {
    double change = 0;
    for (int k = 0; k < W * H; k++) change += fabs((double)rec[0][k] - rec[2][k]);
    CHECK(change > 1.0, "%s: frames 1 and 3 are the same (sum |diff| %g)", config, change);
  }
  for (int n = 0; n < 3; n++) free(rec[n]);
}

static void check_volume_blend(const char *bin, const char *dir) {
  const char *config = "configs/vdb_plume_volume.ini";
  char command[1200];
  snprintf(command, sizeof command,
           "rm -rf '%s/rec' && '%s' record %s --frames 2 --fps 96 --size %dx%d --out '%s/rec' > "
           "'%s/log' 2>&1",
           dir, bin, config, W, H, dir, dir);
  CHECK(system(command) == 0, "%s: record --fps 96 failed", config);
  float *still[2] = {0};
  for (int k = 0; k < 2; k++) {
    char path[400];
    snprintf(path, sizeof path, "%s/still%d.exr", dir, k + 1);
    snprintf(command, sizeof command,
             "'%s' render %s --vdb-frame %d --size %dx%d --out '%s' > /dev/null", bin, config,
             k + 1, W, H, path);
    CHECK(system(command) == 0, "render --vdb-frame %d failed", k + 1);
    still[k] = load_exr_channel(path, "transmittance", W, H);
    unlink(path);
  }
  char path[400];
  snprintf(path, sizeof path, "%s/rec/frame.0002.exr", dir);
  float *mid = load_exr_channel(path, "transmittance", W, H);
  if (mid && still[0] && still[1]) {
    double worst = 0.0, apart = 0.0;
    for (int k = 0; k < W * H; k++) {
      if (still[0][k] < 1e-3f || still[1][k] < 1e-3f) continue;
      double want = -0.75 * log(still[0][k]) - 0.25 * log(still[1][k]);
      worst = fmax(worst, fabs(-log(mid[k]) - want));
      apart = fmax(apart, fabs(log(still[0][k]) - log(still[1][k])));
    }
    printf("plume a quarter of the way from VDB frame 1 to 2: max |depth - (3 d1 + d2)/4| "
           "%.2e (the frames differ by up to %.2e)\n", worst, apart);
    CHECK(apart > 1e-2, "VDB frames 1 and 2 look the same: the check would mean nothing");
    CHECK(worst <= 1e-5, "the blended frame's optical depth is off (3 d1 + d2)/4 by %.3e",
          worst);
  }
  free(mid), free(still[0]), free(still[1]);
}

int main(void) {
  char dir[] = "/tmp/fogpipe_record_vdb_XXXXXX";
  const char *bin = test_bin_and_folder(dir);
  if (!bin) return test_finish("test_record_vdb");
  check_recording(bin, dir, "configs/vdb_groundfog.ini", 12, (const int[3]){1, 3, 5}, 0.02);
  check_recording(bin, dir, "configs/vdb_plume_volume.ini", 1, (const int[3]){1, 25, 48}, 1e-6);
  check_volume_blend(bin, dir);
  char command[1200];
  snprintf(command, sizeof command, "rm -rf '%s'", dir);
  CHECK(system(command) == 0, "cleanup");
  return test_finish("test_record_vdb");
}
