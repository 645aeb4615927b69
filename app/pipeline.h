/* pipeline: one frame of fogpipe, stage by stage (docs/architecture.md):
 *
 *     sim step ──► transform ──►│ upload ──► render (scene + fog pass)
 *     └──── CPU: worker thread ─┘└────────── GL thread (the caller) ──┘
 *
 * The CPU stages run in a worker thread (pthreads), double-buffered against rendering:
 * there are two slots; while the GL thread uploads and renders the pyramid in slot k, the
 * worker steps the simulation and transforms the density into slot k+1. A slot is handed
 * back to the worker as soon as its grids are uploaded (the GL textures hold the copy).
 *
 * Determinism: the simulation advances by a fixed time step per frame in the worker, in
 * order, whatever the thread timing; frame n always shows simulation step n. Recording
 * takes every frame (pipeline_frame with wait = true); the live demo takes the newest one
 * that is ready and re-renders the last one otherwise, so the camera stays smooth.
 *
 * Timings are kept per stage (sim, transform, upload, render, frame) as moving medians
 * over the last PIPELINE_TIMING_WINDOW frames.
 *
 * Lifecycle: pipeline_create (a GL context must be current on the calling thread, which
 * is then the GL thread) → pipeline_frame / pipeline_read_frame per frame → destroy. */
#ifndef FOGPIPE_APP_PIPELINE_H
#define FOGPIPE_APP_PIPELINE_H

#include "transform/fog_error.h"
#include "app/frame_pixels.h"
#include <stdbool.h>

#include "app/config.h"
#include "render/camera.h"

#define PIPELINE_TIMING_WINDOW 31

typedef struct pipeline pipeline;

/* The longest frame the pipeline simulates: 240 sim steps of at most 1/24 s (a longer one
 * would also overflow the step count; --fps 1e-9 used to). */
#define PIPELINE_MAX_FRAME_SECONDS 10.0

typedef struct pipeline_desc {
  const scene_config *config; /* the scene (copied; the pipeline keeps its own) */
  int width, height;          /* render size; 0: the config's image size */
  bool synchronous;           /* run sim + transform on the GL thread (default: worker) */
  double frame_seconds;       /* simulated seconds per frame, > 0 and at most
                               * PIPELINE_MAX_FRAME_SECONDS (1/24: a recording's default) */
  bool time_passes;           /* also time the scene pass alone (one extra glFinish) */
  /* A live view (the demo): the sun's optical-depth volume is refreshed every few steps
   * (and at once when the sun or the shadow setting changes), not every step. false (a
   * recording): every step, so that any frame range is bit for bit the full run's. */
  bool live;
} pipeline_desc;

/* Per-stage times in milliseconds (moving medians, or one frame's values). */
typedef struct pipeline_timings {
  double sim, transform, upload, render, frame; /* wall clock */
  double scene; /* the scene pass's part of render (only with desc.time_passes) */
  /* The CPU stages' own CPU time (thread CPU clock): in the worker thread their wall
   * time also counts the time they waited for a core while the renderer ran. */
  double sim_cpu, transform_cpu;
  double sun_shadow; /* the sun's optical-depth volume of the step (docs/light.md) */
  /* Its CPU time (thread CPU clock) for the step shown, 0 where the step reused the volume
   * before it (live: every LIVE_SHADOW_INTERVAL steps): its mean over frames is the
   * volume's share per step. */
  double sun_shadow_cpu;
} pipeline_timings;

/* The timings as an array in field order, and back: for statistics taken per field. */
#define PIPELINE_TIMING_FIELDS 10
void pipeline_timings_to_array(const pipeline_timings *t, double v[PIPELINE_TIMING_FIELDS]);
pipeline_timings pipeline_timings_from_array(const double v[PIPELINE_TIMING_FIELDS]);

/* What the panel edits live. Changes are applied by the worker before its next step
 * (basis and levels re-plan the transform). */
