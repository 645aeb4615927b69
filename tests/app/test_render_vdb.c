/* `fogpipe render configs/vdb_groundfog.ini` (a [fog] vdb scene) headless at 96x54: the
 * fog is there (transmittance < 0.95 on many pixels) and only where it can be: every
 * pixel whose view ray, up to its first surface, misses the VDB's fog box (placed by the
 * sequence, computed here independently from app/vdb_source.h and the camera) has
 * transmittance 1. --vdb-frame picks a frame (frame 1, where the bake has barely started,
 * has less fog than frame 48); a frame that is not in the sequence is an error. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/vdb_source.h"
#include "render/camera.h"
#include "sim/ray_box.h"
#include "exr_channel_util.h"
#include "test_bin.h"

#define W 96
#define H 54
#define CONFIG "configs/vdb_groundfog.ini"

static int run(const char *bin, const char *extra, const char *out) {
  char command[1024];
  snprintf(command, sizeof command, "'%s' render " CONFIG " --size %dx%d %s --out '%s' > /dev/null",
           bin, W, H, extra, out);
  return system(command);
}

int main(void) {
  char dir[] = "/tmp/fogpipe_render_vdb_XXXXXX";
  const char *bin = test_bin_and_folder(dir);
  if (!bin) return test_finish("test_render_vdb");
  char last[300], first[300], bad[300];
  snprintf(last, sizeof last, "%s/last.exr", dir);
  snprintf(first, sizeof first, "%s/first.exr", dir);
  snprintf(bad, sizeof bad, "%s/bad.exr", dir);
  CHECK(run(bin, "", last) == 0, "render failed");
  CHECK(run(bin, "--vdb-frame 1", first) == 0, "render --vdb-frame 1 failed");
  CHECK(run(bin, "--vdb-frame 999 2>/dev/null", bad) != 0, "--vdb-frame 999 accepted");
  CHECK(access(bad, F_OK) != 0, "an output was written for a bad frame");

  /* The fog box, independently of the renderer: the sequence's placement and profile. */
  scene_config cfg;
  fog_error cerr;
  CHECK(scene_config_load(CONFIG, &cfg, &cerr) == 0, "%s", cerr.message);
  vdb_source source;
  if (vdb_source_open_config(&source, &cfg, &cerr)) { /* the bake missing: nothing to check */
    CHECK(0, "%s", cerr.message);
    return test_finish("test_render_vdb");
  }
  CHECK(vdb_source_apply_config(&source, &cfg, &cerr) == 0, "apply: %s", cerr.message);
  double lo[3] = {cfg.box.origin[0], cfg.box.floor, cfg.box.origin[1]};
  double hi[3] = {lo[0] + source.place.width * cfg.box.cell_size, cfg.box.top,
                  lo[2] + source.place.height * cfg.box.cell_size};
  CHECK(source.mass[0] < source.mass[source.count - 1], "frame 1 has no less fog than the last");
  vdb_source_destroy(&source);
  camera cam;
  scene_config_camera(&cfg, &cam);

  float *tau = load_exr_channel(last, "transmittance", W, H), *depth = load_exr_channel(last, "depth", W, H);
  float *tau_first = load_exr_channel(first, "transmittance", W, H);
  if (tau && depth && tau_first) {
    int foggy = 0, foggy_first = 0, outside = 0, outside_bad = 0;
    double min_tau = 1;
    /* A pixel covers more than its centre ray: widen the box by 1.5 pixels at its
     * farthest corner, so the box's silhouette pixels are not counted as outside. */
    double far = 0;
    for (int c = 0; c < 8; c++) {
      double p[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
      far = fmax(far, hypot(hypot(p[0] - cam.position[0], p[1] - cam.position[1]),
                            p[2] - cam.position[2]));
    }
    double pad = 1.5 * 2.0 * far * tan(cam.fov_y / 2) / H;
    double plo[3], phi[3];
    for (int i = 0; i < 3; i++) plo[i] = lo[i] - pad, phi[i] = hi[i] + pad;
    for (int y = 0; y < H; y++)
      for (int x = 0; x < W; x++) {
        int k = y * W + x;
        double o[3], d[3], t0, t1;
        camera_ray(&cam, x + 0.5, y + 0.5, W, H, o, d);
        /* the ray (t > 0) meets the padded box before the surface */
        int hits = ray_box_clip(o, d, plo, phi, &t0, &t1) && t1 > 0 && t0 < depth[k];
        if (!hits) {
          outside++;
          if (fabs(tau[k] - 1.0f) > 1e-6 || fabs(tau_first[k] - 1.0f) > 1e-6) outside_bad++;
        }
        foggy += tau[k] < 0.95f;
        foggy_first += tau_first[k] < 0.95f;
        min_tau = fmin(min_tau, tau[k]);
      }
    printf("last frame: %d of %d pixels with transmittance < 0.95 (min %.3f); frame 1: %d; "
           "%d pixels miss the fog box\n",
           foggy, W * H, min_tau, foggy_first, outside);
    CHECK(foggy >= W * H / 50, "only %d foggy pixels", foggy);
    CHECK(outside >= W * H / 4, "only %d pixels miss the fog box: the check is weak", outside);
    CHECK(outside_bad == 0, "%d pixels outside the fog box have transmittance != 1",
          outside_bad);
    CHECK(foggy_first < foggy, "frame 1 (%d foggy pixels) not less foggy than 48 (%d)",
          foggy_first, foggy);
  }
  free(tau), free(depth), free(tau_first);
  unlink(last), unlink(first), unlink(bad);
  rmdir(dir);
  return test_finish("test_render_vdb");
}
