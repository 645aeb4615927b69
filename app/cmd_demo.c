/* fogpipe demo [CONFIG]: the live animated fog demo. A GLFW window with the fog simulated,
 * transformed and rendered every frame (app/pipeline.h), a Dear ImGui panel (app/panel.h),
 * a free camera and fog painting. Without a display it says so in one line and records
 * the scene headless instead (app/recorder.h). */
#define _POSIX_C_SOURCE 200809L
#define _XOPEN_SOURCE 700
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <GLFW/glfw3.h>

#include "app/free_camera.h"
#include "app/commands.h"
#include "app/config.h"
#include "app/panel.h"
#include "app/pipeline.h"
#include "app/cli.h"
#include "app/cli_options.h"
#include "app/cmd_record.h"
#include "app/cmd_view.h"
#include "app/live_rung.h"
#include "app/recorder.h"
#include "render/fog_field.h"
#include "render/gl_context.h"
#include "render/gl_present.h"
#include "render/gl_util.h"
#include "sim/sim.h"

#define DEFAULT_CONFIG FOGPIPE_SOURCE_DIR "/configs/default.ini"
#define HEADLESS_FRAMES 48
#define HEADLESS_WIDTH 640
#define HEADLESS_HEIGHT 360


/* ---- the panel ---- */

typedef struct demo_ui {
  float brush_radius;   /* world units */
  float brush_strength; /* density per second at the stroke's centre line */
  float render_scale;
  bool has_bspline_profile;
  /* The lamp tool: the mouse places (left), drags (left on a lamp) and removes (right)
   * point lamps of this colour x intensity, `lamp_height` above the surface clicked. */
  bool placing_lamps;
  float lamp_colour[3], lamp_intensity, lamp_height;
  int dragged_lamp; /* -1: none */
  float frame_history[120];
  int history_next;
} demo_ui;

/* The stage timings and the frame-time plot. */
static void panel_timings(panel *ui, pipeline *pipe, const pipeline_timings *med, demo_ui *d) {
  if (!panel_header(ui, "timings (median ms)", true)) return;
  panel_text(ui, "%.1f fps   step %ld", med->frame > 0 ? 1000.0 / med->frame : 0.0,
             pipeline_step_index(pipe));
  panel_text(ui, "sim %6.2f   transform %6.2f", med->sim, med->transform);
  panel_text(ui, "upload %6.2f   render %6.2f", med->upload, med->render);
  panel_text(ui, "frame %6.2f   sun shadow %6.2f", med->frame, med->sun_shadow);
  float ordered[120], top = 34.0f; /* at least the 30 fps line's scale */
  for (int i = 0; i < 120; i++) {
    ordered[i] = d->frame_history[(d->history_next + i) % 120];
    if (ordered[i] > top) top = ordered[i];
  }
  panel_plot(ui, "frame ms", ordered, 120, 1.1f * top);
}

/* The ladder live: a cheaper model fitted to the simulated fog as it moves, drawn in its
 * place, with its error against it (app/live_rung.h). */
static bool panel_model(panel *ui, pipeline *pipe, const pipeline_timings *med,
                        pipeline_params *params) {
  if (!panel_header(ui, "model", true)) return false;
  bool changed = false;
  changed |= panel_combo(ui, "model", &params->live_rung, live_rung_names, LIVE_RUNG_COUNT);
  live_rung r;
  if (pipeline_live_rung(pipe, &r)) {
    if (r.model.kind == FOG_MODEL_HEIGHT)
      panel_text(ui, "K %.4g at y0 %.1f, H %.1f", r.model.extinction, r.model.y0,
                 r.model.scale_height);
    else if (r.model.kind == FOG_MODEL_RBF)
      panel_text(ui, "%d Gaussians, refitted every %d steps", r.model.rbf_count,
                 LIVE_RUNG_REFIT);
    else if (r.model.kind == FOG_MODEL_QUADRIC)
      panel_text(ui, "%d ellipsoids, refitted every %d steps", r.model.quadric_count,
                 LIVE_RUNG_REFIT);
    else
      panel_text(ui, "K %.4g per unit", r.model.extinction);
    if (r.rays > 0)
      panel_text(ui, "|dtau| vs the fogmap: max %.3f, mean %.3f (%d rays)", r.max_error,
                 r.mean_error, r.rays);
  } else {
    panel_text(ui, "the fogmap itself: the exact walk");
  }
  panel_text(ui, "fog pass + scene %.2f ms (median)", med->render);
  return changed;
}

