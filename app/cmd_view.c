/* fogpipe view CONFIG: the scene config in a window (GLFW) with a free camera:
 * The demo's free camera (app/free_camera.h): W/A/S/D move, Q/E down/up, Shift faster, right
 * or middle drag or the arrow keys look around; Esc quits.
 * The fog is the config's fogmap as it is (no simulation: that is `fogpipe demo`), or its
 * other fog model; a volume's VDB sequence plays with P (or from the start with --play).
 * B turns on the Gaussian brush on an RBF scene (app/rbf_brush.h: paint, erase, copy).
 * --screenshot FILE --frames N renders N frames, saves the last one as seen in the window
 * (read from GL_BACK before the swap) and exits: for tests and for looking at a scene
 * without sitting at the display (xvfb-run); a playing sequence then advances one VDB frame
 * per drawn frame. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GLFW/glfw3.h>

#include "app/free_camera.h"
#include "app/cli.h"
#include "app/cli_options.h"
#include "app/cmd_view.h"
#include "app/commands.h"
#include "app/config.h"
#include "app/fit.h"
#include "app/rbf_brush.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "app/vdb_source.h"
#include "render/gl_present.h"
#include "render/render.h"
#include "sim/sim.h"

/* model = volume: its VDB sequence, played from the config's frame. */
typedef struct volume_playback {
  vdb_sequence sequence;
  double shown;          /* frame index position on screen (vdb_sequence_position) */
  bool playing;
  double start_time;     /* when position `start` was on screen */
  double start;
  bool p_was_down;
} volume_playback;

typedef struct view_state {
  gl_context *ctx;
  scene_geometry geo;
  bool geo_made;
  scene_pass *scene;
  render_fog fog;
  bool has_fog;
  gl_target scene_target, fog_target;
  gl_presenter *presenter;
} view_state;

static int make_targets(view_state *v, int width, int height, fog_error *err) {
  gl_target_destroy(&v->scene_target);
  gl_target_destroy(&v->fog_target);
  if (scene_target_create(&v->scene_target, width, height, err)) return 1;
  if (v->has_fog &&
      gl_target_create(&v->fog_target,
                       &(gl_target_desc){.width = width, .height = height,
                                         .color_formats = {GL_RGBA16F, GL_R32F}},
                       err))
    return 1;
  return 0;
}

/* P toggles playing; while playing, the frame index position follows the clock at
 * vdb_fps, wrapping around, between frames blended as record blends them. Loads and
 * uploads only when the position changes. */
static int volume_playback_update(volume_playback *pb, GLFWwindow *window, double now,
                                  render_fog *fog, const scene_config *cfg, fog_error *err) {
  bool p_down = glfwGetKey(window, GLFW_KEY_P) == GLFW_PRESS;
  if (p_down && !pb->p_was_down) {
    pb->playing = !pb->playing;
    pb->start_time = now;
    pb->start = pb->shown;
  }
  pb->p_was_down = p_down;
  if (!pb->playing) return 0;
  const int count = pb->sequence.count;
  double position = fmod(pb->start + (now - pb->start_time) * cfg->fog.vdb_fps, (double)count);
  if (position == pb->shown) return 0;
  pb->shown = position;
  int a, b;
  double w;
  vdb_sequence_position(position, count, 1, &a, &b, &w);
  return render_fog_set_volume_time(fog, cfg, &pb->sequence, a, b, w, err);
}

/* ---- the Gaussian brush (model = rbf; app/rbf_brush.h) ---- */

enum { BRUSH_KEY_B, BRUSH_KEY_C, BRUSH_KEY_V, BRUSH_KEY_SMALLER, BRUSH_KEY_LARGER,
       BRUSH_KEY_THINNER, BRUSH_KEY_DENSER, BRUSH_KEY_SAVE, BRUSH_KEYS };

typedef struct view_brush {
  bool on;
  rbf_brush brush;
  scene_config *painted;   /* the scene with the brush's Gaussians (owned; made at first B) */
  const char *config_path; /* Ctrl+S writes NAME.painted.ini beside it */
  bool stroke;             /* the left button went down on the surface */
  double carried, last[3];
  bool have_group;
  double group[3];         /* where C picked a group up */
  bool key_was_down[BRUSH_KEYS];
} view_brush;

