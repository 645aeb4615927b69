/* The fog source "as held" of the window program (app/window_program.h): the scene config's
 * fog as the file holds it, in a render session's fog (app/render_fog.h), no simulation.
 * A volume's VDB sequence plays with P (or from the start with --play); RBF emitters' puffs
 * and Perlin octaves drift, lamps on a path move and flicker with the clock; the panel's
 * lamp tool places, drags and removes lamps (app/lamp_tool.h) in the window's copy of the
 * config; B turns on the Gaussian brush on an RBF scene (app/rbf_brush.h: paint, erase,
 * copy); with --fit the panel's rung menu (or [ and ])
 * steps through the model ladder. With --screenshot the clock is the frame count (a
 * sequence advances one VDB frame per drawn frame, drifting fog 1/24 s): the same fog every
 * run (the panel's timings vary: --hide-panel for an image that repeats). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GLFW/glfw3.h>

#include "app/clock.h"
#include "app/window_keys.h"
#include "app/lamp_tool.h"
#include "app/rbf_brush.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "app/vdb_source.h"
#include "app/sun_hue.h"
#include "app/window_program.h"
#include "render/gl_present.h"
#include "render/render.h"
#include "sim/sim.h"

/* model = volume: its VDB sequence, played from the config's frame. */
typedef struct volume_playback {
  vdb_sequence sequence;
  double shown;          /* frame index position on screen (vdb_sequence_position) */
  bool playing;
  bool toggle;           /* the panel's checkbox: toggle at the next update, as P does */
  double start_time;     /* when position `start` was on screen */
  double start;
  bool p_was_down;
} volume_playback;

