/* The one window program of `demo` and `view` (app/window_program.h): the window, the
 * panel's shell, the camera, the screenshot and the frame loop; the fog sources draw. */
#include "app/window_program.h"
#include "app/window_keys.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <GLFW/glfw3.h>

#include "app/sun_hue.h"
#include "render/gl_present.h"
#include "render/gl_util.h"
#include "sim/sim.h"

/* The window's back buffer as an 8-bit PNG, the panel included. */
static int save_screenshot(const window_options *o, const window_frame *f, fog_error *err) {
  float *rgb = malloc((size_t)f->fb_w * f->fb_h * 3 * sizeof(float));
  if (!rgb) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the screenshot");
  int status = gl_read_window(f->fb_w, f->fb_h, rgb, err);
  fog_error serr;
  if (!status && image_write_png(o->screenshot, f->fb_w, f->fb_h, 3, rgb, &serr)) {
    fog_error_pass(err, &serr);
    status = 1;
  }
  free(rgb);
  if (!status)
    printf("fogpipe %s: wrote %s (%dx%d window, frame %d; %s, %s)\n", o->command,
           o->screenshot, f->fb_w, f->fb_h, f->index + 1, gl_context_version(f->gl),
           gl_context_renderer(f->gl));
  return status;
}

bool window_panel_sunlight(panel *ui, window_sunlight *sun) {
  if (!panel_header(ui, "sunlight in the fog", true)) return false;
  bool changed = false;
  /* down to a sun just under the horizon (dusk: the fog's self-shadow turns opaque) */
  changed |= panel_slider_float(ui, "sun azimuth", &sun->azimuth, -180.0f, 180.0f, "%.0f deg",
                                false);
  changed |= panel_slider_float(ui, "sun elevation", &sun->elevation, -5.0f, 90.0f,
                                "%.1f deg", false);
  /* sigma_s = albedo K, Henyey-Greenstein g (docs/light.md) */
  changed |= panel_slider_float(ui, "albedo", &sun->albedo, 0.0f, 1.0f, "%.2f", false);
  changed |= panel_slider_float(ui, "phase g", &sun->phase_g, -0.95f, 0.95f, "%.2f", false);
  changed |= panel_color3(ui, "sun colour", sun->hue);
  changed |= panel_slider_float(ui, "sun strength", &sun->strength, 0.0f, 10.0f, "%.2f", false);
  /* T_s: the fog's shadow on itself and on the ground (albedo > 0) */
  changed |= panel_checkbox(ui, "fog self-shadow", &sun->self_shadow);
  panel_same_line(ui);
  changed |= panel_checkbox(ui, "light shafts", &sun->shafts);
  return changed;
}

bool window_panel_profile(panel *ui, window_profile *profile, bool kind_fixed) {
  bool changed = false;
  /* fog_profile_kind order; the B-spline profile only when the config has one */
  static const char *const kinds[] = {"slab", "exponential", "B-spline (config)"};
  if (!kind_fixed)
    changed |= panel_combo(ui, "profile", &profile->kind, kinds, profile->has_bspline ? 3 : 2);
  if (profile->kind == FOG_PROFILE_EXPONENTIAL) {
    changed |= panel_slider_float(ui, "fog height", &profile->fog_height, -50.0f, 200.0f,
                                  "%.1f", false);
    changed |= panel_slider_float(ui, "scale height", &profile->scale_height, 1.0f, 200.0f,
                                  "%.1f", true);
  }
  return changed;
}

bool window_panel_wavelets(panel *ui, window_wavelets *w) {
  bool changed = false;
  static const char *const bases[] = {"Haar (degree 0)", "linear (CDF 5/3)",
                                      "quadratic (bior3.3)"};
  changed |= panel_combo(ui, "basis", &w->degree, bases, 3);
  changed |= panel_slider_int(ui, "levels J", &w->levels, 0, FOG_MAX_LEVELS);
  changed |= panel_slider_float(ui, "mu", &w->mu, 0.0f, 1.0f, "%.3f", false);
  static const char *const methods[] = {"sum of details (paper)", "switch A_l (ours)"};
  changed |= panel_combo(ui, "LOD", &w->lod_method, methods, 2);
  return changed;
}