/* The surface point under the cursor, from the scene target's distance (false: the sky). */
static bool view_pick(const view_state *v, GLFWwindow *window, const camera *cam, double hit[3]) {
  double x, y;
  int win_w = 0, win_h = 0;
  glfwGetCursorPos(window, &x, &y);
  glfwGetWindowSize(window, &win_w, &win_h);
  const int w = v->scene_target.width, h = v->scene_target.height;
  int px = (int)(x * w / (win_w > 0 ? win_w : 1)), py = (int)(y * h / (win_h > 0 ? win_h : 1));
  if (px < 0 || py < 0 || px >= w || py >= h) return false;
  const float distance = gl_target_read_texel(&v->scene_target, 1, px, py);
  if (!(distance < 0.5f * SCENE_SKY_DISTANCE)) return false;
  double origin[3], dir[3];
  camera_ray(cam, px, py, w, h, origin, dir);
  for (int a = 0; a < 3; a++) hit[a] = origin[a] + distance * dir[a];
  return true;
}

static bool brush_key(view_brush *b, GLFWwindow *window, int key, int which) {
  bool down = glfwGetKey(window, key) == GLFW_PRESS;
  bool pressed = down && !b->key_was_down[which];
  b->key_was_down[which] = down;
  return pressed;
}

static void brush_title(const view_brush *b, GLFWwindow *window) {
  char title[320];
  if (b->on)
    snprintf(title, sizeof title,
             "fogpipe view: brush r %.3g c %.3g, %d Gaussians (drag paints, Shift erases, C/V "
             "copy, -/= size, ,/. density, Ctrl+S saves, B off)",
             b->brush.radius, b->brush.density, b->painted->fog.rbf_count);
  else
    snprintf(title, sizeof title, "fogpipe view: %s", b->config_path);
  glfwSetWindowTitle(window, title);
}

/* Ctrl+S: the painted scene as NAME.painted.ini beside the config. */
static void brush_save(const view_brush *b) {
  char path[SCENE_CONFIG_PATH_MAX + 16];
  size_t n = strlen(b->config_path);
  int stem = n > 4 && !strcmp(b->config_path + n - 4, ".ini") ? (int)(n - 4) : (int)n;
  snprintf(path, sizeof path, "%.*s.painted.ini", stem, b->config_path);
  fog_error werr;
  if (scene_config_write(b->painted, path, &werr))
    fprintf(stderr, "fogpipe view: the brush: %s\n", werr.message);
  else
    printf("fogpipe view: wrote %s (%d Gaussians)\n", path, b->painted->fog.rbf_count);
}

