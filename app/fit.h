/* `fogpipe fit`: the cheapest rung of the model ladder that holds a scene's fog within a
 * tolerance (docs/fit.md). "Model no more than a scene needs", measured:
 *
 *   fit_result result;
 *   fog_error err;
 *   if (fit_run(&(fit_desc){.input = &cfg, .tolerance = 0.02, ...}, &result, &err)) ...
 *   result.rungs[result.chosen].config   the scene with that rung's fog, to write
 *   fit_result_destroy(&result);
 *
 * The reference is the input's own fog: the 3D grid where the input is a volume (a VDB
 * frame), else the input's model as the renderer builds it. Over the fit domain (the fog's
 * bounds; for fog without an end, the terrain's footprint between [box] floor and top) the
 * reference's extinction is sampled and every rung that can represent it is fitted
 * (app/fit_density.h: homogeneous, height, one ellipsoid and banks of 2 to 16, banks of 1
 * to 16 cylinders and of 1 to 16 oriented ellipsoids, banks of 1 to 64 Gaussians; the fogmap at three bases x three LOD factors: the input's fogmap or VDB,
 * or an analytic input's density projected (app/fit_fogmap.h); the volume where the input
 * has one; an analytic input as given). Each rung is then rendered:
 * its error on nine views (app/fit_views.h: max and mean |delta tau| against the
 * reference, CPU twins in double) and its GL milliseconds per frame (a headless session
 * drawn from view 0, the median of timed_frames frames). The choice: the fastest rung within
 * the tolerance (of its max error, or its mean error with by_mean), where rungs within 25 % of its
 * time count as ties that the simpler rung (earlier on the ladder) wins. Needs EGL (a headless GL
 * context). */
#ifndef FOGPIPE_APP_FIT_H
#define FOGPIPE_APP_FIT_H

#include <signal.h>

#include "transform/fog_error.h"
#include "app/config.h"

typedef struct fit_desc {
  const scene_config *input;
  double tolerance;   /* |delta tau| allowed, > 0: on every ray (or on average, by_mean) */
  bool by_mean;       /* the tolerance bounds the mean error instead of the max */
  int rays_per_side;  /* of each view, >= 1 */
  int sample_side;    /* density samples along the domain's longest side, >= 2 */
  int width, height;  /* the timed frames, pixels */
  int timed_frames;   /* >= 1 (after one untimed) */
  /* Frame numbers of the input's [fog] vdb sequence to fit over, the worst frame deciding
   * (the static rungs fit the frames' mean density; the fogmap and volume rungs play
   * the frames); NULL: the input's own frame ([fog] vdb_frame). Timed at the last. */
  const int *frames;
  int frame_count;
  /* Set by the caller (its SIGINT/SIGTERM handler) to stop: fit_run then fails after the
   * rung it is measuring, its scratch folder removed. NULL: it runs to the end. */
  const volatile sig_atomic_t *stop;
} fit_desc;

/* The command's defaults. */
#define FIT_RAYS_PER_SIDE 32
#define FIT_SAMPLE_SIDE 48
#define FIT_WIDTH 320
#define FIT_HEIGHT 180
#define FIT_TIMED_FRAMES 3

#define FIT_MAX_RUNGS 40

typedef struct fit_rung {
  char name[32];     /* "rbf 8", "fogmap linear mu 0.5" */
  char family[16];   /* the chart's series: homogeneous, height, quadric, rbf, fogmap, volume */
  char params[256];  /* the fitted parameters, for the table */
  scene_config *config; /* the input scene with this rung's fog (owned) */
  double max_error, mean_error; /* |delta tau| on the views: the worst ray's, the mean over
                                   the rays (over frames: the worst frame's mean) */
  double ms;         /* GL milliseconds per frame */
  double light_error; /* a lit input ([fog] albedo > 0): the in-scatter's max error relative
                         to the reference's brightest ray (fit_views_light); NAN unlit */
} fit_rung;

typedef struct fit_result {
  fit_rung rungs[FIT_MAX_RUNGS]; /* in ladder order */
  int count;
  int chosen;        /* index of the pick, -1: none within the tolerance */
  double lo[3], hi[3]; /* the fit domain */
  int rays;          /* rays of the views that meet it (per frame) */
  int frame_count;   /* frames measured */
  bool lit;          /* the in-scatter was measured too */
  /* A folder the rungs' own files live in (the fogmap projected from an analytic input,
   * app/fit_fogmap.h), their configs naming them, in $TMPDIR (else /tmp); "" when no rung
   * has one. Removed by
   * fit_result_destroy: a config written from such a rung must take its files along. */
  char scratch[512];
} fit_result;

/* Errors name the input's file (and line where a key is at fault) or the rung that failed
 * to render. On failure nothing stays allocated. */
int fit_run(const fit_desc *desc, fit_result *result, fog_error *err);
void fit_result_destroy(fit_result *result);
/* The pick at another tolerance from the same measurements (fit_run's rule); -1: none. */
int fit_choose(const fit_result *result, double tolerance, bool by_mean);
/* Whether a rung's error (max or mean |dtau|) is within the tolerance: fit_choose's rule,
 * refused rungs included (they are never chosen: their time is NaN). */
bool fit_within(const fit_rung *rung, double tolerance, bool by_mean);
/* A scene around a VDB frame (cfg: model = volume, [fog] vdb set), or around the frames
 * that hold fog among frames[0..frame_count) (NULL: the config's): a low procedural ground
 * (bumps of 1 % of the grid's reach) just under the grid, no boxes, and the camera of view 0 (app/fit_views.h), so the fog is in sight. */
int fit_scene_for_volume(scene_config *cfg, const int *frames, int frame_count,
                         fog_error *err);

#endif