typedef struct pipeline_params {
  int degree;        /* B-spline basis 0 (Haar), 1 (linear), 2 (quadratic) */
  int levels;        /* pyramid levels J */
  float mu;          /* LOD factor in [0, 1] */
  int lod_method;    /* fog_lod_method */
  float density;     /* extinction scale */
  float fog_colour[3];
  fog_sun sun;       /* albedo, phase_g and the sun's colour; its direction is derived
                        from the two angles below each frame */
  float sun_azimuth, sun_elevation; /* degrees ([light]): the sun of the terrain and the fog;
                                       pipeline_frame derives sun.direction from them */
  bool fog_self_shadow; /* [light] fog_self_shadow: T_s on the fog and the ground */
  bool shafts;          /* [light] shafts: the terrain's shadows in the fog */
  fog_lamps lamps;      /* [light] lamp and spot lines (world positions) */
  int profile_kind;  /* fog_profile_kind (slab / exponential) */
  float fog_height;  /* top of the slab or of the flat part (y0) */
  float scale_height;/* exponential falloff H */
  float wind[2];     /* constant drift, world units per second (x, z) */
  float turbulence;  /* wind turbulence amplitude */
  float viscosity;
  float emitter_rate;
  /* Fog pass at 1/divisor resolution, upsampled guided by the surface distance
   * (fog_pass_params.resolution_divisor): 0 or 1 full resolution (render, record), 2 or 4
   * for a live view on a slow (software) renderer. */
  int fog_resolution_divisor;
  bool paused;
  /* live_rung_kind (app/live_rung.h): 0 the fogmap; else a rung of the model ladder fitted
   * to it as it moves, drawn in its place and measured against it (the demo's "model") */
  int live_rung;
} pipeline_params;

pipeline *pipeline_create(const pipeline_desc *desc, fog_error *err);
void pipeline_destroy(pipeline *p);

/* Renders the next frame into the pipeline's target with the given camera. wait: block
 * until the worker has the next simulation step (recording; while paused only for a
 * requested step); otherwise take the next ready step or re-render the current one
 * (live). Returns non-zero on a GL error or a failed CPU stage. */
int pipeline_frame(pipeline *p, const camera *cam, bool wait, fog_error *err);

/* Reads the last frame back into out (app/frame_pixels.h). */
int pipeline_read_frame(pipeline *p, const frame_pixels *out, fog_error *err);

/* Draws the last frame's colour into the default framebuffer (window), scaled to w x h. */
int pipeline_present(pipeline *p, int width, int height, fog_error *err);

/* Render size; resizing re-creates the render targets. */
void pipeline_size(const pipeline *p, int *width, int *height);
int pipeline_resize(pipeline *p, int width, int height, fog_error *err);

/* Number of simulation steps shown so far (the frame index of the last pipeline_frame). */
long pipeline_step_index(const pipeline *p);

/* Runs the simulation alone (no transform, no render) for `steps` frames: how --resume
 * reaches frame n deterministically. Only before the first pipeline_frame. A played
 * sequence (VDB or bake) only moves its frame counter. */
int pipeline_skip(pipeline *p, long steps, fog_error *err);
/* Whether frames come from the simulation (else from a VDB or fogmap sequence). */
bool pipeline_simulates(const pipeline *p);
/* Live only: the last frame drew the fog without the lamps' light, which the renderer's
 * loop cap refused (docs/platform.md; the fog pass's FOG_ERR_UNSUPPORTED). A recording
 * fails with the fog pass's error instead. */
bool pipeline_lamps_dropped(const pipeline *p);
/* The simulation's density after the last step or skip (what the transform of that frame
 * reads); NULL when nothing is simulated. */
const struct fogmap *pipeline_sim_density(const pipeline *p);

/* Whether the fog's vertical profile is a B-spline: the config's, or a VDB sequence's
 * (whose frames bring theirs; the config the caller holds does not show it). */
bool pipeline_has_bspline_profile(const pipeline *p);

pipeline_params pipeline_get_params(const pipeline *p);
void pipeline_set_params(pipeline *p, const pipeline_params *params);
/* While paused: advance one step. */
void pipeline_step_once(pipeline *p);
/* Restart the simulation from its initial state. */
void pipeline_reset(pipeline *p);

/* Paint (amount > 0) or erase (amount < 0) fog with a round brush at world (x, z) of the
 * given world radius; queued and applied by the worker through the sim's stroke function. */
void pipeline_paint(pipeline *p, double x0, double z0, double x1, double z1, double radius,
                    double amount);

/* The first surface of the last frame under image pixel (px, py) (row 0 at the top), from
 * its depth texture along the ray of the camera that frame was drawn from (cam before the
 * first frame); returns false for the sky. */
bool pipeline_pick_surface(pipeline *p, const camera *cam, int px, int py, double world[3]);

/* Moving medians of the last frames; `last` (may be NULL) gets the last frame's values. */
pipeline_timings pipeline_get_timings(const pipeline *p, pipeline_timings *last);
/* The rung drawn in the fogmap's place (params.live_rung > 0): its fitted model and its
 * error on the last measured view (every LIVE_RUNG_INTERVAL frames); false: none (GL
 * thread). */
struct live_rung;
bool pipeline_live_rung(const pipeline *p, struct live_rung *out);

/* The fogmap size (cells) and its world placement, for the panel and painting. */
void pipeline_fog_extent(const pipeline *p, int *cells_x, int *cells_z, double *origin_x,
                         double *origin_z, double *cell_size);

#endif
