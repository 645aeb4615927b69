/* `fogpipe view`: without a display it prints one clear line and exits non-zero; under
 * Xvfb (when xvfb-run is installed) its --screenshot of the window (read from GL_BACK)
 * shows the same image as the headless `fogpipe render` PNG of the same config and size,
 * for the fogmap scene, the RBF fog banks and the plume volume: the window path and the
 * headless path agree (the screenshots with --hide-panel; by default the panel is over the
 * image, a check of its own), and a lamp on a path equals record's frame of the same scene
 * time (the window's clock) and no neighbouring frame. With --fit the window shows the chosen rung of the model
 * ladder. The window dithers its 8 bits as render's PNG does, byte for byte on a flat scene,
 * and with [render] dither = off both round.
 * Tolerance elsewhere: 99% of 8-bit values within
 * 2/255 and the mean within 0.5/255 (the window renders fog into RGBA16F, render into
 * RGBA32F: half-float rounding can move a value by one 8-bit step). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sim/sim.h"
#include "test_bin.h"

static float *load(const char *path, const char *channel, int *w, int *h) {
  fogmap map = {0};
  fog_error err;
  if (fogmap_load(path, &(fogmap_load_desc){.channel = channel}, &map, &err)) {
    CHECK(0, "%s %s: %s", path, channel, err.message);
    return NULL;
  }
  *w = map.width, *h = map.height;
  return map.density;
}

/* --screenshot of `view CONFIG VIEW_OPTIONS` under Xvfb against `render CONFIG
 * RENDER_OPTIONS` (record_frame 0: its sRGB PNG) or frame record_frame of `record CONFIG`
 * (its linear EXR, clamped and sRGB-encoded as the window shows it), 160x90: the same image (expect_same), or one whose mean differs
 * by more than 2/255 in some channel. */
static void compare_window(const char *bin, const char *dir, const char *config,
                           const char *view_options, const char *render_options,
                           int record_frame, bool expect_same) {
  double largest_mean = 0.0;
  char command[1024], shot[256], headless[256];
  snprintf(shot, sizeof shot, "%s/window.png", dir);
  snprintf(headless, sizeof headless, "%s/render.png", dir);
  /* two frames unless the options say how many (an option given twice is refused) */
  const char *frames = strstr(view_options, "--frames") ? "" : "--frames 2";
  snprintf(command, sizeof command,
           "xvfb-run -a -s '-screen 0 640x480x24' '%s' view %s --size 160x90 "
           "--render-scale 1 --hide-panel --screenshot '%s' %s %s",
           bin, config, shot, frames, view_options);
  CHECK(system(command) == 0, "%s", command);
  if (record_frame > 0) {
    snprintf(headless, sizeof headless, "%s/rec/frame.%04d.exr", dir, record_frame);
    snprintf(command, sizeof command,
             "'%s' record %s --frames %d --out '%s/rec' --size 160x90 > /dev/null", bin, config,
             record_frame, dir);
  } else {
    snprintf(command, sizeof command, "'%s' render %s --out '%s' --size 160x90 %s", bin, config,
             headless, render_options);
  }
  CHECK(system(command) == 0, "%s", command);
  const char *channels[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; c++) {
    int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
    float *a = load(shot, channels[c], &w1, &h1), *b = load(headless, channels[c], &w2, &h2);
    CHECK(w1 == 160 && h1 == 90 && w2 == 160 && h2 == 90, "sizes %dx%d %dx%d", w1, h1, w2, h2);
    if (a && b && w1 == w2 && h1 == h2) {
      for (int k = 0; k < w2 * h2 && record_frame > 0; k++) { /* linear -> sRGB, as shown */
        const double x = fmin(fmax(b[k], 0.0), 1.0);
        b[k] = (float)(x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055);
      }
      int within = 0;
      double sum = 0, worst = 0;
      for (int k = 0; k < w1 * h1; k++) {
        double d = fabs(a[k] - b[k]) * 255.0;
        within += d <= 2.0 + 1e-6;
        sum += d;
        if (d > worst) worst = d;
      }
      printf("%s %s %s: max %.0f/255, mean %.3f/255, %d of %d within 2/255\n", config,
             view_options, channels[c], worst, sum / (w1 * h1), within, w1 * h1);
      CHECK(!expect_same || (within >= 0.99 * w1 * h1 && sum / (w1 * h1) < 0.5),
            "%s channel %s: window and headless images differ", config, channels[c]);
      largest_mean = fmax(largest_mean, sum / (w1 * h1));
    }
    free(a);
    free(b);
  }
  CHECK(expect_same || largest_mean > 2.0, "%s %s: the window shows the config's own image "
        "(mean difference %.3f/255)", config, view_options, largest_mean);
  unlink(shot);
  unlink(headless);
  if (record_frame > 0) {
    snprintf(command, sizeof command, "rm -rf '%s/rec'", dir);
    CHECK(system(command) == 0, "%s", command);
  }
}

