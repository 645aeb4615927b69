/* fogpipe demo [CONFIG]: the live animated fog demo: the window program
 * (app/window_program.h) with the config's simulation transformed and rendered every
 * frame (app/pipeline.h), the panel, a free camera, fog painting and lamps. A model without
 * a simulation opens the same window with its fog as the config holds it (`fogpipe view`'s
 * source). Without a display it says so in one line and records the scene headless instead
 * (app/recorder.h). */
#define _POSIX_C_SOURCE 200809L
#define _XOPEN_SOURCE 700
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/cli.h"
#include "app/cli_options.h"
#include "app/cmd_record.h"
#include "app/commands.h"
#include "app/config.h"
#include "app/render_fog.h"
#include "app/live_rung.h"
#include "app/out_folder.h"
#include "app/recorder.h"
#include "app/window_program.h"
#include "render/fog_models.h"
#include "sim/sim.h"

#define DEFAULT_CONFIG FOGPIPE_SOURCE_DIR "/configs/default.ini"
#define HEADLESS_FRAMES 48
#define HEADLESS_WIDTH 640
#define HEADLESS_HEIGHT 360

/* ---- headless fallback ---- */

typedef struct headless_job {
  const char *config_path;
  const scene_config *config; /* as loaded from config_path (the command's) */
  int frames, width, height;
  const char *screenshot; /* the last frame as a PNG too, or NULL */
} headless_job;

/* The recording's last frame (its linear R, G, B) as an 8-bit sRGB PNG at h->screenshot:
 * what the window's screenshot would have held, without the panel (and supersampled if the
 * config says so: the fallback records as `record` does). */
