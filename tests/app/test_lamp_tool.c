/* The window's lamp tool (app/lamp_tool.h), both sources' rules for the mouse: left places a
 * lamp `height` above the surface point, a held left drags the lamp it placed or picked
 * (even past the pick radius), left within 3 heights of a lamp (horizontally) picks it,
 * right removes the nearest within that radius (nothing farther) once a press however long
 * it is held, a drag keeps its lamp across frames over the sky, nothing over the sky or
 * past FOG_MAX_LAMPS, and the edits applied keep the other lamps in order; a new lamp's
 * height and intensity follow the scene's size. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "app/lamp_tool.h"
#include "test_util.h"

int main(void) {
  /* the valley's street lamp; a scene a tenth as wide: a tenth as high, 1/100 as bright */
  lamp_tool tool = lamp_tool_for_scene(1200), small = lamp_tool_for_scene(120);
  CHECK(tool.height == 8.0f && tool.intensity == 2000.0f && fabsf(small.height - 0.8f) < 1e-6f &&
            fabsf(small.intensity - 20.0f) < 1e-4f && small.placing == false &&
            small.dragged == -1 && small.height_range[0] < small.height &&
            small.height < small.height_range[1],
        "scaled defaults: height %g / %g, intensity %g / %g", tool.height, small.height,
        tool.intensity, small.intensity);
  tool.height = 10.0f;
  fog_lamps lamps = {0};
  const double a[3] = {100, 5, -40}, b[3] = {300, 7, 60}, near_a[3] = {120, 2, -30};

  lamp_edit e = lamp_tool_update(&tool, true, false, a, &lamps);
  CHECK(e.kind == LAMP_EDIT_PLACE && e.index == 0 && e.position[0] == 100 &&
            e.position[1] == 15 && e.position[2] == -40,
        "left on the ground: kind %d index %d at (%g %g %g), expected a new lamp 10 above "
        "(100 5 -40)", (int)e.kind, e.index, e.position[0], e.position[1], e.position[2]);
  CHECK(fabs(e.intensity[0] - (double)tool.colour[0] * tool.intensity) < 1e-9 &&
            fabs(e.intensity[2] - (double)tool.colour[2] * tool.intensity) < 1e-9,
        "intensity (%g %g %g): expected colour x intensity", e.intensity[0], e.intensity[1],
        e.intensity[2]);
  lamp_edit_apply(&e, &lamps);
  CHECK(lamps.count == 1 && lamps.lamp[0].kind == FOG_LAMP_POINT &&
            lamps.lamp[0].radius == LAMP_TOOL_RADIUS && lamps.lamp[0].position[1] == 15,
        "applied: %d lamps, radius %g, y %g", lamps.count, lamps.lamp[0].radius,
        lamps.lamp[0].position[1]);

  /* held: the lamp follows the cursor however far it goes */
  e = lamp_tool_update(&tool, true, false, b, &lamps);
  CHECK(e.kind == LAMP_EDIT_MOVE && e.index == 0 && e.position[0] == 300 && e.position[1] == 17,
        "held left far away: kind %d index %d x %g y %g, expected lamp 0 dragged to (300 17)",
        (int)e.kind, e.index, e.position[0], e.position[1]);
  lamp_edit_apply(&e, &lamps);
  /* released; a click far from it places a second one */
  e = lamp_tool_update(&tool, false, false, NULL, &lamps);
  CHECK(e.kind == LAMP_EDIT_NONE && tool.dragged == -1, "released: kind %d dragged %d",
        (int)e.kind, tool.dragged);
  e = lamp_tool_update(&tool, true, false, a, &lamps);
  CHECK(e.kind == LAMP_EDIT_PLACE && e.index == 1, "a click far from lamp 0: kind %d index %d",
        (int)e.kind, e.index);
  lamp_edit_apply(&e, &lamps);
  lamp_tool_update(&tool, false, false, NULL, &lamps);
  /* a click within 3 heights of lamp 1 (22 units away horizontally) picks it */
  e = lamp_tool_update(&tool, true, false, near_a, &lamps);
  CHECK(e.kind == LAMP_EDIT_MOVE && e.index == 1, "a click 22 units from lamp 1: kind %d "
        "index %d, expected it moved", (int)e.kind, e.index);
  lamp_tool_update(&tool, false, false, NULL, &lamps);
  /* the sky (no surface point): nothing, and no drag */
  e = lamp_tool_update(&tool, true, false, NULL, &lamps);
  CHECK(e.kind == LAMP_EDIT_NONE && tool.dragged == -1, "over the sky: kind %d", (int)e.kind);
  /* right far from every lamp: nothing; near lamp 0: it goes, lamp 1 moves down */
  const double nowhere[3] = {-500, 0, -500};
  e = lamp_tool_update(&tool, false, true, nowhere, &lamps);
  CHECK(e.kind == LAMP_EDIT_NONE, "right far from the lamps: kind %d", (int)e.kind);
  lamp_tool_update(&tool, false, false, NULL, &lamps);
  const double at_b[3] = {305, 0, 58};
  e = lamp_tool_update(&tool, false, true, at_b, &lamps);
  CHECK(e.kind == LAMP_EDIT_REMOVE && e.index == 0, "right by lamp 0: kind %d index %d",
        (int)e.kind, e.index);
  const fog_lamp second = lamps.lamp[1];
  lamp_edit_apply(&e, &lamps);
  CHECK(lamps.count == 1 && !memcmp(&lamps.lamp[0], &second, sizeof second),
        "after removing lamp 0: %d lamps, the second not moved down intact", lamps.count);
  /* right held on over more frames (a click lasts a few): no more removals until the next
   * press (it removed one lamp a frame, every lamp near the cursor) */
  {
    fog_lamps three = {.count = 3};
    for (int i = 0; i < 3; i++)
      three.lamp[i] = (fog_lamp){.kind = FOG_LAMP_POINT, .position = {30.0 * i, 10, 0}};
    const double by_first[3] = {10, 0, 0};
    lamp_tool_update(&tool, false, false, NULL, &three); /* the last press let go */
    int removed = 0;
    for (int frame = 0; frame < 4; frame++) {
      lamp_edit r = lamp_tool_update(&tool, false, true, by_first, &three);
      if (r.kind == LAMP_EDIT_REMOVE) removed++, lamp_edit_apply(&r, &three);
    }
    CHECK(removed == 1 && three.count == 2, "right held 4 frames removed %d lamps", removed);
    lamp_tool_update(&tool, false, false, NULL, &three);
    lamp_edit r = lamp_tool_update(&tool, false, true, by_first, &three);
    CHECK(r.kind == LAMP_EDIT_REMOVE, "a second press removed nothing (kind %d)", (int)r.kind);
    /* the tool turned off with right still held, then on: the next press removes one */
    lamp_tool_idle(&tool);
    r = lamp_tool_update(&tool, false, true, by_first, &three);
    CHECK(r.kind == LAMP_EDIT_REMOVE, "a press after the tool was off: kind %d", (int)r.kind);
    lamp_tool_update(&tool, false, false, NULL, &three);
  }
  /* a drag across the sky (no surface point for a frame) keeps its lamp: the cursor back on
   * the ground far away moves it there, no second lamp placed */
  {
    fog_lamps one = {0};
    const double start[3] = {0, 0, 0}, mid[3] = {100, 0, 0}, back[3] = {200, 0, 0};
    lamp_edit r = lamp_tool_update(&tool, true, false, start, &one);
    lamp_edit_apply(&r, &one);
    r = lamp_tool_update(&tool, true, false, mid, &one);
    lamp_edit_apply(&r, &one);
    r = lamp_tool_update(&tool, true, false, NULL, &one);
    CHECK(r.kind == LAMP_EDIT_NONE, "over the sky mid-drag: kind %d", (int)r.kind);
    r = lamp_tool_update(&tool, true, false, back, &one);
    CHECK(r.kind == LAMP_EDIT_MOVE && r.index == 0 && r.position[0] == 200,
          "back on the ground mid-drag: kind %d index %d x %g, expected lamp 0 moved to 200",
          (int)r.kind, r.index, r.position[0]);
    lamp_edit_apply(&r, &one);
    CHECK(one.count == 1, "a drag across the sky left %d lamps", one.count);
    lamp_tool_update(&tool, false, false, NULL, &one);
  }
  /* full: a click away from every lamp places nothing; one on a lamp still drags it */
  lamp_tool_update(&tool, false, false, NULL, &lamps);
  for (int i = lamps.count; i < FOG_MAX_LAMPS; i++) lamps.lamp[lamps.count++] = second;
  e = lamp_tool_update(&tool, true, false, nowhere, &lamps);
  CHECK(e.kind == LAMP_EDIT_NONE, "%d lamps (the most): a click away placed one (kind %d)",
        lamps.count, (int)e.kind);
  e = lamp_tool_update(&tool, true, false, near_a, &lamps);
  CHECK(e.kind == LAMP_EDIT_MOVE, "%d lamps: a click on one did not pick it (kind %d)",
        lamps.count, (int)e.kind);
  return test_finish("test_lamp_tool");
}
