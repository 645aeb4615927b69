/* The simulated fog source of the window program (app/window_program.h): the config's
 * simulation transformed and rendered every frame by the live pipeline (app/pipeline.h),
 * with the demo's panel (timings, the model menu, simulation, fog, sunlight, wavelets,
 * lamps, brush), its keys (Space pauses, N steps, R resets), fog painting and the lamp
 * tool. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GLFW/glfw3.h>

#include "app/lamp_tool.h"
#include "app/window_keys.h"
#include "app/live_rung.h"
#include "app/pipeline.h"
#include "app/sun_hue.h"
#include "app/window_program.h"
#include "render/fog_field.h"

/* ---- the panel ---- */

typedef struct demo_ui {
  float brush_radius;   /* world units */
  float brush_range[2]; /* the radius slider's: a quarter cell to 50 cells */
  float brush_strength; /* density per second at the stroke's centre line */
  float density_range[2]; /* the density slider's: the scene's density / 100 .. x 100 */
  float render_scale;
  bool has_bspline_profile; /* the pipeline's fog has one (a VDB's frames bring theirs) */
  lamp_tool lamps;     /* the mouse places, drags and removes lamps (app/lamp_tool.h) */
  bool lamps_animated; /* the config's lamps follow their paths: the tool is off */
  float sun_hue[3];    /* the sun's last hue, kept while its strength is 0 (app/sun_hue.h) */
} demo_ui;

/* The pipeline's stage timings (the shell shows the frame rate and its plot). */
static void panel_timings(panel *ui, pipeline *pipe, const pipeline_timings *med) {
  if (!panel_header(ui, "timings (median ms)", true)) return;
  panel_text(ui, "step %ld", pipeline_step_index(pipe));
  panel_text(ui, "sim %6.2f   transform %6.2f", med->sim, med->transform);
  panel_text(ui, "upload %6.2f   render %6.2f", med->upload, med->render);
  panel_text(ui, "frame %6.2f   sun shadow %6.2f", med->frame, med->sun_shadow);
}

/* The ladder live: a cheaper model fitted to the simulated fog as it moves, drawn in its
 * place, with its error against it (app/live_rung.h). */
static bool panel_model(panel *ui, pipeline *pipe, const pipeline_timings *med,
                        pipeline_params *params) {
  if (!panel_header(ui, "model", true)) return false;
  bool changed = false;
  /* "##rung": the header above is "model" too, and one ImGui ID for both kept the combo
   * from ever opening with the mouse */
  changed |= panel_combo(ui, "model##rung", &params->live_rung, live_rung_names,
                         LIVE_RUNG_COUNT);
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
  if (!pipeline_simulates(pipe)) { /* a VDB or baked sequence plays: no forces */
    panel_text(ui, "played frames: nothing simulated");
    return changed;
  }
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
  changed |= panel_slider_float(ui, "density", &params->density, d->density_range[0],
                                d->density_range[1], "%.4g", true);
  changed |= panel_color3(ui, "colour", params->fog_colour);
  window_profile profile = {.kind = params->profile_kind, .fog_height = params->fog_height,
                            .scale_height = params->scale_height,
                            .has_bspline = d->has_bspline_profile};
  if (window_panel_profile(ui, &profile, false)) {
    params->profile_kind = profile.kind;
    params->fog_height = profile.fog_height;
    params->scale_height = profile.scale_height;
    changed = true;
  }
  return changed;
}

/* The sun through the window program's section (pipeline_params hold it as the fog sees
 * it: radiance = SCENE_SUN_IRRADIANCE_PER_COLOUR x [light] sun_colour; the pipeline relights
 * the surfaces and the fog). */
static bool panel_sunlight(panel *ui, pipeline_params *params, float sun_hue[3]) {
  window_sunlight sun = {.azimuth = params->sun_azimuth, .elevation = params->sun_elevation,
                         .albedo = (float)params->sun.albedo,
                         .phase_g = (float)params->sun.phase_g,
                         .hue = {sun_hue[0], sun_hue[1], sun_hue[2]},
                         .self_shadow = params->fog_self_shadow, .shafts = params->shafts};
  double colour[3];
  for (int c = 0; c < 3; c++) colour[c] = params->sun.radiance[c] / SCENE_SUN_IRRADIANCE_PER_COLOUR;
  window_sunlight_set_colour(&sun, colour);
  const bool changed = window_panel_sunlight(ui, &sun);
  for (int c = 0; c < 3; c++) sun_hue[c] = sun.hue[c];
  if (!changed) return false;
  params->sun_azimuth = sun.azimuth;
  params->sun_elevation = sun.elevation;
  params->sun.albedo = sun.albedo;
  params->sun.phase_g = sun.phase_g;
  window_sunlight_colour(&sun, colour);
  for (int c = 0; c < 3; c++) params->sun.radiance[c] = SCENE_SUN_IRRADIANCE_PER_COLOUR * colour[c];
  params->fog_self_shadow = sun.self_shadow;
  params->shafts = sun.shafts;
  return true;
}

