/* Scene configs: the .ini files in configs/ (format: docs/config.md), parsed with libinih.
 *
 *   scene_config cfg;
 *   fog_error err;
 *   if (scene_config_load("configs/default.ini", &cfg, &err)) { print err.message; exit }
 *
 * scene_config_init() fills every documented default, so a config file only names what it
 * changes; after loading every field holds a concrete value. Enumerations number their
 * default 0. Paths in a file are relative to the file's folder and are stored resolved
 * (usable from the current directory). Errors name "FILE:LINE: [section] key: ..." and what
 * was expected (unknown section or key, bad number, bad enum with the allowed values,
 * a fogmap or heightmap file that cannot be opened). */
#ifndef FOGPIPE_APP_CONFIG_H
#define FOGPIPE_APP_CONFIG_H

#include "transform/fog_error.h"
#include <stdbool.h>
#include <stdint.h>

#include "render/camera.h"
#include "render/display.h"
#include "render/fog_lamp.h"
#include "render/fog_light.h"
#include "render/fog_models.h"
#include "render/fog_rbf_emitter.h"
#include "render/fog_pass.h"
#include "render/scene.h"

#define SCENE_CONFIG_PATH_MAX 1024
#define SCENE_CONFIG_MAX_PROFILE 64
/* The most a colour key may hold (sun_colour, colour, ambient, the sky): under half
 * float's 65504, which the recordings' R G B hold. */
#define SCENE_CONFIG_MAX_RADIANCE 1e4
/* The most far / near a camera may have: the float depth buffer of a standard projection
 * loses surfaces past near x 3.4e7 (they round to the cleared depth, 1) */
#define SCENE_CAMERA_MAX_DEPTH_RATIO 1e7
/* The most `rbf =` lines a config holds (a scene config is a value; the renderer takes
 * up to FOG_MAX_RBFS Gaussians from code: bench models' 3000-Gaussian banks). */
#define SCENE_CONFIG_MAX_RBFS 1024
/* The most `rbf_emitter` lines (their puffs together at most FOG_MAX_RBFS). */
#define SCENE_CONFIG_MAX_EMITTERS 4

/* Values equal to render/fog_field.h's enums where one exists. */
typedef enum scene_lod {
  SCENE_LOD_SUM = 0, /* "sum": the paper's sum of details up to d_l = |OP| mu^l */
  SCENE_LOD_SWITCH,  /* "switch": one approximation A_l per ray segment (ours) */
} scene_lod;

typedef enum scene_filtering {
  SCENE_FILTERING_MANUAL = 0, /* "manual": exact coefficient fetches */
  SCENE_FILTERING_HARDWARE,   /* "hardware": GL_LINEAR (weights quantised, often 1/256) */
} scene_filtering;

typedef enum scene_profile {
  SCENE_PROFILE_SLAB = 0,    /* "slab": g = 1 on [box floor, box top] */
  SCENE_PROFILE_EXPONENTIAL, /* "exponential": 1 up to fog_height, exp(-(y-fog_height)/H) above */
  SCENE_PROFILE_BSPLINE,     /* "bspline": g = sum b_k phi_p((y - origin)/spacing - k) */
} scene_profile;

typedef enum scene_boundary {
  SCENE_BOUNDARY_SYMMETRIC = 0, /* "symmetric" (fog is not periodic) */
  SCENE_BOUNDARY_PERIODIC,      /* "periodic" (the FFT simulation's domain) */
} scene_boundary;

typedef enum scene_rbf_carrier {
  SCENE_RBF_CARRIER_WIND = 0, /* "wind": each emitter's wind, a closed form of time */
  SCENE_RBF_CARRIER_SIM,      /* "sim": the [sim] flow plus the wind (app/rbf_carrier.h) */
} scene_rbf_carrier;