/* Pause, step, reset and the fluid's forces. */
static bool panel_simulation(panel *ui, pipeline *pipe, pipeline_params *params) {
  if (!panel_header(ui, "simulation", true)) return false;
  bool changed = false;
  changed |= panel_checkbox(ui, "pause", &params->paused);
  panel_same_line(ui);
  if (panel_button(ui, "step")) pipeline_step_once(pipe);
  panel_same_line(ui);
  if (panel_button(ui, "reset")) pipeline_reset(pipe);
  changed |= panel_slider_float(ui, "wind x", &params->wind[0], -40.0f, 40.0f, "%.1f", false);
  changed |= panel_slider_float(ui, "wind z", &params->wind[1], -40.0f, 40.0f, "%.1f", false);
  changed |= panel_slider_float(ui, "turbulence", &params->turbulence, 0.0f, 40.0f, "%.2f", false);
  changed |= panel_slider_float(ui, "viscosity", &params->viscosity, 0.0f, 10.0f, "%.5f", true);
  changed |= panel_slider_float(ui, "emitter rate", &params->emitter_rate, 0.0f, 5.0f, "%.2f", false);
  return changed;
}

/* Density, colour and the vertical profile. */
static bool panel_fog(panel *ui, pipeline_params *params, demo_ui *d) {
  if (!panel_header(ui, "fog", true)) return false;
  bool changed = false;
  changed |= panel_slider_float(ui, "density", &params->density, 0.0001f, 1.0f, "%.4f", true);
  changed |= panel_color3(ui, "colour", params->fog_colour);
  /* fog_profile_kind order; the B-spline profile only when the config has one. */
  static const char *const profiles[] = {"slab", "exponential", "B-spline (config)"};
  changed |= panel_combo(ui, "profile", &params->profile_kind, profiles,
                         d->has_bspline_profile ? 3 : 2);
  if (params->profile_kind == FOG_PROFILE_EXPONENTIAL) {
    changed |= panel_slider_float(ui, "fog height", &params->fog_height, -50.0f, 200.0f, "%.1f", false);
    changed |= panel_slider_float(ui, "scale height", &params->scale_height, 1.0f, 200.0f, "%.1f", true);
  }
  return changed;
}

/* The sun (a time of day), its colour, albedo, phase and shadows. */
static bool panel_sunlight(panel *ui, pipeline_params *params) {
  if (!panel_header(ui, "sunlight in the fog", true)) return false;
  bool changed = false;
  /* sigma_s = albedo K, Henyey-Greenstein g (docs/light.md); the sun (a time of day)
   * lights the terrain and the fog */
  float albedo = (float)params->sun.albedo, g = (float)params->sun.phase_g;
  /* down to a sun just under the horizon (dusk: the fog's self-shadow turns opaque) */
  changed |= panel_slider_float(ui, "sun azimuth", &params->sun_azimuth, -180.0f, 180.0f,
                                "%.0f deg", false);
  changed |= panel_slider_float(ui, "sun elevation", &params->sun_elevation, -5.0f, 90.0f,
                                "%.1f deg", false);
  if (panel_slider_float(ui, "albedo", &albedo, 0.0f, 1.0f, "%.2f", false)) {
    params->sun.albedo = albedo;
    changed = true;
  }
  if (panel_slider_float(ui, "phase g", &g, -0.95f, 0.95f, "%.2f", false)) {
    params->sun.phase_g = g;
    changed = true;
  }
  /* [light] sun_colour (HDR) as a hue and a strength: the surfaces' sun and pi x it the
   * fog's (the pipeline relights both) */
  float hue[3], strength = 0.0f;
  for (int c = 0; c < 3; c++) {
    hue[c] = (float)(params->sun.radiance[c] / SCENE_SUN_IRRADIANCE_PER_COLOUR);
    strength = fmaxf(strength, hue[c]);
  }
  for (int c = 0; c < 3; c++) hue[c] = strength > 0.0f ? hue[c] / strength : 1.0f;
  bool hue_changed = panel_color3(ui, "sun colour", hue);
  if (panel_slider_float(ui, "sun strength", &strength, 0.0f, 10.0f, "%.2f", false) ||
      hue_changed) {
    for (int c = 0; c < 3; c++)
      params->sun.radiance[c] = SCENE_SUN_IRRADIANCE_PER_COLOUR * hue[c] * strength;
    changed = true;
  }
  /* T_s: the fog's shadow on itself and on the ground (albedo > 0) */
  changed |= panel_checkbox(ui, "fog self-shadow", &params->fog_self_shadow);
  panel_same_line(ui);
  changed |= panel_checkbox(ui, "light shafts", &params->shafts);
  return changed;
}

