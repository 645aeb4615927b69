/* The Gaussian brush (app/rbf_brush.h). */
#include "app/rbf_brush.h"

#include <math.h>

rbf_brush rbf_brush_for(const fog_rbf *rbfs, int count, double size, double fallback_density) {
  double radius = size / 40.0, density = fallback_density;
  if (count > 0) {
    radius = density = 0.0;
    for (int i = 0; i < count; i++) radius += rbfs[i].radius, density += rbfs[i].density;
    radius /= count, density /= count;
  }
  return (rbf_brush){.radius = radius, .density = density, .spacing = 0.5 * radius,
                     .lift = 0.5 * radius};
}

double rbf_brush_stroke_start(const rbf_brush *brush) { return brush->spacing; }

static bool append(rbf_bank *bank, const fog_rbf *g) {
  if (bank->count >= bank->capacity) return false;
  bank->rbfs[bank->count++] = *g;
  return true;
}

int rbf_brush_stroke(rbf_bank *bank, const rbf_brush *brush, const double from[3],
                     const double to[3], double *carried) {
  double d[3], length = 0.0;
  for (int a = 0; a < 3; a++) d[a] = to[a] - from[a], length += d[a] * d[a];
  length = sqrt(length);
  int added = 0;
  /* the stroke's points at s = spacing - carried, + spacing, ... along this segment */
  double s = brush->spacing - *carried;
  if (s < 0.0) s = 0.0;
  for (; s <= length; s += brush->spacing) {
    const double f = length > 0.0 ? s / length : 0.0;
    fog_rbf g = {.radius = brush->radius, .density = brush->density};
    for (int a = 0; a < 3; a++) g.centre[a] = from[a] + f * d[a];
    g.centre[1] += brush->lift;
    if (!append(bank, &g)) break;
    added++;
    *carried = length - s; /* the stroke since this one */
  }
  if (added == 0) *carried += length;
  return added;
}

static double horizontal_distance(const double a[3], const double b[3]) {
  return hypot(a[0] - b[0], a[2] - b[2]);
}

int rbf_brush_erase(rbf_bank *bank, const double p[3], double reach) {
  int kept = 0;
  for (int i = 0; i < bank->count; i++)
    if (!(horizontal_distance(bank->rbfs[i].centre, p) <= reach))
      bank->rbfs[kept++] = bank->rbfs[i];
  int removed = bank->count - kept;
  bank->count = kept;
  return removed;
}

int rbf_brush_copy(rbf_bank *bank, const double from[3], double reach, const double to[3]) {
  const int existing = bank->count; /* the copies themselves are not copied again */
  int added = 0;
  for (int i = 0; i < existing; i++) {
    if (!(horizontal_distance(bank->rbfs[i].centre, from) <= reach)) continue;
    fog_rbf g = bank->rbfs[i];
    for (int a = 0; a < 3; a++) g.centre[a] += to[a] - from[a];
    if (!append(bank, &g)) break;
    added++;
  }
  return added;
}
