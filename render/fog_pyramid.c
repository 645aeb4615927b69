/* fog_pyramid: the owned grids of one wavelet pyramid (render/fog_field.h). */
#include "render/fog_field.h"

void fog_pyramid_destroy(fog_pyramid *pyramid) {
  for (int l = 0; l <= FOG_MAX_LEVELS; l++) {
    transform_grid_destroy(&pyramid->approx[l]);
    transform_grid_destroy(&pyramid->detail[l]);
  }
  *pyramid = (fog_pyramid){0};
}

fog_lod fog_pyramid_lod(const fog_pyramid *pyramid, double mu) {
  return (fog_lod){.levels = pyramid->levels, .approx = pyramid->approx,
                   .detail = &pyramid->detail[1], .mu = mu};
}