/* The transform's basis and levels, the LOD and the fog pass's resolution. */
static bool panel_wavelets(panel *ui, pipeline_params *params) {
  if (!panel_header(ui, "wavelets", true)) return false;
  bool changed = false;
  static const char *const bases[] = {"Haar (degree 0)", "linear (CDF 5/3)", "quadratic (bior3.3)"};
  changed |= panel_combo(ui, "basis", &params->degree, bases, 3);
  changed |= panel_slider_int(ui, "levels J", &params->levels, 0, 7);
  changed |= panel_slider_float(ui, "mu", &params->mu, 0.0f, 1.0f, "%.3f", false);
  static const char *const methods[] = {"sum of details (paper)", "switch A_l (ours)"};
  changed |= panel_combo(ui, "LOD", &params->lod_method, methods, 2);
  static const char *const divisors[] = {"full", "1/2", "1/4"};
  int divisor_index = params->fog_resolution_divisor >= 4 ? 2 : params->fog_resolution_divisor >= 2;
  if (panel_combo(ui, "fog resolution", &divisor_index, divisors, 3)) {
    params->fog_resolution_divisor = 1 << divisor_index;
    changed = true;
  }
  return changed;
}

/* Placing lamps with the mouse: their colour, intensity and height. */
static void panel_lamps(panel *ui, const pipeline_params *params, demo_ui *d) {
  if (!panel_header(ui, "lamps", false)) return;
  panel_checkbox(ui, "place lamps with the mouse", &d->placing_lamps);
  panel_color3(ui, "lamp colour", d->lamp_colour);
  panel_slider_float(ui, "lamp intensity", &d->lamp_intensity, 10.0f, 20000.0f, "%.0f", true);
  panel_slider_float(ui, "lamp height", &d->lamp_height, 0.5f, 100.0f, "%.1f", true);
  panel_text(ui, "left: place / drag a lamp   right: remove");
  panel_text(ui, "%d of %d lamps (scattered with albedo > 0)", params->lamps.count,
             FOG_MAX_LAMPS);
}

/* The density brush. */
static void panel_brush(panel *ui, demo_ui *d) {
  if (!panel_header(ui, "brush", false)) return;
  panel_slider_float(ui, "radius", &d->brush_radius, 1.0f, 200.0f, "%.0f", true);
  panel_slider_float(ui, "strength", &d->brush_strength, 0.1f, 20.0f, "%.1f", true);
  panel_text(ui, "left drag: paint   right / shift: erase");
  panel_slider_float(ui, "render scale", &d->render_scale, 0.25f, 1.0f, "%.2f", false);
}

static void panel_contents(panel *ui, pipeline *pipe, demo_ui *d) {
  pipeline_params params = pipeline_get_params(pipe);
  bool changed = false;
  if (panel_window_begin(ui, "fogpipe", 10, 10, 330)) {
    pipeline_timings last;
    pipeline_timings med = pipeline_get_timings(pipe, &last);
    d->frame_history[d->history_next] = (float)last.frame;
    d->history_next = (d->history_next + 1) % 120;
    panel_timings(ui, pipe, &med, d);
    changed |= panel_model(ui, pipe, &med, &params);
    changed |= panel_simulation(ui, pipe, &params);
    changed |= panel_fog(ui, &params, d);
    changed |= panel_sunlight(ui, &params);
    changed |= panel_wavelets(ui, &params);
    panel_lamps(ui, &params, d);
    panel_brush(ui, d);
  }
  panel_window_end(ui);
  if (changed) pipeline_set_params(pipe, &params);
}

