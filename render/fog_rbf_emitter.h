/* RBF fog that moves: an emitter of Gaussian puffs carried by a wind (Fogshop's fog from
 * particles, Zhou et al. 2007 §6; issue 17). Each puff is one Gaussian of FOG_MODEL_RBF.
 *
 * Puff k of an emitter is born at t_k = (k - k0) / rate, k0 = ceil(rate * lifetime), so the
 * stream is already full at t = 0, at the emitter plus an offset of up to `spread` in a
 * ball (a hash of k and the seed: the same puff whatever frame asks for it), and drifts with
 * the wind: centre(t) = start_k + wind (t - t_k). It spreads as a diffusing Gaussian,
 * r(age)^2 = radius^2 + 4 diffusion age, keeping its mass (density r^3 constant), and fades
 * out over the last fifth of its life (smoothstep). Everything is a closed form of t, so
 * frame n of a recording needs no frame before it (farm ranges, resumes). */
#ifndef FOGPIPE_RENDER_FOG_RBF_EMITTER_H
#define FOGPIPE_RENDER_FOG_RBF_EMITTER_H

#include <stdint.h>

#include "render/fog_models.h"

typedef struct fog_rbf_emitter {
  double position[3];
  double rate;      /* puffs per second, > 0 */
  double lifetime;  /* seconds, > 0: rate x lifetime puffs live at once */
  double radius;    /* at birth, > 0 */
  double density;   /* at birth, >= 0 */
  double spread;    /* >= 0: births within this distance of position */
  double diffusion; /* >= 0, world units^2 per second */
  double wind[3];   /* world units per second */
  uint64_t seed;
} fog_rbf_emitter;

/* How many puffs of e live at any time: ceil(rate x lifetime). */
int fog_rbf_emitter_count(const fog_rbf_emitter *e);
/* The puffs of e alive at `time` (>= 0) into out[0 .. count), count = fog_rbf_emitter_count,
 * oldest first; returns count, or -1 when capacity is smaller. */
int fog_rbf_emitter_puffs(const fog_rbf_emitter *e, double time, fog_rbf *out, int capacity);

/* The pieces of a puff, for carriers other than the wind (app/rbf_carrier.h): the index k
 * of the newest puff alive at `time` (the live ones are k - count + 1 .. k); puff k's
 * birth time and birth position (the emitter plus its offset within `spread`); and its
 * radius and density at `age` (centre untouched). */
long fog_rbf_emitter_newest(const fog_rbf_emitter *e, double time);
double fog_rbf_emitter_birth(const fog_rbf_emitter *e, long k);
void fog_rbf_emitter_start(const fog_rbf_emitter *e, long k, double start[3]);
void fog_rbf_emitter_shape(const fog_rbf_emitter *e, double age, fog_rbf *g);

#endif