typedef struct view_state {
  const char *command; /* messages begin "fogpipe COMMAND: " */
  scene_geometry geo;
  bool geo_made;
  scene_pass *scene;
  render_fog fog;
  bool has_fog;
  gl_target scene_target, fog_target;
  /* the camera scene_target was drawn from: a pick reads its distances along its rays */
  camera drawn_camera;
  bool drawn;
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
static int volume_playback_update(volume_playback *pb, GLFWwindow *window, bool keyboard,
                                  bool active, double now, render_fog *fog,
                                  const scene_config *cfg, fog_error *err) {
  /* read every frame, whatever is shown: a press latched meanwhile is let go */
  const bool p_down = window_key_down(GLFW_KEY_P);
  const bool pressed = keyboard && p_down && !pb->p_was_down;
  pb->p_was_down = p_down;
  if (!active) return 0; /* a rung is shown: the sequence waits */
  if (pressed || pb->toggle) {
    pb->toggle = false;
    pb->playing = !pb->playing;
    pb->start_time = now;
    pb->start = pb->shown;
  }
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
  const char *command;
  bool on;
  rbf_brush brush;
  scene_config *painted;   /* the session's own config, whose Gaussians the brush edits */
  bool started;            /* the brush's radius and density are set (at the first B) */
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
  /* the distance is the last frame's, so its ray is too: the camera has moved since (0.24
   * rad a frame turning at 5 fps: 120 units off at 500) */
  double origin[3], dir[3];
  camera_ray(v->drawn ? &v->drawn_camera : cam, px, py, w, h, origin, dir);
  for (int a = 0; a < 3; a++) hit[a] = origin[a] + distance * dir[a];
  return true;
}


static void brush_title(const view_brush *b, GLFWwindow *window) {
  char title[320];
  if (b->on)
    snprintf(title, sizeof title,
             "fogpipe %s: brush r %.3g c %.3g, %d Gaussians (drag paints, Shift erases, C/V "
             "copy, -/= size, ,/. density, Ctrl+S saves, B off)",
             b->command, b->brush.radius, b->brush.density, b->painted->fog.rbf_count);
  else
    snprintf(title, sizeof title, "fogpipe %s: %s", b->command, b->config_path);
  glfwSetWindowTitle(window, title);
}

/* Ctrl+S: the painted scene as NAME.painted.ini beside the config. */
static void brush_save(const view_brush *b) {
  char path[SCENE_CONFIG_PATH_MAX + 16];
  size_t n = strlen(b->config_path);
  int stem = n > 4 && !strcmp(b->config_path + n - 4, ".ini") ? (int)(n - 4) : (int)n;
  if (snprintf(path, sizeof path, "%.*s.painted.ini", stem, b->config_path) >=
      (int)sizeof path) { /* cut short, it would name another file */
    fprintf(stderr, "fogpipe %s: the brush: %s: the path is too long for its .painted.ini "
            "(more than %zu characters)\n", b->command, b->config_path, sizeof path - 1);
    return;
  }
  fog_error werr;
  if (scene_config_write(b->painted, path, &werr))
    fprintf(stderr, "fogpipe %s: the brush: %s\n", b->command, werr.message);
  else
    printf("fogpipe %s: wrote %s (%d Gaussians)\n", b->command, path,
           b->painted->fog.rbf_count);
}

/* B, the mouse and the brush's keys for one frame (acting only when `active` and the
 * panel holds neither); the fog takes the changed Gaussians. */
static int view_brush_update(view_brush *b, view_state *v, const window_frame *frame,
                             bool active, const scene_config *cfg, double time,
                             fog_error *err) {
  static const int keys[BRUSH_KEYS] = {GLFW_KEY_B,     GLFW_KEY_C,     GLFW_KEY_V,
                                       GLFW_KEY_MINUS, GLFW_KEY_EQUAL, GLFW_KEY_COMMA,
                                       GLFW_KEY_PERIOD, GLFW_KEY_S};
  GLFWwindow *window = frame->window;
  const bool keyboard = active && frame->keyboard, mouse = active && frame->mouse;
  bool pressed[BRUSH_KEYS];
  /* Every key is read every frame: a press GLFW latched (sticky keys) while the panel held
   * the keyboard is let go, not acted on later. */
  for (int k = 0; k < BRUSH_KEYS; k++) {
    const bool down = window_key_down(keys[k]);
    pressed[k] = keyboard && down && !b->key_was_down[k];
    b->key_was_down[k] = down;
  }
  if (pressed[BRUSH_KEY_B]) {
    if (cfg->fog.model != FOG_MODEL_RBF || !v->has_fog) {
      printf("fogpipe %s: the brush paints Gaussians: it needs [fog] model = rbf\n",
             b->command);
      return 0;
    }
    if (!b->started) {
      b->started = true;
      b->brush = rbf_brush_for(cfg->fog.rbfs, cfg->fog.rbf_count,
                               fmax(cfg->terrain.size[0], cfg->terrain.size[1]), 0.02);
    }
    b->on = !b->on;
    brush_title(b, window);
  }
  if (!b->on || !mouse) {
    b->stroke = false; /* a stroke ends where the mouse leaves the scene */
    if (!b->on) return 0;
  }
  bool ctrl = window_key_down(GLFW_KEY_LEFT_CONTROL) ||
              window_key_down(GLFW_KEY_RIGHT_CONTROL);
  bool shift = window_key_down(GLFW_KEY_LEFT_SHIFT) ||
               window_key_down(GLFW_KEY_RIGHT_SHIFT);
  rbf_brush *brush = &b->brush;
  bool retitle = false;
  if (pressed[BRUSH_KEY_SMALLER]) brush->radius /= 1.25, retitle = true;
  if (pressed[BRUSH_KEY_LARGER]) brush->radius *= 1.25, retitle = true;
  if (pressed[BRUSH_KEY_THINNER]) brush->density /= 1.25, retitle = true;
  if (pressed[BRUSH_KEY_DENSER]) brush->density *= 1.25, retitle = true;
  brush->spacing = brush->lift = 0.5 * brush->radius;
  if (pressed[BRUSH_KEY_SAVE] && ctrl) brush_save(b);
  scene_fog_config *f = &b->painted->fog;
  rbf_bank bank = {.rbfs = f->rbfs, .count = f->rbf_count, .capacity = SCENE_CONFIG_MAX_RBFS};
  int changed = 0;
  double hit[3];
  const bool picked = mouse && view_pick(v, window, &frame->fc->cam, hit);
  if (pressed[BRUSH_KEY_C] && picked) {
    b->have_group = true;
    memcpy(b->group, hit, sizeof hit);
  }
  if (pressed[BRUSH_KEY_V] && picked && b->have_group)
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
  int wanted; /* the panel's menu */
  bool bracket_was_down[2];
  bool zero_was_down;
} rung_selector;

/* A rung's time in fit as said: "1.25 ms", or not timed where the renderer refused it with
 * the scene's lamps (its ms is NaN: "nan ms"). */
typedef struct rung_time_text {
  char text[40];
} rung_time_text;
static rung_time_text rung_time(const fit_rung *r) {
  rung_time_text t;
  if (isnan(r->ms))
    snprintf(t.text, sizeof t.text, "not timed (refused with the lamps)");
  else
    snprintf(t.text, sizeof t.text, "%.2f ms", r->ms);
  return t;
}

/* What the panel's light edits, from one config to another: the sun, the fog's ambient
 * colour and the lamps (the lamp tool's). */
static void copy_light(scene_config *to, const scene_config *from) {
  to->light = from->light;
  memcpy(to->lamps, from->lamps, sizeof to->lamps);
  to->lamp_count = from->lamp_count;
  to->lamp_method = from->lamp_method;
  if (to->fog.model != FOG_MODEL_RBF && to->lamp_method.integral == FOG_LAMP_FOGSHOP)
    to->lamp_method.integral = FOG_LAMP_ANGLE; /* Fogshop's is for Gaussians only */
  memcpy(to->fog.colour, from->fog.colour, sizeof to->fog.colour);
  to->fog.albedo = from->fog.albedo;
  to->fog.phase_g = from->fog.phase_g;
  to->shadow.fog_self_shadow = from->shadow.fog_self_shadow;
  to->shadow.shafts = from->shadow.shafts;
}

/* The fog of `shown` in place of the one shown, lit by the scene pass's shadow maps. */
static int make_fog(view_state *v, const scene_config *shown, fog_error *err) {
  v->has_fog = false;
  if (render_fog_remake(&v->fog, shown, err)) return 1;
  render_fog_set_shafts(&v->fog, shown, scene_pass_sun_shadow(v->scene));
  render_fog_set_lamp_shadows(&v->fog, scene_pass_lamp_shadows(v->scene));
  v->has_fog = true;
  return 0;
}

/* The config whose fog rung `index` shows (-1: cfg itself), in cfg's light. */
static const scene_config *rung_config(rung_selector *sel, int index, const scene_config *cfg) {
  if (index < 0) return cfg;
  copy_light(sel->fit.rungs[index].config, cfg);
  return sel->fit.rungs[index].config;
}

/* The fog of rung `index` (-1: the config's, cfg) in place of the one shown, in cfg's
 * light. */
static int show_rung(view_state *v, rung_selector *sel, int index, const scene_config *cfg,
                     fog_error *err) {
  if (make_fog(v, rung_config(sel, index, cfg), err)) return 1;
  sel->shown = index;
  if (index < 0)
    printf("fogpipe %s: showing the config's own fog\n", v->command);
  else
    printf("fogpipe %s: showing rung %d: %s (max |dtau| %.3g, mean %.3g, %s in fit)\n",
           v->command, index, sel->fit.rungs[index].name, sel->fit.rungs[index].max_error,
           sel->fit.rungs[index].mean_error, rung_time(&sel->fit.rungs[index]).text);
  return 0;
}

/* The panel's menu, or [ and ] step through the rungs, 0 returns to the config's fog; the
 * title says which. */
static int rung_selector_update(rung_selector *sel, view_state *v, GLFWwindow *window,
                                const scene_config *cfg, double fps, bool keyboard,
                                fog_error *err) {
  static const int keys[2] = {GLFW_KEY_LEFT_BRACKET, GLFW_KEY_RIGHT_BRACKET};
  int next = sel->wanted;
  for (int k = 0; k < 2; k++) {
    const bool down = window_key_down(keys[k]); /* read: see the brush */
    if (keyboard && down && !sel->bracket_was_down[k]) next += k ? 1 : -1;
    sel->bracket_was_down[k] = down;
  }
  const bool zero = window_key_down(GLFW_KEY_0);
  if (keyboard && zero && !sel->zero_was_down) next = -1;
  sel->zero_was_down = zero;
  if (next < -1) next = sel->fit.count - 1;
  if (next >= sel->fit.count) next = -1;
  sel->wanted = next;
  if (next != sel->shown && show_rung(v, sel, next, cfg, err)) return 1;
  char title[320];
  if (sel->shown < 0)
    snprintf(title, sizeof title, "fogpipe %s: the config's own fog, %.1f fps ([ ] rungs)",
             v->command, fps);
  else
    snprintf(title, sizeof title,
             "fogpipe %s: rung %d/%d %s: max |dtau| %.3g, %s in fit; %.1f fps ([ ] 0)",
             v->command, sel->shown, sel->fit.count, sel->fit.rungs[sel->shown].name,
             sel->fit.rungs[sel->shown].max_error, rung_time(&sel->fit.rungs[sel->shown]).text,
             fps);
  glfwSetWindowTitle(window, title);
  return 0;
}

/* ---- the source ---- */

typedef struct session_source {
  scene_config *cfg; /* the config's own copy (owned): the brush and the panel edit it */
  bool remake;       /* the panel changed the sun or the fog: the next input makes it again */
  double remake_ms;  /* the last remake's time (0: none yet) */
  bool lamps_animated; /* [light] lamp_path or lamp_flicker: the lamps follow the clock */
  double clock_start;  /* glfwGetTime() at the start: scene time 0 (P does not reset it) */
  float density_range[2]; /* the density slider's: the config's value / 100 .. x 100 */
  float sun_hue[3]; /* the sun's last hue, kept while its strength is 0 (app/sun_hue.h) */
  double render_scale;
  bool fixed_clock; /* --screenshot: time from the frame count */
  view_state v;
  volume_playback playback;
  view_brush brush;
  lamp_tool lamps;
  char lamp_note[160]; /* why the last lamp was not placed ("": it was) */
  bool lamps_dropped;   /* the last frame's fog was drawn without the lamps' light */
  rung_selector sel;
  const char *rung_names[FIT_MAX_RUNGS + 1]; /* the panel's menu: the config's fog, rungs */
} session_source;

static void source_destroy(void *self) {
  session_source *s = self;
  view_state *v = &s->v;
  gl_presenter_destroy(v->presenter);
  gl_target_destroy(&v->scene_target);
  gl_target_destroy(&v->fog_target);
  render_fog_destroy(&v->fog);
  scene_pass_destroy(v->scene);
  if (v->geo_made) scene_geometry_destroy(&v->geo);
  if (s->playback.sequence.count) vdb_sequence_destroy(&s->playback.sequence);
  if (s->sel.on) fit_result_destroy(&s->sel.fit);
  free(s->cfg);
  free(s);
}

/* The config's vertical profile and, for a fogmap, its wavelets, as the simulated source's
 * panel has them (window_panel_profile, window_panel_wavelets): the height fog's and Perlin
 * fog's exponential falloff; a fogmap's profile (a VDB's comes with its frames) and its
 * basis, levels, mu and LOD. An edit makes the fog again (s->remake). */
static void panel_fog_shape(session_source *s, panel *ui) {
  scene_fog_config *fog = &s->cfg->fog;
  const bool fogmap = fog->model == FOG_MODEL_FOGMAP;
  const bool falloff = fog->model == FOG_MODEL_HEIGHT || fog->model == FOG_MODEL_PERLIN;
  if (falloff || (fogmap && !fog->vdb[0])) {
    window_profile profile = {.kind = falloff ? FOG_PROFILE_EXPONENTIAL : (int)fog->profile,
                              .fog_height = (float)fog->fog_height,
                              .scale_height = (float)fog->scale_height,
                              .has_bspline = fog->profile_count > 0};
    if (window_panel_profile(ui, &profile, falloff)) {
      if (fogmap) fog->profile = (scene_profile)profile.kind;
      fog->fog_height = profile.fog_height;
      fog->scale_height = profile.scale_height;
      /* the height and Perlin fog grow below their fog height: kept a float (as loaded) */
      if (falloff)
        fog->scale_height = fmax(fog->scale_height, 1.001 * scene_config_min_scale_height(s->cfg));
      s->remake = true;
    }
  }
  if (!fogmap || !panel_header(ui, "wavelets", false)) return;
  window_wavelets w = {.degree = fog->degree, .levels = fog->levels, .mu = (float)fog->mu,
                       .lod_method = (int)fog->lod};
  if (window_panel_wavelets(ui, &w)) {
    fog->degree = w.degree, fog->levels = w.levels, fog->mu = w.mu;
    fog->lod = (scene_lod)w.lod_method;
    s->remake = true;
  }
}

/* What the fog is and how it moves, its density and ambient colour, its profile and
 * wavelets; with --fit the rung menu. An edit makes the fog again at the next input
 * (s->remake). */
static void panel_fog(session_source *s, panel *ui) {
  if (!panel_header(ui, "fog as the config holds it", true)) return;
  scene_fog_config *fog = &s->cfg->fog;
  const bool carried = fog->model == FOG_MODEL_RBF && fog->rbf_emitter_count > 0 &&
                       fog->rbf_carrier == SCENE_RBF_CARRIER_SIM;
  panel_text(ui, "model: %s (%s)", fog_model_table[fog->model].label,
             carried ? "puffs carried by the simulation's flow" : "no simulation");
  if (s->playback.sequence.count && s->sel.shown < 0) { /* a rung shown: the sequence waits */
    bool playing = s->playback.playing;
    if (panel_checkbox(ui, "play the VDB sequence (P)", &playing))
      s->playback.toggle = !s->playback.toggle;
    const int at = (int)s->playback.shown; /* between frames at and at + 1 */
    panel_text(ui, "VDB frame %d (%d of %d)", s->playback.sequence.frames[at], at + 1,
               s->playback.sequence.count);
  }
  if (fog->model == FOG_MODEL_RBF)
    panel_text(ui, "B: the Gaussian brush (%s)", s->brush.on ? "on" : "off");
  /* the config's own density (a rung has its fitted one), where it draws anything: linear
   * fog reads fog_start and fog_end alone */
  if (s->sel.shown < 0 && scene_config_draws_density_scale(s->cfg)) {
    float density = (float)fog->density_scale;
    if (panel_slider_float(ui, "density scale", &density, s->density_range[0],
                           s->density_range[1], "%.4g", true)) {
      fog->density_scale = density;
      s->remake = true;
    }
  }
  if (panel_color3(ui, "fog colour (ambient)", fog->colour)) s->remake = true;
  if (s->sel.shown < 0) panel_fog_shape(s, ui);
  if (s->sel.on) {
    int shown = s->sel.shown + 1;
    if (panel_combo(ui, "rung", &shown, s->rung_names, s->sel.fit.count + 1))
      s->sel.wanted = shown - 1;
    if (s->sel.shown >= 0) {
      const fit_rung *r = &s->sel.fit.rungs[s->sel.shown];
      panel_text(ui, "|dtau| vs the config's fog: max %.3g, mean %.3g", r->max_error,
                 r->mean_error);
      panel_text(ui, "%s a frame in fit", rung_time(r).text);
    }
  }
}

/* The sun, as the simulated source's panel has it (window_panel_sunlight). */
static void panel_sun(session_source *s, panel *ui) {
  scene_config *cfg = s->cfg;
  window_sunlight sun = {.azimuth = (float)cfg->light.sun_azimuth,
                         .elevation = (float)cfg->light.sun_elevation,
                         .albedo = (float)cfg->fog.albedo, .phase_g = (float)cfg->fog.phase_g,
                         .hue = {s->sun_hue[0], s->sun_hue[1], s->sun_hue[2]},
                         .self_shadow = cfg->shadow.fog_self_shadow,
                         .shafts = cfg->shadow.shafts};
  double colour[3];
  for (int c = 0; c < 3; c++) colour[c] = cfg->light.sun_colour[c];
  window_sunlight_set_colour(&sun, colour);
  const bool changed = window_panel_sunlight(ui, &sun);
  for (int c = 0; c < 3; c++) s->sun_hue[c] = sun.hue[c];
  if (!changed) return;
  cfg->light.sun_azimuth = sun.azimuth;
  cfg->light.sun_elevation = sun.elevation;
  window_sunlight_colour(&sun, colour);
  for (int c = 0; c < 3; c++) cfg->light.sun_colour[c] = (float)colour[c];
  cfg->fog.albedo = sun.albedo;
  cfg->fog.phase_g = sun.phase_g;
  cfg->shadow.fog_self_shadow = sun.self_shadow;
  cfg->shadow.shafts = sun.shafts;
  s->remake = true;
}

static void source_panel(void *self, panel *ui, const window_frame *f) {
  (void)f;
  session_source *s = self;
  panel_fog(s, ui);
  panel_sun(s, ui);
  if (s->lamps_dropped) /* outside the lamps' section: it may be closed */
    panel_text(ui, "%s", LAMP_TOOL_DROPPED_NOTE);
  lamp_tool_panel(ui, &s->lamps, s->cfg->lamp_count, s->lamps_animated, s->lamp_note);
  if (s->remake_ms > 0) panel_text(ui, "fog made again after an edit: %.0f ms", s->remake_ms);
}

/* The config's fog, made again (render_fog_create shows vdb_frame), at the played volume's
 * time on screen. */
static int show_volume_time(session_source *s, fog_error *err) {
  const volume_playback *pb = &s->playback;
  if (!pb->sequence.count || s->sel.shown >= 0 || !s->v.has_fog) return 0;
  int a, b;
  double w;
  vdb_sequence_position(pb->shown, pb->sequence.count, 1, &a, &b, &w);
  return render_fog_set_volume_time(&s->v.fog, s->cfg, &pb->sequence, a, b, w, err);
}

/* The panel changed the sun or the fog: the surfaces' light and shadow map (the scene pass
 * renders the map again when the sun differs), and the fog shown made again (its sun-shadow
 * volume; a played volume at the time shown; a rung in the same light). */
static int remake_now(session_source *s, fog_error *err) {
  view_state *v = &s->v;
  s->remake = false;
  v->geo.light = s->cfg->light;
  scene_light_sun_direction(&v->geo.light, v->geo.sun_direction);
  if (!v->has_fog) return 0;
  return make_fog(v, rung_config(&s->sel, s->sel.shown, s->cfg), err) ||
         show_volume_time(s, err);
}

/* The lamp tool's edit on the window's config (so a remade fog, a rung and a saved scene
 * keep it), then on the surfaces and the fog shown. A lamp whose light this renderer could
 * not draw (the fog pass's loop cap: many Gaussians on llvmpipe) is not placed. */
static int apply_lamp_edit(session_source *s, const lamp_edit *e, fog_error *err) {
  view_state *v = &s->v;
  scene_config *cfg = s->cfg;
  scene_config *edited = malloc(sizeof *edited);
  if (!edited) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for a lamp");
  memcpy(edited, cfg, sizeof *edited);
  scene_lamp_config *lamp = &edited->lamps[e->index];
  if (e->kind == LAMP_EDIT_PLACE) {
    edited->lamp_count++;
    *lamp = (scene_lamp_config){.radius = LAMP_TOOL_RADIUS};
    memcpy(lamp->colour, e->intensity, sizeof lamp->colour);
  }
  if (e->kind == LAMP_EDIT_PLACE || e->kind == LAMP_EDIT_MOVE)
    memcpy(lamp->position, e->position, sizeof lamp->position);
  if (e->kind == LAMP_EDIT_REMOVE) {
    for (int i = e->index; i + 1 < edited->lamp_count; i++) edited->lamps[i] = edited->lamps[i + 1];
    edited->lamp_count--;
  }
  fog_lamps lamps = scene_config_fog_lamps(edited);
  /* integrated as the fog shown integrates them: a rung not of Gaussians draws Fogshop
   * lamps by angle (copy_light), and the pass refuses Fogshop's method on it */
  if (v->has_fog) lamps.method = v->fog.params.lamps.method;
  if (v->has_fog && e->kind == LAMP_EDIT_PLACE) { /* moving or removing adds no loops */
    /* the bound the pass will check: with a shadow cube for every lamp (the scene pass
     * renders the new one), and the view ray's loops over every Gaussian */
    fog_pass_params p = v->fog.params;
    p.lamps = lamps;
    lamp_shadow_maps cubes = {.count = lamps.count};
    if (scene_config_lamp_shadow_size(edited) > 0) p.lamp_shadows = &cubes;
    const double loops = fog_pass_loop_bound(&p, p.model_rbf_count);
    if (loops > fog_pass_loops_allowed(v->fog.pass)) {
      snprintf(s->lamp_note, sizeof s->lamp_note,
               "lamp not placed: %d lamp%s over this fog\nwould need ~%.0f shader loops a "
               "pixel;\nthis renderer runs %ld (docs/platform.md)", lamps.count,
               lamps.count == 1 ? "" : "s", loops,
               (long)fog_pass_loops_allowed(v->fog.pass));
      free(edited);
      s->lamps.dragged = -1;
      return 0;
    }
  }
  s->lamp_note[0] = '\0';
  memcpy(cfg, edited, sizeof *cfg);
  free(edited);
  if (scene_pass_set_lamps(v->scene, &lamps, err)) return 1;
  if (v->has_fog) {
    v->fog.params.lamps = lamps;
    render_fog_set_lamp_shadows(&v->fog, scene_pass_lamp_shadows(v->scene));
  }
  return 0;
}

/* The lamp tool for one frame: the surface under the cursor from the last frame's
 * distances. */
static int session_lamps(session_source *s, const window_frame *f, fog_error *err) {
  const bool left = glfwGetMouseButton(f->window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool right = glfwGetMouseButton(f->window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  double hit[3];
  const bool picked = f->mouse && (left || right) && view_pick(&s->v, f->window, &f->fc->cam, hit);
  const fog_lamps shown = scene_config_fog_lamps(s->cfg);
  const lamp_edit edit = lamp_tool_update(&s->lamps, left, right, picked ? hit : NULL, &shown);
  return edit.kind == LAMP_EDIT_NONE ? 0 : apply_lamp_edit(s, &edit, err);
}

static int source_input(void *self, const window_frame *f, fog_error *err) {
  session_source *s = self;
  view_state *v = &s->v;
  const scene_config *cfg = s->cfg;
  if (s->remake) {
    const double t0 = app_clock_seconds();
    if (remake_now(s, err)) return 1;
    s->remake_ms = 1e3 * (app_clock_seconds() - t0);
  }
  const int rung_before = s->sel.shown;
  if (s->sel.on && rung_selector_update(&s->sel, v, f->window, cfg, f->fps, f->keyboard, err))
    return 1;
  /* back from a rung: the config's fog at the time on screen (playing, the update below
   * loads the clock's) */
  if (s->sel.shown < 0 && rung_before >= 0 && !s->playback.playing && show_volume_time(s, err))
    return 1;
  /* With --screenshot the sequence advances one VDB frame per drawn frame (the same fog
   * every run), else with the clock. The fixed clock counts from the session's start, not
   * from the playback's (which a toggle moves to the clock: Play at frame i then jumped i
   * frames ahead). */
  const double clock = s->fixed_clock ? s->clock_start + f->index / cfg->fog.vdb_fps : f->now;
  if (s->playback.sequence.count &&
      volume_playback_update(&s->playback, f->window, f->keyboard, s->sel.shown < 0, clock,
                             &v->fog, cfg, err))
    return 1;
  /* RBF fog from emitters moves with the clock (with --screenshot at 24 frames a second:
   * the same fog every run) */
  const double fog_time = s->fixed_clock ? f->index / 24.0 : f->now - s->clock_start;
  if (v->has_fog && s->sel.shown < 0 && render_fog_animated(cfg) &&
      render_fog_set_time(&v->fog, cfg, fog_time, err))
    return 1;
  /* lamps that move or flicker ([light] lamp_path, lamp_flicker) on the same clock, as
   * record shows them: the fog's in-scatter and the surfaces they light */
  if (s->lamps_animated) {
    fog_lamps lamps = scene_config_fog_lamps_at(cfg, fog_time);
    if (v->has_fog) {
      lamps.method = v->fog.params.lamps.method; /* the shown fog's (as the lamp tool's) */
      v->fog.params.lamps = lamps;
    }
    if (scene_pass_set_lamps(v->scene, &lamps, err)) return 1;
  }
  /* the lamp tool and the brush pick from the last frame's distances; the brush's keys are
   * read while the tool holds the mouse (a press latched then is let go) */
  if (!s->lamps.placing) lamp_tool_idle(&s->lamps);
  if (f->index > 0 && s->lamps.placing && session_lamps(s, f, err)) return 1;
  return f->index > 0 && view_brush_update(&s->brush, v, f, s->sel.shown < 0 && !s->lamps.placing,
                                           cfg, fog_time, err);
}

/* The right button looks around, except while it removes lamps. */
static int source_look_buttons(const void *self) {
  const session_source *s = self;
  return FREE_CAMERA_LOOK_MIDDLE | (s->lamps.placing ? 0 : FREE_CAMERA_LOOK_RIGHT);
}

static int source_draw(void *self, const window_frame *f, fog_error *err) {
  session_source *s = self;
  view_state *v = &s->v;
  const int w = (int)fmax(1.0, floor(f->fb_w * s->render_scale));
  const int h = (int)fmax(1.0, floor(f->fb_h * s->render_scale));
  const gl_target *t = &v->scene_target;
  if ((w != t->width || h != t->height || !t->framebuffer) && make_targets(v, w, h, err))
    return 1;
  scene_pass_run(v->scene, &f->fc->cam, &v->scene_target);
  v->drawn_camera = f->fc->cam, v->drawn = true;
  const gl_target *shown = &v->scene_target;
  s->lamps_dropped = false;
  if (v->has_fog && render_fog_draw(&v->fog, &f->fc->cam, &v->scene_target, &v->fog_target,
                                     err)) {
    /* the fog pass refused the lamps' light (the renderer's loop cap: Gaussians painted
     * with the brush, a rung's fog under the lamps): the fog without it, and a note; if
     * the view ray alone is still too much, without the sun's shadow in the fog too */
    if (err->code != FOG_ERR_UNSUPPORTED) return 1;
    s->lamps_dropped = true;
    const fog_pass_params kept = v->fog.params;
    v->fog.params.lamps.count = 0;
    int failed = render_fog_draw(&v->fog, &f->fc->cam, &v->scene_target, &v->fog_target, err);
    if (failed && err->code == FOG_ERR_UNSUPPORTED) { /* the sun's mean over the Gaussians */
      v->fog.params.self_shadow = FOG_SUN_SHADOW_NONE, v->fog.params.shafts = NULL;
      failed = render_fog_draw(&v->fog, &f->fc->cam, &v->scene_target, &v->fog_target, err);
    }
    v->fog.params = kept;
    if (failed) return 1;
    *err = (fog_error){0};
  }
  if (v->has_fog) shown = &v->fog_target;
  const display_transform display = scene_config_display(s->cfg);
  gl_presenter_draw(v->presenter, shown, f->fb_w, f->fb_h, GL_PRESENT_NEAREST, &display);
  return 0;
}

/* Scene, fog, playback and presenter in the current context. */
static int session_open(session_source *s, const window_options *opts, fog_error *err) {
  view_state *v = &s->v;
  const scene_config *cfg = s->cfg;
  if (render_scene_geometry_create(&v->geo, cfg, err)) return 1;
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
  volume_playback *playback = &s->playback;
  playback->playing = opts->play;
  playback->start_time = s->clock_start = glfwGetTime();
  if (cfg->fog.model == FOG_MODEL_VOLUME) {
    if (render_fog_volume_sequence(cfg, &playback->sequence, err)) return 1;
    /* render_fog_create showed vdb_frame (so it is in the sequence) */
    playback->shown = playback->start = vdb_frame_index(
        playback->sequence.frames, playback->sequence.count, cfg->fog.vdb_frame);
  }
  if (!(v->presenter = gl_presenter_create(err))) return 1;
  const int first = opts->rung >= 0 ? opts->rung : s->sel.fit.chosen;
  return s->sel.on && first >= 0 && show_rung(v, &s->sel, first, cfg, err);
}

int window_session_source(window_source *src, gl_context *gl, const scene_config *cfg,
                          const window_options *opts, fit_result *fit, fog_error *err) {
  (void)gl;
  session_source *s = calloc(1, sizeof *s);
  if (!s) {
    if (fit) fit_result_destroy(fit);
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the window's fog");
  }
  if (!(s->cfg = malloc(sizeof *s->cfg))) {
    free(s);
    if (fit) fit_result_destroy(fit);
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the window's fog");
  }
  *s->cfg = *cfg;
  const float density = cfg->fog.density_scale > 0 ? (float)cfg->fog.density_scale : 0.01f;
  s->density_range[0] = density / 100.0f, s->density_range[1] = density * 100.0f;
  const double sun_colour[3] = {cfg->light.sun_colour[0], cfg->light.sun_colour[1],
                                cfg->light.sun_colour[2]};
  float sun_strength;
  s->sun_hue[0] = s->sun_hue[1] = s->sun_hue[2] = 1.0f;
  sun_hue_split(sun_colour, s->sun_hue, &sun_strength);
  s->render_scale = opts->render_scale > 0 ? opts->render_scale : 0.5;
  s->fixed_clock = opts->screenshot != NULL;
  s->lamps_animated = scene_config_lamps_animated(cfg);
  s->lamps = lamp_tool_for_scene(fmax(cfg->terrain.size[0], cfg->terrain.size[1]));
  s->v.command = opts->command;
  s->brush = (view_brush){.command = opts->command, .config_path = opts->config_path,
                          .painted = s->cfg};
  s->sel = (rung_selector){.shown = -1, .wanted = -1};
  if (fit) {
    s->sel.fit = *fit; /* taken over */
    s->sel.on = true;
    s->rung_names[0] = "the config's own fog";
    for (int r = 0; r < fit->count; r++) s->rung_names[r + 1] = s->sel.fit.rungs[r].name;
  }
  if (session_open(s, opts, err)) {
    source_destroy(s);
    return 1;
  }
  s->sel.wanted = s->sel.shown;
  *src = (window_source){
      .self = s, .look_buttons = FREE_CAMERA_LOOK_MIDDLE | FREE_CAMERA_LOOK_RIGHT,
      .look_buttons_now = source_look_buttons,
      .camera_speed = 0.05 * fmax(cfg->terrain.size[0], cfg->terrain.size[1]),
      .panel = source_panel, .input = source_input, .draw = source_draw,
      .destroy = source_destroy};
  return 0;
}