void window_sunlight_set_colour(window_sunlight *sun, const double colour[3]) {
  sun_hue_split(colour, sun->hue, &sun->strength);
}

void window_sunlight_colour(const window_sunlight *sun, double colour[3]) {
  sun_hue_join(sun->hue, sun->strength, colour);
}

/* The panel's window: the frame rate and the frame times the loop measures, then the
 * source's sections. */
typedef struct window_shell {
  panel *ui;
  bool shown, tab_was_down;
  float frame_ms[120];
  int next, filled; /* the ring's next slot; how many it holds */
} window_shell;

static void shell_panel(window_shell *s, window_source *src, const window_frame *f) {
  if (f->index > 0) {
    s->frame_ms[s->next] = (float)(1e3 * f->dt);
    s->next = (s->next + 1) % 120;
    if (s->filled < 120) s->filled++;
  }
  if (!s->shown) return;
  if (panel_window_begin(s->ui, "fogpipe", 10, 10, 330)) {
    float ordered[120], top = 34.0f; /* at least the 30 fps line's scale */
    for (int i = 0; i < s->filled; i++) { /* oldest first */
      ordered[i] = s->frame_ms[(s->next - s->filled + i + 120) % 120];
      if (ordered[i] > top) top = ordered[i];
    }
    panel_text(s->ui, "%.1f fps (Tab hides the panel)", f->fps);
    panel_plot(s->ui, "frame ms", ordered, s->filled, 1.1f * top);
    src->panel(src->self, s->ui, f);
  }
  panel_window_end(s->ui);
}

/* Frames until the window closes, or the screenshot is taken. */
static int window_loop(gl_context *gl, window_shell *shell, window_source *src,
                       const scene_config *cfg, const window_options *o, fog_error *err) {
  GLFWwindow *window = gl_context_glfw_window(gl);
  /* A key tapped or a button clicked between two polls still counts as pressed once: at a
   * few frames a second (software GL) a quick tap fell between frames, and the lamp tool
   * missed clicks (0 of 2 placed at 16 fps). */
  glfwSetInputMode(window, GLFW_STICKY_KEYS, GLFW_TRUE);
  glfwSetInputMode(window, GLFW_STICKY_MOUSE_BUTTONS, GLFW_TRUE);
  free_camera fc = {.speed = src->camera_speed};
  scene_config_camera(cfg, &fc.cam);
  window_frame f = {.window = window, .gl = gl, .fc = &fc};
  double last_time = glfwGetTime();
  /* index counts the frames drawn: waits while minimised are none of --frames, of
   * --screenshot's frame or of the scene's clock (they counted, and a sequence jumped) */
  for (int index = 0; !gl_context_should_close(gl);) {
    gl_context_poll_events(gl);
    const double now = glfwGetTime(), dt = now - last_time;
    /* the first frame's dt is the set-up's tail, not a frame */
    if (index > 0 && now > last_time)
      f.fps = f.fps > 0 ? 0.9 * f.fps + 0.1 / (now - last_time) : 1 / (now - last_time);
    last_time = now;
    gl_context_framebuffer_size(gl, &f.fb_w, &f.fb_h);
    if (f.fb_w < 1 || f.fb_h < 1) { /* minimised: wait for events, not spin a core */
      glfwWaitEventsTimeout(0.1);
      continue;
    }
    f.index = index, f.now = now, f.dt = dt;

    panel_begin_frame(shell->ui);
    shell_panel(shell, src, &f);
    f.keyboard = !panel_wants_keyboard(shell->ui);
    f.mouse = !panel_wants_mouse(shell->ui);
    /* every key read once, for every reader of this frame (app/window_keys.h); read every
     * frame, a press latched while the panel held the keyboard is let go */
    window_keys_read(window);
    const bool tab = window_key_down(GLFW_KEY_TAB);
    if (f.keyboard && tab && !shell->tab_was_down) shell->shown = !shell->shown;
    shell->tab_was_down = tab;
    const bool escape = window_key_down(GLFW_KEY_ESCAPE);
    if (f.keyboard && escape) glfwSetWindowShouldClose(window, 1);
    const free_camera_input input =
        free_camera_read(window, src->look_buttons_now ? src->look_buttons_now(src->self)
                                                       : src->look_buttons,
                         f.keyboard, f.mouse);
    /* real time up to a second a frame (a few frames a second on software GL), no jump
     * across a longer stall */
    free_camera_step(&fc, &input, fmin(dt, 1.0));

    if (src->input(src->self, &f, err) || src->draw(src->self, &f, err)) return 1;
    /* a click latched by the sticky buttons and not read this frame (no tool took it, or
     * the panel held the mouse) is let go, not acted on frames later */
    for (int b = GLFW_MOUSE_BUTTON_1; b <= GLFW_MOUSE_BUTTON_3; b++) glfwGetMouseButton(window, b);
    panel_end_frame(shell->ui);
    if (o->screenshot && index + 1 >= o->frames) return save_screenshot(o, &f, err);
    gl_context_swap_buffers(gl);
    if (gl_util_check("window frame", err)) return 1;
    if (o->quit_after_frames && index + 1 >= o->frames) return 0;
    index++;
  }
  return 0;
}