static int last_frame_png(const headless_job *h, const char *folder) {
  recorder rec = {.name = "frame", .width = h->width, .height = h->height}; /* as opened */
  snprintf(rec.folder, sizeof rec.folder, "%s", folder);
  fog_error err = {0};
  float *rgb = malloc(sizeof(float) * 3 * (size_t)h->width * (size_t)h->height);
  int status = rgb ? recorder_read_rgb(&rec, h->frames, rgb, &err)
                   : fog_fail(&err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory", h->screenshot);
  /* through the config's display transform, as the window shows it */
  if (!status) {
    const display_transform display = scene_config_display(h->config);
    display_map_values(&display, rgb, rgb, 3 * (size_t)h->width * (size_t)h->height);
    status = image_write_png_srgb(h->screenshot, h->width, h->height, 3, rgb,
                                  display.dither ? SRGB8_DITHER : SRGB8_ROUND, &err);
  }
  free(rgb);
  if (status) {
    fprintf(stderr, "fogpipe demo: --screenshot: %s\n", err.message);
    return 1;
  }
  printf("fogpipe demo: wrote %s (frame %d of the recording)\n", h->screenshot, h->frames);
  return 0;
}

static int record_instead(const headless_job *h, const char *reason) {
  char folder[PATH_MAX + 1] = "out/demo";
  recorder probe = {0}; /* its made: the folders a failed run takes away again */
  fog_error rerr = {0};
  char temp[] = "/tmp/fogpipe-demo-XXXXXX";
  bool made_temp = false;
  if (recorder_open(&probe, &(recorder_desc){.folder = folder, .width = h->width,
                                             .height = h->height},
                    &rerr)) {
    out_folder_undo(&probe.made);
    probe = (recorder){0};
    if (!mkdtemp(temp)) {
      fprintf(stderr, "fogpipe demo: %s, and no folder to record into (%s)\n", reason,
              rerr.message);
      return 1;
    }
    made_temp = true;
    snprintf(folder, sizeof folder, "%s", temp);
  }
  /* Print where the frames are as an absolute path: the user may not know the cwd. */
  char absolute[PATH_MAX];
  if (realpath(folder, absolute)) snprintf(folder, sizeof folder, "%s", absolute);
  /* none of the frames to be written or cleared may be a file the scene reads: checked
   * before the earlier frames go (record_run checks again, too late for those) */
  char frames[PATH_MAX + 32];
  snprintf(frames, sizeof frames, "%s/frame.####.exr", folder);
  const int refused =
      cli_sequence_not_scene_input("demo", "the recording folder", frames, h->config);
  if (refused) {
    if (made_temp) rmdir(temp);
    out_folder_undo(&probe.made);
    return refused;
  }
  printf("fogpipe demo: %s: recording %d frame%s of %s headless into %s instead\n", reason,
         h->frames, h->frames == 1 ? "" : "s", h->config_path, folder);
  fflush(stdout);
  /* out/demo holds the last demo's recording: an earlier, longer run's later frames would
   * stay beside this one's, so they go, but only once this run's scene has loaded (a scene
   * that fails to load used to leave the folder empty) */
  record_job job = {.command = "demo", .config_path = h->config_path, .frames = h->frames,
                    .fps = 24, .out = folder, .width = h->width, .height = h->height,
                    .quiet = !isatty(fileno(stdout)), .replace_earlier = true};
  int status = record_run(&job);
  if (!status && h->screenshot) status = last_frame_png(h, folder);
  if (status && made_temp) rmdir(temp); /* left only if empty: frames written stay */
  /* out/demo (and out/) made for a run that failed: gone again while empty, as record's */
  if (status) out_folder_undo(&probe.made);
  return status;
}

typedef struct demo_options demo_options;
static int demo_headless(const demo_options *o, const headless_job *h, const char *reason);

typedef struct demo_options {
  const char *config_path, *screenshot;
  int width, height, frames; /* frames 0: HEADLESS_FRAMES headless, 30 before a screenshot */
  bool size_given;           /* --size: the headless recording's size too */
  double scale;              /* 0: chosen from the renderer */
  int live_rung;             /* live_rung_kind the panel starts with */
  bool paused;               /* start with the simulation (or a volume's sequence) paused */
  bool hide_panel;
} demo_options;

/* 0 to go on, CLI_HELP, or the exit status of a bad command line. */
static int parse_demo_options(int argc, char **argv, demo_options *o) {
  static const char *const models[LIVE_RUNG_COUNT + 1] = {
      "fogmap", "homogeneous", "height", "gaussians", "ellipsoids", NULL};
  int size[2] = {0, 0};
  const cli_option options[] = {
      {.kind = CLI_SIZE, .name = "--size", .value = "WxH", .target = size,
       .help = "window size (default 1280x720; without a display, the\n"
               "recording's, default " CLI_TEXT_OF(HEADLESS_WIDTH) "x"
               CLI_TEXT_OF(HEADLESS_HEIGHT) ")"},
      {.kind = CLI_NUMBER, .name = "--scale", .value = "S", .target = &o->scale, .min = 0.25,
       .max = 1.0,
       .help = "render at S times the window size, 0.25..1 (default 1 on\n"
               "a GPU; 0.5 on a software renderer such as llvmpipe, with\n"
               "the fog at half of that, upsampled by depth: the fog pass\n"
               "costs per pixel; the panel changes both; there the terrain\n"
               "LOD's error is doubled and the lamps take the live rule).\n"
               "A model without a simulation: 0.5 unless given"},
      {.kind = CLI_CHOICE, .name = "--model", .value = "NAME", .target = &o->live_rung,
       .choices = models,
       .help = "start with the panel's model: fogmap (default),\n"
               "homogeneous, height, gaussians (16) or ellipsoids (4),\n"
               "fitted to the simulated fog live (a model without a\n"
               "simulation shows its own fog)"},
      {.kind = CLI_FLAG, .name = "--paused", .target = &o->paused,
       .help = "start with the simulation paused (Space plays it; P a\n"
               "volume's VDB sequence)"},
      {.kind = CLI_FLAG, .name = "--hide-panel", .target = &o->hide_panel,
       .help = "start with the panel hidden (Tab shows it)"},
      {.kind = CLI_OUTPUT, .name = "--screenshot", .value = "FILE.png", .target = &o->screenshot,
       .extensions = (const char *const[]){".png", NULL},
       .help = "after --frames frames, save the window as a PNG and quit\n"
               "(the panel in it from the 2nd frame, unless hidden);\n"
               "without a display, the recording's last frame"},
      {.kind = CLI_INT, .name = "--frames", .value = "N", .target = &o->frames, .min = 1,
       .max = 1000000,
       .help = "frames before the screenshot (default 30; 1 for a model\n"
               "without a simulation); without --screenshot, the window\n"
               "closes after N frames; without a display, frames recorded\n"
               "(default " CLI_TEXT_OF(HEADLESS_FRAMES) ")"},
  };
  const cli_spec spec = {
      .command = "demo",
      .usage = "[CONFIG] [options]",
      .about = "The live fog demo: the fog is simulated (FFT stable fluids), wavelet-transformed and\n"
               "rendered with the exact extinction integral every frame. CONFIG defaults to\n"
               DEFAULT_CONFIG ".\n\n"
               "In the window:\n"
               "  W A S D         move (Q/E down/up, Shift faster)\n"
               "  middle drag     look around (or the arrow keys)\n"
               "  left drag       paint fog on the terrain (with the panel's lamp tool on:\n"
               "                  place or drag a lamp; right click removes one)\n"
               "  right drag or Shift+left drag   erase fog\n"
               "  Space           pause / resume the simulation;  N: one step;  R: reset\n"
               "  Tab             hide / show the panel;  Esc: quit\n"
               "The panel shows the frame rate, a frame-time plot and the per-stage timings,\n"
               "and sets the basis, levels, mu, LOD method, fog resolution, render scale,\n"
               "density, colour, vertical profile, wind, turbulence, viscosity, emitter rate,\n"
               "the sun (time of day, colour, albedo, g, self-shadow, shafts) and lamps; its\n"
               "model menu draws a cheaper model fitted to the fog live, with its error.\n"
               "A model without a simulation opens in the same window as `fogpipe view` shows it\n"
               "(its panel: density, colour and the sun; P plays a volume's sequence).\n\n"
               "Without a display (no DISPLAY/WAYLAND_DISPLAY, or the window cannot open) the\n"
               "scene is recorded headless instead: " CLI_TEXT_OF(HEADLESS_FRAMES) " frames at "
               CLI_TEXT_OF(HEADLESS_WIDTH) "x" CLI_TEXT_OF(HEADLESS_HEIGHT) " into ./out/demo (or a\n"
               "temporary folder if that is not writable).",
      .operand = "CONFIG", .min_operands = 0, .max_operands = 1,
      CLI_OPTIONS(options)};
  int parsed = cli_parse_one(&spec, argc, argv, &o->config_path);
  if (parsed) return parsed;
  o->size_given = size[0] > 0;
  if (o->size_given) o->width = size[0], o->height = size[1];
  if (!o->config_path) o->config_path = DEFAULT_CONFIG;
  return 0;
}

/* The recording instead of the window: the options only a window has are named, not
 * silently dropped. */
static int demo_headless(const demo_options *o, const headless_job *h, const char *reason) {
  char unused[128] = "";
  if (o->scale > 0) strcat(unused, " --scale");
  if (o->live_rung != LIVE_RUNG_FOGMAP) strcat(unused, " --model");
  if (o->paused) strcat(unused, " --paused");
  if (o->hide_panel) strcat(unused, " --hide-panel");
  if (unused[0])
    fprintf(stderr, "fogpipe demo: without a window,%s %s no effect\n", unused,
            strchr(unused + 1, ' ') ? "have" : "has");
  return record_instead(h, reason);
}

int cmd_demo(int argc, char **argv) {
  demo_options o = {.width = 1280, .height = 720};
  int parsed = parse_demo_options(argc, argv, &o);
  if (parsed) return parsed == CLI_HELP ? 0 : parsed;
  scene_config config;
  fog_error cerr = {0};
  if (scene_config_load(o.config_path, &config, &cerr)) {
    fprintf(stderr, "fogpipe demo: %s\n", cerr.message);
    return 1;
  }
  if (o.screenshot && cli_output_not_scene_input("demo", "--screenshot", o.screenshot, &config))
    return 2;
  const headless_job headless = {
      .config_path = o.config_path, .config = &config, .frames = o.frames ? o.frames : HEADLESS_FRAMES,
      .width = o.size_given ? o.width : HEADLESS_WIDTH,
      .height = o.size_given ? o.height : HEADLESS_HEIGHT, .screenshot = o.screenshot};
  if (!cli_display_available())
    return demo_headless(&o, &headless,
                          "no display (DISPLAY and WAYLAND_DISPLAY are unset)");
  /* Nothing to simulate in the other models: the window shows their fog as the config holds
   * it, playing what moves by itself (a volume's sequence, emitters, drifting noise). */
  const bool simulate = fog_model_table[config.fog.model].pyramid;
  char note[SCENE_CONFIG_PATH_MAX + 96];
  snprintf(note, sizeof note, "%s's [fog] model has no fogmap to simulate: showing it as the "
           "config holds it%s", o.config_path,
           render_fog_animated(&config) ? ", moving by itself" : "");
  /* --paused holds the simulation or a volume's sequence: said, not dropped, where the
   * scene has neither (what moves by itself, drifting noise or emitters, moves on) */
  if (o.paused && !simulate && config.fog.model != FOG_MODEL_VOLUME)
    fprintf(stderr, "fogpipe demo: --paused has no effect: %s has no simulation or VDB "
            "sequence to hold\n", o.config_path);
  fog_error window_failure;
  /* --scale 0 (not given): the simulated source chooses by the renderer, the other 0.5 */
  const double scale = simulate || o.scale > 0 ? o.scale : 0.5;
  int status = window_program_run(
      &config, &(window_options){.command = "demo", .config_path = o.config_path,
                                 .width = o.width, .height = o.height, .render_scale = scale,
                                 .simulate = simulate, .play = !o.paused,
                                 .live_rung = o.live_rung, .hide_panel = o.hide_panel,
                                 .screenshot = o.screenshot,
                                 .frames = o.frames > 0 ? o.frames : (simulate ? 30 : 1),
                                 .quit_after_frames = o.frames > 0 && !o.screenshot,
                                 .rung = -1, .window_failure = &window_failure,
                                 .note = simulate ? NULL : note});
  if (status != WINDOW_PROGRAM_NO_WINDOW) return status;
  char reason[sizeof window_failure.message + 16];
  snprintf(reason, sizeof reason, "no window (%s)", window_failure.message);
  return demo_headless(&o, &headless, reason);
}