/* B, the mouse and the brush's keys for one frame; the fog takes the changed Gaussians. */
static int view_brush_update(view_brush *b, view_state *v, GLFWwindow *window,
                             const scene_config *cfg, const camera *cam, double time,
                             fog_error *err) {
  if (brush_key(b, window, GLFW_KEY_B, BRUSH_KEY_B)) {
    if (cfg->fog.model != FOG_MODEL_RBF || !v->has_fog) {
      printf("fogpipe view: the brush paints Gaussians: it needs [fog] model = rbf\n");
      return 0;
    }
    if (!b->painted) {
      if (!(b->painted = malloc(sizeof *b->painted))) {
        fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the brush");
        return 1;
      }
      *b->painted = *cfg;
      b->brush = rbf_brush_for(cfg->fog.rbfs, cfg->fog.rbf_count,
                               fmax(cfg->terrain.size[0], cfg->terrain.size[1]), 0.02);
    }
    b->on = !b->on;
    brush_title(b, window);
  }
  if (!b->on) return 0;
  bool ctrl = glfwGetKey(window, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
              glfwGetKey(window, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
  bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
               glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  rbf_brush *brush = &b->brush;
  bool retitle = false;
  if (brush_key(b, window, GLFW_KEY_MINUS, BRUSH_KEY_SMALLER)) brush->radius /= 1.25, retitle = true;
  if (brush_key(b, window, GLFW_KEY_EQUAL, BRUSH_KEY_LARGER)) brush->radius *= 1.25, retitle = true;
  if (brush_key(b, window, GLFW_KEY_COMMA, BRUSH_KEY_THINNER)) brush->density /= 1.25, retitle = true;
  if (brush_key(b, window, GLFW_KEY_PERIOD, BRUSH_KEY_DENSER)) brush->density *= 1.25, retitle = true;
  brush->spacing = brush->lift = 0.5 * brush->radius;
  if (brush_key(b, window, GLFW_KEY_S, BRUSH_KEY_SAVE) && ctrl) brush_save(b);
  scene_fog_config *f = &b->painted->fog;
  rbf_bank bank = {.rbfs = f->rbfs, .count = f->rbf_count, .capacity = SCENE_CONFIG_MAX_RBFS};
  int changed = 0;
  double hit[3];
  bool picked = view_pick(v, window, cam, hit);
  if (brush_key(b, window, GLFW_KEY_C, BRUSH_KEY_C) && picked) {
    b->have_group = true;
    memcpy(b->group, hit, sizeof hit);
  }
  if (brush_key(b, window, GLFW_KEY_V, BRUSH_KEY_V) && picked && b->have_group)
    changed += rbf_brush_copy(&bank, b->group, 2.0 * brush->radius, hit);
  bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  if (left && picked && shift) {
    changed += rbf_brush_erase(&bank, hit, 1.5 * brush->radius);
  } else if (left && picked) {
    if (!b->stroke) b->carried = rbf_brush_stroke_start(brush), memcpy(b->last, hit, sizeof hit);
    changed += rbf_brush_stroke(&bank, brush, b->last, hit, &b->carried);
    memcpy(b->last, hit, sizeof hit);
  }
  b->stroke = left && picked && !shift;
  f->rbf_count = bank.count;
  if (changed) {
    if (render_fog_set_rbfs(&v->fog, b->painted, time, err)) return 1;
    retitle = true;
  }
  if (retitle) brush_title(b, window);
  return 0;
}

/* --fit: the rungs and the one shown (-1: the config's own fog). */
typedef struct rung_selector {
  fit_result fit;
  bool on;
  int shown;
  bool bracket_was_down[2];
  bool zero_was_down;
} rung_selector;

/* The fog of rung `index` (-1: the config's) in place of the one shown. */
static int show_rung(view_state *v, rung_selector *sel, int index, const scene_config *cfg,
                     fog_error *err) {
  const scene_config *shown = index < 0 ? cfg : sel->fit.rungs[index].config;
  render_fog_destroy(&v->fog);
  v->has_fog = false;
  if (render_fog_create(&v->fog, shown, err)) return 1;
  render_fog_set_shafts(&v->fog, shown, scene_pass_sun_shadow(v->scene));
  v->has_fog = true;
  sel->shown = index;
  if (index < 0)
    printf("fogpipe view: showing the config's own fog\n");
  else
    printf("fogpipe view: showing rung %d: %s (max |dtau| %.3g, mean %.3g, %.2f ms in fit)\n",
           index, sel->fit.rungs[index].name, sel->fit.rungs[index].max_error,
           sel->fit.rungs[index].mean_error, sel->fit.rungs[index].ms);
  return 0;
}

/* [ and ] step through the rungs, 0 returns to the config's fog; the title says which. */
static int rung_selector_update(rung_selector *sel, view_state *v, GLFWwindow *window,
                                const scene_config *cfg, double fps, fog_error *err) {
  static const int keys[2] = {GLFW_KEY_LEFT_BRACKET, GLFW_KEY_RIGHT_BRACKET};
  int next = sel->shown;
  for (int k = 0; k < 2; k++) {
    bool down = glfwGetKey(window, keys[k]) == GLFW_PRESS;
    if (down && !sel->bracket_was_down[k]) next += k ? 1 : -1;
    sel->bracket_was_down[k] = down;
  }
  bool zero = glfwGetKey(window, GLFW_KEY_0) == GLFW_PRESS;
  if (zero && !sel->zero_was_down) next = -1;
  sel->zero_was_down = zero;
  if (next < -1) next = sel->fit.count - 1;
  if (next >= sel->fit.count) next = -1;
  if (next != sel->shown && show_rung(v, sel, next, cfg, err)) return 1;
  char title[320];
  if (sel->shown < 0)
    snprintf(title, sizeof title, "fogpipe view: the config's own fog, %.1f fps ([ ] rungs)",
             fps);
  else
    snprintf(title, sizeof title,
             "fogpipe view: rung %d/%d %s: max |dtau| %.3g, %.2f ms in fit; %.1f fps ([ ] 0)",
             sel->shown, sel->fit.count, sel->fit.rungs[sel->shown].name,
             sel->fit.rungs[sel->shown].max_error, sel->fit.rungs[sel->shown].ms, fps);
  glfwSetWindowTitle(window, title);
  return 0;
}

static void view_destroy(view_state *v) {
  gl_presenter_destroy(v->presenter);
  gl_target_destroy(&v->scene_target);
  gl_target_destroy(&v->fog_target);
  render_fog_destroy(&v->fog);
  scene_pass_destroy(v->scene);
  if (v->geo_made) scene_geometry_destroy(&v->geo);
  if (v->ctx) gl_context_destroy(v->ctx);
}

/* Scene, fog, playback and presenter for a window whose GL context v->ctx is current.
 * Errors in err. */
static int view_open(view_state *v, volume_playback *playback, const scene_config *cfg,
                     const view_options *opts, fog_error *err) {
  if (render_scene_geometry_create(cfg, &v->geo, err)) return 1;
  v->geo_made = true;
  if (!(v->scene = scene_pass_create(&v->geo, err))) return 1;
  const fog_lamps lamps = scene_config_fog_lamps(cfg);
  if (scene_pass_set_lamp_shadows(v->scene, scene_config_lamp_shadow_size(cfg), err) ||
      scene_pass_set_lamps(v->scene, &lamps, err))
    return 1;
  if (scene_config_has_fog(cfg)) {
    if (render_fog_create(&v->fog, cfg, err)) return 1;
    render_fog_set_shafts(&v->fog, cfg, scene_pass_sun_shadow(v->scene));
    render_fog_set_lamp_shadows(&v->fog, scene_pass_lamp_shadows(v->scene));
    v->has_fog = true;
  }
  playback->playing = opts->play;
  playback->start_time = glfwGetTime();
  if (cfg->fog.model == FOG_MODEL_VOLUME) {
    if (render_fog_volume_sequence(cfg, &playback->sequence, err)) return 1;
    /* render_fog_create showed vdb_frame (so it is in the sequence) */
    playback->shown = playback->start = vdb_frame_index(
        playback->sequence.frames, playback->sequence.count, cfg->fog.vdb_frame);
  }
  v->presenter = gl_presenter_create(err);
  return v->presenter ? 0 : 1;
}

/* The window's last frame as an 8-bit PNG. */
static int view_screenshot(const view_state *v, const char *path, int width, int height, int frame,
                           fog_error *err) {
  float *rgb = malloc((size_t)width * height * 3 * sizeof(float));
  if (!rgb) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the screenshot");
  int status = gl_read_window(width, height, rgb, err);
  fog_error serr;
  if (!status && image_write_png(path, width, height, 3, rgb, &serr)) {
    fog_error_pass(err, &serr);
    status = 1;
  }
  free(rgb);
  if (!status)
    printf("fogpipe view: wrote %s (%dx%d window, frame %d; %s, %s)\n", path, width, height,
           frame, gl_context_version(v->ctx), gl_context_renderer(v->ctx));
  return status;
}

/* Draws frames until the window closes, or the screenshot is taken. */
static int view_loop(view_state *v, volume_playback *playback, rung_selector *sel,
                     view_brush *brush, const scene_config *cfg, const view_options *opts,
                     fog_error *err) {
  GLFWwindow *window = gl_context_glfw_window(v->ctx);
  /* A key tapped between two polls still counts as pressed once: at a few frames a second
   * (software GL) a quick tap of B or [ fell between frames. */
  glfwSetInputMode(window, GLFW_STICKY_KEYS, GLFW_TRUE);
  free_camera fc = {.speed = 0.05 * fmax(cfg->terrain.size[0], cfg->terrain.size[1])};
  scene_config_camera(cfg, &fc.cam);
  double last_time = glfwGetTime();
  int target_w = 0, target_h = 0;
  double fps = 0.0;
  for (int frame = 1; !gl_context_should_close(v->ctx); frame++) {
    gl_context_poll_events(v->ctx);
    double now = glfwGetTime();
    if (now > last_time) fps = fps > 0 ? 0.9 * fps + 0.1 / (now - last_time) : 1 / (now - last_time);
    if (sel->on && rung_selector_update(sel, v, window, cfg, fps, err)) return 1;
    const free_camera_input input = free_camera_read(
        window, FREE_CAMERA_LOOK_MIDDLE | FREE_CAMERA_LOOK_RIGHT, true, true);
    free_camera_step(&fc, &input, now - last_time);
    if (glfwGetKey(window, GLFW_KEY_ESCAPE) == GLFW_PRESS) glfwSetWindowShouldClose(window, 1);
    last_time = now;
    /* With --screenshot the sequence advances one VDB frame per drawn frame (the same
     * image every run), else with the clock. */
    double clock =
        opts->screenshot ? playback->start_time + (frame - 1) / cfg->fog.vdb_fps : now;
    if (playback->sequence.count && sel->shown < 0 &&
        volume_playback_update(playback, window, clock, &v->fog, cfg, err))
      return 1;
    /* RBF fog from emitters moves with the clock (with --screenshot at 24 frames a second:
     * the same image every run) */
    const double fog_time = opts->screenshot ? (frame - 1) / 24.0 : now - playback->start_time;
    const scene_config *fog_cfg = brush->painted ? brush->painted : cfg;
    if (v->has_fog && sel->shown < 0 && render_fog_animated(fog_cfg) &&
        render_fog_set_time(&v->fog, fog_cfg, fog_time, err))
      return 1;
    /* the brush picks from the last frame's distances */
    if (frame > 1 && sel->shown < 0 &&
        view_brush_update(brush, v, window, cfg, &fc.cam, fog_time, err))
      return 1;
    int fb_w, fb_h;
    gl_context_framebuffer_size(v->ctx, &fb_w, &fb_h);
    if (fb_w < 1 || fb_h < 1) continue; /* minimised */
    int w = (int)fmax(1.0, floor(fb_w * opts->render_scale));
    int h = (int)fmax(1.0, floor(fb_h * opts->render_scale));
    if (w != target_w || h != target_h) {
      if (make_targets(v, w, h, err)) return 1;
      target_w = w, target_h = h;
    }
    scene_pass_run(v->scene, &fc.cam, &v->scene_target);
    const gl_target *shown = &v->scene_target;
    if (v->has_fog) {
      if (render_fog_draw(&v->fog, &fc.cam, &v->scene_target, &v->fog_target, err)) return 1;
      shown = &v->fog_target;
    }
    gl_presenter_draw(v->presenter, shown, fb_w, fb_h, GL_PRESENT_NEAREST);
    if (opts->screenshot && frame >= opts->frames)
      return view_screenshot(v, opts->screenshot, fb_w, fb_h, frame, err);
    gl_context_swap_buffers(v->ctx);
    if (gl_util_check("view frame", err)) return 1;
  }
  return 0;
}

int view_window_run(const scene_config *cfg, const char *title, const view_options *opts) {
  view_state v = {0};
  volume_playback playback = {0};
  fog_error err = {0};
  rung_selector sel = {.shown = -1};
  view_brush brush = {.config_path = title};
  if (opts->fit) { /* before the window: fit makes headless contexts of its own */
    fog_error ferr;
    if (fit_run(&(fit_desc){.input = cfg, .tolerance = opts->fit_tolerance,
                            .rays_per_side = FIT_RAYS_PER_SIDE, .sample_side = FIT_SAMPLE_SIDE,
                            .width = FIT_WIDTH, .height = FIT_HEIGHT,
                            .timed_frames = FIT_TIMED_FRAMES},
                &sel.fit, &ferr)) {
      fprintf(stderr, "fogpipe view: --fit: %s\n", ferr.message);
      return 1;
    }
    sel.on = true;
    if (opts->rung >= sel.fit.count) {
      fprintf(stderr, "fogpipe view: --rung %d: the fit has rungs 0..%d\n", opts->rung,
              sel.fit.count - 1);
      fit_result_destroy(&sel.fit);
      return 2;
    }
    printf("fogpipe view: fit %d rungs; the pick within %g: %s\n", sel.fit.count,
           opts->fit_tolerance, sel.fit.chosen < 0 ? "none" : sel.fit.rungs[sel.fit.chosen].name);
  }
  int width = opts->width > 0 ? opts->width : cfg->width;
  int height = opts->height > 0 ? opts->height : cfg->height;
  v.ctx = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_WINDOW, .width = width,
                                               .height = height, .title = title,
                                               .vsync = true},
                            &err);
  const int first = opts->rung >= 0 ? opts->rung : sel.fit.chosen;
  int status = !v.ctx || view_open(&v, &playback, cfg, opts, &err) ||
               (sel.on && first >= 0 && show_rung(&v, &sel, first, cfg, &err)) ||
               view_loop(&v, &playback, &sel, &brush, cfg, opts, &err);
  if (status) fprintf(stderr, "fogpipe view: %s\n", err.message);
  if (playback.sequence.count) vdb_sequence_destroy(&playback.sequence);
  view_destroy(&v);
  if (sel.on) fit_result_destroy(&sel.fit);
  free(brush.painted);
  return status;
}

