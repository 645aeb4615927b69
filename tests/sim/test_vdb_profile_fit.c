/* Fitting the vertical profile (sim/vdb_profile.c).
 *
 * The sequence profile over frames whose layers start at different heights
 * (vdb_profile_fit_columns): every frame's mass lands in the layers it overlaps, and the
 * summed array spans every frame's top. Reference: the mass per layer of y0 + j·h
 * computed by interval overlap with each frame's layers, fitted by vdb_profile_fit.
 * A frame half a layer above another used to be rounded onto the layer above and written
 * one past the end of the array (a heap overflow; its top layer's mass lost). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim/vdb_import.h"
#include "test_util.h"

enum { max_layers = 64 };

typedef struct frame {
  double y_min;
  int layers;
  double mass[max_layers];
} frame;

/* The reference: summed mass per layer [y0 + j h, y0 + (j+1) h) by overlap. */
static int reference_mass(const frame *frames, int count, double h, double y0, double *mass) {
  int layers = 0;
  for (int j = 0; j < 2 * max_layers; j++) {
    const double a = y0 + j * h, b = a + h;
    mass[j] = 0;
    for (int i = 0; i < count; i++)
      for (int l = 0; l < frames[i].layers; l++) {
        const double c = frames[i].y_min + l * h, d = c + h;
        const double overlap = fmin(b, d) - fmax(a, c);
        if (overlap > 1e-9 * h) mass[j] += frames[i].mass[l] * overlap / h;
      }
    if (mass[j] > 0) layers = j + 1;
  }
  return layers;
}

static void check_case(const char *name, frame *frames, int count, double h) {
  vdb_columns columns[4];
  const vdb_columns *pointers[4];
  double y0 = INFINITY;
  for (int i = 0; i < count; i++) {
    columns[i] = (vdb_columns){.layers = frames[i].layers, .y_min = frames[i].y_min,
                               .layer_height = h, .layer_mass = frames[i].mass};
    pointers[i] = &columns[i];
    y0 = fmin(y0, frames[i].y_min);
  }
  double mass[2 * max_layers];
  const int layers = reference_mass(frames, count, h, y0, mass);
  const vdb_profile_desc desc = {.kind = VDB_PROFILE_BSPLINE, .degree_box = 1};
  vdb_profile got, want;
  fog_error err = {0};
  CHECK(!vdb_profile_fit_columns(pointers, count, &desc, &got, &err), "%s: %s", name,
        err.message);
  CHECK(!vdb_profile_fit(mass, layers, y0, h, &desc, &want, &err), "%s: reference: %s", name,
        err.message);
  CHECK(got.count == want.count, "%s: %d layers in the profile, expected %d", name, got.count,
        want.count);
  CHECK(fabs(got.y_bottom - want.y_bottom) < 1e-12 && fabs(got.y_top - want.y_top) < 1e-12,
        "%s: profile spans [%.17g, %.17g], expected [%.17g, %.17g]", name, got.y_bottom,
        got.y_top, want.y_bottom, want.y_top);
  CHECK(fabs(got.thickness - want.thickness) < 1e-12 * want.thickness,
        "%s: thickness %.17g, expected %.17g", name, got.thickness, want.thickness);
  for (int k = 0; k < got.count && k < want.count; k++)
    CHECK(fabs(got.values[k] - want.values[k]) < 1e-12, "%s: layer %d: %.17g, expected %.17g",
          name, k, got.values[k], want.values[k]);
}

/* Nearly uniform fog in large units: a 20 m column of 50 layers, the bottom one 1.2e-5
 * denser. The exponential's scale height stays within what a scene config takes
 * (it was 1.4e7: the import's sidecar did not load), and its thickness is the closed form
 * of the scale height given, within the data's own: the column's mass per unit g. */
static void check_flat_exponential(void) {
  double mass[50];
  for (int l = 0; l < 50; l++) mass[l] = 0.4 * (l == 0 ? 1 + 1.2e-5 : 1);
  vdb_profile p;
  fog_error err = {0};
  const vdb_profile_desc desc = {.kind = VDB_PROFILE_EXPONENTIAL};
  CHECK(!vdb_profile_fit(mass, 50, 0.0, 0.4, &desc, &p, &err), "flat exponential: %s",
        err.message);
  CHECK(p.scale_height > 0 && p.scale_height <= 1e7,
        "flat exponential: scale height %.9g, expected in (0, 1e7] (a scene's largest)",
        p.scale_height);
  const double closed = p.scale_height * -expm1(-20.0 / p.scale_height);
  CHECK(fabs(p.thickness - closed) <= 1e-12 * closed,
        "flat exponential: thickness %.17g, expected H (1 - e^{-L/H}) = %.17g", p.thickness,
        closed);
  CHECK(fabs(p.thickness - 20.0) < 1e-4, "flat exponential: thickness %.9g, expected about 20",
        p.thickness);
}

int main(void) {
  check_flat_exponential();
  const double h = 0.1;
  frame frames[3];
  /* Half a layer apart (the first frame's span (2.0 + 0.05) / 0.1 rounds to 20.4999...). */
  frames[0] = (frame){.y_min = -0.05, .layers = 20};
  frames[1] = (frame){.y_min = 0.0, .layers = 20};
  for (int l = 0; l < 20; l++) frames[0].mass[l] = 1.0 + l, frames[1].mass[l] = 40.0 - l;
  check_case("half a layer apart", frames, 2, h);
  /* A quarter of a layer, the higher frame first. */
  frames[0].y_min = 0.325;
  frames[1].y_min = 0.3;
  check_case("a quarter apart", frames, 2, h);
  /* On one lattice, the heights differing by rounding only (0.1 * 3 vs 0.3). */
  frames[0] = (frame){.y_min = 0.1 * 3, .layers = 5, .mass = {1, 2, 3, 4, 5}};
  frames[1] = (frame){.y_min = 0.0, .layers = 4, .mass = {7, 0, 1, 2}};
  frames[2] = (frame){.y_min = 0.7, .layers = 3, .mass = {3, 3, 9}};
  check_case("one lattice", frames, 3, h);
  return test_finish("test_vdb_profile_fit");
}
