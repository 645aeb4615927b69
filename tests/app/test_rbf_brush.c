/* The Gaussian brush (app/rbf_brush.h), against what a stroke must give:
 *   - a straight stroke of length L paints floor(L / spacing) + 1 Gaussians, one spacing
 *     apart along it from its first point, each `lift` above its point, with the brush's
 *     radius and density;
 *   - the same stroke drawn as many short segments (frames of a drag, most shorter than the
 *     spacing) paints the same Gaussians;
 *   - erase takes exactly those within reach horizontally, the rest keep their order;
 *   - copy puts the group within reach down again moved by the offset, the originals kept;
 *   - a full bank takes no more (stroke and copy stop at its capacity);
 *   - the brush for a bank takes its mean radius and density. */
#include <math.h>
#include <stdio.h>

#include "app/rbf_brush.h"
#include "test_util.h"

enum { CAPACITY = 64 };

static bool near(double a, double b) { return fabs(a - b) <= 1e-12 * fmax(1.0, fabs(b)); }

static void check_stroke(const rbf_bank *bank, const rbf_brush *b, const double from[3],
                         const double dir[3], int want, const char *what) {
  CHECK(bank->count == want, "%s: %d Gaussians, want %d", what, bank->count, want);
  for (int i = 0; i < bank->count && i < want; i++) {
    const fog_rbf *g = &bank->rbfs[i];
    double expect[3];
    for (int a = 0; a < 3; a++) expect[a] = from[a] + i * b->spacing * dir[a];
    expect[1] += b->lift;
    CHECK(near(g->centre[0], expect[0]) && near(g->centre[1], expect[1]) &&
              near(g->centre[2], expect[2]) && g->radius == b->radius && g->density == b->density,
          "%s: Gaussian %d at %g %g %g r %g c %g, want %g %g %g", what, i, g->centre[0],
          g->centre[1], g->centre[2], g->radius, g->density, expect[0], expect[1], expect[2]);
  }
}

int main(void) {
  const rbf_brush b = {.radius = 4.0, .density = 0.03, .spacing = 2.0, .lift = 1.5};
  const double from[3] = {10, 5, -3}, dir[3] = {0.6, 0.0, 0.8}, length = 13.0;
  double to[3];
  for (int a = 0; a < 3; a++) to[a] = from[a] + length * dir[a];
  const int want = (int)floor(length / b.spacing) + 1; /* 7 */

  fog_rbf one[CAPACITY], many[CAPACITY];
  rbf_bank whole = {.rbfs = one, .capacity = CAPACITY};
  double carried = rbf_brush_stroke_start(&b);
  CHECK(rbf_brush_stroke(&whole, &b, from, to, &carried) == want, "one segment");
  check_stroke(&whole, &b, from, dir, want, "one segment");

  /* the drag's frames: segments of 0.7 (shorter than the spacing) */
  rbf_bank pieces = {.rbfs = many, .capacity = CAPACITY};
  carried = rbf_brush_stroke_start(&b);
  double at[3] = {from[0], from[1], from[2]};
  for (double s = 0.0; s < length;) {
    double next = fmin(length, s + 0.7), p[3];
    for (int a = 0; a < 3; a++) p[a] = from[a] + next * dir[a];
    rbf_brush_stroke(&pieces, &b, at, p, &carried);
    for (int a = 0; a < 3; a++) at[a] = p[a];
    s = next;
  }
  check_stroke(&pieces, &b, from, dir, want, "many segments");

  /* erase: reach 3 around the stroke's point at 6 takes those at 4, 6, 8 (not 2 or 10) */
  double p[3];
  for (int a = 0; a < 3; a++) p[a] = from[a] + 6.0 * dir[a];
  p[1] += 50; /* horizontally: the height does not matter */
  CHECK(rbf_brush_erase(&whole, p, 3.0) == 3 && whole.count == want - 3,
        "erase: %d left, want %d", whole.count, want - 3);
  const double kept_at[4] = {0, 2, 10, 12};
  for (int i = 0; i < whole.count && i < 4; i++)
    CHECK(near(whole.rbfs[i].centre[0], from[0] + kept_at[i] * dir[0]),
          "erase: Gaussian %d at x %g, want the one at %g along the stroke", i,
          whole.rbfs[i].centre[0], kept_at[i]);

  /* copy: the two first ones (reach 2.5 around the stroke's start) to 100 units away */
  const double dest[3] = {from[0] + 100, from[1] - 7, from[2] + 40};
  const int before = whole.count;
  CHECK(rbf_brush_copy(&whole, from, 2.5, dest) == 2 && whole.count == before + 2,
        "copy: %d added", whole.count - before);
  for (int i = 0; i < 2 && before + i < whole.count; i++) {
    const fog_rbf *c = &whole.rbfs[before + i], *o = &whole.rbfs[i];
    CHECK(near(c->centre[0], o->centre[0] + 100) && near(c->centre[1], o->centre[1] - 7) &&
              near(c->centre[2], o->centre[2] + 40) && c->radius == o->radius &&
              c->density == o->density,
          "copy %d: at %g %g %g", i, c->centre[0], c->centre[1], c->centre[2]);
  }

  /* capacity */
  fog_rbf small[3];
  rbf_bank full = {.rbfs = small, .capacity = 3};
  carried = rbf_brush_stroke_start(&b);
  CHECK(rbf_brush_stroke(&full, &b, from, to, &carried) == 3 && full.count == 3,
        "a bank of 3 took %d", full.count);
  CHECK(rbf_brush_copy(&full, from, 100.0, dest) == 0 && full.count == 3, "copy into a full bank");

  /* the brush of a bank: its mean radius and density */
  const fog_rbf bank[2] = {{.radius = 10, .density = 0.01}, {.radius = 30, .density = 0.05}};
  rbf_brush mean = rbf_brush_for(bank, 2, 1000.0, 0.5);
  CHECK(near(mean.radius, 20.0) && near(mean.density, 0.03) && near(mean.spacing, 10.0),
        "the bank's brush: r %g c %g spacing %g", mean.radius, mean.density, mean.spacing);
  rbf_brush empty = rbf_brush_for(NULL, 0, 1000.0, 0.5);
  CHECK(near(empty.radius, 25.0) && empty.density == 0.5, "an empty bank's brush: r %g c %g",
        empty.radius, empty.density);
  return test_finish("test_rbf_brush");
}
