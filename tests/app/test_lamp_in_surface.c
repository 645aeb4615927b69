/* A lamp a hair inside a surface (render/scene_lamp_shadow.c): the lamp tool sets a lamp a
 * height above the point clicked, so on a box's wall or roof rounding puts it just inside
 * about half the time. The shadow cube's face that looks into the surface then drew
 * nothing nearer than its near plane (1 cm) and the light escaped through the roof in a
 * hard-edged 90-degree pyramid: homogeneous fog above a box's roof glowed (in-scatter 0.3
 * to 0.7 where it is 0.05 with the lamp 2 cm down). Drawn with depth clamping, the roof is
 * in the cube at any distance: the lamp 5 mm, 2 cm and 10 cm under the roof draws the fog
 * outside the box alike (5 mm: 2 pixels differ; without depth clamping 3309). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "app/config.h"
#include "test_util.h"

enum { W = 160, H = 90 };
#include "frame_util.h"

static frame frames[3];

int main(void) {
  char folder[] = "/tmp/fogpipe_lamp_in_surface_XXXXXX";
  if (!test_scratch_folder(folder)) return 1;
  const double below[3] = {0.005, 0.02, 0.1}; /* under the roof at y = 10 */
  for (int k = 0; k < 3; k++) {
    char path[200], text[1024];
    snprintf(path, sizeof path, "%s/lamp%d.ini", folder, k);
    snprintf(text, sizeof text,
             "[terrain]\nheight = 0\n"
             "[objects]\nbox = 0 0 10 10 10\n"
             "[camera]\nposition = 30 25 40\nlook_at = 0 4 0\n"
             "[light]\nsun_colour = 0 0 0\nambient = 0 0 0\nlamp = 0 %.6f 0 4000 3300 2400\n"
             "[fog]\nmodel = homogeneous\ndensity_scale = 0.02\nalbedo = 0.9\n"
             "colour = 0 0 0\n",
             10.0 - below[k]);
    test_write_text(path, text);
    scene_config cfg;
    fog_error err = {0};
    CHECK(!scene_config_load(path, &cfg, &err), "%s: %s", path, err.message);
    if (err.message[0] || render(&cfg, &frames[k], path)) return test_finish("test_lamp_in_surface");
  }
  /* the fog's in-scatter outside the box, the lamp 5 mm and 10 cm down against 2 cm down:
   * the pixels that differ by more than half the 2 cm frame's largest value. A pixel or two
   * next to the lamp's own may (rays grazing the roof within the cube's documented slack,
   * epsilon times the distance, are lit or not as the lamp moves); the leak lit hundreds. */
  double peak = 0.0;
  for (int i = 0; i < W * H; i++) peak = fmax(peak, frames[1].inscatter[3 * i]);
  int differ[3] = {0, 0, 0};
  for (int k = 0; k < 3; k += 2)
    for (int i = 0; i < W * H; i++)
      differ[k] += fabs(frames[k].inscatter[3 * i] - frames[1].inscatter[3 * i]) > 0.5 * peak;
  printf("a lamp under a box's roof, against 2 cm down (largest in-scatter %.3e): %d pixels "
         "differ 5 mm down, %d 10 cm down\n", peak, differ[0], differ[2]);
  CHECK(peak > 0.0, "no light in the fog");
  for (int k = 0; k < 3; k += 2)
    CHECK(differ[k] <= 3, "the lamp %g cm under the roof: %d pixels differ (the light shines "
          "through the roof)", 100.0 * below[k], differ[k]);
  test_remove_tree(folder);
  return test_finish("test_lamp_in_surface");
}