/* ---- headless fallback ---- */

static int record_instead(const char *config_path, int frames, const char *reason) {
  char folder[PATH_MAX + 1] = "out/demo";
  recorder probe;
  fog_error rerr = {0};
  if (recorder_open(&probe, &(recorder_desc){.folder = folder, .width = HEADLESS_WIDTH,
                                             .height = HEADLESS_HEIGHT},
                    &rerr)) {
    char temp[] = "/tmp/fogpipe-demo-XXXXXX";
    if (!mkdtemp(temp)) {
      fprintf(stderr, "fogpipe demo: %s, and no folder to record into (%s)\n", reason,
              rerr.message);
      return 1;
    }
    snprintf(folder, sizeof folder, "%s", temp);
  }
  /* Print where the frames are as an absolute path: the user may not know the cwd. */
  char absolute[PATH_MAX];
  if (realpath(folder, absolute)) snprintf(folder, sizeof folder, "%s", absolute);
  printf("fogpipe demo: %s: recording %d frame%s of %s headless into %s instead\n", reason,
         frames, frames == 1 ? "" : "s", config_path, folder);
  fflush(stdout);
  record_job job = {.command = "demo", .config_path = config_path, .frames = frames,
                    .out = folder, .width = HEADLESS_WIDTH, .height = HEADLESS_HEIGHT,
                    .quiet = !isatty(fileno(stdout))};
  return record_run(&job);
}

/* ---- the window ---- */

static int save_screenshot(const char *path, int width, int height) {
  float *pixels = malloc((size_t)width * height * 3 * sizeof(float));
  if (!pixels) return 1;
  fog_error rerr = {0};
  fog_error serr = {0};
  int status = gl_read_window(width, height, pixels, &rerr);
  if (status) fprintf(stderr, "fogpipe demo: screenshot: %s\n", rerr.message);
  if (!status && image_write_png(path, width, height, 3, pixels, &serr)) {
    fprintf(stderr, "fogpipe demo: screenshot: %s\n", serr.message);
    status = 1;
  }
  if (!status) printf("screenshot: %s\n", path);
  free(pixels);
  return status;
}

typedef struct demo_options {
  const char *config_path, *screenshot;
  int width, height, frames; /* frames 0: HEADLESS_FRAMES headless, 30 before a screenshot */
  double scale;              /* 0: chosen from the renderer */
  int live_rung;             /* live_rung_kind the panel starts with */
} demo_options;

/* 0 to go on, CLI_HELP, or the exit status of a bad command line. */
static int parse_demo_options(int argc, char **argv, demo_options *o) {
  static const char *const models[LIVE_RUNG_COUNT + 1] = {
      "fogmap", "homogeneous", "height", "gaussians", "ellipsoids", NULL};
  int size[2] = {o->width, o->height};
  const cli_option options[] = {
      {.kind = CLI_SIZE, .name = "--size", .value = "WxH", .target = size,
       .help = "window size (default 1280x720)"},
      {.kind = CLI_NUMBER, .name = "--scale", .value = "S", .target = &o->scale, .min = 0.25,
       .max = 1.0,
       .help = "render at S times the window size, 0.25..1 (default 1 on\n"
               "a GPU; 0.5 on a software renderer such as llvmpipe, with\n"
               "the fog at half of that, upsampled by depth: the fog pass\n"
               "costs per pixel; the panel changes both)"},
      {.kind = CLI_CHOICE, .name = "--model", .value = "NAME", .target = &o->live_rung,
       .choices = models,
       .help = "start with the panel's model: fogmap (default),\n"
               "homogeneous, height, gaussians (16) or ellipsoids (4),\n"
               "fitted to the fog live"},
      {.kind = CLI_TEXT, .name = "--screenshot", .value = "FILE", .target = &o->screenshot,
       .help = "after --frames frames, save the window as a PNG and quit"},
      {.kind = CLI_INT, .name = "--frames", .value = "N", .target = &o->frames, .min = 1,
       .max = 1000000,
       .help = "frames before the screenshot (default 30); without a\n"
               "display, frames recorded (default " CLI_TEXT_OF(HEADLESS_FRAMES) ")"},
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
               "  left drag       paint fog on the terrain\n"
               "  right drag or Shift+left drag   erase fog\n"
               "  Space           pause / resume the simulation;  N: one step;  R: reset\n"
               "  Esc             quit\n"
               "The panel sets the basis, levels, mu, LOD method, density, colour, vertical\n"
               "profile, wind, viscosity and emitter rate, and shows the per-stage timings; its\n"
               "model menu draws a cheaper model fitted to the fog live, with its error.\n\n"
               "Without a display (no DISPLAY/WAYLAND_DISPLAY, or the window cannot open) the\n"
               "scene is recorded headless instead: " CLI_TEXT_OF(HEADLESS_FRAMES) " frames at "
               CLI_TEXT_OF(HEADLESS_WIDTH) "x" CLI_TEXT_OF(HEADLESS_HEIGHT) " into ./out/demo (or a\n"
               "temporary folder if that is not writable).",
      .operand = "CONFIG", .min_operands = 0, .max_operands = 1,
      .options = options, .option_count = sizeof options / sizeof options[0]};
  int operands = 0, parsed = cli_parse(&spec, argc, argv, &o->config_path, &operands);
  if (parsed) return parsed;
  o->width = size[0], o->height = size[1];
  if (!o->config_path) o->config_path = DEFAULT_CONFIG;
  return 0;
}