typedef struct scene_fog_config {
  fog_model_kind model;               /* a row of render/fog_models.def (its name in [fog] model) */
  int model_line;                     /* where model was set (0: default), for errors */
  int quadric_noise_line; /* the first quadric line with NOISE > 0 (0: none), for errors */
  char fogmap[SCENE_CONFIG_PATH_MAX]; /* resolved path; "" means no fog */
  char channel[16];                   /* image channel ("" : the only one) */
  double density_scale;               /* extinction per world unit where f = g = 1 */
  int degree;                         /* basis: haar 0, linear 1, quadratic 2 */
  int levels;                         /* pyramid levels J */
  double mu;                          /* LOD factor in [0, 1] (1 keeps every detail) */
  scene_lod lod;
  scene_filtering filtering;
  scene_boundary boundary;
  scene_profile profile;
  double fog_height;                  /* exponential: y0, where the decay starts */
  double scale_height;                /* exponential: H */
  double fog_start, fog_end;          /* model = linear: the factor's distances (GL_LINEAR) */
  int profile_degree;                 /* bspline: degree p of the profile (0..3) */
  double profile_origin, profile_spacing;
  double profile_coefficients[SCENE_CONFIG_MAX_PROFILE];
  int profile_count;
  float colour[3];                    /* L_fog, linear: the ambient in-scatter L_amb */
  double albedo;                      /* sunlight scattered: sigma_s = albedo K (docs/light.md) */
  double phase_g;                     /* Henyey-Greenstein asymmetry of that scattering */
  int fogmap_line;                    /* where fogmap was set (0: default), for errors */
  bool profile_set;                   /* `profile` was set in the file (a VDB keeps it) */
  /* model = rbf: the Gaussians (densities before density_scale) and the base under them. */
  fog_rbf rbfs[SCENE_CONFIG_MAX_RBFS];
  int rbf_count;
  /* and puffs from emitters carried by a wind (render/fog_rbf_emitter.h): the fog moves */
  fog_rbf_emitter rbf_emitters[SCENE_CONFIG_MAX_EMITTERS];
  int rbf_emitter_count;
  scene_rbf_carrier rbf_carrier; /* what carries the puffs */
  int rbf_carrier_line;          /* the line that set it (0: default), for errors */
  double rbf_base;
  /* model = quadric: the volumes (densities before density_scale), from `quadric = SHAPE
   * ...` lines (docs/config.md), held as their ten coefficients and box. */
  fog_quadric quadrics[FOG_MAX_QUADRICS];
  int quadric_count;
  /* Each volume's line as written (its shape and numbers): scene_config_write gives it back. */
  struct scene_quadric_line {
    int shape; /* index in the shape names: sphere, ellipsoid, cylinder, cone, general */
    int count;
    double numbers[19];
  } quadric_lines[FOG_MAX_QUADRICS];
  /* model = perlin (render/fog_perlin.h): the octaves' count, texture size, feature size and
   * seed; perlin_wind holds 3 numbers (every octave's drift) or 3 per octave; the integral.
   * Its height fog is density_scale, fog_height, scale_height; its box the terrain's
   * footprint between [box] floor and top. */
  int perlin_octaves, perlin_size;
  double perlin_feature;
  unsigned perlin_seed;
  double perlin_wind[SCENE_CONFIG_MAX_PROFILE];
  int perlin_wind_count;
  int perlin_integral; /* fog_perlin_integral: exact 0, paper 1 */
  int perlin_wind_line, perlin_size_line; /* where they were set, for errors */
  /* model = volume: 0 integrates the grid exactly; > 0 marches it at this step (world). */
  double volume_step;
  /* A fogmap per frame (`fogpipe bake`'s output): frame n of a recording shows the file of
   * frame number n, `#`s in the pattern standing for its digits; the simulation is off.
   * Exclusive with fogmap and vdb. */
  char sequence[SCENE_CONFIG_PATH_MAX];
  int sequence_line;
  /* OpenVDB fog (app/vdb_source.h): exclusive with fogmap. */
  char vdb[SCENE_CONFIG_PATH_MAX];    /* resolved file / pattern / folder / glob; "" none */
  int vdb_line;
  char vdb_grid[128];                 /* grid name ("density") */
  int vdb_up;                         /* vdb_up_axis: 0 z (Blender), 1 y (Houdini) */
  double vdb_fps;                     /* playback rate of the sequence (frames per second) */
  int vdb_frame;                      /* frame number for a still render; -1: the last */
  int vdb_frame_line;                 /* its line (0: not given) */
  int vdb_resolution;                 /* fogmap cells along the longer side; 0: native */
  int vdb_loop;                       /* 1: the sequence repeats; 0: holds its last frame */
} scene_fog_config;

