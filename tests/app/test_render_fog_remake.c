/* render_fog_remake (app/render_fog.h), what the window calls after each panel edit: with
 * puffs carried by the simulation's flow (configs/rbf_steam_eddies.ini) the remade fog keeps
 * the flow where it was (the same carrier, at the same time: no replay from the start, which
 * after minutes in a window would cost seconds a frame) and shows the same puffs at the same
 * time, bit for bit, also after a fog of another model between (a fogmap: a window's rung);
 * a config whose flow differs ([sim] seed) gets a flow of its own. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "app/render_fog.h"
#include "render/render.h"
#include "test_util.h"

int main(void) {
  fog_error err = {0};
  gl_context *ctx = gl_context_create(&(gl_context_desc){0}, &err);
  CHECK(ctx != NULL, "headless context: %s", err.message);
  if (!ctx) return test_finish("test_render_fog_remake");
  static scene_config cfg;
  CHECK(scene_config_load("configs/rbf_steam_eddies.ini", &cfg, &err) == 0, "%s", err.message);
  render_fog fog;
  CHECK(render_fog_create(&fog, &cfg, &err) == 0, "create: %s", err.message);
  CHECK(render_fog_set_time(&fog, &cfg, 5.0, &err) == 0, "time 5: %s", err.message);
  const rbf_carrier *carrier = fog.carrier;
  CHECK(carrier != NULL, "rbf_carrier = sim made no carrier");
  const double flow_time = carrier ? rbf_carrier_time(carrier) : 0.0;
  const int count = fog.rbf_count;
  fog_rbf *before = malloc(sizeof *before * (size_t)count);
  if (before) memcpy(before, fog.rbfs, sizeof *before * (size_t)count);

  CHECK(render_fog_remake(&fog, &cfg, &err) == 0, "remake: %s", err.message);
  CHECK(fog.carrier == carrier, "the remade fog made a flow of its own");
  CHECK(fog.carrier && rbf_carrier_time(fog.carrier) == flow_time,
        "the remade fog's flow is at %g s, not %g", fog.carrier ? rbf_carrier_time(fog.carrier) : 0,
        flow_time);
  CHECK(render_fog_set_time(&fog, &cfg, 5.0, &err) == 0, "time 5 again: %s", err.message);
  CHECK(before && fog.rbf_count == count &&
            memcmp(before, fog.rbfs, sizeof *before * (size_t)count) == 0,
        "the remade fog's puffs at 5 s differ from the first's");
  printf("remade: the same flow at %.4f s, %d puffs the same bit for bit\n", flow_time, count);

  /* Through a fogmap's fog and back (a window's rung): the flow is still the one at 5 s. */
  static scene_config fogmap_cfg;
  CHECK(scene_config_load("configs/default.ini", &fogmap_cfg, &err) == 0, "%s", err.message);
  CHECK(render_fog_remake(&fog, &fogmap_cfg, &err) == 0, "to the fogmap: %s", err.message);
  CHECK(render_fog_remake(&fog, &cfg, &err) == 0, "and back: %s", err.message);
  CHECK(fog.carrier && rbf_carrier_time(fog.carrier) == flow_time,
        "after a fogmap's fog the flow is at %g s, not %g",
        fog.carrier ? rbf_carrier_time(fog.carrier) : 0, flow_time);

  cfg.sim.seed += 1; /* another flow */
  CHECK(render_fog_remake(&fog, &cfg, &err) == 0 && render_fog_set_time(&fog, &cfg, 5.0, &err) == 0,
        "remake with another seed: %s", err.message);
  CHECK(before && fog.rbf_count == count &&
            memcmp(before, fog.rbfs, sizeof *before * (size_t)count) != 0,
        "another [sim] seed carried the puffs the same way");
  free(before);
  render_fog_destroy(&fog);
  gl_context_destroy(ctx);
  return test_finish("test_render_fog_remake");
}
