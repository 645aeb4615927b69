/* The sun's colour as the window's panel edits it: a hue (its largest channel 1) and a
 * strength (the colour's largest channel), and back. */
#ifndef FOGPIPE_APP_SUN_HUE_H
#define FOGPIPE_APP_SUN_HUE_H

/* colour = hue x strength. A colour of strength 0 (black) has no hue of its own: hue keeps
 * what it holds (the caller's last hue), so that a sun dimmed to 0 and up again comes back
 * in its colour, not white. */
void sun_hue_split(const double colour[3], float hue[3], float *strength);
/* Each channel at most SCENE_CONFIG_MAX_RADIANCE (a hue channel may be typed past 1). */
void sun_hue_join(const float hue[3], float strength, double colour[3]);

#endif
