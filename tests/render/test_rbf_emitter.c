/* Puffs of Gaussian fog from an emitter (render/fog_rbf_emitter.h), against the documented
 * closed form, written out here: at any time t the ceil(rate x lifetime) puffs born in
 * (t - lifetime, t] at times k / rate (k whole), each within `spread` of the emitter plus
 * wind x age, of radius sqrt(radius^2 + 4 diffusion age), with density r^3 = density
 * radius^3 (mass kept) until the last fifth of its life, then fading to 0; a puff keeps its
 * own offset whenever it is asked for (frames are independent), the stream is full at t = 0,
 * and puffs are born one after another at the rate. */
#include <math.h>
#include <stdio.h>

#include "render/fog_rbf_emitter.h"
#include "test_util.h"

enum { CAP = 4096 };

int main(void) {
  const fog_rbf_emitter e = {.position = {10, 50, -20}, .rate = 12.5, .lifetime = 8.0,
                             .radius = 3.0, .density = 0.2, .spread = 2.5, .diffusion = 1.5,
                             .wind = {4, 0.5, -2}, .seed = 42};
  static fog_rbf a[CAP], b[CAP];
  const int count = fog_rbf_emitter_count(&e);
  CHECK(count == 100, "12.5 puffs a second for 8 s: %d alive, expected 100", count);
  CHECK(fog_rbf_emitter_puffs(&e, 0.0, a, 99) == -1, "too little room is refused");
  double worst_place = 0.0, worst_radius = 0.0, worst_mass = 0.0, worst_keep = 0.0;
  int faded = 0, full = 0;
  for (int step = 0; step < 200; step++) {
    const double t = 0.037 * step, dt = 0.61;
    CHECK(fog_rbf_emitter_puffs(&e, t, a, CAP) == count &&
              fog_rbf_emitter_puffs(&e, t + dt, b, CAP) == count,
          "puff count at %g", t);
    /* the newest puff was born at floor(rate t) / rate; puff i at that minus (count-1-i)/rate */
    const double newest = floor(t * e.rate + 1e-9) / e.rate;
    for (int i = 0; i < count; i++) {
      const double age = t - (newest - (count - 1 - i) / e.rate);
      CHECK(age >= -1e-12 && age < count / e.rate + 1e-9, "t %g puff %d: age %g", t, i, age);
      double off2 = 0.0;
      for (int c = 0; c < 3; c++) {
        double off = a[i].centre[c] - e.position[c] - e.wind[c] * age;
        off2 += off * off;
      }
      worst_place = fmax(worst_place, sqrt(off2) - e.spread); /* <= 0: within spread */
      const double r = sqrt(e.radius * e.radius + 4.0 * e.diffusion * age);
      worst_radius = fmax(worst_radius, fabs(a[i].radius - r));
      const double mass = e.density * pow(e.radius, 3.0), left = (e.lifetime - age) / e.lifetime;
      if (left >= 0.2) {
        worst_mass = fmax(worst_mass, fabs(a[i].density * pow(a[i].radius, 3.0) - mass) / mass);
        full++;
      } else {
        CHECK(a[i].density * pow(a[i].radius, 3.0) <= mass * (1 + 1e-12) && a[i].density >= 0,
              "a fading puff gains mass");
        faded += a[i].density < 0.5 * mass / pow(a[i].radius, 3.0);
      }
      /* the same puff dt later (if still in the list): moved by wind x dt exactly */
      const int later = i - (int)llround((floor((t + dt) * e.rate + 1e-9) / e.rate - newest) * e.rate);
      if (later >= 0)
        for (int c = 0; c < 3; c++)
          worst_keep = fmax(worst_keep, fabs(b[later].centre[c] - a[i].centre[c] - e.wind[c] * dt));
    }
  }
  printf("puffs: placed within the spread (excess %.2e), radius %.2e, mass %.2e relative, "
         "%d fading, kept their offset between frames %.2e\n", worst_place, worst_radius,
         worst_mass, faded, worst_keep);
  CHECK(worst_place <= 1e-12, "a puff lies %.3e beyond the spread", worst_place);
  CHECK(worst_radius <= 1e-12 && worst_mass <= 1e-12, "radius %.3e, mass %.3e", worst_radius,
        worst_mass);
  CHECK(worst_keep <= 1e-10, "a puff moved other than with the wind: %.3e", worst_keep);
  CHECK(faded > 0 && full > 0, "no puff fading (%d) or none in full (%d)", faded, full);
  return test_finish("test_rbf_emitter");
}
