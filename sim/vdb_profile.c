/* The vertical profile g(y) of an imported fog grid: a centred B-spline (degree 0 or 1)
 * or an exponential fitted to the mean vertical distribution (mass per layer), normalised
 * to max g = 1 so that f = tau / ∫g dy is the extinction at the densest height and
 * f·∫g dy is the column optical depth exactly (sim/vdb_import.h). The parameters are
 * those of render/fog_field.h's fog_profile. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/vdb_import.h"

/* Mean height of the truncated exponential density e^{-s/H} on [0, L]:
 *   m(H) = H - L/(e^{L/H} - 1),  m -> L/2 as H -> inf; increasing in H. */
static double exponential_mean(double H, double L) {
  const double x = L / H;
  if (x < 1e-6) return L * (0.5 - x / 12.0);
  return H - L / expm1(x);
}

int vdb_profile_fit(const double *layer_mass, int layers, double y_min, double layer_height,
                    const vdb_profile_desc *desc, vdb_profile *out, fog_error *err) {
  *out = (vdb_profile){0};
  const double L = layers * layer_height;
  double total = 0, moment = 0;
  for (int l = 0; l < layers; l++) {
    total += layer_mass[l];
    moment += layer_mass[l] * (l + 0.5) * layer_height;
  }
  if (layers <= 0 || !(total > 0) || !isfinite(total) || !(L > 0)) {
    fog_fail(err, FOG_ERR_BAD_FILE, "cannot fit a vertical profile: total mass %g over %d layers",
             total, layers);
    return 1;
  }
  out->kind = desc ? desc->kind : VDB_PROFILE_BSPLINE;
  if (out->kind == VDB_PROFILE_EXPONENTIAL) {
    /* Moment fit: the scale height whose truncated exponential has the data's mean
     * height (bisection; m(H) is increasing). Mean in the upper half: a slab. */
    const double mean = moment / total;
    out->y_bottom = y_min;
    out->y_top = y_min + L;
    if (mean >= 0.5 * L * (1 - 1e-9)) {
      out->scale_height = 0;
      out->thickness = L;
      return 0;
    }
    /* at most a scene's largest scale height: nearly uniform fog in large units (a 20 m
     * column 1.2e-5 denser at its foot) fitted 1.4e7, a sidecar no scene loaded; the
     * profile at the cap differs from the data's by less than L / 1e7 in g */
    double lo = 1e-6 * L, hi = fmin(1e6 * L, VDB_PROFILE_MAX_SCALE_HEIGHT);
    if (lo > hi) lo = hi;
    const double target = fmax(mean, exponential_mean(lo, L));
    for (int it = 0; it < 200; it++) {
      const double mid = sqrt(lo * hi); /* geometric: H spans many decades */
      if (exponential_mean(mid, L) < target)
        lo = mid;
      else
        hi = mid;
    }
    const double H = sqrt(lo * hi);
    out->scale_height = H;
    out->thickness = -H * expm1(-L / H); /* ∫_0^L e^{-s/H} ds */
    return 0;
  }
  /* B-spline: span k of the height range carries the mean density of the layers it
   * covers (conservative, non-negative); coefficient k = that mean / the largest. */
  int n = desc && desc->knots > 0 ? desc->knots : layers;
  if (n > VDB_PROFILE_MAX_KNOTS) n = VDB_PROFILE_MAX_KNOTS;
  const double h = L / n;
  double values[VDB_PROFILE_MAX_KNOTS] = {0};
  for (int l = 0; l < layers; l++) {
    const double a0 = l * layer_height, a1 = a0 + layer_height;
    const double density = layer_mass[l] / layer_height; /* mass per unit height */
    for (int k = (int)floor(a0 / h); k <= (int)floor(a1 / h) && k < n; k++) {
      if (k < 0) continue;
      const double overlap = fmin(a1, (k + 1) * h) - fmax(a0, k * h);
      if (overlap > 0) values[k] += density * overlap / h;
    }
  }
  double peak = 0;
  for (int k = 0; k < n; k++) peak = fmax(peak, values[k]);
  double sum = 0;
  for (int k = 0; k < n; k++) {
    out->values[k] = values[k] / peak;
    sum += out->values[k];
  }
  out->degree = desc && desc->degree_box ? 0 : 1;
  out->count = n;
  out->spacing = h;
  out->origin = y_min + 0.5 * h;
  const double reach = 0.5 * (out->degree + 1) * h;
  out->y_bottom = out->origin - reach;
  out->y_top = out->origin + (n - 1) * h + reach;
  out->thickness = h * sum; /* every centred B-spline integrates to one spacing */
  return 0;
}

