/* `fogpipe demo` opens its window (under Xvfb: xvfb-run must be installed, otherwise the
 * test is skipped with ctest's code 77), renders a few frames with the Dear ImGui panel
 * and saves a screenshot: the PNG has the window's size, the panel's corner (dark ImGui
 * window) differs from the same run's with --hide-panel while the scene on the right
 * agrees, and the image is not a flat colour. */
#include "tests/app/record_util.h"
#include "tests/test_util.h"

int main(void) {
  if (system("command -v xvfb-run >/dev/null 2>&1") != 0) {
    printf("test_demo_window: xvfb-run is not installed; skipped\n");
    return 77;
  }
  char root[] = "/tmp/fogpipe-demo-window-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char png[600], log[600], cmd[2400];
  snprintf(png, sizeof png, "%s/window.png", root);
  snprintf(log, sizeof log, "%s/demo.log", root);
  snprintf(cmd, sizeof cmd,
           "xvfb-run -a -s '-screen 0 800x600x24' '%s' demo configs/default.ini --size 480x270 "
           "--scale 0.25 --frames 3 --screenshot '%s' >'%s' 2>&1",
           record_bin(), png, log);
  int status = system(cmd);
  CHECK(status == 0, "the demo under xvfb-run failed (status %d)", status);
  if (status != 0) record_print_log(log);

  fogmap r = {0}, g = {0}, b = {0};
  fog_error err = {0};
  int loaded = !fogmap_load(png, &(fogmap_load_desc){.channel = "R"}, &r, &err) &&
               !fogmap_load(png, &(fogmap_load_desc){.channel = "G"}, &g, &err) &&
               !fogmap_load(png, &(fogmap_load_desc){.channel = "B"}, &b, &err);
  CHECK(loaded, "screenshot unreadable: %s", err.message);
  if (loaded) {
    CHECK(r.width == 480 && r.height == 270, "screenshot is %dx%d, expected 480x270", r.width,
          r.height);
    double lo = 1e9, hi = -1e9;
    for (int i = 0; i < r.width * r.height; i++) {
      double v = r.density[i] + g.density[i] + b.density[i];
      lo = v < lo ? v : lo;
      hi = v > hi ? v : hi;
    }
    CHECK(hi - lo > 0.3, "the window is a flat colour (range %g)", hi - lo);
  }
  /* The panel sits at (10, 10): the same run with --hide-panel differs inside its title bar
   * (60, 25) and agrees far right (440, 135), the scene in both. (Comparing (60, 25) with
   * (440, 135) of one image passed with no panel at all: sky against terrain.) */
  char bare[600];
  snprintf(bare, sizeof bare, "%s/no_panel.png", root);
  snprintf(cmd, sizeof cmd,
           "xvfb-run -a -s '-screen 0 800x600x24' '%s' demo configs/default.ini --size 480x270 "
           "--scale 0.25 --frames 3 --hide-panel --screenshot '%s' >'%s' 2>&1",
           record_bin(), bare, log);
  status = system(cmd);
  CHECK(status == 0, "the demo with --hide-panel failed (status %d)", status);
  fogmap br = {0}, bg = {0}, bb = {0};
  const int bare_loaded = loaded &&
                          !fogmap_load(bare, &(fogmap_load_desc){.channel = "R"}, &br, &err) &&
                          !fogmap_load(bare, &(fogmap_load_desc){.channel = "G"}, &bg, &err) &&
                          !fogmap_load(bare, &(fogmap_load_desc){.channel = "B"}, &bb, &err) &&
                          br.width == r.width && br.height == r.height;
  CHECK(bare_loaded, "the --hide-panel screenshot: %s", err.message);
  if (bare_loaded) {
    const int panel = 25 * r.width + 60, scene = 135 * r.width + 440;
    double at_panel = 0.0, at_scene = 0.0;
    const fogmap *with[3] = {&r, &g, &b}, *without[3] = {&br, &bg, &bb};
    for (int c = 0; c < 3; c++) {
      at_panel += fabs(with[c]->density[panel] - without[c]->density[panel]);
      at_scene += fabs(with[c]->density[scene] - without[c]->density[scene]);
    }
    printf("with the panel and without: (60,25) differs by %.3f, (440,135) by %.3f\n",
           at_panel, at_scene);
    CHECK(at_panel > 0.05, "no panel visible: pixel (60,25) is the same without the panel "
          "(differs by %g)", at_panel);
    CHECK(at_scene < 0.02, "the scene at (440,135) differs between the runs by %g", at_scene);
  }
  fogmap_destroy(&br);
  fogmap_destroy(&bg);
  fogmap_destroy(&bb);
  fogmap_destroy(&r);
  fogmap_destroy(&g);
  fogmap_destroy(&b);

  /* A model without a simulation opens the same window over its fog as held (`view`'s
   * source) with the demo's own options: the screenshot is taken at the demo's --size and
   * the demo exits (it once handed the view a made-up command line without them, and ran
   * until killed). */
  char view_png[600];
  snprintf(view_png, sizeof view_png, "%s/banks.png", root);
  snprintf(cmd, sizeof cmd,
           "timeout 120 xvfb-run -a -s '-screen 0 800x600x24' '%s' demo configs/rbf_fog_banks.ini "
           "--size 320x180 --frames 2 --screenshot '%s' >'%s' 2>&1",
           record_bin(), view_png, log);
  status = system(cmd);
  CHECK(status == 0, "demo of an rbf config with --screenshot: status %d", status);
  if (status != 0) record_print_log(log);
  fogmap shot = {0};
  CHECK(!fogmap_load(view_png, &(fogmap_load_desc){.channel = "R"}, &shot, &err) &&
            shot.width == 320 && shot.height == 180,
        "the view's screenshot: %s (%dx%d, expected 320x180)", err.message, shot.width,
        shot.height);
  fogmap_destroy(&shot);
  test_remove_tree(root);
  return test_finish("test_demo_window");
}
