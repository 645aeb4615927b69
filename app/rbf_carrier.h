/* RBF puffs carried by the simulation (issue 17, `[fog] rbf_carrier = sim`): the puffs of
 * the scene's emitters (render/fog_rbf_emitter.h: born, spreading and fading as there) move
 * with the velocity of a stable-fluid simulation (sim/fluid.h) over the flow's domain, plus
 * each emitter's own wind. The simulation gives the eddies of `[sim] turbulence` and the
 * drift of `[sim] wind`; the emitter's wind adds a draft, and its vertical part is the
 * puffs' only vertical motion (the flow is 2D, in x and z).
 *
 * Time: the flow and the puffs advance in fixed steps of `step` seconds from t = -(the
 * longest lifetime), so the stream is full and already carried at t = 0. Puff k's centre
 * is its birth position plus the explicit Euler sum of the velocity at its position over
 * the steps since its birth (the first step from its birth time), and the velocity times the
 * time since the last step. A time is reached by stepping from that start, whatever was asked
 * before (an earlier time starts again from the beginning), so the puffs at time t are the
 * same bit for bit whether t is one frame of a recording, a farm's range or a window's clock.
 * Stepping costs the simulation's step and the puffs' (a 64² grid and 1000 puffs: 0.2 ms
 * here, 6 ms per second of scene time) for every step from the start to the first time
 * asked. */
#ifndef FOGPIPE_APP_RBF_CARRIER_H
#define FOGPIPE_APP_RBF_CARRIER_H

#include <stdbool.h>
#include <stdint.h>

#include "render/fog_models.h"
#include "render/fog_rbf_emitter.h"

/* The flow's grid (cells on the longer side of the domain) and step: fine enough for eddies
 * a quarter of the domain across (16 cells), cheap enough to replay a minute in a second. */
#define RBF_CARRIER_GRID 64
#define RBF_CARRIER_STEP (1.0 / 30.0)
/* The longest LIFETIME a config may give an emitter whose puffs the flow carries: the fog's
 * every making replays the flow for that long first (9000 steps, ~2 s here). */
#define RBF_CARRIER_MAX_LIFETIME 300.0
/* The most flow beyond time 0 the carrier replays to reach a time asked (an hour: 108000
 * steps, ~22 s here, plus the emitters' lead-in of at most RBF_CARRIER_MAX_LIFETIME), from
 * its start or on from the time it reached: a time further is refused rather than run for
 * hours (a time given in ms, say); a window stepping on runs for ever. */
#define RBF_CARRIER_MAX_TIME 3600.0

typedef struct rbf_carrier_desc {
  const fog_rbf_emitter *emitters; /* copied at create */
  int emitter_count;               /* >= 1 */
  /* The flow's domain: world x, z of its corner and its extent (> 0). Square cells cover
   * it, the longer side `grid` of them and each side's count rounded up to an even one of 18
   * or more (the simulation's least side), and the flow is periodic over those cells (what
   * leaves one side enters the other; the period exceeds the extent by less than two cells,
   * or more where a side has under 18): puffs outside take the velocity of the periodic
   * copy. */
  double origin[2], size[2];
  int grid;         /* cells on the longer side (>= 8): RBF_CARRIER_GRID */
  double step;      /* seconds (> 0): RBF_CARRIER_STEP */
  double wind[2];   /* the flow's mean drift, world units per second (x, z) */
  double turbulence;/* rms speed of the synthesised turbulence, world units per second (>= 0):
                       its largest eddies a quarter of the shorter side across, Kolmogorov's
                       -5/3 spectrum, the flow pulled toward it at 2 a second (sim/wind.h) */
  double viscosity; /* kinematic, world units^2 per second (>= 0) */
  uint64_t seed;    /* the turbulence's phases */
} rbf_carrier_desc;

typedef struct rbf_carrier rbf_carrier;

/* NULL on error (err names the field). */
rbf_carrier *rbf_carrier_create(const rbf_carrier_desc *desc, fog_error *err);
void rbf_carrier_destroy(rbf_carrier *carrier);
/* Whether a carrier made from `desc` would be this one (the same emitters, domain, grid, step
 * and flow settings): a caller whose config may have changed makes a new one when not. */
bool rbf_carrier_serves(const rbf_carrier *carrier, const rbf_carrier_desc *desc);
/* The puffs alive at `time` (>= 0; at most RBF_CARRIER_MAX_TIME from the start or past the
 * time reached, rbf_carrier.h's bound), emitter by emitter, oldest first,
 * into out[0 .. count): returns count, or -1 (err set) when capacity is smaller, the time
 * out of range or the flow fails. */
int rbf_carrier_puffs(rbf_carrier *carrier, double time, fog_rbf *out, int capacity,
                      fog_error *err);
/* The time the flow has reached (a step's), for tests. */
double rbf_carrier_time(const rbf_carrier *carrier);

#endif