/* The window program's panel: over the image by default, gone with --hide-panel. Inside
 * the panel's title bar (60, 25) the two screenshots differ; right of the panel's 330
 * pixels, at (440, 135), they do not. */
static void panel_shown_unless_hidden(const char *bin, const char *dir) {
  float *shot[2] = {NULL, NULL};
  int w = 0, h = 0;
  for (int hidden = 0; hidden < 2; hidden++) {
    char command[1024], png[256];
    snprintf(png, sizeof png, "%s/panel%d.png", dir, hidden);
    snprintf(command, sizeof command,
             "xvfb-run -a -s '-screen 0 640x480x24' '%s' view configs/default.ini --size 480x270 "
             "--render-scale 1 %s --screenshot '%s' --frames 2 > /dev/null",
             bin, hidden ? "--hide-panel" : "", png);
    CHECK(system(command) == 0, "%s", command);
    shot[hidden] = load(png, "G", &w, &h);
    unlink(png);
  }
  CHECK(w == 480 && h == 270, "the screenshots are %dx%d, not 480x270", w, h);
  if (shot[0] && shot[1] && w == 480 && h == 270) {
    const float in_panel = fabsf(shot[0][25 * w + 60] - shot[1][25 * w + 60]);
    const float outside = fabsf(shot[0][135 * w + 440] - shot[1][135 * w + 440]);
    printf("panel: title bar differs by %.3f with it hidden, the scene by %.3f\n", in_panel,
           outside);
    CHECK(in_panel > 0.05f, "no panel in the view's window (%.3f)", in_panel);
    CHECK(outside < 2.0f / 255.0f, "the scene beside the panel changed (%.3f)", outside);
  }
  free(shot[0]);
  free(shot[1]);
}

/* The window's 8-bit dither (scene_present_fs.glsl) is render's (sim/image_srgb.c) pixel for
 * pixel: a scene of one flat colour inside dense fog, 255 srgb(13/64) = 124.45 (13/64 is
 * exact in half and float, so the window's RGBA16F holds what render's RGBA32F holds),
 * dithers to levels 124 and 125 in the Bayer pattern, byte for byte the same in both
 * (a mirrored or shifted pattern, or none, differs at thousands of pixels). */