/* What the window's input remembers between frames. */
typedef struct demo_input {
  bool painting;
  double last_paint[3];
  bool space_down, n_down, r_down;
} demo_input;

/* Esc quits, Space pauses, N steps, R restarts (on the key's press). */
static void demo_keys(GLFWwindow *window, pipeline *pipe, demo_input *in) {
  if (glfwGetKey(window, GLFW_KEY_ESCAPE) == GLFW_PRESS) glfwSetWindowShouldClose(window, 1);
  bool space = glfwGetKey(window, GLFW_KEY_SPACE) == GLFW_PRESS;
  bool n = glfwGetKey(window, GLFW_KEY_N) == GLFW_PRESS;
  bool r = glfwGetKey(window, GLFW_KEY_R) == GLFW_PRESS;
  if (space && !in->space_down) {
    pipeline_params params = pipeline_get_params(pipe);
    params.paused = !params.paused;
    pipeline_set_params(pipe, &params);
  }
  if (n && !in->n_down) pipeline_step_once(pipe);
  if (r && !in->r_down) pipeline_reset(pipe);
  in->space_down = space, in->n_down = n, in->r_down = r;
}

/* The surface point under the cursor (the last frame's distance, in render pixels); false
 * over the sky. */
static bool surface_under_cursor(GLFWwindow *window, pipeline *pipe, const free_camera *fc,
                                 double hit[3]) {
  int render_w, render_h, win_w = 0, win_h = 0;
  pipeline_size(pipe, &render_w, &render_h);
  glfwGetWindowSize(window, &win_w, &win_h);
  int px = (int)(fc->last_x * render_w / (win_w > 0 ? win_w : 1));
  int py = (int)(fc->last_y * render_h / (win_h > 0 ? win_h : 1));
  return pipeline_pick_surface(pipe, &fc->cam, px, py, hit);
}

/* Painting: the surface point under the cursor from the last frame's distance texture, in
 * render pixels; left paints, right (or Shift) erases, along the stroke since last frame. */
static void demo_paint(GLFWwindow *window, pipeline *pipe, const free_camera *fc,
                       const demo_ui *d, bool mouse, double dt, demo_input *in) {
  bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
               glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  double hit[3];
  if (!mouse || !(left || right) || !surface_under_cursor(window, pipe, fc, hit)) {
    in->painting = false;
    return;
  }
  const double *from = in->painting ? in->last_paint : hit;
  double sign = (right || shift) ? -1.0 : 1.0;
  pipeline_paint(pipe, from[0], from[2], hit[0], hit[2], d->brush_radius,
                 sign * d->brush_strength * dt);
  memcpy(in->last_paint, hit, sizeof hit);
  in->painting = true;
}

/* The lamp tool (the panel's "lamps"): left places a lamp above the surface under the
 * cursor, or drags the lamp nearest it (within 3 lamp heights, horizontally); right removes
 * that lamp. The pipeline lights the fog and the surfaces with the params' lamps. */