/* World placement of the fogmap: the corner of cell (0, 0) at (origin_x, origin_z), one
 * fogmap cell is cell_size world units; the box spans [floor, top] vertically. */
typedef struct scene_box_config {
  double origin[2];
  double cell_size;
  double floor, top;
  /* Set in the file (a VDB places the box itself unless these are set). */
  bool origin_set, cell_size_set, floor_set, top_set;
  int floor_line, top_line; /* where floor and top were set (0: not in the file), for errors */
} scene_box_config;

typedef struct scene_camera_config {
  double position[3];
  double yaw, pitch; /* degrees (camera.h conventions) */
  double fov;        /* vertical, degrees */
  bool look_at_set;  /* look_at overrides yaw and pitch */
  double look_at[3];
  double near_plane, far_plane;
} scene_camera_config;

typedef struct scene_terrain_config {
  char heightmap[SCENE_CONFIG_PATH_MAX]; /* resolved path; "" means procedural */
  int heightmap_line;
  double origin[3];
  double size[2];
  double height;
  int resolution, octaves;
  double frequency, persistence;
  unsigned seed;
  double lod_error; /* pixels of height error the scene pass's terrain LOD may show; 0: full mesh */
} scene_terrain_config;

/* [sim]: read now, used by the simulation (upcoming: see docs/config.md). */
typedef struct scene_sim_config {
  double wind[2];     /* constant drift, world units per second (x, z) */
  double turbulence;  /* wind turbulence amplitude */
  double viscosity;
  double emitter_rate;
  unsigned seed;
} scene_sim_config;

/* [light]'s fog shadows (docs/light.md): only with [fog] albedo > 0 (albedo 0 is Giroud &
 * Biri's eq. 4, the fog a flat colour with no sun in it). */
typedef struct scene_shadow_config {
  int fog_self_shadow; /* 1 (on): T_s, the fog's shadow on itself and on the surfaces */
  int shafts;          /* 1 (on): V in the fog, the terrain's and boxes' shadows: shafts */
  int resolution;      /* the sun's optical-depth volume: samples along each axis */
  int steps;           /* segments of the view ray's T_s mean (fog_light.glsl) */
  int nodes;           /* its samples per segment: 1 midpoint, 2 Gauss-Legendre (or per
                          piece, with pieces) */
  int shaft_samples;   /* V's samples a segment (fog_light_rule.shaft_samples) */
  int pieces;          /* the mean per piece of the exact walk (Perlin fog and the volume):
                          0 off, 1 on, 2 auto (on for Perlin fog only:
                          scene_config_light_rule resolves it) */
  int lamp_shadows;     /* 1 (on): each lamp's shadow cube, V_i in the fog and on surfaces */
  int lamp_shadow_size; /* its texels per face side (LAMP_SHADOW_SIZE_MIN..MAX) */
} scene_shadow_config;

/* [light] lamp and spot lines as written (docs/config.md): a spot's axis as given (made
 * unit by scene_config_fog_lamps), its cone's half-angles in degrees. */
#define SCENE_LAMP_MAX_KEYS 32
typedef struct scene_lamp_config {
  bool spot;
  double position[3], colour[3]; /* colour x intensity: radiant intensity, linear */
  double radius;                 /* > 0 */
  double axis[3];                /* spot: the direction it shines, any length > 0 */
  double inner, outer;           /* spot: half-angles, degrees, 0 <= inner < outer <= 180 */
  /* [light] lamp_path lines: key positions (time in seconds, x, y, z), times increasing;
   * between keys the lamp moves in a straight line, before the first and after the last it
   * stays there. None: it stays at position. */
  double keys[SCENE_LAMP_MAX_KEYS][4];
  int key_count;
  /* [light] lamp_flicker: intensity x (1 - amount n(rate t)), n smooth value noise in
   * [0, 1] drawn from seed; amount 0: steady. */
  double flicker_amount, flicker_rate;
  unsigned flicker_seed;
} scene_lamp_config;

