/* OpenVDB import: a 3D fog grid (Blender/Mantaflow, Houdini, EmberGen caches) projected
 * to a 2D fogmap f(x,z) and a vertical profile g(y), so that K(x,y,z) = f(x,z)·g(y).
 * (Part of the sim library; include "sim/sim.h". The OpenVDB reading and vdb_frame_load
 * live in the fogpipe_vdb library, a thin C++ adapter; everything else is C in
 * fogpipe_sim. Link fogpipe_vdb to use any of it.)
 *
 * Lifecycle for one frame (what the demo/render/record commands call):
 *   vdb_frame f;
 *   if (vdb_frame_load("cache/data/fluid_data_0048.vdb", &(vdb_frame_desc){0}, &f, &err))
 *     ... err.message names the file ...
 *   f.map (the fogmap), f.profile (g), f.fogmap_place (where f lies in the world)
 *   vdb_frame_destroy(&f);
 * For a sequence: vdb_sequence_find() lists the frames, then vdb_frame_load() each.
 *
 * Conventions (docs/vdb_import.md has the derivations):
 * - fogpipe world: Y up, right-handed. The fogmap spans X (column) and Z (row).
 * - OpenVDB voxel n covers index coordinates [n-0.5, n+0.5] (its centre at n).
 *   A Mantaflow cell n covers [n, n+1]·dx from the domain's min corner; the config
 *   reader and the placement turn one into the other (README of the test data).
 * - Z-up sources (Blender, Mantaflow; the default): fogpipe (X, Y, Z) = (x, z, -y),
 *   the glTF/Blender exporter convention. Y-up sources (Houdini, EmberGen): identity.
 * - Profile: g is dimensionless with max g = 1, thickness T = ∫g dy, and
 *   f(x,z) = (∫ρ dy)/T, so f·∫g dy is exactly the column optical depth and f is the
 *   extinction at the profile's densest height. */
#ifndef FOGPIPE_SIM_VDB_IMPORT_H
#define FOGPIPE_SIM_VDB_IMPORT_H

#include <stdbool.h>
#include <stddef.h>