static void demo_lamps(GLFWwindow *window, pipeline *pipe, const free_camera *fc, demo_ui *d,
                       bool mouse) {
  bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  double hit[3];
  if (!mouse || !(left || right) || !surface_under_cursor(window, pipe, fc, hit)) {
    d->dragged_lamp = -1;
    return;
  }
  pipeline_params params = pipeline_get_params(pipe);
  fog_lamps *lamps = &params.lamps;
  int nearest = -1;
  double best = 3.0 * d->lamp_height;
  for (int i = 0; i < lamps->count; i++) {
    double dx = lamps->lamp[i].position[0] - hit[0], dz = lamps->lamp[i].position[2] - hit[2];
    if (sqrt(dx * dx + dz * dz) < best) best = sqrt(dx * dx + dz * dz), nearest = i;
  }
  if (right) {
    if (nearest < 0) return;
    for (int i = nearest; i + 1 < lamps->count; i++) lamps->lamp[i] = lamps->lamp[i + 1];
    lamps->count--;
    d->dragged_lamp = -1;
  } else {
    int moved = d->dragged_lamp >= 0 && d->dragged_lamp < lamps->count ? d->dragged_lamp : nearest;
    if (moved < 0) { /* a new lamp */
      if (lamps->count == FOG_MAX_LAMPS) return;
      moved = lamps->count++;
      lamps->lamp[moved] = (fog_lamp){.kind = FOG_LAMP_POINT, .radius = 0.5};
      for (int c = 0; c < 3; c++)
        lamps->lamp[moved].intensity[c] = d->lamp_colour[c] * d->lamp_intensity;
    }
    for (int c = 0; c < 3; c++) lamps->lamp[moved].position[c] = hit[c];
    lamps->lamp[moved].position[1] += d->lamp_height;
    d->dragged_lamp = moved;
  }
  pipeline_set_params(pipe, &params);
}

/* Frames until the window closes (or the screenshot is taken); the exit status. */
static int demo_loop(gl_context *gl, pipeline *pipe, panel *ui, demo_ui *d,
                     const scene_config *config, const demo_options *o) {
  GLFWwindow *window = gl_context_glfw_window(gl);
  free_camera fc = {.speed = 80.0};
  scene_config_camera(config, &fc.cam);
  demo_input in = {0};
  fog_error perr = {0};
  double last_time = glfwGetTime();
  for (int frame = 0; !gl_context_should_close(gl); frame++) {
    gl_context_poll_events(gl);
    double t = glfwGetTime(), dt = fmin(t - last_time, 0.25);
    last_time = t;
    int fb_w = 0, fb_h = 0, render_w, render_h;
    gl_context_framebuffer_size(gl, &fb_w, &fb_h);
    if (fb_w < 1 || fb_h < 1) continue; /* minimised */
    int want_w = (int)fmax(16, fb_w * d->render_scale), want_h = (int)fmax(16, fb_h * d->render_scale);
    pipeline_size(pipe, &render_w, &render_h);
    if (want_w != render_w || want_h != render_h) pipeline_resize(pipe, want_w, want_h, &perr);

    panel_begin_frame(ui);
    panel_contents(ui, pipe, d);
    bool keyboard = !panel_wants_keyboard(ui), mouse = !panel_wants_mouse(ui);
    if (keyboard) demo_keys(window, pipe, &in);
    const free_camera_input input =
        free_camera_read(window, FREE_CAMERA_LOOK_MIDDLE, keyboard, mouse);
    free_camera_step(&fc, &input, dt);
    if (frame > 0 && d->placing_lamps) demo_lamps(window, pipe, &fc, d, mouse);
    else if (frame > 0) demo_paint(window, pipe, &fc, d, mouse, dt, &in);

    if (pipeline_frame(pipe, &fc.cam, false, &perr)) {
      fprintf(stderr, "fogpipe demo: %s\n", perr.message);
      return 1;
    }
    if (pipeline_present(pipe, fb_w, fb_h, &perr)) {
      fprintf(stderr, "fogpipe demo: %s\n", perr.message);
      return 1;
    }
    panel_end_frame(ui);
    if (o->screenshot && frame + 1 >= (o->frames ? o->frames : 30))
      return save_screenshot(o->screenshot, fb_w, fb_h);
    gl_context_swap_buffers(gl);
  }
  return 0;
}