/* The transform's basis and levels, the LOD and the fog pass's resolution. */
static bool panel_wavelets(panel *ui, pipeline_params *params) {
  if (!panel_header(ui, "wavelets", true)) return false;
  bool changed = false;
  window_wavelets w = {.degree = params->degree, .levels = params->levels, .mu = params->mu,
                       .lod_method = params->lod_method};
  if (window_panel_wavelets(ui, &w)) {
    params->degree = w.degree, params->levels = w.levels, params->mu = w.mu;
    params->lod_method = w.lod_method;
    changed = true;
  }
  static const char *const divisors[] = {"full", "1/2", "1/4"};
  int divisor_index = params->fog_resolution_divisor >= 4 ? 2 : params->fog_resolution_divisor >= 2;
  if (panel_combo(ui, "fog resolution", &divisor_index, divisors, 3)) {
    params->fog_resolution_divisor = 1 << divisor_index;
    changed = true;
  }
  return changed;
}

/* The density brush. */
static void panel_brush(panel *ui, pipeline *pipe, demo_ui *d) {
  if (!panel_header(ui, "brush", false)) return;
  if (!pipeline_simulates(pipe)) { /* strokes paint into the simulation */
    panel_text(ui, "played frames: nothing to paint");
  } else {
    panel_slider_float(ui, "radius", &d->brush_radius, d->brush_range[0], d->brush_range[1],
                       "%.3g", true);
    panel_slider_float(ui, "strength", &d->brush_strength, 0.1f, 20.0f, "%.1f", true);
    panel_text(ui, "left drag: paint   right / shift: erase");
  }
  panel_slider_float(ui, "render scale", &d->render_scale, 0.25f, 1.0f, "%.2f", false);
}

static void panel_contents(panel *ui, pipeline *pipe, demo_ui *d) {
  pipeline_params params = pipeline_get_params(pipe);
  pipeline_timings last;
  pipeline_timings med = pipeline_get_timings(pipe, &last);
  panel_timings(ui, pipe, &med);
  bool changed = panel_model(ui, pipe, &med, &params);
  changed |= panel_simulation(ui, pipe, &params);
  changed |= panel_fog(ui, &params, d);
  changed |= panel_sunlight(ui, &params, d->sun_hue);
  changed |= panel_wavelets(ui, &params);
  if (pipeline_lamps_dropped(pipe)) panel_text(ui, "%s", LAMP_TOOL_DROPPED_NOTE);
  lamp_tool_panel(ui, &d->lamps, params.lamps.count, d->lamps_animated, NULL);
  panel_brush(ui, pipe, d);
  if (changed) pipeline_set_params(pipe, &params);
}

/* ---- the window's input ---- */

/* What the window's input remembers between frames. */
typedef struct demo_input {
  bool painting;
  double last_paint[3];
  bool space_down, n_down, r_down;
} demo_input;

/* Space pauses, N steps, R restarts (on the key's press, while the panel does not hold the
 * keyboard; read every frame, so a press GLFW latched meanwhile is let go). */