typedef struct scene_config {
  char path[SCENE_CONFIG_PATH_MAX]; /* the file it was read from */
  scene_fog_config fog;
  scene_box_config box;
  scene_camera_config camera;
  scene_terrain_config terrain;
  scene_box_desc objects[SCENE_MAX_BOXES];
  int object_count;
  scene_light light;
  scene_shadow_config shadow; /* in [light] */
  scene_lamp_config lamps[FOG_MAX_LAMPS]; /* [light] lamp and spot lines, in file order */
  int lamp_count;
  fog_lamp_method lamp_method; /* [light] lamp_integral, lamp_angle_pieces, _span_pieces,
                                  _depth_steps, _shadow_steps */
  int lamp_integral_line;       /* the line that set lamp_integral, for its error */
  int width, height; /* [render] image size */
  /* [render] the fog walk's speed settings (docs/config.md): transmittance_cutoff
   * (fog_pass_params.transmittance_cutoff, 0: whole rays), empty_skip (1 on: skip blocks
   * of zero fog, exactly) and skip_below (> 0: also blocks whose fog is <= it). */
  double transmittance_cutoff;
  int empty_skip;
  double skip_below;
  /* [render] the display transform of PNGs, the window and the preview video
   * (render/display.h): exposure in stops, tone_map a display_tone_map, dither 1 on */
  double exposure;
  int tone_map;
  int dither;
  /* [render] supersample k (1 to 4): render and record draw k x k samples a pixel
   * (app/supersample.h); the window draws one */
  int supersample;
  int supersample_line; /* the line that set it (0: the default), for the player's error */
  scene_sim_config sim;
} scene_config;

/* Whether the config has fog at all: a fogmap, a VDB sequence or an analytic model. */
bool scene_config_has_fog(const scene_config *cfg);

/* Whether [fog] density_scale changes what is drawn: the model reads it (its row's keys in
 * render/fog_models.def; quadric lines beside a model come only with models that do). The
 * window's density slider is shown only then: linear fog ignores it. */
bool scene_config_draws_density_scale(const scene_config *cfg);

/* Whether [section] key is a key configs may set. */
bool scene_config_knows_key(const char *section, const char *key);

/* The path of frame n of a `[fog] sequence` pattern: the last run of #s in its file name
 * replaced by n, zero-padded to the run's length (a folder's '#' is itself). False when the
 * file name has no # or out (size bytes) is too small. */
bool scene_config_sequence_path(const char *pattern, long n, char *out, size_t size);

/* Writes cfg as a config file that loads back into the same scene (the same fingerprint):
 * every key with its value, in full precision, paths made absolute. The text is read back
 * as the loader reads a file (every key's range and the cross-key checks; the files it
 * names are not looked at) before anything is written. Non-zero and err naming the file
 * (and the key) when it cannot be written (nothing is left behind then). */
int scene_config_write(const scene_config *cfg, const char *path, fog_error *err);
/* The loader's checks of what each fog model needs of the other keys (scene_config_load
 * runs them after reading a file), on a scene made in memory: 0, or 1 with err naming the
 * key ("[fog] model: ..."). scene_config_write refuses a scene that fails them, which would
 * be a config that does not load. */
int scene_config_check(const scene_config *cfg, fog_error *err);

/* Every documented default (docs/config.md). */
void scene_config_init(scene_config *cfg);
/* init + parse path. Non-zero and err on the first error. */
int scene_config_load(const char *path, scene_config *cfg, fog_error *err);

/* A 64-bit FNV-1a hash of the resolved scene: every key's value (defaults included) and
 * the bytes of the fogmap and heightmap files it names (a VDB sequence by its frame
 * numbers and file sizes). Equal scenes hash equal whatever their comments, order,
 * spelling of numbers, or the path by which the config and its files are reached;
 * record uses it to refuse resuming a folder made from another scene. */
uint64_t scene_config_fingerprint(const scene_config *cfg);

/* The camera the config describes (radians, look_at applied). */
void scene_config_camera(const scene_config *cfg, camera *cam);
/* The terrain LOD's pixel error the live demo uses on a software renderer: twice the
 * config's, at least 2 (0, the full mesh, stays 0). */
double scene_live_terrain_lod(double lod_error);
/* The lamps' integral the live demo uses on a software renderer: at most 4 + 4 pieces and
 * a walk of at most 4 steps to each lamp (`bench lights`' live row, docs/light.md: 2.6x
 * cheaper than 8 + 8 and 8 on the valley, max error 7.6e-3 of the peak against 1.4e-3). */