int cmd_demo(int argc, char **argv) {
  demo_options o = {.width = 1280, .height = 720};
  int parsed = parse_demo_options(argc, argv, &o);
  if (parsed) return parsed == CLI_HELP ? 0 : parsed;
  int fog_divisor = 1; /* fog resolution divisor; 2 with the automatic scale on software GL */
  scene_config config;
  fog_error cerr = {0};
  if (scene_config_load(o.config_path, &config, &cerr)) {
    fprintf(stderr, "fogpipe demo: %s\n", cerr.message);
    return 1;
  }
  const int headless_frames = o.frames ? o.frames : HEADLESS_FRAMES;
  const char *display = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
  if (!(display && *display) && !(wayland && *wayland))
    return record_instead(o.config_path, headless_frames,
                          "no display (DISPLAY and WAYLAND_DISPLAY are unset)");
  if (!fog_model_table[config.fog.model].pyramid) {
    /* Nothing to simulate live in the other models: show the scene with the free camera. */
    printf("fogpipe demo: %s's [fog] model has no simulation to animate: opening it in "
           "fogpipe view\n", o.config_path);
    fflush(stdout);
    return view_window_run(&config, o.config_path,
                           &(view_options){.width = o.width, .height = o.height,
                                           .render_scale = o.scale > 0 ? o.scale : 0.5,
                                           .play = true, .screenshot = o.screenshot,
                                           .frames = o.frames > 0 ? o.frames : 1, .rung = -1});
  }
  fog_error gerr = {0};
  gl_context *gl = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_WINDOW,
                                                        .width = o.width, .height = o.height,
                                                        .title = "fogpipe demo", .vsync = true},
                                     &gerr);
  if (!gl) {
    char reason[sizeof gerr.message + 16];
    snprintf(reason, sizeof reason, "no window (%s)", gerr.message);
    return record_instead(o.config_path, headless_frames, reason);
  }
  if (o.scale == 0.0) {
    /* The fog pass costs per pixel: a software renderer (Mesa llvmpipe/softpipe) renders
     * at half the window's resolution per axis with the fog at half of that (upsampled
     * guided by the surface distance), a GPU at full resolution. */
    bool software = gl_context_is_software(gl);
    o.scale = software ? 0.5 : 1.0;
    fog_divisor = software ? 2 : 1;
    /* and lets the terrain's LOD show twice its pixel error (unless the config asks for
     * the full mesh): turning the camera then costs ~15 % of a frame, not ~30 % */
    if (software) config.terrain.lod_error = scene_live_terrain_lod(config.terrain.lod_error);
  }
  int fb_w = 0, fb_h = 0;
  gl_context_framebuffer_size(gl, &fb_w, &fb_h);
  demo_ui d = {.brush_radius = 30.0f, .brush_strength = 3.0f, .render_scale = (float)o.scale,
               .lamp_colour = {1.0f, 0.8f, 0.55f}, .lamp_intensity = 2000.0f, .lamp_height = 8.0f,
               .dragged_lamp = -1,
               .has_bspline_profile = config.fog.profile_count > 0};
  fog_error perr = {0};
  pipeline *pipe = pipeline_create(&(pipeline_desc){.config = &config,
                                                    .width = (int)(fb_w * d.render_scale),
                                                    .height = (int)(fb_h * d.render_scale),
                                                    .frame_seconds = 1.0 / 30.0,
                                                    .live = true},
                                   &perr);
  panel *ui = pipe ? panel_create(gl_context_glfw_window(gl)) : NULL;
  int status = 1;
  if (!pipe) {
    fprintf(stderr, "fogpipe demo: %s\n", perr.message);
  } else if (!ui) {
    fprintf(stderr, "fogpipe demo: cannot start Dear ImGui on this window\n");
  } else {
    pipeline_params initial = pipeline_get_params(pipe);
    initial.fog_resolution_divisor = fog_divisor;
    initial.live_rung = o.live_rung;
    pipeline_set_params(pipe, &initial);
    status = demo_loop(gl, pipe, ui, &d, &config, &o);
  }
  panel_destroy(ui);
  pipeline_destroy(pipe);
  gl_context_destroy(gl);
  return status;
}