/* fogmap.h has no C++ guard of its own: include it with C linkage from here. */
#ifdef __cplusplus
extern "C" {
#endif

#include "sim/fogmap.h"

/* ---------------------------------------------------------------- reading (C++) */

typedef struct vdb_grid_info {
  char name[128];
  char value_type[32];   /* as OpenVDB names it: "float", "double", "vec3s", ... */
  char grid_class[32];   /* "fog volume", "level set", "staggered", "unknown" */
  double voxel_size[3];  /* from the grid's transform */
  int bbox_min[3], bbox_max[3];  /* active voxels incl. tiles, inclusive; empty: min > max */
  long long active_voxels;       /* voxels in leaves and in active tiles; -1 (and min > max):
                                    not known (a grid other than float or double whose file
                                    holds no statistics: its tree is not read) */
} vdb_grid_info;

/* Checks (in C, without OpenVDB, in about a millisecond) that a .vdb file's header,
 * metadata, grid descriptors, grid headers and trees (every node's masks and compressed
 * chunk sizes, for the plain value types) fit its size as OpenVDB 10 reads them: every
 * length, count and offset against the bytes there. OpenVDB allocates such lengths
 * before any check (a bit flip made it take gigabytes); vdb_list_grids and vdb_read_dense
 * call this first. 0: looks sound; 1: err->message names the file and what is damaged. */
int vdb_precheck_file(const char *path, fog_error *err);

/* Lists the grids of a .vdb file (at most capacity; *count is the number in the file).
 * Fails naming the file for missing, unreadable, non-VDB or truncated files. */
int vdb_list_grids(const char *path, vdb_grid_info *grids, int capacity, int *count,
                   fog_error *err);

/* A float grid copied to a dense box (the active bounding box). */
typedef struct vdb_dense_grid {
  int dim[3];             /* voxels along index axes i, j, k */
  int index_min[3];       /* index coordinate of values[0] */
  double voxel_size[3];   /* index->world scale per index axis (axis-aligned maps only) */
  double translation[3];  /* world position of index (0,0,0)'s centre */
  float *values;          /* values[((k-kmin)*dim[1] + (j-jmin))*dim[0] + (i-imin)]; owned */
  long long active_voxels;
  long long tile_voxels;  /* of those, how many came from active tiles */
  long long negative_voxels;  /* negative values found (clamped to 0: fog is never negative) */
} vdb_dense_grid;

typedef struct vdb_read_desc {
  const char *grid;       /* NULL: "density" */
  long long max_voxels;   /* refuse bigger dense boxes; 0: 2^28 (1 GiB of floats) */
  int empty_ok;           /* an empty grid (a sequence's frame before the smoke) reads as one
                             voxel of 0 at index (0, 0, 0), active_voxels 0; else an error */
} vdb_read_desc;

/* Reads one float (or double) grid, leaf voxels and active tiles alike, half-float or
 * full, any compression OpenVDB supports. Fails naming the file (and the grids that
 * exist) for: no such grid, a non-scalar grid, a level set, a background value above 0,
 * an empty grid (unless desc->empty_ok), NaN/Inf voxels (the first is named), a rotated
 * or sheared transform, more than max_voxels. Every OpenVDB exception becomes
 * err->message; nothing is allocated on failure. */
int vdb_read_dense(const char *path, const vdb_read_desc *desc, vdb_dense_grid *out,
                   fog_error *err);
void vdb_dense_grid_destroy(vdb_dense_grid *grid);

/* Writes one float grid (fog volume) to a .vdb file: for tests and tools. values as in
 * vdb_dense_grid (values of exactly 0 stay inactive); as_tiles: store each fully constant
 * 8^3 block as an active tile instead of voxels (half: 16-bit float on disk). */
typedef enum vdb_compression {
  VDB_COMPRESSION_DEFAULT = 0,  /* OpenVDB's default (BLOSC if built with it) */
  VDB_COMPRESSION_NONE,
  VDB_COMPRESSION_ZIP,
  VDB_COMPRESSION_BLOSC,
} vdb_compression;

typedef struct vdb_write_desc {
  const char *grid;  /* NULL: "density" */
  int as_half;
  int constant_blocks_as_tiles;
  vdb_compression compression;
} vdb_write_desc;
int vdb_write_dense(const char *path, const vdb_dense_grid *grid, const vdb_write_desc *desc,
                    fog_error *err);

/* ----------------------------------------------------- Mantaflow config (.uni, C) */

/* Blender 3.x fluid cache config/config_####.uni (gzip; MANTA::writeConfiguration). */
typedef struct mantaflow_config {
  int active_fields;
  int res[3];            /* current (adaptive) grid resolution */
  float dx;              /* Mantaflow's normalised cell size (1/max res), not metres */
  float dt;
  float p0[3], p1[3];    /* domain box in domain-object space */
  float dp0[3];
  int shift[3];
  float obj_shift_f[3];
  float obmat[4][4];     /* object->world, obmat[row][col] (translation in column 3) */
  int base_res[3];       /* full-domain resolution */
  int res_min[3], res_max[3];  /* the adaptive sub-box in base cells */
  float active_color[3];
  float time_total;
  char cache_version[5];
} mantaflow_config;

/* Fails naming the file for missing, non-gzip, wrong-size files. */
int mantaflow_config_read(const char *path, mantaflow_config *out, fog_error *err);

/* ------------------------------------------------------------- placement (C) */

typedef enum vdb_up_axis { VDB_UP_Z = 0, VDB_UP_Y = 1 } vdb_up_axis;

typedef struct vdb_placement {
  vdb_up_axis up;                  /* 0: Z-up (Blender) */
  double scale;                    /* world scale about the source origin; 0 means 1 */
  double offset[3];                /* fogpipe world offset, added last */
  const mantaflow_config *config;  /* NULL: the VDB transform alone */
} vdb_placement;

/* Index->fogpipe-world map: for fogpipe axis a (0 X, 1 Y up, 2 Z) the world coordinate
 * of continuous index coordinate u along source axis index_axis[a] is
 *   w_a = base[a] + step[a]·u     (step may be negative; voxel n spans u in [n-.5,n+.5]) */
typedef struct vdb_world_map {
  int index_axis[3];
  double base[3], step[3];
  int used_config;      /* 1 when a Mantaflow config placed the domain */
  int domain_min[3], domain_max[3];  /* with a config: the full domain's index box */
  char warning[256];    /* e.g. adaptive-domain voxel size replaced; "" if none */
} vdb_world_map;

/* Combines the grid's transform, the optional config and the options. Fails for a
 * config whose base_res or box is degenerate. */
int vdb_world_map_make(const vdb_dense_grid *grid, const vdb_placement *desc, vdb_world_map *out,
                       fog_error *err);

/* ------------------------------------------------------------- projection (C) */

/* The column integral on the grid's own footprint, in world orientation. */
typedef struct vdb_columns {
  int width, height;          /* world-X columns, world-Z rows */
  double origin_x, origin_z;  /* world min corner of the footprint */
  double cell_x, cell_z;      /* world size of one column */
  double *tau;                /* ∫ρ dy per column, tau[z*width + x] (density × length) */
  int layers;                 /* voxel layers along world Y */
  double y_min, layer_height; /* world Y of the lowest layer's bottom face */
  double *layer_mass;         /* ∫∫ρ dx dz per layer (density × area), bottom first */
  double mass;                /* Σ ρ·voxel volume (density × volume) */
} vdb_columns;

/* box: NULL projects the dense box; else an index box {imin,jmin,kmin,imax,jmax,kmax}
 * (inclusive, e.g. the Mantaflow domain) that must contain the dense box. */
int vdb_columns_project(const vdb_dense_grid *grid, const vdb_world_map *map, const int *box,
                        vdb_columns *out, fog_error *err);
void vdb_columns_destroy(vdb_columns *columns);

/* Where a fogmap lies in the world: cell (x, z) covers
 * [origin_x + x·cell, origin_x + (x+1)·cell] × [origin_z + z·cell, ...]; its value is
 * the cell's mean density (fogmap row index = world Z). */
typedef struct vdb_fogmap_place {
  double origin_x, origin_z;
  double cell_size;
  int width, height;
} vdb_fogmap_place;

/* A fogmap grid over the world rectangle [x0,x1]×[z0,z1]: resolution > 0 cells along
 * the longer side, else cell_size > 0, else the columns' own cell (native). */
int vdb_fogmap_place_fit(double x0, double x1, double z0, double z1, int resolution,
                         double cell_size, double native_cell, vdb_fogmap_place *out,
                         fog_error *err);
/* One fogmap grid for a sequence's frames: vdb_fogmap_place_fit over the union of their
 * footprints, the native cell the first frame's. Frames without fog (no columns: an empty
 * grid, vdb_frame_desc.empty_ok) have no footprint and are passed over. */
int vdb_fogmap_place_fit_columns(const vdb_columns *const *columns, int count, int resolution,
                                 double cell_size, vdb_fogmap_place *out, fog_error *err);

/* Area-weighted (conservative) resampling of tau/thickness onto place: every column's
 * optical depth × area is split over the fogmap cells by overlap area, so
 * Σ f·cell²·thickness = Σ tau·column area to rounding. map must be place's size. */
int vdb_columns_resample(const vdb_columns *columns, const vdb_fogmap_place *place,
                         double thickness, fogmap *map, fog_error *err);

/* ------------------------------------------------------------- profile (C) */

/* The renderer's limit (render/fog_field.h FOG_PROFILE_MAX_COEFFICIENTS). */
#define VDB_PROFILE_MAX_KNOTS 64

typedef enum vdb_profile_kind {
  VDB_PROFILE_BSPLINE = 0,      /* centred B-spline of degree 0 or 1 */
  VDB_PROFILE_EXPONENTIAL = 1,  /* exp(-(y - y_bottom)/scale_height) on [y_bottom, y_top] */
} vdb_profile_kind;

/* The largest exponential scale height fitted: a scene config's largest (app/config.h's
 * SCENE_MAX_SCALE_HEIGHT, a world length), so that an import's sidecar loads. */
#define VDB_PROFILE_MAX_SCALE_HEIGHT 1e7

typedef struct vdb_profile_desc {
  vdb_profile_kind kind;
  int knots;              /* B-spline coefficients; 0: one per voxel layer (max 64) */
  int degree_box;         /* 1: degree 0 (box, the layer histogram); 0: degree 1 (hats) */
} vdb_profile_desc;

/* g(y) >= 0, dimensionless, max g = 1, zero outside [y_bottom, y_top]; thickness = ∫g dy.
 * The same parameters as render/fog_field.h's fog_profile, so the renderer takes them
 * as they are:
 * B-spline (FOG_PROFILE_BSPLINE): g = Σ_k values[k]·φ_degree((y - origin)/spacing - k),
 *   φ the centred B-spline; knot k at origin + k·spacing = the centre of span k of the
 *   grid's height range; values[k] = the mean density of span k / the largest such mean.
 *   Support [origin - (degree+1)/2·spacing, origin + (count-1+(degree+1)/2)·spacing]
 *   (degree 1 reaches half a span beyond the grid); thickness = spacing·Σ values exactly.
 * Exponential (FOG_PROFILE_EXPONENTIAL with y_floor = y0 = y_bottom): g = exp(-(y -
 *   y_bottom)/scale_height) on [y_bottom, y_top], scale_height fitted so that g's mean
 *   height equals the data's (moment fit); scale_height = 0 means a slab g = 1 (data
 *   whose mean height is in the upper half: an exponential cannot fall upward). */
typedef struct vdb_profile {
  vdb_profile_kind kind;
  double y_bottom, y_top;
  double thickness;
  int degree, count;
  double origin, spacing;
  double values[VDB_PROFILE_MAX_KNOTS];
  double scale_height;
} vdb_profile;

/* Fits g to a mean vertical distribution (mass per layer, bottom first, uniform layers
 * of layer_height from y_min). Fails for zero or non-finite total mass. */
int vdb_profile_fit(const double *layer_mass, int layers, double y_min, double layer_height,
                    const vdb_profile_desc *desc, vdb_profile *out, fog_error *err);
/* The sequence profile: the summed vertical distribution of several frames (their layers
 * may start at different heights; the layer height must be the same). Frames without fog
 * (no layers) are passed over. */
int vdb_profile_fit_columns(const vdb_columns *const *columns, int count,
                            const vdb_profile_desc *desc, vdb_profile *out, fog_error *err);
double vdb_profile_eval(const vdb_profile *profile, double y);

/* ------------------------------------------------------------- sequences (C) */

/* Files of a sequence, sorted by frame number. */
typedef struct vdb_sequence {
  int count;
  int *frames;       /* frame number of each file (from the last digit run in its name) */
  char **paths;
  int missing_count; /* frames absent inside [first, last] */
  int *missing;
} vdb_sequence;

/* inputs: files, directories (every *.vdb inside), printf patterns (fluid_data_%04d.vdb),
 * #### patterns (fluid_data_####.vdb) or globs (fluid_data_*.vdb). A path that exists is
 * itself, whatever its name holds; a #### pattern's frame number is the last run of '#' in
 * its file name (a folder's '#' is itself). first/last: a frame range (last < 0: open).
 * Missing frames inside the range are listed, not an error here; two files whose names
 * number one frame are (the same file however spelt is one). Fails when nothing matches
 * (naming the input), and for more than 2^20 frames from the first to the last (the
 * range, or the frame numbers found: VDB_SEQUENCE_MAX_SPAN). A printf pattern has one
 * integer conversion and otherwise only "%%" (else it is a file name or glob). */
enum { VDB_SEQUENCE_MAX_SPAN = 1 << 20 };
int vdb_sequence_find(const char *const *inputs, int input_count, int first, int last,
                      vdb_sequence *out, fog_error *err);
/* The run of '#' that stands for the frame number in a #### pattern: the last run in its
 * file name (a folder's '#' is itself). False when the file name has none. */
bool vdb_pattern_hash_run(const char *pattern, size_t *start, size_t *length);
void vdb_sequence_destroy(vdb_sequence *sequence);

/* The config beside a Blender cache file: DIR/data/fluid_data_0048.vdb ->
 * DIR/config/config_0048.uni. Returns 0 and fills out if such a file exists. */
int vdb_config_path_beside(const char *vdb_path, char *out, size_t out_size);
/* Whether every frame of the sequence is placed one way: each has its config beside it, or
 * none has (frames placed both ways land a domain's corner apart, a metre on the plume).
 * 1 with err naming a frame of each kind when not; 0 when they agree. */
int vdb_sequence_check_placement(const vdb_sequence *seq, fog_error *err);
/* Whether the frame numbers run without a hole: a player steps through the files in order,
 * so playing across a hole would silently change the speed. 1 with err naming `pattern`,
 * the count and the first missing frame; 0 when there is none. */
int vdb_sequence_check_gaps(const vdb_sequence *seq, const char *pattern, fog_error *err);

/* ------------------------------------------------------------- one frame (C++ glue) */

typedef struct vdb_frame_desc {
  const char *grid;           /* NULL: "density" */
  vdb_up_axis up;
  double scale;               /* 0 means 1 */
  double offset[3];
  const char *config;         /* NULL: the config beside the file if any; "none": never */
  int resolution;             /* fogmap cells along the longer side; 0: native */
  double cell_size;           /* or a world cell size; 0: native */
  const vdb_fogmap_place *place;  /* or exactly this fogmap grid (sequences share one) */
  vdb_profile_desc profile;
  const vdb_profile *fixed_profile;  /* use this g instead of fitting one */
  int keep_grid;              /* keep the dense grid in frame->grid (for --report) */
  int grid_only;              /* read and place the grid only (frame->grid and ->world; no
                                 columns, profile or fogmap): the 3D volume model */
  long long max_voxels;       /* 0: 2^28 */
  int empty_ok;               /* an empty grid is a frame without fog (a sequence's frame
                                 before or after the smoke): active_voxels 0, no columns
                                 (width 0, mass 0), the fixed profile or none (count 0), a
                                 zero fogmap where `place` is given; grid_only: one voxel of 0
                                 (vdb_read_desc.empty_ok). Else an error naming the file */
} vdb_frame_desc;

typedef struct vdb_frame {
  vdb_dense_grid grid;        /* only with keep_grid */
  vdb_world_map world;
  vdb_columns columns;
  vdb_profile profile;
  vdb_fogmap_place fogmap_place;
  fogmap map;
  char config_path[1024];     /* the config used, "" if none */
  long long active_voxels;    /* of the grid read (leaf voxels + tile voxels) */
  int empty;                  /* no fog (empty_ok): an empty grid, or voxels all 0 */
  long long negative_voxels;  /* negative values clamped to 0 */
} vdb_frame;

/* Reads path, places it, projects it and fits (or applies) the profile. On failure
 * nothing is allocated and err->message names the file. */
int vdb_frame_load(const char *path, const vdb_frame_desc *desc, vdb_frame *out, fog_error *err);
void vdb_frame_destroy(vdb_frame *frame);

/* ------------------------------------------------------------- 2.5D accuracy (C) */

typedef struct vdb_report_row {
  double elevation_deg;
  int rays;                  /* rays that met fog (reference optical depth > 1e-4) */
  double mean_abs_error;     /* |T_2.5D - T_3D| averaged over those rays */
  double max_abs_error;
  double mean_transmittance; /* mean T_3D over those rays */
} vdb_report_row;

typedef struct vdb_report_desc {
  int rays_per_side;         /* parallel rays per view side; 0: 48 */
  int azimuths;              /* views per elevation; 0: 4 */
  double step;               /* march step as a fraction of the smallest cell; 0: 0.25 */
  /* Optional: receives the 3D grid's optical depth per ray (the reference march), at
   * ((row * azimuths + azimuth) * side + iz) * side + ix, -1 where a ray misses the box;
   * row_count * azimuths * side^2 doubles. For comparing another march of the same rays. */
  double *reference_depth;
} vdb_report_desc;

/* The views' geometry, shared by vdb_report_run and any other march of the same rays:
 * the box [lo, hi] holding both models, the height y_mid of the ray origins, the march
 * step (world units), and the unit direction of view `azimuth` at an elevation:
 * (cos el cos phi, -sin el, cos el sin phi), phi = (azimuth + 1/2) 2 pi / azimuths.
 * Ray (ix, iz) starts at (lo.x + (ix + 1/2)(hi.x - lo.x)/side, y_mid,
 * lo.z + (iz + 1/2)(hi.z - lo.z)/side), is clipped to the box and sampled at
 * n = ceil((t1 - t0)/step) midpoints. */
int vdb_report_geometry(const vdb_dense_grid *grid, const vdb_world_map *world,
                        const vdb_fogmap_place *place, const vdb_profile *profile,
                        const vdb_report_desc *desc, double lo[3], double hi[3], double *y_mid,
                        double *step, fog_error *err);
void vdb_report_direction(double elevation_deg, int azimuth, int azimuths, double dir[3]);

/* Orthographic views at each elevation: transmittance of the original 3D grid
 * (trilinear, fine march) against the 2.5D model f·g (f bilinear on cell centres,
 * the linear B-spline), same rays and steps. rows[n].elevation_deg are inputs. */
int vdb_report_run(const vdb_dense_grid *grid, const vdb_world_map *world, const fogmap *map,
                   const vdb_fogmap_place *place, const vdb_profile *profile,
                   const vdb_report_desc *desc, vdb_report_row *rows, int row_count,
                   fog_error *err);

#ifdef __cplusplus
}
#endif

#endif