fog_lamp_method scene_live_lamp_method(fog_lamp_method method);
/* Height and Perlin fog (K0 e^{-(y - y0)/H} below y0): the smallest [fog] scale_height that
 * keeps the extinction a float down to the lowest point the view reaches (the camera, the
 * terrain's base, the box's floor); 0 when any does. A config below it is refused; the
 * window's panel holds its slider above it. */
double scene_config_min_scale_height(const scene_config *cfg);
/* [fog] scale_height's largest (a world length) */
#define SCENE_MAX_SCALE_HEIGHT 1e7
/* The clear air a fogmap scene without a map starts from: SCENE_CLEAR_AIR_CELLS square
 * cells of 0 (the pipeline's simulation; render's quadric volumes beside it) */
#define SCENE_CLEAR_AIR_CELLS 256
/* Both, in cfg: the live demo's settings on a software renderer (the window and `bench
 * pipeline`, which measures it). */
void scene_config_live_software(scene_config *cfg);
/* The fogmap's extinction scale and vertical profile as they are shown: the config's own
 * ([fog] density_scale, profile, fog_height, scale_height: scene_config_fog_shape), or the
 * live demo's panel edits of them. */
typedef struct scene_fog_shape {
  double extinction;       /* per world unit for f = g = 1, >= 0 */
  fog_profile_kind profile;
  double y0, scale_height; /* the exponential profile's; scale_height > 0 */
} scene_fog_shape;
scene_fog_shape scene_config_fog_shape(const scene_config *cfg);
/* [fog]'s quadric volumes with density_scale applied (their densities are before it) into
 * out; returns their count. */
int scene_config_fog_quadrics(const scene_config *cfg, fog_quadric out[FOG_MAX_QUADRICS]);
/* The fogmap's fog_volume for a map of map_width x map_height samples: [box] places it,
 * shape gives its extinction and profile; a B-spline profile takes the config's knots
 * (pointing into cfg->fog: copy them where cfg does not outlive the volume), and becomes
 * the slab where the config has none. */
fog_volume scene_config_fog_volume(const scene_config *cfg, int map_width, int map_height,
                                   const scene_fog_shape *shape);
/* The solver's seed for [sim] seed: seed + 1, since the solver takes 0 for 1 (every config
 * seed its own turbulence; the default 0 keeps the solver's default 1). */
uint64_t scene_config_sim_seed(const scene_config *cfg);
/* [render] exposure, tone_map and dither. */
display_transform scene_config_display(const scene_config *cfg);
/* How the fog pass walks: [render] transmittance_cutoff, empty_skip, skip_below. */
fog_walk_settings scene_config_walk(const scene_config *cfg);
/* The sun as the fog sees it: [fog] albedo and phase_g, [light]'s resolved sun. */
fog_sun scene_config_fog_sun(const scene_config *cfg);
/* [light] shadow_steps, shadow_nodes and shadow_pieces as the view ray's light rule. */
fog_light_rule scene_config_light_rule(const scene_config *cfg);
/* The surfaces show albedo x sun_colour x cos: [light] sun_colour is the sun's irradiance
 * over pi, so the fog's fog_sun.radiance is SCENE_SUN_IRRADIANCE_PER_COLOUR x sun_colour. */
#define SCENE_SUN_IRRADIANCE_PER_COLOUR 3.14159265358979323846
/* The lamps as the fog pass takes them (world positions, unit spot axes, cone cosines) at
 * scene time 0, and at `time` seconds (lamp_path and lamp_flicker applied). */
fog_lamps scene_config_fog_lamps(const scene_config *cfg);
fog_lamps scene_config_fog_lamps_at(const scene_config *cfg, double time);
/* Whether any lamp moves or flickers (frames must then set the lamps of their time). */
bool scene_config_lamps_animated(const scene_config *cfg);
/* The lamp shadow cubes' size for scene_pass_set_lamp_shadows: [light] lamp_shadow_size, or
 * 0 with lamp_shadows = off. */
int scene_config_lamp_shadow_size(const scene_config *cfg);
/* The scene pass's description. heights (may be NULL) are the loaded heightmap (values in
 * [0, 1], width x height) when cfg->terrain.heightmap is set. */
void scene_config_scene_desc(const scene_config *cfg, const float *heights, int width,
                             int height, scene_desc *desc);

#endif
