/* fogpipe render CONFIG --out FILE.exr|png [--size WxH]: one frame of a scene config,
 * headless (EGL), written as OpenEXR (R, G, B, A half; transmittance, depth, Z, inscatter
 * float) or as an 8-bit sRGB PNG. */
#include <math.h>
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "app/cli.h"
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/config.h"
#include "app/frame_exr.h"
#include "app/player.h"
#include "app/render_fog.h"
#include "app/stop_signals.h"
#include "app/vdb_source.h"
#include "sim/sim.h"

/* The frame's EXR (app/frame_exr.h) with the camera as the standard header matrices.
 * Without fog the transmittance is 1 and the in-scatter 0: written anyway, so every
 * render has the same channels for a compositor. */
static int write_exr(const char *out, int width, int height, const frame_pixels *frame,
                     const camera *cam, fog_error *err) {
  float *planes = malloc((size_t)width * height * FRAME_EXR_PLANES * sizeof(float));
  if (!planes) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
  image_channel channels[FRAME_EXR_CHANNELS];
  const bool beauty_float = frame_exr_channels(frame->rgba, frame->transmittance, frame->depth,
                                               frame->inscatter, cam, width, height, false,
                                               planes, channels);
  image_exr_matrix matrices[2] = {{.name = "worldToCamera"}, {.name = "worldToNDC"}};
  camera_exr_matrices(cam, width, height, matrices[0].m, matrices[1].m);
  const image_exr_header header = {.matrices = matrices, .matrix_count = 2};
  int status = image_write_exr_with(out, width, height, channels, FRAME_EXR_CHANNELS, &header,
                                    err);
  if (!status && beauty_float)
    fprintf(stderr, "fogpipe render: %s: R G B A written as 32-bit float: some pixels are "
            "brighter than half-float holds (%g)\n", out, (double)FRAME_EXR_HALF_MAX);
  free(planes);
  return status;
}

/* 8-bit sRGB RGB through the config's display transform. */
static int write_png(const char *out, int width, int height, const float *rgba,
                     const display_transform *display, fog_error *err) {
  /* refused as the EXR writer refuses it: the display transform would draw NaN black */
  static const char *const names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; c++)
    if (image_check_finite(out, names[c], rgba + c, width, height, 4, FLT_MAX, err)) return 1;
  size_t pixels = (size_t)width * height;
  float *rgb = malloc(pixels * 3 * sizeof(float));
  if (!rgb) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
  for (size_t k = 0; k < pixels; k++)
    for (int c = 0; c < 3; c++) rgb[3 * k + c] = rgba[4 * k + c];
  display_map_values(display, rgb, rgb, 3 * pixels);
  int status = image_write_png_srgb(out, width, height, 3, rgb,
                                    display->dither ? SRGB8_DITHER : SRGB8_ROUND, err);
  free(rgb);
  return status;
}

