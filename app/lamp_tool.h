/* The window's lamp tool (docs/demo.md, Lamps), shared by both fog sources: the mouse
 * places point lamps on the surface (left), drags the lamp nearest the cursor (left held on
 * it) and removes it (right). The tool reads the mouse and decides; each source applies
 * the edit to what it holds (the live pipeline's lamps, or the window's copy of the config,
 * so that a remade fog and a saved scene keep them). */
#ifndef FOGPIPE_APP_LAMP_TOOL_H
#define FOGPIPE_APP_LAMP_TOOL_H

#include <stdbool.h>

#include "app/panel.h"
#include "render/fog_lamp.h"

typedef struct lamp_tool {
  bool placing;    /* the panel's checkbox: the mouse places lamps (else it paints) */
  float colour[3]; /* a new lamp's colour x intensity is its radiant intensity */
  float intensity;
  float height;    /* above the surface clicked, world units */
  int dragged;     /* the lamp the held button moves; -1: none */
  bool right_held; /* right was down the frame before (a removal is once a press) */
  /* the panel sliders' ranges, from the scene's size */
  float intensity_range[2], height_range[2];
} lamp_tool;

/* Off, warm white, at the scale of a scene `scene_size` wide (the terrain's larger side): a
 * street lamp in the 1200-unit valley, 8 units up at 2000, and in a scene s wide 8 s / 1200
 * units up at 2000 (s / 1200)^2, so it lights the same share of the ground. */
lamp_tool lamp_tool_for_scene(double scene_size);

typedef enum lamp_edit_kind {
  LAMP_EDIT_NONE = 0,
  LAMP_EDIT_PLACE,  /* a new point lamp at position, of intensity, radius LAMP_TOOL_RADIUS */
  LAMP_EDIT_MOVE,   /* lamp `index` to position */
  LAMP_EDIT_REMOVE, /* lamp `index`; the later ones move down one */
} lamp_edit_kind;

typedef struct lamp_edit {
  lamp_edit_kind kind;
  int index;
  double position[3], intensity[3];
} lamp_edit;

#define LAMP_TOOL_RADIUS 0.5

/* What the window says when the fog pass refused the lamps' light (the renderer's loop
 * cap) and the frame was drawn without it. */
#define LAMP_TOOL_DROPPED_NOTE                                                         \
  "the lamps' light in this fog is not drawn:\nit needs more shader loops a pixel than\n" \
  "this renderer runs (docs/platform.md)"

/* One frame of the tool: the buttons held, the surface point under the cursor (NULL: none,
 * over the sky or the panel) and the lamps shown. Left places a lamp `height` above hit,
 * or (within 3 heights of a lamp, horizontally, or while dragging one) moves it there; a
 * drag lasts while left is held, across frames with no hit; right removes the nearest
 * within 3 heights, once a press. Nothing once FOG_MAX_LAMPS are placed. */
lamp_edit lamp_tool_update(lamp_tool *tool, bool left, bool right, const double *hit,
                           const fog_lamps *lamps);
/* A frame the tool is off (the panel's checkbox cleared): its drag and its right button
 * forgotten, so that a press held when it was turned off does not hide the next one. */
void lamp_tool_idle(lamp_tool *tool);
/* The edit applied to lamps (the pipeline's list). */
void lamp_edit_apply(const lamp_edit *edit, fog_lamps *lamps);

/* The panel's "lamps" section (app/lamp_tool_panel.c, in the executable): the checkbox,
 * colour, intensity, height, the count and the source's note (NULL or "": none); with
 * `animated` lamps (the config's lamp_path or lamp_flicker) the tool is off: they follow
 * the clock. */
void lamp_tool_panel(panel *ui, lamp_tool *tool, int lamp_count, bool animated,
                     const char *note);

#endif