static void demo_keys(GLFWwindow *window, bool keyboard, pipeline *pipe, demo_input *in) {
  const bool space = window_key_down(GLFW_KEY_SPACE);
  const bool n = window_key_down(GLFW_KEY_N);
  const bool r = window_key_down(GLFW_KEY_R);
  if (!keyboard) {
    in->space_down = space, in->n_down = n, in->r_down = r;
    return;
  }
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
  bool shift = window_key_down(GLFW_KEY_LEFT_SHIFT) ||
               window_key_down(GLFW_KEY_RIGHT_SHIFT);
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

/* The lamp tool (the panel's "lamps", app/lamp_tool.h) on the pipeline's lamps, which
 * light the fog and the surfaces. */
static void demo_lamps(GLFWwindow *window, pipeline *pipe, const free_camera *fc, demo_ui *d,
                       bool mouse) {
  const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  double hit[3];
  const bool picked = mouse && (left || right) && surface_under_cursor(window, pipe, fc, hit);
  pipeline_params params = pipeline_get_params(pipe);
  const lamp_edit edit = lamp_tool_update(&d->lamps, left, right, picked ? hit : NULL,
                                          &params.lamps);
  if (edit.kind == LAMP_EDIT_NONE) return;
  lamp_edit_apply(&edit, &params.lamps);
  pipeline_set_params(pipe, &params);
}

/* ---- the source ---- */

typedef struct pipeline_source {
  pipeline *pipe;
  demo_ui ui;
  demo_input in;
} pipeline_source;

static void source_panel(void *self, panel *ui, const window_frame *f) {
  (void)f;
  pipeline_source *s = self;
  panel_contents(ui, s->pipe, &s->ui);
}

static int source_input(void *self, const window_frame *f, fog_error *err) {
  (void)err;
  pipeline_source *s = self;
  demo_keys(f->window, f->keyboard, s->pipe, &s->in);
  /* the tools pick from the last frame's distances */
  if (!s->ui.lamps.placing) lamp_tool_idle(&s->ui.lamps);
  if (f->index > 0 && s->ui.lamps.placing)
    demo_lamps(f->window, s->pipe, f->fc, &s->ui, f->mouse);
  else if (f->index > 0)
    demo_paint(f->window, s->pipe, f->fc, &s->ui, f->mouse, fmin(f->dt, 0.25), &s->in);
  return 0;
}

static int source_draw(void *self, const window_frame *f, fog_error *err) {
  pipeline_source *s = self;
  int render_w, render_h;
  const int want_w = (int)fmax(16, f->fb_w * s->ui.render_scale);
  const int want_h = (int)fmax(16, f->fb_h * s->ui.render_scale);
  pipeline_size(s->pipe, &render_w, &render_h);
  if ((want_w != render_w || want_h != render_h) &&
      pipeline_resize(s->pipe, want_w, want_h, err))
    return 1;
  return pipeline_frame(s->pipe, &f->fc->cam, false, err) ||
         pipeline_present(s->pipe, f->fb_w, f->fb_h, err);
}

static void source_destroy(void *self) {
  pipeline_source *s = self;
  pipeline_destroy(s->pipe);
  free(s);
}

int window_pipeline_source(window_source *src, gl_context *gl, scene_config *cfg,
                           const window_options *opts, fog_error *err) {
  double scale = opts->render_scale;
  int fog_divisor = 1; /* fog resolution divisor; 2 with the automatic scale on software GL */
  if (scale == 0.0) {
    /* The fog pass costs per pixel: a software renderer (Mesa llvmpipe/softpipe) renders
     * at half the window's resolution per axis with the fog at half of that (upsampled
     * guided by the surface distance), a GPU at full resolution. */
    bool software = gl_context_is_software(gl);
    scale = software ? 0.5 : 1.0;
    fog_divisor = software ? 2 : 1;
    /* and lets the terrain's LOD show twice its pixel error (unless the config asks for
     * the full mesh): turning the camera then costs ~15 % of a frame, not ~30 %; and
     * integrates the lamps with fewer pieces and a shorter walk to each: half the lamps'
     * cost (night_lamps, 9 lights at 960x540: 1.36 s -> 0.71 s a frame, measured before
     * fog_lamps.glsl's shadowed pieces took their nodes once) */
    if (software) scene_config_live_software(cfg);
  }
  pipeline_source *s = calloc(1, sizeof *s);
  if (!s) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the window's fog");
  const double scene_size = fmax(cfg->terrain.size[0], cfg->terrain.size[1]);
  s->ui = (demo_ui){.brush_strength = 3.0f, .render_scale = (float)scale,
                    .lamps = lamp_tool_for_scene(scene_size),
                    .lamps_animated = scene_config_lamps_animated(cfg),
                    .sun_hue = {1.0f, 1.0f, 1.0f}};
  const double sun_colour[3] = {cfg->light.sun_colour[0], cfg->light.sun_colour[1],
                                cfg->light.sun_colour[2]};
  float strength;
  sun_hue_split(sun_colour, s->ui.sun_hue, &strength);
  int fb_w = 0, fb_h = 0;
  gl_context_framebuffer_size(gl, &fb_w, &fb_h);
  s->pipe = pipeline_create(&(pipeline_desc){.config = cfg,
                                             .width = (int)(fb_w * scale),
                                             .height = (int)(fb_h * scale),
                                             .frame_seconds = 1.0 / 30.0, .live = true},
                            err);
  if (!s->pipe) {
    free(s);
    return 1;
  }
  /* Sized to the scene the pipeline made (a VDB's frames bring their own box, profile and
   * density): the brush 7.5 cells wide (30 units on the default 4-unit cells), the density
   * slider around the scene's, the profile menu with the frames' B-spline. */
  int cells_x, cells_z;
  double origin_x, origin_z, cell;
  pipeline_fog_extent(s->pipe, &cells_x, &cells_z, &origin_x, &origin_z, &cell);
  s->ui.brush_radius = (float)(7.5 * cell);
  s->ui.brush_range[0] = (float)(0.25 * cell), s->ui.brush_range[1] = (float)(50.0 * cell);
  pipeline_params initial = pipeline_get_params(s->pipe);
  const float density = initial.density > 0 ? initial.density : 0.01f;
  s->ui.density_range[0] = density / 100.0f, s->ui.density_range[1] = density * 100.0f;
  s->ui.has_bspline_profile = pipeline_has_bspline_profile(s->pipe);
  initial.fog_resolution_divisor = fog_divisor;
  initial.live_rung = opts->live_rung;
  initial.paused = !opts->play;
  pipeline_set_params(s->pipe, &initial);
  *src = (window_source){.self = s, .look_buttons = FREE_CAMERA_LOOK_MIDDLE,
                         /* 80 units a second over the default 1200-unit terrain */
                         .camera_speed = scene_size / 15.0, .panel = source_panel,
                         .input = source_input,
                         .draw = source_draw, .destroy = source_destroy};
  return 0;
}