/* (y_min - y0) / h, snapped to the whole number within 1e-6 of it: frames on one voxel
 * lattice differ by rounding in their world heights. */
static double layer_offset(double y_min, double y0, double h) {
  const double offset = (y_min - y0) / h, whole = round(offset);
  return fabs(offset - whole) < 1e-6 ? whole : offset;
}

int vdb_profile_fit_columns(const vdb_columns *const *columns, int count,
                            const vdb_profile_desc *desc, vdb_profile *out, fog_error *err) {
  int first = 0; /* the first frame with fog (one without has no layers) */
  while (first < count && !columns[first]->layers) first++;
  if (first == count) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "no frames with fog to fit a profile to");
    return 1;
  }
  const double h = columns[first]->layer_height;
  double y0 = columns[first]->y_min;
  for (int i = first + 1; i < count; i++) {
    if (!columns[i]->layers) continue;
    if (fabs(columns[i]->layer_height - h) > 1e-9 * h) {
      fog_fail(err, FOG_ERR_BAD_FILE,
               "frames have different layer heights (%g and %g): fit the profile per frame", h,
               columns[i]->layer_height);
      return 1;
    }
    y0 = fmin(y0, columns[i]->y_min);
  }
  /* Each frame's layers start `offset` layers above y0: a whole number on the lowest
   * frame's lattice (to rounding), where each layer lands on one; a fraction where a
   * container moved by part of a voxel, where each layer's mass is shared between the two
   * layers it overlaps by the overlap. The array spans every frame's top (rounding each
   * frame's offset apart from the span wrote one past its end). */
  int layers = 0;
  for (int i = first; i < count; i++) {
    if (!columns[i]->layers) continue;
    const int top = (int)ceil(layer_offset(columns[i]->y_min, y0, h)) + columns[i]->layers;
    if (top > layers) layers = top;
  }
  double *mass = calloc((size_t)layers, sizeof(double));
  if (!mass) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for %d layers", layers);
    return 1;
  }
  for (int i = first; i < count; i++) {
    if (!columns[i]->layers) continue;
    const double offset = layer_offset(columns[i]->y_min, y0, h);
    const int base = (int)floor(offset);
    const double above = offset - base; /* the share of each layer in the one above */
    for (int l = 0; l < columns[i]->layers; l++) {
      mass[base + l] += (1 - above) * columns[i]->layer_mass[l];
      if (above > 0) mass[base + l + 1] += above * columns[i]->layer_mass[l];
    }
  }
  int status = vdb_profile_fit(mass, layers, y0, h, desc, out, err);
  free(mass);
  return status;
}

/* Centred B-splines of degree 0 and 1 (render/fog_field.h). */
static double bspline(int degree, double x) {
  if (degree == 0) return x >= -0.5 && x < 0.5 ? 1.0 : 0.0;
  const double a = fabs(x);
  return a < 1 ? 1 - a : 0;
}

double vdb_profile_eval(const vdb_profile *p, double y) {
  if (!(y >= p->y_bottom && y <= p->y_top)) return 0;
  if (p->kind == VDB_PROFILE_EXPONENTIAL)
    return p->scale_height > 0 ? exp(-(y - p->y_bottom) / p->scale_height) : 1.0;
  const double x = (y - p->origin) / p->spacing;
  const int k0 = (int)floor(x) - 1;
  double g = 0;
  for (int k = k0; k <= k0 + 2; k++)
    if (k >= 0 && k < p->count) g += p->values[k] * bspline(p->degree, x - k);
  return g;
}
