/* fog_pyramid: the owned grids of one wavelet pyramid (render/fog_field.h). */
#include <stdlib.h>

#include "render/fog_field.h"

int fog_pyramid_create(fog_pyramid *pyramid, const float *density, int width, int height,
                       int degree, int levels, transform_boundary boundary, fog_error *err) {
  *pyramid = (fog_pyramid){0};
  if (levels < 0 || levels > FOG_MAX_LEVELS)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "pyramid levels %d: expected 0..%d", levels,
                    FOG_MAX_LEVELS);
  const transform_desc desc = {.width = width, .height = height, .levels = levels,
                               .basis = transform_basis_of_degree(degree), .boundary = boundary};
  fog_error terr = {0};
  transform_plan *plan = transform_plan_create(&desc, &terr);
  if (!plan) return fog_error_pass(err, &terr);
  float *coefficients = transform_alloc_floats((size_t)width * height);
  float *approx[FOG_MAX_LEVELS + 1] = {0}, *detail[FOG_MAX_LEVELS + 1] = {0};
  int status =
      coefficients ? 0 : fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the fog transform");
  for (int l = 0; l <= levels && !status; l++) {
    int w, h;
    transform_level_size(plan, l, &w, &h);
    approx[l] = transform_alloc_floats((size_t)w * h);
    detail[l] = transform_alloc_floats((size_t)w * h);
    if (!approx[l] || !detail[l])
      status = fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the fog pyramid");
  }
  if (!status) {
    transform_forward(plan, density, coefficients);
    /* non-negative levels (a ray never gains light) and the fogmap itself as A_J; fog_pass
     * binds every slot of the pyramid (details too) whatever the LOD method */
    if (transform_density_pyramid(plan, density, coefficients, approx, detail, &terr))
      status = fog_error_wrap(err, &terr, "fog pyramid: ");
  }
  for (int l = 0; l <= levels && !status; l++)
    if (transform_grid_create_level(plan, l, approx[l], &pyramid->approx[l], &terr) ||
        (l > 0 && transform_grid_create_level(plan, l, detail[l], &pyramid->detail[l], &terr)))
      status = fog_error_wrap(err, &terr, "fog pyramid: ");
  for (int l = 0; l <= FOG_MAX_LEVELS; l++) free(approx[l]), free(detail[l]);
  free(coefficients);
  transform_plan_destroy(plan);
  if (status) {
    fog_pyramid_destroy(pyramid);
    return 1;
  }
  pyramid->levels = levels;
  pyramid->degree = transform_basis_degree(desc.basis);
  pyramid->has_details = levels > 0;
  return 0;
}

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