int window_program_run(scene_config *cfg, const window_options *o) {
  fog_error err = {0};
  fit_result fit_made, *fit = NULL;
  if (o->fit && o->simulate) { /* --fit steps through the fog as held's rungs */
    fprintf(stderr, "fogpipe %s: --fit shows the fog as held, not a simulation\n", o->command);
    return 2;
  }
  if (o->fit) { /* before the window: fit makes headless contexts of its own */
    if (fit_run(&(fit_desc){.input = cfg, .tolerance = o->fit_tolerance,
                            .rays_per_side = FIT_RAYS_PER_SIDE, .sample_side = FIT_SAMPLE_SIDE,
                            .width = FIT_WIDTH, .height = FIT_HEIGHT,
                            .timed_frames = FIT_TIMED_FRAMES},
                &fit_made, &err)) {
      fprintf(stderr, "fogpipe %s: --fit: %s: %s\n", o->command, cfg->path, err.message);
      return 1;
    }
    fit = &fit_made;
    if (o->rung >= fit->count) {
      fprintf(stderr, "fogpipe %s: --rung %d: the fit has rungs 0..%d\n", o->command, o->rung,
              fit->count - 1);
      fit_result_destroy(fit);
      return 2;
    }
    printf("fogpipe %s: fit %d rungs; the pick within %g: %s\n", o->command, fit->count,
           o->fit_tolerance, fit->chosen < 0 ? "none" : fit->rungs[fit->chosen].name);
  }
  gl_context *gl = gl_context_create(
      &(gl_context_desc){.kind = GL_CONTEXT_WINDOW, .width = o->width, .height = o->height,
                         .title = o->config_path, .vsync = true},
      &err);
  window_source src = {0};
  window_shell shell = {.shown = !o->hide_panel};
  int status = 1;
  if (!gl) {
    if (fit) fit_result_destroy(fit);
    if (o->window_failure) {
      *o->window_failure = err;
      return WINDOW_PROGRAM_NO_WINDOW;
    }
  } else if (o->simulate ? window_pipeline_source(&src, gl, cfg, o, &err)
                         : window_session_source(&src, gl, cfg, o, fit, &err)) {
  } else if (!(shell.ui = panel_create(gl_context_glfw_window(gl)))) {
    fog_fail(&err, FOG_ERR_GRAPHICS, "cannot start Dear ImGui on this window");
  } else {
    if (o->note) printf("fogpipe %s: %s\n", o->command, o->note);
    fflush(stdout);
    status = window_loop(gl, &shell, &src, cfg, o, &err);
  }
  if (status) fprintf(stderr, "fogpipe %s: %s\n", o->command, err.message);
  panel_destroy(shell.ui);
  if (src.destroy) src.destroy(src.self);
  if (gl) gl_context_destroy(gl);
  return status;
}
