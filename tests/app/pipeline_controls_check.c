/* The demo's controls at their edges, headless (a synchronous pipeline on the default
 * scene):
 *  - N (pipeline_step_once) while running changes nothing: the simulation steps anyway,
 *    and after a pause no queued step plays (they used to: N three times, then Space,
 *    and three more steps ran); while paused, one N is one step;
 *  - a stroke beside the fog's box paints nothing (the periodic simulation wrapped it onto
 *    the box's far side, 1000 units from the cursor); a stroke across the edge, or just
 *    outside it within the brush's radius, paints the inside part and nothing wraps;
 *  - levels asked past what the map allows read back as the levels it allows (the panel
 *    showed the asked count while the transform used fewer);
 *  - a density typed in while paused relights the fog (its sun-shadow volume made again):
 *    the frame equals, colour and transmittance, that of a pipeline whose config had that
 *    density from the start (the volume once stayed the old density's, keyed on the sun
 *    alone). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "app/config.h"
#include "app/pipeline.h"
#include "pipeline_check_util.h"
#include "sim/sim.h"
#include "transform/transform.h"
#include "test_util.h"

enum { W = 64, H = 36 };

static pipeline *make(const scene_config *cfg) { return pipeline_check_make(cfg, W, H); }

static int frame(pipeline *p, const camera *cam) {
  static float tau[W * H];
  return pipeline_check_frame(p, cam, &(frame_pixels){.transmittance = tau});
}

static void set_paused(pipeline *p, bool paused) {
  pipeline_params params = pipeline_get_params(p);
  params.paused = paused;
  pipeline_set_params(p, &params);
}

static void check_steps(const scene_config *cfg, const camera *cam) {
  pipeline *p = make(cfg);
  CHECK(p != NULL, "pipeline not created");
  if (!p) return;
  CHECK(!frame(p, cam), "first frame");
  for (int k = 0; k < 3; k++) pipeline_step_once(p);
  CHECK(!frame(p, cam), "a running frame");
  const long running = pipeline_step_index(p);
  set_paused(p, true);
  for (int k = 0; k < 3; k++) CHECK(!frame(p, cam), "a paused frame");
  CHECK(pipeline_step_index(p) == running,
        "paused after N was pressed while running: step %ld, then %ld", running,
        pipeline_step_index(p));
  pipeline_step_once(p);
  for (int k = 0; k < 2; k++) CHECK(!frame(p, cam), "a paused frame");
  CHECK(pipeline_step_index(p) == running + 1, "one N while paused: step %ld, then %ld",
        running, pipeline_step_index(p));
  /* a step asked for while paused and dropped by Space does not play at the next pause */
  pipeline_step_once(p);
  set_paused(p, false);
  set_paused(p, true);
  CHECK(!frame(p, cam), "a paused frame");
  CHECK(pipeline_step_index(p) == running + 1, "N, Space, Space: step %ld, then %ld",
        running + 1, pipeline_step_index(p));
  pipeline_destroy(p);
  /* on a 24^2 map (fewer levels than the renderer's 7) */
  char dir[] = "/tmp/fogpipe_controls_XXXXXX";
  if (!test_scratch_folder(dir)) {
    CHECK(0, "no scratch folder");
    return;
  }
  scene_config small = *cfg;
  snprintf(small.fog.fogmap, sizeof small.fog.fogmap, "%s/small.exr", dir);
  fogmap map;
  fog_error err = {0};
  if (fogmap_create(&map, 24, 24, &err)) {
    CHECK(0, "%s", err.message);
    test_remove_tree(dir);
    return;
  }
  for (int i = 0; i < 24 * 24; i++) map.density[i] = (float)(i % 7) / 7.0f;
  CHECK(!fogmap_save_exr(small.fog.fogmap, &map, &err), "%s", err.message);
  fogmap_destroy(&map);
  pipeline *q = make(&small);
  test_remove_tree(dir);
  CHECK(q != NULL, "a pipeline on a 24^2 map");
  if (!q) return;
  pipeline_params params = pipeline_get_params(q);
  params.levels = 99;
  pipeline_set_params(q, &params);
  const int shown = pipeline_get_params(q).levels;
  int cells_x, cells_z;
  double origin_x, origin_z, cell;
  pipeline_fog_extent(q, &cells_x, &cells_z, &origin_x, &origin_z, &cell);
  const int most = transform_max_levels(cells_x, cells_z, TRANSFORM_SYMMETRIC);
  CHECK(most < 7 && shown == most, "levels 99 asked on a %dx%d map (it allows %d): %d shown",
        cells_x, cells_z, most, shown);
  pipeline_destroy(q);
}

/* The density after one frame that painted world (x0, z) -> (x1, z), radius 30, amount 1,
 * minus an unpainted twin's: the largest change in cells x < split and split <= x < end. */