int cmd_render(int argc, char **argv) {
  const char *out = NULL;
  int size[2] = {0, 0}, vdb_frame = -2;
  double time = 0.0;
  const cli_option options[] = {
      {.kind = CLI_OUTPUT, .name = "--out", .value = "FILE", .target = &out,
       .extensions = (const char *const[]){".exr", ".png", NULL},
       .required = true, .help = "output image: .exr (channels R G B A as half, as float where\n"
               "a pixel is beyond half's range; transmittance,\n"
               "depth, Z, inscatter.R/G/B as float; depth = distance along\n"
               "the view ray to the first surface, Z = its camera-space depth\n"
               "along the view axis (the far plane for the sky, both); RGB =\n"
               "transmittance x surface + inscatter) or .png\n"
               "(8-bit sRGB RGB)"},
      {.kind = CLI_SIZE, .name = "--size", .value = "WxH", .target = size,
       .help = "image size (default: [render] width and height of the config)"},
      {.kind = CLI_INT, .name = "--vdb-frame", .value = "N", .target = &vdb_frame, .min = 0,
       .max = INT_MAX,
       .help = "with a [fog] vdb sequence: render its frame number N (as in the\n"
               "file names; default: [fog] vdb_frame, else the last frame)"},
      {.kind = CLI_NUMBER, .name = "--time", .value = "SECONDS", .target = &time, .min = 0,
       .max = 1e6,
       .help = "the scene's time (default 0): where moving lamps, RBF puffs and\n"
               "drifting Perlin noise are, as `record` shows them at that time (a\n"
               "fogmap or volume is drawn as its file holds it)"},
  };
  const cli_spec spec = {
      .command = "render",
      .usage = "CONFIG --out FILE.exr|FILE.png [--size WxH] [--vdb-frame N] [--time SECONDS]",
      .about = "Renders one frame of the scene config headless (EGL; no display needed).",
      .operand = "CONFIG", .min_operands = 1, .max_operands = 1,
      CLI_OPTIONS(options),
      .footer = "The config format is described in docs/config.md."};
  const char *config_path = NULL;
  int parsed = cli_parse_one(&spec, argc, argv, &config_path);
  if (parsed) return parsed == CLI_HELP ? 0 : parsed;
  int width = size[0], height = size[1];
  bool exr = cli_ends_with(out, ".exr");

  scene_config cfg;
  fog_error cfg_err;
  if (scene_config_load(config_path, &cfg, &cfg_err)) {
    fprintf(stderr, "fogpipe render: %s\n", cfg_err.message);
    return 1;
  }
  if (cli_output_not_scene_input("render", "--out", out, &cfg)) return 2;
  if (width == 0) width = cfg.width, height = cfg.height;
  if (vdb_frame != -2) {
    if (!cfg.fog.vdb[0]) {
      fprintf(stderr, "fogpipe render: --vdb-frame: %s has no [fog] vdb\n", config_path);
      return 2;
    }
    /* a frame the sequence lacks is the command line's mistake, not the config's */
    vdb_sequence seq;
    fog_error seq_err = {0};
    if (render_fog_volume_sequence(&cfg, &seq, &seq_err)) {
      fprintf(stderr, "fogpipe render: %s\n", seq_err.message);
      return 1;
    }
    const bool found = vdb_frame_index(seq.frames, seq.count, vdb_frame) >= 0;
    if (!found)
      fprintf(stderr, "fogpipe render: --vdb-frame %d: %s has no such frame (frames %d..%d)\n",
              vdb_frame, cfg.fog.vdb, seq.frames[0], seq.frames[seq.count - 1]);
    vdb_sequence_destroy(&seq);
    if (!found) return 2;
    cfg.fog.vdb_frame = vdb_frame;
  }

  /* Ctrl-C or SIGTERM while drawing: nothing written, exit 130 (a second one ends it at
   * once, nothing to clean then); held while the file is written, so that it is whole
   * (a signal there left .OUT.tmp.PID.N that no later run removes) */
  stop_signals stop;
  stop_signals_clear();
  stop_signals_catch(&stop, true);
  size_t pixels = (size_t)width * height;
  float *rgba = malloc(pixels * 4 * sizeof(float));
  float *transmittance = malloc(pixels * sizeof(float));
  float *depth = malloc(pixels * sizeof(float));
  float *inscatter = malloc(pixels * 3 * sizeof(float));
  const frame_pixels frame = {.rgba = rgba, .transmittance = transmittance, .depth = depth,
                              .inscatter = inscatter};
  int status = 1;
  if (!rgba || !transmittance || !depth || !inscatter) {
    fprintf(stderr, "fogpipe render: out of memory for a %dx%d image\n", width, height);
    goto done;
  }
  /* The scene as its files hold it, no simulation step: frame 1, at time 0 or --time. */
  fog_error err = {0};
  player *frames = player_create(&(player_desc){.config = &cfg, .width = width,
                                                .height = height, .fps = 24.0,
                                                .start_time = time},
                                 &err);
  if (!frames || player_frame(frames, 1, &frame, &err)) {
    fprintf(stderr, "fogpipe render: %s\n", err.message);
    player_destroy(frames);
    goto done;
  }
  char gl_description[256];
  snprintf(gl_description, sizeof gl_description, "%s", player_gl_description(frames));
  const camera cam = *player_camera(frames);
  player_destroy(frames);
  fog_error werr = {0};
  const display_transform display = scene_config_display(&cfg);
  if (stop_signals_caught()) {
    fprintf(stderr, "fogpipe render: interrupted: nothing written\n");
    status = 130;
    goto done;
  }
  stop_signals_hold(&stop);
  const int written = exr ? write_exr(out, width, height, &frame, &cam, &werr)
                          : write_png(out, width, height, rgba, &display, &werr);
  stop_signals_release(&stop); /* one held now only sets the flag: the file is whole */
  if (written) {
    fprintf(stderr, "fogpipe render: %s\n", werr.message);
    goto done;
  }
  printf("fogpipe render: wrote %s (%dx%d, %s; %s)\n", out, width, height,
         scene_config_has_fog(&cfg) ? "scene + fog" : "scene only, no fog", gl_description);
  status = 0;
done:
  stop_signals_restore(&stop);
  free(rgba);
  free(transmittance);
  free(depth);
  free(inscatter);
  return status;
}