static void dither_as_render(const char *bin, const char *dir) {
  char ini[300], shot[300], png[300], command[1400];
  snprintf(ini, sizeof ini, "%s/flat.ini", dir);
  snprintf(shot, sizeof shot, "%s/flat_window.png", dir);
  snprintf(png, sizeof png, "%s/flat_render.png", dir);
  FILE *f = fopen(ini, "w");
  CHECK(f != NULL, "%s", ini);
  if (!f) return;
  fputs("[camera]\nposition = 0 20 120\nlook_at = 0 10 0\nfov = 60\n[fog]\n"
        "model = homogeneous\ndensity_scale = 50\ncolour = 0.203125 0.203125 0.203125\n",
        f);
  fclose(f);
  snprintf(command, sizeof command,
           "xvfb-run -a -s '-screen 0 640x480x24' '%s' view '%s' --size 160x90 --render-scale 1 "
           "--hide-panel --screenshot '%s' --frames 2 > /dev/null && '%s' render '%s' --out '%s' "
           "--size 160x90 > /dev/null",
           bin, ini, shot, bin, ini, png);
  CHECK(system(command) == 0, "%s", command);
  int w[2] = {0}, h[2] = {0};
  float *window = load(shot, "R", &w[0], &h[0]), *rendered = load(png, "R", &w[1], &h[1]);
  if (window && rendered && w[0] == w[1] && h[0] == h[1]) {
    long differ = 0, up = 0, other = 0;
    for (int i = 0; i < w[0] * h[0]; i++) {
      const long a = lrintf(255.0f * window[i]), b = lrintf(255.0f * rendered[i]);
      differ += a != b;
      up += b == 125;
      other += b != 124 && b != 125;
    }
    const double share = (double)up / (w[0] * h[0]);
    CHECK(differ == 0, "%ld of %d window pixels differ from render's dithered PNG", differ,
          w[0] * h[0]);
    CHECK(other == 0 && fabs(share - 0.4466) < 0.02,
          "render's flat 124.45 is not dithered to 124 and 125 (%.3f at 125, %ld others)",
          share, other);
  } else {
    CHECK(0, "%s and %s: missing or of different sizes", shot, png);
  }
  free(window);
  free(rendered);
  /* [render] dither = off: rounded, 124 everywhere, in the window as in the PNG */
  f = fopen(ini, "a");
  CHECK(f != NULL, "%s", ini);
  if (f) fputs("[render]\ndither = off\n", f), fclose(f);
  CHECK(system(command) == 0, "%s", command);
  window = load(shot, "R", &w[0], &h[0]), rendered = load(png, "R", &w[1], &h[1]);
  CHECK(window && rendered && w[0] == w[1] && h[0] == h[1] && w[0] > 0,
        "dither = off: %s and %s missing or of different sizes", shot, png);
  long not_124 = 0;
  for (int i = 0; window && rendered && i < w[0] * h[0] && w[0] == w[1] && h[0] == h[1]; i++)
    not_124 += (lrintf(255.0f * window[i]) != 124) + (lrintf(255.0f * rendered[i]) != 124);
  CHECK(window && rendered && not_124 == 0,
        "dither = off: %ld window or PNG values are not the nearest level 124", not_124);
  free(window);
  free(rendered);
  unlink(ini), unlink(shot), unlink(png);
}

