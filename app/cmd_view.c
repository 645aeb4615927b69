/* fogpipe view CONFIG: the scene config in the window program (app/window_program.h) with
 * the fog as the config holds it, no simulation (that is `fogpipe demo`): a free camera,
 * the panel, a volume's VDB sequence played with P, the Gaussian brush (B) on an RBF scene,
 * the model ladder with --fit. --screenshot FILE --frames N renders N frames, saves the
 * last one as seen in the window (read from GL_BACK before the swap) and exits: for tests
 * and for looking at a scene without sitting at the display (xvfb-run). */
#include <stdio.h>

#include "app/cli.h"
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/config.h"
#include "app/fit.h"
#include "app/window_program.h"

int cmd_view(int argc, char **argv) {
  window_options opts = {.command = "view", .render_scale = 0.5, .frames = 1, .rung = -1};
  int size[2] = {0, 0};
  bool frames_given = false;
  const cli_option options[] = {
      {.kind = CLI_NUMBER, .name = "--render-scale", .value = "F", .target = &opts.render_scale,
       .min = 0.05, .max = 4,
       .help = "render at F times the window size, shown scaled up\n"
               "(default 0.5, for software GL; use 1 on a GPU)"},
      {.kind = CLI_SIZE, .name = "--size", .value = "WxH", .target = size,
       .help = "window size (default: [render] width and height)"},
      {.kind = CLI_FLAG, .name = "--play", .target = &opts.play,
       .help = "start playing the volume's sequence (with --screenshot: one\n"
               "VDB frame per drawn frame)"},
      {.kind = CLI_OUTPUT, .name = "--screenshot", .value = "FILE.png",
       .target = &opts.screenshot, .extensions = (const char *const[]){".png", NULL},
       .help = "save the window's last frame as an 8-bit PNG and exit (the\n"
               "panel in it from the 2nd frame, unless hidden: --hide-panel\n"
               "for the scene alone, an image that repeats)"},
      {.kind = CLI_FLAG, .name = "--hide-panel", .target = &opts.hide_panel,
       .help = "start with the panel hidden (Tab shows it)"},
      {.kind = CLI_INT, .name = "--frames", .value = "N", .target = &opts.frames, .min = 1,
       .max = 1000000, .given = &frames_given, .help = "frames to draw before the screenshot (default 1)"},
      {.kind = CLI_NUMBER, .name = "--fit", .value = "T", .target = &opts.fit_tolerance,
       .min = 1e-12, .max = 1.0, .given = &opts.fit,
       .help = "first run `fogpipe fit` on the scene at tolerance T, then show\n"
               "its pick: the panel's rung menu, or [ and ], step through every\n"
               "rung of the model ladder, 0 returns to the config's own fog; the\n"
               "panel and the title show the rung, its measured error against\n"
               "the scene's fog and its time"},
      {.kind = CLI_INT, .name = "--rung", .value = "N", .target = &opts.rung, .min = 0,
       .max = FIT_MAX_RUNGS - 1,
       .help = "with --fit: start on rung N (its row in fit's table, from 0)"},
  };
  const cli_spec spec = {
      .command = "view",
      .usage = "CONFIG [--size WxH] [--render-scale F] [--play] [--hide-panel]\n"
               "                           [--screenshot FILE.png --frames N] [--fit T [--rung N]]",
      .about = "Opens the scene config in a window with a free camera and the panel, its fog as\n"
               "the config holds it (needs a display; for headless images use `fogpipe render`).\n"
               "The panel (Tab) edits the fog's density scale, ambient colour, profile and\n"
               "wavelets, the sun (time of day, colour, albedo, g, self-shadow, shafts) and the\n"
               "lamps (the lamp tool); the fog is made again after each edit.\n"
               "  W A S D  move     Q E  down / up     Shift  4x faster\n"
               "  right or middle drag, arrow keys  look around     Esc  quit\n"
               "  Tab  hide / show the panel\n"
               "  P  play / pause the VDB sequence of [fog] model = volume (from vdb_frame, looping\n"
               "     at vdb_fps, blended between frames)\n"
               "  B  the Gaussian brush of [fog] model = rbf (Fogshop's; the title shows it):\n"
               "     left drag paints Gaussians on the surface, Shift + left drag erases them,\n"
               "     C picks up the group under the cursor and V puts a copy of it down there,\n"
               "     - and = size, , and . density, Ctrl+S writes CONFIG.painted.ini",
      .operand = "CONFIG", .min_operands = 1, .max_operands = 1,
      CLI_OPTIONS(options)};
  int parsed = cli_parse_one(&spec, argc, argv, &opts.config_path);
  if (parsed) return parsed == CLI_HELP ? 0 : parsed;
  if (opts.rung >= 0 && !opts.fit) return cli_usage_error("view", "--rung needs --fit T");
  /* without a screenshot the window runs until closed: a frame count would be dropped */
  if (frames_given && !opts.screenshot)
    return cli_usage_error("view", "--frames N counts the frames before --screenshot FILE.png; "
                           "without it the window stays open");
  scene_config cfg;
  fog_error cfg_err;
  if (scene_config_load(opts.config_path, &cfg, &cfg_err)) {
    fprintf(stderr, "fogpipe view: %s\n", cfg_err.message);
    return 1;
  }
  if (opts.screenshot && cli_output_not_scene_input("view", "--screenshot", opts.screenshot, &cfg))
    return 2;
  /* --play plays a volume's VDB sequence: said, not dropped, on another model */
  if (opts.play && cfg.fog.model != FOG_MODEL_VOLUME)
    fprintf(stderr, "fogpipe view: --play has no effect: it plays the VDB sequence of [fog] "
            "model = volume (%s's fog is drawn as the config holds it)\n", opts.config_path);
  opts.width = size[0] > 0 ? size[0] : cfg.width;
  opts.height = size[1] > 0 ? size[1] : cfg.height;
  /* no display: said now, not after --fit's minutes of work (the window opens after it) */
  if (!cli_display_available()) {
    fprintf(stderr, "fogpipe view: cannot open a window: no display (DISPLAY and "
            "WAYLAND_DISPLAY are unset); for headless rendering use `fogpipe render`, or run "
            "under xvfb-run\n");
    return 1;
  }
  return window_program_run(&cfg, &opts);
}
