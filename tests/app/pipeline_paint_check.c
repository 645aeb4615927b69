/* The pipeline's picking and painting (what the demo's mouse does), headless:
 *  - pipeline_pick_surface at a pixel returns the point on that pixel's camera ray at the
 *    distance the CPU scene geometry gives (scene_geometry_pixel_distance), so the brush
 *    lands where the cursor is, and along the drawn frame's ray when the camera has moved
 *    since;
 *  - a painted stroke there lowers the transmittance at that pixel in the next frame
 *    compared with an identical pipeline that was not painted, and leaves a pixel far from
 *    the stroke unchanged; erasing raises it.
 * Built by tests/app/pipeline.cmake with the app's pipeline sources (it is not a plain
 * tests/app/test_*.c because those link the libraries only). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "app/config.h"
#include "app/pipeline.h"
#include "render/gl_context.h"
#include "render/scene.h"
#include "sim/sim.h"
#include "pipeline_check_util.h"
#include "test_util.h"

enum { W = 96, H = 54 };

static pipeline *make(const scene_config *cfg) { return pipeline_check_make(cfg, W, H); }

static int frame(pipeline *p, const camera *cam, float *transmittance) {
  return pipeline_check_frame(p, cam, &(frame_pixels){.transmittance = transmittance});
}

int main(void) {
  scene_config cfg;
  camera cam;
  gl_context *gl = pipeline_check_begin("configs/default.ini", &cfg, &cam);
  if (!gl) return 1;
  fog_error rerr = {0};
  pipeline *painted = make(&cfg), *plain = make(&cfg);
  CHECK(painted && plain, "pipelines not created");
  if (!painted || !plain) return test_finish("pipeline_paint_check");
  static float t_painted[W * H], t_plain[W * H], t_erased[W * H];
  CHECK(!frame(painted, &cam, t_painted) && !frame(plain, &cam, t_plain), "first frame failed");

  /* Picking: the hit lies on the pixel's ray at the CPU geometry's distance. */
  const int px = W / 2, py = H / 2;
  double hit[3];
  bool picked = pipeline_pick_surface(painted, &cam, px, py, hit);
  CHECK(picked, "no surface under the centre pixel");
  scene_desc desc;
  scene_config_scene_desc(&cfg, NULL, 0, 0, &desc);
  scene_geometry geo;
  CHECK(!scene_geometry_create(&geo, &desc, &rerr), "%s", rerr.message);
  double expected = scene_geometry_pixel_distance(&geo, &cam, px, py, W, H);
  double got = sqrt((hit[0] - cam.position[0]) * (hit[0] - cam.position[0]) +
                    (hit[1] - cam.position[1]) * (hit[1] - cam.position[1]) +
                    (hit[2] - cam.position[2]) * (hit[2] - cam.position[2]));
  CHECK(fabs(got - expected) <= 1e-3 * expected, "picked distance %.6f, CPU geometry %.6f", got,
        expected);
  scene_geometry_destroy(&geo);
  /* A camera moved since that frame (the window's, a frame later) picks the same point:
   * the distance read is along the drawn camera's ray. */
  camera moved = cam;
  moved.position[0] += 50.0;
  double again[3];
  CHECK(pipeline_pick_surface(painted, &moved, px, py, again) &&
            fabs(again[0] - hit[0]) + fabs(again[1] - hit[1]) + fabs(again[2] - hit[2]) < 1e-9,
        "a moved camera picked (%g, %g, %g), the drawn frame's point is (%g, %g, %g)", again[0],
        again[1], again[2], hit[0], hit[1], hit[2]);

  /* Paint a dense stroke at the picked point; the plain pipeline steps the same. */
  pipeline_paint(painted, hit[0] - 10, hit[2], hit[0] + 10, hit[2], 40.0, 20.0);
  CHECK(!frame(painted, &cam, t_painted) && !frame(plain, &cam, t_plain), "second frame failed");
  const int centre = py * W + px, corner = 2 * W + 2; /* top-left: sky, far from the stroke */
  CHECK(t_painted[centre] < t_plain[centre] - 0.05f,
        "painting did not thicken the fog under the brush: tau %g painted, %g plain",
        t_painted[centre], t_plain[centre]);
  CHECK(t_painted[corner] == t_plain[corner], "painting changed a far pixel: %g vs %g",
        t_painted[corner], t_plain[corner]);

  /* Erase a wide area around the point: less fog than without painting. */
  pipeline_paint(painted, hit[0], hit[2], hit[0], hit[2], 150.0, -1000.0);
  CHECK(!frame(painted, &cam, t_erased) && !frame(plain, &cam, t_plain), "third frame failed");
  CHECK(t_erased[centre] > t_plain[centre] || t_plain[centre] == 1.0f,
        "erasing did not clear the fog under the brush: tau %g erased, %g plain",
        t_erased[centre], t_plain[centre]);

  /* Paused, a brush held still for 300 frames queues its stroke 300 times: the next step
   * paints all of it, as one stroke of 300 times the amount (the queue held 256 and
   * dropped the rest, silently). */
  pipeline *held = make(&cfg), *once = make(&cfg);
  CHECK(held && once, "pipelines not created");
  if (held && once) {
    pipeline *both[2] = {held, once};
    for (int k = 0; k < 2; k++) {
      pipeline_params params = pipeline_get_params(both[k]);
      params.paused = true;
      pipeline_set_params(both[k], &params);
      CHECK(!frame(both[k], &cam, t_plain), "paused frame failed");
    }
    for (int i = 0; i < 300; i++)
      pipeline_paint(held, hit[0], hit[2], hit[0], hit[2], 30.0, 0.01);
    pipeline_paint(once, hit[0], hit[2], hit[0], hit[2], 30.0, 300 * 0.01);
    for (int k = 0; k < 2; k++) {
      pipeline_step_once(both[k]);
      CHECK(!frame(both[k], &cam, t_plain), "stepped frame failed");
    }
    const fogmap *a = pipeline_sim_density(held), *b = pipeline_sim_density(once);
    double worst = 0, peak = 0;
    for (int k = 0; a && b && k < a->width * a->height; k++) {
      worst = fmax(worst, fabs(a->density[k] - b->density[k]));
      peak = fmax(peak, b->density[k]);
    }
    printf("paused, a brush held 300 frames against one stroke of 300 times the amount: max "
           "|d density| %.2e (peak %.3f)\n", worst, peak);
    CHECK(a && b && peak > 1.0 && worst <= 1e-4 * peak,
          "paused, a brush held 300 frames: %.3e off one stroke of the whole amount", worst);
  }
  pipeline_destroy(held);
  pipeline_destroy(once);
  pipeline_destroy(painted);
  pipeline_destroy(plain);
  gl_context_destroy(gl);
  return test_finish("pipeline_paint_check");
}