int main(void) {
  char dir[] = "/tmp/fogpipe_view_XXXXXX";
  const char *bin = test_bin_and_folder(dir);
  if (!bin) return test_finish("test_view_window");
  char command[1024], path[256], text[1024] = "";

  /* No display: one line, non-zero exit. */
  snprintf(path, sizeof path, "%s/stderr.txt", dir);
  snprintf(command, sizeof command,
           "env -u DISPLAY -u WAYLAND_DISPLAY '%s' view configs/default.ini 2> '%s'", bin, path);
  int status = system(command);
  FILE *f = fopen(path, "r");
  size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
  text[n] = '\0';
  if (f) fclose(f);
  unlink(path);
  CHECK(status != 0, "view without a display exited 0");
  CHECK(strstr(text, "fogpipe view: cannot open a window: no display") == text, "stderr: %s", text);
  CHECK(strchr(text, '\n') == text + strlen(text) - 1, "not one line: %s", text);
  /* and with --fit, said before the fit runs (it printed its rungs first, for seconds) */
  snprintf(command, sizeof command,
           "env -u DISPLAY -u WAYLAND_DISPLAY '%s' view configs/vdb_groundfog.ini --fit 0.1 "
           "> '%s' 2>&1", bin, path);
  status = system(command);
  f = fopen(path, "r");
  n = f ? fread(text, 1, sizeof text - 1, f) : 0;
  text[n] = '\0';
  if (f) fclose(f);
  unlink(path);
  CHECK(status != 0 && strstr(text, "no display") && !strstr(text, "rung"),
        "view --fit without a display: %s", text);

  if (system("command -v xvfb-run > /dev/null 2>&1") != 0) {
    printf("xvfb-run is not installed: the window comparison is not run\n");
  } else {
    /* The fogmap scene, and two other rungs of the model ladder. */
    /* quadric_volumes: its tone_map = aces, the window's shader against render's C */
    static const char *const configs[] = {"configs/default.ini", "configs/rbf_fog_banks.ini",
                                          "configs/vdb_plume_volume.ini",
                                          "configs/quadric_volumes.ini"};
    for (size_t k = 0; k < sizeof configs / sizeof configs[0]; k++)
      compare_window(bin, dir, configs[k], "", "", 0, true);
    /* The plume's sequence played: from its vdb_frame 48, three drawn frames advance two
     * VDB frames, wrapping around to frame 2. */
    compare_window(bin, dir, "configs/vdb_plume_volume.ini", "--play --frames 3",
                   "--vdb-frame 2", 0, true);
    /* --fit: the window shows a rung of the model ladder. Rung 1 of the linear fog is the
     * linear factor fitted to it (start and end to 1e-9: the config's own image); rung 0,
     * homogeneous fog, is not. */
    compare_window(bin, dir, "configs/classic_fog.ini", "--fit 0.01 --rung 1", "", 0, true);
    compare_window(bin, dir, "configs/classic_fog.ini", "--fit 0.01 --rung 0", "", 0, false);
    /* A lamp on a path ([light] lamp_path): the window moves it on the clock record does.
     * 13 drawn frames with --screenshot are scene time 12/24 s, record's frame 13: the lamp
     * halfway, the same image; record's frames 12 and 14 (the lamp 33 units either side: a
     * clock one frame off) and render (time 0, the lamp at its start) are other images. */
    char lamp_ini[300];
    snprintf(lamp_ini, sizeof lamp_ini, "%s/lamp_path.ini", dir);
    FILE *ini = fopen(lamp_ini, "w");
    CHECK(ini != NULL, "%s", lamp_ini);
    if (ini) {
      fputs("[camera]\nposition = 0 20 120\nlook_at = 0 10 0\nfov = 60\n"
            "[fog]\nmodel = homogeneous\ndensity_scale = 0.01\nalbedo = 0.9\nphase_g = 0.3\n"
            "colour = 0 0 0\n[light]\nsun_colour = 0.01 0.01 0.01\n"
            "lamp = -400 10 0 3000 2500 2000\nlamp_path = 1 0 -400 10 0\n"
            "lamp_path = 1 1 400 10 0\n",
            ini);
      fclose(ini);
      compare_window(bin, dir, lamp_ini, "--frames 13", "", 13, true);
      compare_window(bin, dir, lamp_ini, "--frames 13", "", 12, false);
      compare_window(bin, dir, lamp_ini, "--frames 13", "", 14, false);
      compare_window(bin, dir, lamp_ini, "--frames 13", "", 0, false);
      unlink(lamp_ini);
    }
    /* Fogshop's lamps (Gaussian fog only) moving on a path, under --fit's homogeneous
     * rung: the rung draws them by angle, each frame too (the window closed on frame 1,
     * "lamp integral 1 with model 1": the moved lamps took the config's method) */
    char fogshop_ini[300], fogshop_shot[300], fogshop_command[1024];
    snprintf(fogshop_ini, sizeof fogshop_ini, "%s/fogshop_path.ini", dir);
    snprintf(fogshop_shot, sizeof fogshop_shot, "%s/fogshop.png", dir);
    test_write_text(fogshop_ini,
                    "[camera]\nposition = 0 20 120\nlook_at = 0 10 0\n"
                    "[fog]\nmodel = rbf\nrbf = 0 10 0 30 0.02\ncolour = 0 0 0\nalbedo = 0.9\n"
                    "[light]\nsun_colour = 0.01 0.01 0.01\nlamp = -40 10 0 3000 2500 2000\n"
                    "lamp_path = 1 0 -40 10 0\nlamp_path = 1 1 40 10 0\n"
                    "lamp_integral = fogshop\n");
    snprintf(fogshop_command, sizeof fogshop_command,
             "xvfb-run -a -s '-screen 0 640x480x24' '%s' view '%s' --fit 0.5 --rung 0 "
             "--size 64x48 --hide-panel --frames 2 --screenshot '%s' > /dev/null 2>&1",
             bin, fogshop_ini, fogshop_shot);
    const int fogshop_status = system(fogshop_command);
    CHECK(WIFEXITED(fogshop_status) && WEXITSTATUS(fogshop_status) == 0 &&
              access(fogshop_shot, F_OK) == 0,
          "view --fit --rung 0 over Fogshop lamps on a path: exit %d",
          WIFEXITED(fogshop_status) ? WEXITSTATUS(fogshop_status) : -1);
    unlink(fogshop_ini), unlink(fogshop_shot);
    panel_shown_unless_hidden(bin, dir);
    dither_as_render(bin, dir);
    /* `demo --frames N` without --screenshot closes the window after N frames (it was
     * dropped: the window ran until closed) */
    char command[1024];
    snprintf(command, sizeof command,
             "timeout 120 xvfb-run -a -s '-screen 0 640x480x24' '%s' demo configs/default.ini "
             "--frames 3 --size 160x90 > /dev/null 2>&1", bin);
    const int status = system(command);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0,
          "demo --frames 3 without --screenshot: exit %d (124: still open after 120 s)",
          WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  }
  rmdir(dir);
  return test_finish("test_view_window");
}
