/* The live demo under the renderer's loop cap (docs/platform.md): 16 lamps placed through the
 * params (the demo's lamp tool) over the model menu's 16-Gaussian rung pass llvmpipe's cap. A
 * live pipeline draws that frame without the lamps' light in the fog and says so
 * (pipeline_lamps_dropped): its in-scatter equals that of the same frame with no lamps; a
 * recording pipeline (not live) fails with the fog pass's FOG_ERR_UNSUPPORTED; over the fogmap
 * itself the 16 lamps are drawn. On a renderer without a cap every frame draws its lamps.
 * Built by tests/app/pipeline.cmake. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "app/live_rung.h"
#include "pipeline_check_util.h"
#include "test_util.h"

enum { W = 64, H = 36 };

static void sixteen_lamps(pipeline_params *params) {
  params->lamps.count = FOG_MAX_LAMPS;
  for (int i = 0; i < FOG_MAX_LAMPS; i++)
    params->lamps.lamp[i] = (fog_lamp){.kind = FOG_LAMP_POINT, .radius = 0.5,
                                       .position = {-200.0 + 25.0 * i, 60.0, -40.0},
                                       .intensity = {900, 700, 500}};
}

/* A pipeline (live or a recording's) on the rung `kind` with 16 lamps or none; its frame's
 * in-scatter (3 a pixel) into inscatter. */
static int live_frame(const scene_config *cfg, const camera *cam, int kind, bool lamps,
                      bool live, float *inscatter, bool *dropped, fog_error *err) {
  pipeline *p = pipeline_create(&(pipeline_desc){.config = cfg, .width = W, .height = H,
                                                 .frame_seconds = 1.0 / 24.0,
                                                 .synchronous = true, .live = live}, err);
  if (!p) return 1;
  pipeline_params params = pipeline_get_params(p);
  params.live_rung = kind;
  params.paused = true;
  if (lamps) sixteen_lamps(&params);
  pipeline_set_params(p, &params);
  int failed = pipeline_frame(p, cam, true, err) ||
               pipeline_read_frame(p, &(frame_pixels){.inscatter = inscatter}, err);
  *dropped = pipeline_lamps_dropped(p);
  pipeline_destroy(p);
  return failed;
}

int main(void) {
  scene_config cfg;
  camera cam;
  gl_context *gl = pipeline_check_begin("configs/default.ini", &cfg, &cam);
  CHECK(gl != NULL, "no GL context");
  if (!gl) return test_finish("pipeline_lamps_check");
  const bool capped = strstr(gl_context_renderer(gl), "llvmpipe") != NULL;
  static float lit[3 * W * H], dark[3 * W * H];
  fog_error err = {0};
  bool dropped = false, none_dropped = false;
  /* the Gaussian rung under 16 lamps, live: drawn without their light, and said so */
  CHECK(!live_frame(&cfg, &cam, LIVE_RUNG_GAUSSIANS, true, true, lit, &dropped, &err),
        "live, 16 lamps over the Gaussian rung: %s", err.message);
  CHECK(!live_frame(&cfg, &cam, LIVE_RUNG_GAUSSIANS, false, true, dark, &none_dropped, &err),
        "live, no lamps over the Gaussian rung: %s", err.message);
  double differs = 0;
  for (int k = 0; k < 3 * W * H; k++) differs = fmax(differs, fabs(lit[k] - dark[k]));
  printf("16 lamps over the Gaussian rung: dropped %d (no lamps: %d), the fog's in-scatter "
         "differs from the lamp-less frame's by %.3g\n", dropped, none_dropped, differs);
  CHECK(dropped == capped && !none_dropped, "lamps dropped %d on a %s renderer", dropped,
        capped ? "capped" : "cap-free");
  if (capped) /* the surfaces keep the lamps' light (the scene pass); the fog has none */
    CHECK(differs == 0, "the fog drawn without the lamps' light: its in-scatter differs from "
          "the lamp-less frame's by %.3g", differs);
  /* not live (a recording): the fog pass's refusal is the frame's error */
  err = (fog_error){0};
  const int recorded = live_frame(&cfg, &cam, LIVE_RUNG_GAUSSIANS, true, false, lit, &dropped,
                                  &err);
  if (capped)
    CHECK(recorded && err.code == FOG_ERR_UNSUPPORTED && !dropped,
          "a recording pipeline past the cap: failed %d, code %d, dropped %d", recorded,
          (int)err.code, dropped);
  /* the fogmap itself: its 16 lamps are drawn */
  CHECK(!live_frame(&cfg, &cam, LIVE_RUNG_FOGMAP, true, true, lit, &dropped, &err) && !dropped,
        "live, 16 lamps over the fogmap: %s (dropped %d)", err.message, dropped);
  gl_context_destroy(gl);
  return test_finish("pipeline_lamps_check");
}