int cmd_view(int argc, char **argv) {
  view_options opts = {.render_scale = 0.5, .frames = 1, .rung = -1};
  int size[2] = {0, 0};
  const cli_option options[] = {
      {.kind = CLI_NUMBER, .name = "--render-scale", .value = "F", .target = &opts.render_scale,
       .min = 0.05, .max = 4,
       .help = "render at F times the window size, shown scaled up\n"
               "(default 0.5: software GL is slow; 1 on a GPU)"},
      {.kind = CLI_SIZE, .name = "--size", .value = "WxH", .target = size,
       .help = "window size (default: [render] width and height)"},
      {.kind = CLI_FLAG, .name = "--play", .target = &opts.play,
       .help = "start playing the volume's sequence (with --screenshot: one\n"
               "VDB frame per drawn frame)"},
      {.kind = CLI_TEXT, .name = "--screenshot", .value = "FILE", .target = &opts.screenshot,
       .help = "save the window's last frame as an 8-bit PNG and exit"},
      {.kind = CLI_INT, .name = "--frames", .value = "N", .target = &opts.frames, .min = 1,
       .max = 1000000, .help = "frames to draw before the screenshot (default 1)"},
      {.kind = CLI_NUMBER, .name = "--fit", .value = "T", .target = &opts.fit_tolerance,
       .min = 1e-12, .max = 1.0, .given = &opts.fit,
       .help = "first run `fogpipe fit` on the scene at tolerance T, then show\n"
               "its pick: [ and ] step through every rung of the model ladder,\n"
               "0 returns to the config's own fog; the window title shows the\n"
               "rung, its measured error against the scene's fog and its time"},
      {.kind = CLI_INT, .name = "--rung", .value = "N", .target = &opts.rung, .min = 0,
       .max = FIT_MAX_RUNGS - 1,
       .help = "with --fit: start on rung N (its row in fit's table, from 0)"},
  };
  const cli_spec spec = {
      .command = "view",
      .usage = "CONFIG [--size WxH] [--render-scale F] [--play]\n"
               "                           [--screenshot FILE.png --frames N] [--fit T [--rung N]]",
      .about = "Opens the scene config in a window with a free camera (needs a display; for\n"
               "headless images use `fogpipe render`).\n"
               "  W A S D  move     Q E  down / up     Shift  4x faster\n"
               "  right or middle drag, arrow keys  look around     Esc  quit\n"
               "  P  play / pause the VDB sequence of [fog] model = volume (from vdb_frame, looping\n"
               "     at vdb_fps, blended between frames)\n"
               "  B  the Gaussian brush of [fog] model = rbf (Fogshop's; the title shows it):\n"
               "     left drag paints Gaussians on the surface, Shift + left drag erases them,\n"
               "     C picks up the group under the cursor and V puts a copy of it down there,\n"
               "     - and = size, , and . density, Ctrl+S writes CONFIG.painted.ini",
      .operand = "CONFIG", .min_operands = 1, .max_operands = 1,
      .options = options, .option_count = sizeof options / sizeof options[0]};
  const char *config_path = NULL;
  int operands = 0, parsed = cli_parse(&spec, argc, argv, &config_path, &operands);
  if (parsed) return parsed == CLI_HELP ? 0 : parsed;
  opts.width = size[0], opts.height = size[1];
  if (opts.rung >= 0 && !opts.fit) return cli_usage_error("view", "--rung needs --fit T");
  scene_config cfg;
  fog_error cfg_err;
  if (scene_config_load(config_path, &cfg, &cfg_err)) {
    fprintf(stderr, "fogpipe view: %s\n", cfg_err.message);
    return 1;
  }
  return view_window_run(&cfg, config_path, &opts);
}
