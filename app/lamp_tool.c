/* The window's lamp tool (app/lamp_tool.h). */
#include "app/lamp_tool.h"

#include <math.h>
#include <string.h>

lamp_tool lamp_tool_for_scene(double scene_size) {
  const double k = scene_size > 0 ? scene_size / 1200.0 : 1.0;
  const float height = (float)(8.0 * k), intensity = (float)(2000.0 * k * k);
  return (lamp_tool){.colour = {1.0f, 0.8f, 0.55f}, .intensity = intensity, .height = height,
                     .dragged = -1,
                     .intensity_range = {intensity / 200.0f, intensity * 10.0f},
                     .height_range = {height / 16.0f, height * 12.5f}};
}

lamp_edit lamp_tool_update(lamp_tool *tool, bool left, bool right, const double *hit,
                           const fog_lamps *lamps) {
  lamp_edit edit = {.kind = LAMP_EDIT_NONE, .index = -1};
  /* right acts once a press: held over several frames (a click lasts a few) it removed one
   * lamp a frame, every lamp near the cursor */
  const bool right_pressed = right && !tool->right_held;
  tool->right_held = right;
  /* a drag ends when left is let go; over the sky or the panel (no hit) it waits, so the
   * lamp is picked up again where the cursor comes back (it was dropped, and a new lamp
   * placed there) */
  if (!left) tool->dragged = -1;
  if (!(left || right) || !hit) return edit;
  int nearest = -1;
  double best = 3.0 * tool->height;
  for (int i = 0; i < lamps->count; i++) {
    double dx = lamps->lamp[i].position[0] - hit[0], dz = lamps->lamp[i].position[2] - hit[2];
    if (sqrt(dx * dx + dz * dz) < best) best = sqrt(dx * dx + dz * dz), nearest = i;
  }
  if (right) {
    tool->dragged = -1;
    if (right_pressed && nearest >= 0)
      edit = (lamp_edit){.kind = LAMP_EDIT_REMOVE, .index = nearest};
    return edit;
  }
  int moved = tool->dragged >= 0 && tool->dragged < lamps->count ? tool->dragged : nearest;
  if (moved < 0 && lamps->count == FOG_MAX_LAMPS) return edit;
  edit.kind = moved < 0 ? LAMP_EDIT_PLACE : LAMP_EDIT_MOVE;
  edit.index = moved < 0 ? lamps->count : moved;
  memcpy(edit.position, hit, sizeof edit.position);
  edit.position[1] += tool->height;
  for (int c = 0; c < 3; c++) edit.intensity[c] = (double)tool->colour[c] * tool->intensity;
  tool->dragged = edit.index;
  return edit;
}

void lamp_tool_idle(lamp_tool *tool) {
  tool->dragged = -1;
  tool->right_held = false;
}

void lamp_edit_apply(const lamp_edit *edit, fog_lamps *lamps) {
  switch (edit->kind) {
    case LAMP_EDIT_PLACE:
      lamps->lamp[lamps->count++] = (fog_lamp){
          .kind = FOG_LAMP_POINT, .radius = LAMP_TOOL_RADIUS,
          .position = {edit->position[0], edit->position[1], edit->position[2]},
          .intensity = {edit->intensity[0], edit->intensity[1], edit->intensity[2]}};
      break;
    case LAMP_EDIT_MOVE:
      memcpy(lamps->lamp[edit->index].position, edit->position, sizeof edit->position);
      break;
    case LAMP_EDIT_REMOVE:
      for (int i = edit->index; i + 1 < lamps->count; i++) lamps->lamp[i] = lamps->lamp[i + 1];
      lamps->count--;
      break;
    case LAMP_EDIT_NONE:
      break;
  }
}
