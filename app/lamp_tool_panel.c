/* The lamp tool's panel section (app/lamp_tool.h): with the window program, beside the
 * ImGui adapter (the tool's rules are in the library, app/lamp_tool.c). */
#include "app/lamp_tool.h"

void lamp_tool_panel(panel *ui, lamp_tool *tool, int lamp_count, bool animated,
                     const char *note) {
  if (!panel_header(ui, "lamps", false)) return;
  if (note && note[0]) panel_text(ui, "%s", note);
  if (animated) {
    tool->placing = false;
    panel_text(ui, "%d lamps on the config's paths (lamp_path, lamp_flicker):", lamp_count);
    panel_text(ui, "they follow the clock; the lamp tool is off");
    return;
  }
  panel_checkbox(ui, "place lamps with the mouse", &tool->placing);
  panel_color3(ui, "lamp colour", tool->colour);
  panel_slider_float(ui, "lamp intensity", &tool->intensity, tool->intensity_range[0],
                     tool->intensity_range[1], "%.4g", true);
  panel_slider_float(ui, "lamp height", &tool->height, tool->height_range[0],
                     tool->height_range[1], "%.4g", true);
  panel_text(ui, "left: place / drag a lamp   right: remove");
  panel_text(ui, "%d of %d lamps (scattered with albedo > 0)", lamp_count, FOG_MAX_LAMPS);
}
