/* A VDB sequence played as fog: the fogmap at any time, linearly interpolated between the
 * two frames around time·fps (`[fog] vdb` in a scene config, docs/config.md).
 *
 *   vdb_source src;
 *   if (vdb_source_open(&src, &(vdb_source_desc){.path = "cache/data/fluid_data_####.vdb"},
 *                       &err)) ... err.message names the files ...
 *   fogmap map = {0};                              // sized by the first call
 *   vdb_source_fogmap_at(&src, seconds, &map, &err);
 *   ... src.place (where the fogmap lies), src.profile (g, shared by all frames) ...
 *   fogmap_destroy(&map); vdb_source_destroy(&src);
 *
 * Opening reads every frame once (sim/vdb_import.h, ~1-2 ms a frame for the test caches):
 * that is needed anyway to fit the sequence's shared fogmap grid (the union of the
 * frames' footprints) and its one profile g (docs/vdb_import.md, "sequences"). Of each
 * frame only the column integrals are kept (τ per column and the layer masses: the 3D
 * grid is dropped), so the files are never read again. At most two frames are held as
 * fogmaps: the pair around the current time. When the pair changes, a frame not cached
 * yet is resampled from its columns into one of the two cached fogmaps
 * (vdb_columns_resample, which uses a temporary buffer of its own); while the pair stays
 * the same, vdb_source_fogmap_at only blends and allocates nothing. */
#ifndef FOGPIPE_APP_VDB_SOURCE_H
#define FOGPIPE_APP_VDB_SOURCE_H

#include "app/config.h"
#include "sim/sim.h"

typedef struct vdb_source_desc {
  const char *path;     /* a file, a folder, a #### or %04d pattern or a glob */
  const char *grid;     /* NULL: "density" */
  vdb_up_axis up;       /* 0: Z-up (Blender / Mantaflow) */
  double fps;           /* frames per second of playback (> 0; configs: [fog] vdb_fps, 24) */
  int resolution;       /* fogmap cells along the longer side; 0: native (one per column) */
  int loop;             /* 1: time wraps around (last frame blends into the first);
                           0: times before the first / after the last frame hold it */
} vdb_source_desc;

typedef struct vdb_source {
  int count;                /* frames (files) of the sequence */
  int *frame_numbers;       /* from the file names, ascending */
  vdb_columns *columns;     /* per frame */
  double *mass;             /* per frame: Σ ρ·voxel volume (density × volume) */
  vdb_fogmap_place place;   /* the shared fogmap grid */
  vdb_profile profile;      /* the shared profile g */
  double fps;
  int loop;
  fogmap cache[2];          /* fogmaps of two frames ... */
  int cached[2];            /* ... their frame indices (-1: empty) */
} vdb_source;

/* Fails (naming the pattern or the file) for no matching files, missing frames inside
 * the sequence's range, or any frame vdb_frame_load refuses. Nothing stays allocated on
 * failure. */
int vdb_source_open(vdb_source *source, const vdb_source_desc *desc, fog_error *err);
void vdb_source_destroy(vdb_source *source);

/* The fogmap at time t (seconds; frame index position p = t·fps, index 0 the first file):
 * (1 - w)·F[a] + w·F[b] with a = floor(p), b = a + 1, w = p - a (w = 0 exactly at integer
 * p: the frame itself). Out of range: clamped to [first, last] frame, or with loop p is
 * taken modulo count (b = 0 after the last frame). out: an empty fogmap ({0}) is created
 * at place's size; otherwise it must have that size. */
int vdb_source_fogmap_at(vdb_source *source, double t, fogmap *out, fog_error *err);

/* Frame index position p (time · fps; index 0 the first file) as the two frames around it
 * and the weight of the second, (1 - w) F[a] + w F[b]: out of range wrapped modulo count
 * with loop (b = 0 after the last frame), else held at the first / last frame. A p within
 * 1e-9 of an integer is that frame exactly. */
void vdb_sequence_position(double p, int count, int loop, int *a, int *b, double *weight);

/* The index of frame number `number` among numbers[0 .. count) (-1: the last), or -1. */
int vdb_frame_index(const int *numbers, int count, int number);
/* The index of the file with frame number `number` (-1: the last), or -1 if none. */
int vdb_source_index_of(const vdb_source *source, int number);
/* Duration of one pass: count frames at fps (the loop period). */
double vdb_source_duration(const vdb_source *source);

/* ---- scene configs ---- */

/* Opens cfg->fog.vdb with the config's [fog] vdb_* keys; errors are
 * "FILE:LINE: [fog] vdb: ...". */
int vdb_source_open_config(vdb_source *source, const scene_config *cfg, fog_error *err);
/* Puts the source's placement and profile into cfg, except what the file set itself:
 * [box] origin and cell_size from the fogmap grid, floor and top from g's support, and
 * g as [fog] profile = bspline (or exponential), unless `profile` was set. 1 with err
 * naming the config and the key when the file set one of floor and top and it does not
 * lie on its side of the other, which g gave (an empty box). */
int vdb_source_apply_config(const vdb_source *source, scene_config *cfg, fog_error *err);

#endif
