/* `fogpipe record` of a [fog] vdb config (configs/vdb_groundfog.ini): the sequence is
 * played, not simulated. 3 tiny frames at --fps 12 against the VDB's 24 fps: recorded
 * frame n (1-based) shows time (n-1)/12 s = VDB frame 2n-1, so its transmittance must
 * match `fogpipe render --vdb-frame 2n-1` (a separate code path: app/render_fog.c instead
 * of the pipeline), and the frames must differ from each other (the fog moves). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sim/sim.h"
#include "exr_channel_util.h"
#include "test_util.h"

#define W 48
#define H 27
#define CONFIG "configs/vdb_groundfog.ini"

int main(void) {
  const char *bin = getenv("FOGPIPE_BIN");
  CHECK(bin != NULL, "FOGPIPE_BIN is not set (run through ctest)");
  if (!bin) return test_finish("test_record_vdb");
  char dir[] = "/tmp/fogpipe_record_vdb_XXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  char command[1200];
  snprintf(command, sizeof command,
           "'%s' record " CONFIG " --frames 3 --fps 12 --size %dx%d --out '%s/rec' > '%s/log' 2>&1",
           bin, W, H, dir, dir);
  int status = system(command);
  CHECK(status == 0, "record failed (%d)", status);
  float *rec[3] = {0};
  for (int n = 1; n <= 3; n++) {
    char path[400], still[400];
    snprintf(path, sizeof path, "%s/rec/frame.%04d.exr", dir, n);
    snprintf(still, sizeof still, "%s/still%d.exr", dir, n);
    snprintf(command, sizeof command,
             "'%s' render " CONFIG " --vdb-frame %d --size %dx%d --out '%s' > /dev/null", bin,
             2 * n - 1, W, H, still);
    CHECK(system(command) == 0, "render --vdb-frame %d failed", 2 * n - 1);
    rec[n - 1] = load_exr_channel(path, "transmittance", W, H);
    float *want = load_exr_channel(still, "transmittance", W, H);
    if (rec[n - 1] && want) {
      double worst = 0;
      int foggy = 0;
      for (int k = 0; k < W * H; k++) {
        worst = fmax(worst, fabs((double)rec[n - 1][k] - want[k]));
        foggy += rec[n - 1][k] < 0.95f;
      }
      printf("frame %d: %d foggy pixels, max |record - render| = %.3g\n", n, foggy, worst);
      CHECK(foggy > 0, "frame %d has no fog", n);
      CHECK(worst < 0.02, "frame %d: record differs from render --vdb-frame %d by %g", n,
            2 * n - 1, worst);
    }
    free(want);
    unlink(still);
  }
  if (rec[0] && rec[2]) {
    double change = 0;
    for (int k = 0; k < W * H; k++) change += fabs((double)rec[0][k] - rec[2][k]);
    CHECK(change > 1.0, "frames 1 and 3 are the same (sum |diff| %g)", change);
  }
  for (int n = 0; n < 3; n++) free(rec[n]);
  snprintf(command, sizeof command, "rm -rf '%s'", dir);
  CHECK(system(command) == 0, "cleanup");
  return test_finish("test_record_vdb");
}
