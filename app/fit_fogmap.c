/* The fogmap projection of fit's samples (app/fit_fogmap.h). */
#include "app/fit_fogmap.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int fit_fogmap_project(const fog_model *model, const double lo[3], const double hi[3], int side,
                       fit_fogmap *out, fog_error *err) {
  *out = (fit_fogmap){0};
  const double wide = fmax(hi[0] - lo[0], hi[2] - lo[2]);
  const int n[3] = {(int)ceil(side * (hi[0] - lo[0]) / wide), FIT_FOGMAP_LAYERS,
                    (int)ceil(side * (hi[2] - lo[2]) / wide)};
  fit_samples samples;
  fog_error serr = {0};
  if (fit_samples_create_grid(&samples, model, lo, hi, n, &serr))
    return fog_error_wrap(err, &serr, "projecting the fog to a fogmap: ");
  const fit_samples *s = &samples;
  const int nx = s->n[0], ny = s->n[1], nz = s->n[2];
  _Static_assert(FIT_FOGMAP_LAYERS <= SCENE_CONFIG_MAX_PROFILE, "a config holds the profile");
  /* the samples as import's columns: x the columns, z the rows, y the layers */
  vdb_columns c = {.width = nx, .height = nz, .origin_x = s->lo[0], .origin_z = s->lo[2],
                   .cell_x = s->cell[0], .cell_z = s->cell[2], .layers = ny,
                   .y_min = s->lo[1], .layer_height = s->cell[1]};
  c.tau = calloc((size_t)nx * nz, sizeof *c.tau);
  c.layer_mass = calloc((size_t)ny, sizeof *c.layer_mass);
  int status = 1;
  if (!c.tau || !c.layer_mass) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory projecting the fog to a fogmap");
    goto done;
  }
  const double area = s->cell[0] * s->cell[2];
  for (int l = 0; l < nz; l++)
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        const double k = s->k[((size_t)l * ny + j) * nx + i];
        c.tau[(size_t)l * nx + i] += k * s->cell[1]; /* midpoint rule up the column */
        c.layer_mass[j] += k * area;
        c.mass += k * area * s->cell[1];
      }
  if (!(c.mass > 0.0)) { /* no fog in the domain: nothing to project */
    status = -1;
    goto done;
  }
  /* degree 1, a knot per layer (FIT_FOGMAP_LAYERS <= SCENE_CONFIG_MAX_PROFILE) */
  if (vdb_profile_fit(c.layer_mass, ny, c.y_min, c.layer_height,
                      &(vdb_profile_desc){.kind = VDB_PROFILE_BSPLINE}, &out->profile, &serr) ||
      vdb_fogmap_place_fit(s->lo[0], s->hi[0], s->lo[2], s->hi[2], nx > nz ? nx : nz, 0.0,
                           0.0, &out->place, &serr) ||
      fogmap_create(&out->map, out->place.width, out->place.height, &serr) ||
      vdb_columns_resample(&c, &out->place, out->profile.thickness, &out->map, &serr)) {
    fog_error_wrap(err, &serr, "the fogmap rungs: ");
    fogmap_destroy(&out->map);
    goto done;
  }
  status = 0;
done:
  fit_samples_destroy(&samples);
  free(c.tau);
  free(c.layer_mass);
  return status;
}

void fit_fogmap_destroy(fit_fogmap *f) {
  fogmap_destroy(&f->map);
  *f = (fit_fogmap){0};
}

void fit_fogmap_apply(const fit_fogmap *f, const char *path, scene_config *c) {
  /* The input's light method carries over: a fog lit per piece of its walk (Perlin fog's
   * `auto`) stays so, which for the fogmap `auto` is not (docs/light.md). */
  if (scene_config_light_rule(c).pieces) c->shadow.pieces = 1;
  scene_fog_config *fog = &c->fog;
  fog->model = FOG_MODEL_FOGMAP;
  snprintf(fog->fogmap, sizeof fog->fogmap, "%s", path);
  fog->channel[0] = fog->vdb[0] = fog->sequence[0] = '\0';
  fog->rbf_count = fog->rbf_emitter_count = fog->quadric_count = 0;
  fog->rbf_base = 0.0;
  fog->density_scale = 1.0;
  fog->volume_step = 0.0;
  const vdb_profile *g = &f->profile;
  fog->profile = SCENE_PROFILE_BSPLINE;
  fog->profile_degree = g->degree;
  fog->profile_origin = g->origin;
  fog->profile_spacing = g->spacing;
  fog->profile_count = g->count;
  memcpy(fog->profile_coefficients, g->values, (size_t)g->count * sizeof g->values[0]);
  fog->profile_set = true;
  /* g's support: a degree-d B-spline reaches (d + 1)/2 spacings past its end knots */
  const double half = 0.5 * (g->degree + 1) * g->spacing;
  scene_box_config *box = &c->box;
  box->origin[0] = f->place.origin_x, box->origin[1] = f->place.origin_z;
  box->cell_size = f->place.cell_size;
  box->floor = g->origin - half;
  box->top = g->origin + (g->count - 1) * g->spacing + half;
  box->origin_set = box->cell_size_set = box->floor_set = box->top_set = true;
}