static void painted_change(const scene_config *cfg, const camera *cam, double x0, double x1,
                           int split, int end, double *west, double *east) {
  *west = *east = -1.0;
  pipeline *painted = make(cfg), *plain = make(cfg);
  CHECK(painted && plain, "pipelines not created");
  if (painted && plain && !frame(painted, cam) && !frame(plain, cam)) {
    pipeline_paint(painted, x0, 0.0, x1, 0.0, 30.0, 1.0);
    if (!frame(painted, cam) && !frame(plain, cam)) {
      const fogmap *a = pipeline_sim_density(painted), *b = pipeline_sim_density(plain);
      *west = *east = 0.0;
      for (int z = 0; z < a->height; z++)
        for (int x = 0; x < a->width; x++) {
          const size_t i = (size_t)z * a->width + x;
          double *side = x < split ? west : x < end ? east : NULL;
          if (side) *side = fmax(*side, fabs((double)a->density[i] - b->density[i]));
        }
    }
  }
  if (painted) pipeline_destroy(painted);
  if (plain) pipeline_destroy(plain);
}

static void check_paint_edges(const scene_config *cfg, const camera *cam) {
  int cells_x, cells_z;
  double origin_x, origin_z, cell;
  pipeline *p = make(cfg);
  if (!p) return;
  pipeline_fog_extent(p, &cells_x, &cells_z, &origin_x, &origin_z, &cell);
  pipeline_destroy(p);
  const double west_edge = origin_x;  /* the box's west side, world x */
  double west, east;
  /* beside the box: 80 and 60 units west of it */
  painted_change(cfg, cam, west_edge - 80.0, west_edge - 60.0, cells_x / 2, cells_x, &west,
                 &east);
  CHECK(west == 0.0 && east == 0.0, "a stroke beside the box painted %g (west half), %g (east)",
        west, east);
  /* across the edge: the inside part paints the west half; nothing lands in the east half
   * (a few cells at the seam left out for the step's wind) */
  painted_change(cfg, cam, west_edge - 80.0, west_edge + 100.0, cells_x / 2, cells_x - 4,
                 &west, &east);
  CHECK(west > 0.5, "a stroke across the west edge painted only %g inside", west);
  CHECK(east == 0.0, "a stroke across the west edge painted %g on the far side", east);
  /* a dab 10 units outside, radius 30: its inside part, and nothing on the far side */
  painted_change(cfg, cam, west_edge - 10.0, west_edge - 10.0, cells_x / 2, cells_x - 4,
                 &west, &east);
  CHECK(west > 0.05, "a dab just outside the west edge painted only %g inside", west);
  CHECK(east == 0.0, "a dab just outside the west edge painted %g on the far side", east);
}

static void check_paused_density(const scene_config *cfg, const camera *cam) {
  scene_config denser = *cfg;
  denser.fog.density_scale = 3.0 * cfg->fog.density_scale;
  pipeline *edited = make(cfg), *made = make(&denser);
  CHECK(edited && made, "pipelines not created");
  static float rgba_a[4 * W * H], tau_a[W * H], rgba_b[4 * W * H], tau_b[W * H];
  if (edited && made) {
    set_paused(edited, true);
    set_paused(made, true);
    CHECK(!frame(edited, cam), "first frame");
    pipeline_params params = pipeline_get_params(edited);
    params.density = pipeline_get_params(made).density;
    pipeline_set_params(edited, &params);
    const frame_pixels a = {.rgba = rgba_a, .transmittance = tau_a},
                       b = {.rgba = rgba_b, .transmittance = tau_b};
    CHECK(!pipeline_check_frame(edited, cam, &a) && !pipeline_check_frame(made, cam, &b),
          "paused frames");
    CHECK(pipeline_step_index(edited) == 1 && pipeline_step_index(made) == 1,
          "paused pipelines stepped (%ld, %ld)", pipeline_step_index(edited),
          pipeline_step_index(made));
    double colour = 0.0, transmittance = 0.0;
    for (int k = 0; k < W * H; k++) {
      transmittance = fmax(transmittance, fabs(tau_a[k] - tau_b[k]));
      for (int c = 0; c < 3; c++)
        colour = fmax(colour, fabs(rgba_a[4 * k + c] - rgba_b[4 * k + c]));
    }
    CHECK(transmittance <= 1e-6 && colour <= 1e-5,
          "a density typed in while paused: |dtau| %g, |dcolour| %g against the config's",
          transmittance, colour);
  }
  if (edited) pipeline_destroy(edited);
  if (made) pipeline_destroy(made);
}

int main(void) {
  scene_config cfg;
  camera cam;
  gl_context *gl = pipeline_check_begin("configs/default.ini", &cfg, &cam);
  if (!gl) return 1;
  check_steps(&cfg, &cam);
  check_paint_edges(&cfg, &cam);
  check_paused_density(&cfg, &cam);
  gl_context_destroy(gl);
  return test_finish("pipeline_controls_check");
}
