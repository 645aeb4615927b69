/* Scene config parsing (config.h, format in docs/config.md) with libinih.
 *
 * Line numbers: Debian's libinih is built without INI_HANDLER_LINENO, so we parse through
 * ini_parse_stream with our own reader that reads whole lines and counts them; inih calls
 * the handler right after reading a key's line, so the count is that key's line. */
#define _XOPEN_SOURCE 700 /* lstat, getcwd, fmemopen, open_memstream */
#include "app/config.h"
#include "app/rbf_carrier.h"

#include "render/render.h"
#include "sim/sim.h"
#include "sim/vdb_import.h"

#include <errno.h>
#include <fcntl.h>
#include <ini.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#define DEG (3.14159265358979323846 / 180.0)

typedef enum value_kind {
  V_DOUBLE,   /* one number */
  V_DOUBLE2,  /* two numbers */
  V_DOUBLE3,  /* three numbers */
  V_FLOAT3,   /* colour: three numbers */
  V_INT,
  V_UINT,
  V_ENUM,     /* int, one of names */
  V_PATH,     /* resolved against the config's folder; line stored at line_offset */
  V_STRING,
  V_LIST,     /* up to SCENE_CONFIG_MAX_PROFILE numbers, count at count_offset */
  V_OBJECT,   /* box = X Z WIDTH HEIGHT DEPTH [R G B], appended */
  V_RBF,      /* rbf = X Y Z RADIUS DENSITY, appended */
  V_QUADRIC,  /* quadric = SHAPE NUMBERS..., appended */
  V_RBF_EMITTER, /* rbf_emitter = X Y Z RATE LIFETIME RADIUS DENSITY SPREAD DIFFUSION WX WY WZ [SEED] */
  V_LAMP,     /* lamp = X Y Z R G B [RADIUS], spot = ... DX DY DZ INNER OUTER [RADIUS] */
  V_LAMP_PATH,    /* lamp_path = INDEX T X Y Z, appended to lamp INDEX's keys */
  V_LAMP_FLICKER, /* lamp_flicker = INDEX AMOUNT RATE [SEED] */
  V_LOOK_AT,
} value_kind;

typedef struct key_spec {
  const char *section, *key;
  value_kind kind;
  size_t offset;
  double min, max;          /* allowed range for numbers (inclusive); V_STRING: min is
                               the least length */
  const char *names;        /* V_ENUM: "a|b|c" (value = index) */
  size_t aux_offset;        /* V_PATH and V_INT (when not 0): line; V_LIST: count */
  size_t size;              /* V_STRING / V_PATH buffer size */
} key_spec;

#define F(member) offsetof(scene_config, member)
_Static_assert((long long)SCENE_MAX_SCALE_HEIGHT == (long long)VDB_PROFILE_MAX_SCALE_HEIGHT,
               "an import's fitted scale height must load as [fog] scale_height");
/* The bounds of the numbers a config may hold: past them float (in which the GPU works)
 * overflows or loses the scene, and pixels turn NaN. WORLD: world coordinates and lengths
 * (a float still resolves 1 unit at 1e7). MIN_LENGTH: the smallest scale of a feature
 * (scale heights, Gaussian radii, cells): 1/MIN_LENGTH^2 stays finite in float.
 * MAX_EXTINCTION: extinction per world unit (FOGMAP_MAX_DENSITY's bound, so that a fogmap
 * value times density_scale stays finite). MAX_RADIANCE: colours, under half float's 65504. */
#define BIG 1e300
#define WORLD 1e7
#define MIN_LENGTH 1e-4
#define MAX_EXTINCTION 1e12
#define MAX_RADIANCE SCENE_CONFIG_MAX_RADIANCE
/* "|fogmap|homogeneous|...": the model table's names in kind order (V_ENUM's value is the
 * index, so the kind); keys[] reads it from its second character. */
static const char model_names[] =
#define FOG_MODEL_ROW(KIND, id, label, keys, pyramid) "|" #id
#include "render/fog_models.def"
#undef FOG_MODEL_ROW
    ;
static const key_spec keys[] = {
    {"fog", "model", V_ENUM, F(fog.model), 0, 0, model_names + 1, 0, 0},
    {"fog", "fogmap", V_PATH, F(fog.fogmap), 0, 0, NULL, F(fog.fogmap_line), sizeof(((scene_config *)0)->fog.fogmap)},
    {"fog", "channel", V_STRING, F(fog.channel), 0, 0, NULL, 0, sizeof(((scene_config *)0)->fog.channel)},
    {"fog", "density_scale", V_DOUBLE, F(fog.density_scale), 0, MAX_EXTINCTION, NULL, 0, 0},
    {"fog", "basis", V_ENUM, F(fog.degree), 0, 0, "haar|linear|quadratic", 0, 0},
    {"fog", "levels", V_INT, F(fog.levels), 0, FOG_MAX_LEVELS, NULL, 0, 0},
    {"fog", "mu", V_DOUBLE, F(fog.mu), 0, 1, NULL, 0, 0},
    {"fog", "lod", V_ENUM, F(fog.lod), 0, 0, "sum|switch", 0, 0},
    {"fog", "filtering", V_ENUM, F(fog.filtering), 0, 0, "manual|hardware", 0, 0},
    {"fog", "boundary", V_ENUM, F(fog.boundary), 0, 0, "symmetric|periodic", 0, 0},
    {"fog", "profile", V_ENUM, F(fog.profile), 0, 0, "slab|exponential|bspline", 0, 0},
    {"fog", "fog_height", V_DOUBLE, F(fog.fog_height), -WORLD, WORLD, NULL, 0, 0},
    {"fog", "scale_height", V_DOUBLE, F(fog.scale_height), MIN_LENGTH, SCENE_MAX_SCALE_HEIGHT, NULL,
     0, 0},
    {"fog", "fog_start", V_DOUBLE, F(fog.fog_start), 0, WORLD, NULL, 0, 0},
    {"fog", "fog_end", V_DOUBLE, F(fog.fog_end), MIN_LENGTH, WORLD, NULL, 0, 0},
    {"fog", "profile_degree", V_INT, F(fog.profile_degree), 0, 3, NULL, 0, 0},
    {"fog", "profile_origin", V_DOUBLE, F(fog.profile_origin), -WORLD, WORLD, NULL, 0, 0},
    {"fog", "profile_spacing", V_DOUBLE, F(fog.profile_spacing), MIN_LENGTH, WORLD, NULL, 0, 0},
    {"fog", "profile_coefficients", V_LIST, F(fog.profile_coefficients), 0, MAX_EXTINCTION, NULL, F(fog.profile_count), 0},
    {"fog", "colour", V_FLOAT3, F(fog.colour), 0, MAX_RADIANCE, NULL, 0, 0},
    {"fog", "albedo", V_DOUBLE, F(fog.albedo), 0, 1, NULL, 0, 0},
    {"fog", "phase_g", V_DOUBLE, F(fog.phase_g), -FOG_PHASE_G_MAX, FOG_PHASE_G_MAX, NULL, 0, 0},
    {"fog", "rbf", V_RBF, 0, 0, WORLD, NULL, 0, 0},
    {"fog", "quadric", V_QUADRIC, 0, 0, WORLD, NULL, 0, 0},
    {"fog", "rbf_emitter", V_RBF_EMITTER, 0, 0, WORLD, NULL, 0, 0},
    {"fog", "rbf_carrier", V_ENUM, F(fog.rbf_carrier), 0, 0, "wind|sim", 0, 0},
    {"fog", "rbf_base", V_DOUBLE, F(fog.rbf_base), 0, MAX_EXTINCTION, NULL, 0, 0},
    {"fog", "volume_step", V_DOUBLE, F(fog.volume_step), 0, WORLD, NULL, 0, 0},
    {"fog", "perlin_octaves", V_INT, F(fog.perlin_octaves), 1, FOG_PERLIN_MAX_OCTAVES, NULL, 0, 0},
    {"fog", "perlin_size", V_INT, F(fog.perlin_size), FOG_PERLIN_MIN_SIZE, FOG_PERLIN_MAX_SIZE, NULL, 0, 0},
    {"fog", "perlin_feature", V_DOUBLE, F(fog.perlin_feature), 1.0, WORLD, NULL, 0, 0},
    {"fog", "perlin_seed", V_UINT, F(fog.perlin_seed), 0, 4294967295.0, NULL, 0, 0},
    {"fog", "perlin_wind", V_LIST, F(fog.perlin_wind), -WORLD, WORLD, NULL, F(fog.perlin_wind_count), 0},
    {"fog", "perlin_integral", V_ENUM, F(fog.perlin_integral), 0, 0, "exact|paper", 0, 0},
    {"fog", "sequence", V_PATH, F(fog.sequence), 0, 0, NULL, F(fog.sequence_line), sizeof(((scene_config *)0)->fog.sequence)},
    {"fog", "vdb", V_PATH, F(fog.vdb), 0, 0, NULL, F(fog.vdb_line), sizeof(((scene_config *)0)->fog.vdb)},
    {"fog", "vdb_grid", V_STRING, F(fog.vdb_grid), 1, 0, NULL, 0, sizeof(((scene_config *)0)->fog.vdb_grid)},
    {"fog", "vdb_up", V_ENUM, F(fog.vdb_up), 0, 0, "z|y", 0, 0},
    {"fog", "vdb_fps", V_DOUBLE, F(fog.vdb_fps), 1e-6, 1e6, NULL, 0, 0},
    {"fog", "vdb_frame", V_INT, F(fog.vdb_frame), -1, 1e9, NULL, F(fog.vdb_frame_line), 0},
    {"fog", "vdb_resolution", V_INT, F(fog.vdb_resolution), 0, 16384, NULL, 0, 0},
    {"fog", "vdb_loop", V_INT, F(fog.vdb_loop), 0, 1, NULL, 0, 0},
    {"box", "origin", V_DOUBLE2, F(box.origin), -WORLD, WORLD, NULL, 0, 0},
    {"box", "cell_size", V_DOUBLE, F(box.cell_size), MIN_LENGTH, WORLD, NULL, 0, 0},
    {"box", "floor", V_DOUBLE, F(box.floor), -WORLD, WORLD, NULL, 0, 0},
    {"box", "top", V_DOUBLE, F(box.top), -WORLD, WORLD, NULL, 0, 0},
    {"camera", "position", V_DOUBLE3, F(camera.position), -WORLD, WORLD, NULL, 0, 0},
    {"camera", "yaw", V_DOUBLE, F(camera.yaw), -360, 360, NULL, 0, 0},
    {"camera", "pitch", V_DOUBLE, F(camera.pitch), -90, 90, NULL, 0, 0},
    {"camera", "fov", V_DOUBLE, F(camera.fov), 1, 170, NULL, 0, 0},
    {"camera", "look_at", V_LOOK_AT, F(camera.look_at), -WORLD, WORLD, NULL, 0, 0},
    {"camera", "near", V_DOUBLE, F(camera.near_plane), 1e-6, WORLD, NULL, 0, 0},
    {"camera", "far", V_DOUBLE, F(camera.far_plane), 1e-6, WORLD, NULL, 0, 0},
    {"terrain", "heightmap", V_PATH, F(terrain.heightmap), 0, 0, NULL, F(terrain.heightmap_line), sizeof(((scene_config *)0)->terrain.heightmap)},
    {"terrain", "origin", V_DOUBLE3, F(terrain.origin), -WORLD, WORLD, NULL, 0, 0},
    {"terrain", "size", V_DOUBLE2, F(terrain.size), 1e-6, WORLD, NULL, 0, 0},
    {"terrain", "height", V_DOUBLE, F(terrain.height), 0, WORLD, NULL, 0, 0},
    {"terrain", "resolution", V_INT, F(terrain.resolution), 2, TERRAIN_MAX_RESOLUTION, NULL, 0, 0},
    {"terrain", "octaves", V_INT, F(terrain.octaves), 1, 16, NULL, 0, 0},
    {"terrain", "frequency", V_DOUBLE, F(terrain.frequency), 1e-6, 1e6, NULL, 0, 0},
    {"terrain", "persistence", V_DOUBLE, F(terrain.persistence), 1e-6, 1, NULL, 0, 0},
    {"terrain", "seed", V_UINT, F(terrain.seed), 0, 4294967295.0, NULL, 0, 0},
    {"terrain", "lod_error", V_DOUBLE, F(terrain.lod_error), 0, 100, NULL, 0, 0},
    {"objects", "box", V_OBJECT, 0, -WORLD, WORLD, NULL, 0, 0},
    {"light", "sun_azimuth", V_DOUBLE, F(light.sun_azimuth), -360, 360, NULL, 0, 0},
    {"light", "sun_elevation", V_DOUBLE, F(light.sun_elevation), -90, 90, NULL, 0, 0},
    {"light", "sun_colour", V_FLOAT3, F(light.sun_colour), 0, MAX_RADIANCE, NULL, 0, 0},
    {"light", "ambient", V_FLOAT3, F(light.ambient), 0, MAX_RADIANCE, NULL, 0, 0},
    {"light", "sky_horizon", V_FLOAT3, F(light.sky_horizon), 0, MAX_RADIANCE, NULL, 0, 0},
    {"light", "sky_zenith", V_FLOAT3, F(light.sky_zenith), 0, MAX_RADIANCE, NULL, 0, 0},
    {"light", "fog_self_shadow", V_ENUM, F(shadow.fog_self_shadow), 0, 0, "off|on", 0, 0},
    {"light", "shafts", V_ENUM, F(shadow.shafts), 0, 0, "off|on", 0, 0},
    {"light", "shadow_resolution", V_INT, F(shadow.resolution), 2, FOG_SUN_SHADOW_MAX_SIZE, NULL, 0, 0},
    {"light", "shadow_steps", V_INT, F(shadow.steps), 1, 1024, NULL, 0, 0},
    {"light", "shadow_nodes", V_INT, F(shadow.nodes), 1, 2, NULL, 0, 0},
    {"light", "shadow_pieces", V_ENUM, F(shadow.pieces), 0, 0, "off|on|auto", 0, 0},
    {"light", "shaft_samples", V_INT, F(shadow.shaft_samples), 1, FOG_PASS_MAX_SHAFT_SAMPLES,
     NULL, 0, 0},
    {"light", "lamp", V_LAMP, 0, -WORLD, WORLD, NULL, 0, 0},
    {"light", "spot", V_LAMP, 0, -WORLD, WORLD, NULL, 0, 0},
    {"light", "lamp_path", V_LAMP_PATH, 0, -WORLD, WORLD, NULL, 0, 0},
    {"light", "lamp_flicker", V_LAMP_FLICKER, 0, 0, 0, NULL, 0, 0},
    {"light", "lamp_integral", V_ENUM, F(lamp_method.integral), 0, 0, "angle|fogshop|march", 0, 0},
    {"light", "lamp_march_steps", V_INT, F(lamp_method.march_steps), 1, 65536, NULL, 0, 0},
    {"light", "lamp_angle_pieces", V_INT, F(lamp_method.angle_pieces), 1, 256, NULL, 0, 0},
    {"light", "lamp_span_pieces", V_INT, F(lamp_method.span_pieces), 0, 256, NULL, 0, 0},
    {"light", "lamp_depth_steps", V_INT, F(lamp_method.depth_steps), 1, FOG_LAMP_MAX_DEPTH_STEPS, NULL, 0, 0},
    {"light", "lamp_shadow_steps", V_INT, F(lamp_method.shadow_steps), 1, 1024, NULL, 0, 0},
    {"light", "lamp_shadows", V_ENUM, F(shadow.lamp_shadows), 0, 0, "off|on", 0, 0},
    {"light", "lamp_shadow_size", V_INT, F(shadow.lamp_shadow_size), LAMP_SHADOW_SIZE_MIN, LAMP_SHADOW_SIZE_MAX, NULL, 0, 0},
    {"render", "width", V_INT, F(width), 1, 16384, NULL, 0, 0},
    {"render", "height", V_INT, F(height), 1, 16384, NULL, 0, 0},
    {"render", "transmittance_cutoff", V_DOUBLE, F(transmittance_cutoff), 0, 0.5, NULL, 0, 0},
    {"render", "empty_skip", V_ENUM, F(empty_skip), 0, 0, "off|on", 0, 0},
    {"render", "skip_below", V_DOUBLE, F(skip_below), 0, MAX_EXTINCTION, NULL, 0, 0},
    {"render", "exposure", V_DOUBLE, F(exposure), -20, 20, NULL, 0, 0},
    {"render", "tone_map", V_ENUM, F(tone_map), 0, 0, "clamp|aces|reinhard", 0, 0},
    {"render", "dither", V_ENUM, F(dither), 0, 0, "off|on", 0, 0},
    {"render", "supersample", V_INT, F(supersample), 1, 4, NULL, 0, 0},
    {"sim", "wind", V_DOUBLE2, F(sim.wind), -WORLD, WORLD, NULL, 0, 0},
    {"sim", "turbulence", V_DOUBLE, F(sim.turbulence), 0, WORLD, NULL, 0, 0},
    {"sim", "viscosity", V_DOUBLE, F(sim.viscosity), 0, WORLD, NULL, 0, 0},
    {"sim", "emitter_rate", V_DOUBLE, F(sim.emitter_rate), 0, MAX_EXTINCTION, NULL, 0, 0},
    {"sim", "seed", V_UINT, F(sim.seed), 0, 4294967295.0, NULL, 0, 0},
};
static int sequence_first_frame(const char *pattern);
static const char *const sections = "fog, box, camera, terrain, objects, light, render, sim";

void scene_config_init(scene_config *cfg) {
  const fog_perlin_desc perlin = fog_perlin_desc_default();
  *cfg = (scene_config){
      .fog = {.density_scale = 1.0, .degree = 1, .levels = 3, .mu = 1.0,
              .lod = SCENE_LOD_SWITCH, .filtering = SCENE_FILTERING_MANUAL,
              .boundary = SCENE_BOUNDARY_SYMMETRIC, .profile = SCENE_PROFILE_SLAB,
              .fog_height = 0.0, .scale_height = 10.0, .fog_start = 0.0, .fog_end = 1000.0,
              .profile_degree = 1,
              .profile_spacing = 1.0, .colour = {0.75f, 0.78f, 0.82f},
              .albedo = 0.0, .phase_g = 0.7,
              .vdb_grid = "density", .vdb_fps = 24.0, .vdb_frame = -1,
              .perlin_octaves = 3, .perlin_size = 32, .perlin_feature = 48.0, .perlin_seed = 1,
              .perlin_wind_count = 3 * FOG_PERLIN_MAX_OCTAVES},
      .box = {.origin = {-500, -500}, .cell_size = 1.0, .floor = 0.0, .top = 50.0},
      .camera = {.position = {0, 50, 100}, .fov = 60.0, .near_plane = 0.1, .far_plane = 100000.0},
      .terrain = {.origin = {-500, 0, -500}, .size = {1000, 1000}, .height = 150,
                  .resolution = 257, .octaves = 6, .frequency = 3.0, .persistence = 0.5,
                  .seed = 1, .lod_error = 1.0},
      .light = scene_light_default(),
      .shadow = {.fog_self_shadow = 1, .shafts = 1, .resolution = 48, .steps = 8, .nodes = 2,
                 .shaft_samples = 8, .pieces = 2, .lamp_shadows = 1, .lamp_shadow_size = LAMP_SHADOW_SIZE},
      .lamp_method = {.angle_pieces = FOG_LAMP_ANGLE_PIECES,
                      .span_pieces = FOG_LAMP_SPAN_PIECES, .march_steps = 64, .depth_steps = FOG_LAMP_DEPTH_STEPS,
                      .shadow_steps = FOG_LAMP_SHADOW_STEPS},
      .width = 1280,
      .height = 720,
      .transmittance_cutoff = FOG_PASS_TRANSMITTANCE_CUTOFF,
      .empty_skip = 1,
      .skip_below = 0.0,
      .exposure = 0.0,
      .tone_map = DISPLAY_CLAMP,
      .dither = 1,
      .supersample = 1,
  };
  memcpy(cfg->fog.perlin_wind, perlin.wind, sizeof perlin.wind); /* a drift per octave */
}

/* ---- parsing state ---- */

typedef struct parse_state {
  scene_config *cfg;
  const char *path;
  char folder[SCENE_CONFIG_PATH_MAX];
  FILE *file;
  int line;
  char *whole_line; /* the line being read, whatever its length (getline) */
  size_t whole_line_size;
  int error_line;     /* first error (0: none) */
  /* The line starts with blanks after a key of the same section: libinih
   * (INI_ALLOW_MULTILINE) hands it over as more of that key's value; a list (V_LIST)
   * appends it. after_key: a key was read since the section began (libinih's prev_name). */
  bool continuation, after_key;
  bool list_comma_open; /* the list line before ended with a comma (a list's next line may
                         * not start with one: two in a row) */
  /* A quadric line is stored once it is whole: it may go on over indented lines (a general
   * quadric's 17 numbers in full precision pass 199 bytes), so it waits for the next key or
   * the end of the file (finish_quadric). */
  char quadric_text[1024];
  int quadric_line; /* its first line; 0: none waiting */
  fog_error *err;
  int key_line[sizeof keys / sizeof keys[0]]; /* where each key was last set (0: default) */
  int flicker_line[FOG_MAX_LAMPS]; /* each lamp's lamp_flicker line (0: none) */
  int box_line[SCENE_MAX_BOXES];   /* each [objects] box's line */
  bool in_memory; /* scene_config_check: a scene, not a file; errors name the key alone */
  /* scene_config_write's check of its own text: the files it names are not looked at (bake
   * writes its config before its frames) */
  bool no_files;
} parse_state;

/* The line of [section] key (0: not in the file: its default). */
static int key_line(const parse_state *s, const char *section, const char *key) {
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
    if (!strcmp(keys[i].section, section) && !strcmp(keys[i].key, key)) return s->key_line[i];
  return 0;
}

static int finish_quadric(parse_state *s);

/* fgets-style reader for ini_parse_stream that counts lines. */
static char *read_line(char *buffer, int size, void *stream) {
  parse_state *s = stream;
  ssize_t n = getline(&s->whole_line, &s->whole_line_size, s->file);
  if (n < 0) return NULL;
  s->line++;
  /* a UTF-8 byte order mark (an editor's) is not text: the first line's checks below looked
   * past it at nothing ("[fog] x" was taken as [fog]) */
  if (s->line == 1 && n >= 3 && !memcmp(s->whole_line, "\xEF\xBB\xBF", 3)) {
    memmove(s->whole_line, s->whole_line + 3, (size_t)n - 2);
    n -= 3;
  }
  /* a NUL byte ends the line for libinih: the rest of it was dropped without a word */
  if (strlen(s->whole_line) < (size_t)n && !s->error_line) {
    s->error_line = s->line;
    fog_fail(s->err, FOG_ERR_BAD_CONFIG, "%s:%d: a NUL byte at column %zu: expected text",
             s->path, s->line, strlen(s->whole_line) + 1);
    return NULL;
  }
  /* libinih hands its reader a fixed buffer (INI_MAX_LINE, 200 bytes in Debian's build) and
   * used to parse the rest of a longer line as a line of its own, so the tail of a long
   * comment became a key. Here a whole line is read: a long comment or blank line is
   * passed on cut short (it means nothing), a long line with content is an error. */
  const char *p = s->whole_line + strspn(s->whole_line, " \t\r\n");
  if (*p == '[' && p > s->whole_line && s->after_key && !s->error_line) {
    /* libinih takes an indented line after a key as more of that key's value: the
     * section would be lost and the key reported for what the header says */
    s->error_line = s->line;
    fog_fail(s->err, FOG_ERR_BAD_CONFIG, "%s:%d: '%.*s' is indented, which continues the key "
             "above; a section header starts at the line's beginning", s->path, s->line,
             (int)strcspn(p, "\r\n"), p);
    return NULL;
  }
  if (*p == '[') {
    s->after_key = false; /* a section starts: no key to go on */
    /* libinih takes "[fog] x" and "[fog]]" as [fog], ignoring the rest: refuse them */
    const char *close = strchr(p, ']');
    const char *rest = close ? close + 1 + strspn(close + 1, " \t\r\n") : NULL;
    if (!s->error_line && close && ((*rest && *rest != ';' && *rest != '#') || close == p + 1)) {
      s->error_line = s->line;
      fog_fail(s->err, FOG_ERR_BAD_CONFIG, "%s:%d: expected '[section]', got '%.*s'", s->path,
               s->line, (int)strcspn(p, "\r\n"), p);
      return NULL;
    }
  }
  s->continuation = s->after_key && p > s->whole_line && *p && *p != ';' && *p != '#';
  /* libinih also splits a key from its value at ':' ("density_scale: 0.5" loaded as a key):
   * a config's keys take '=' alone (a value may hold ':', a path's) */
  if (*p != '[' && *p != ';' && *p != '#' && *p && !s->continuation && !s->error_line &&
      p[strcspn(p, "=:")] == ':') {
    s->error_line = s->line;
    fog_fail(s->err, FOG_ERR_BAD_CONFIG, "%s:%d: expected KEY = VALUE, got '%.*s' (a key "
             "takes '=', not ':')", s->path, s->line, (int)strcspn(p, "\r\n"), p);
    return NULL;
  }
  /* the line's bytes without its end (\n or \r\n), which libinih strips anyway: a line of
   * 199 bytes fits the buffer whatever ends it */
  while (n > 0 && (s->whole_line[n - 1] == '\n' || s->whole_line[n - 1] == '\r')) n--;
  s->whole_line[n] = '\0';
  if (n < size) {
    memcpy(buffer, s->whole_line, (size_t)n + 1);
  } else if (*p == ';' || *p == '#' || !*p) {
    snprintf(buffer, (size_t)size, ";\n");
  } else if (!s->error_line && (s->continuation || finish_quadric(s))) {
    /* (a quadric held from above is whole: its own mistake comes first) */
    s->error_line = s->line;
    fog_fail(s->err, FOG_ERR_BAD_CONFIG,
             "%s:%d: the line is %zd bytes long; a config line other than a comment can hold "
             "at most %d",
             s->path, s->line, n, size - 1);
    return NULL;
  } else {
    return NULL;
  }
  return buffer;
}

/* The first error of the file: FILE:LINE: [section] key: and the text, with `code` (a
 * config's own mistake is FOG_ERR_BAD_CONFIG; a sound line naming a file that is not there,
 * the file's). Returns 0 for the parser (stop). */
static int vfail_as(parse_state *s, fog_result code, const char *section, const char *key,
                    const char *fmt, va_list args) {
  if (s->error_line) return 0; /* keep the first error */
  s->error_line = s->line ? s->line : -1;
  char detail[sizeof s->err->message];
  vsnprintf(detail, sizeof detail, fmt, args);
  /* line 0: a check after parsing on a key the file does not set (its default) */
  if (s->in_memory)
    fog_fail(s->err, code, "[%s] %s: %s", section, key, detail);
  else if (s->line)
    fog_fail(s->err, code, "%s:%d: [%s] %s: %s", s->path, s->line, section, key, detail);
  else
    fog_fail(s->err, code, "%s: [%s] %s (its default): %s", s->path, section, key, detail);
  return 0;
}

static int fail_as(parse_state *s, fog_result code, const char *section, const char *key,
                   const char *fmt, ...) __attribute__((format(printf, 5, 6)));
static int fail_as(parse_state *s, fog_result code, const char *section, const char *key,
                   const char *fmt, ...) {
  va_list args;
  va_start(args, fmt);
  vfail_as(s, code, section, key, fmt, args);
  va_end(args);
  return 0;
}

static int fail(parse_state *s, const char *section, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int fail(parse_state *s, const char *section, const char *key, const char *fmt, ...) {
  va_list args;
  va_start(args, fmt);
  vfail_as(s, FOG_ERR_BAD_CONFIG, section, key, fmt, args);
  va_end(args);
  return 0;
}

/* Reads up to max numbers separated by spaces and/or commas; returns the count, or -1 if
 * something is not a number. */
static int parse_numbers(const char *text, double *out, int max) {
  int count = 0;
  const char *p = text;
  for (;;) {
    /* numbers apart by blanks and at most one comma ("1,,2" read as two numbers: a list
     * lost one silently); a comma may lead or end a line (a list over several lines) */
    while (*p == ' ' || *p == '\t') p++;
    if (*p == ',') {
      p++;
      while (*p == ' ' || *p == '\t') p++;
      if (*p == ',') return -1;
    }
    if (!*p) return count;
    if (count == max) return -1;
    char *end;
    double v = strtod(p, &end);
    /* no ERANGE test: an overflow is infinite (refused), an underflow (1e-320) the number
     * nearest it, which the key's range then takes or names */
    if (end == p || !isfinite(v)) return -1;
    if (memchr(p, 'x', (size_t)(end - p)) || memchr(p, 'X', (size_t)(end - p)))
      return -1; /* strtod reads hexadecimal too; numbers here are decimal */
    if (*end && *end != ' ' && *end != '\t' && *end != ',') return -1;
    out[count++] = v;
    p = end;
  }
}

static int numbers(parse_state *s, const key_spec *k, const char *section, const char *key,
                   const char *value, double *out, int want_min, int want_max,
                   const char *expected) {
  int n = parse_numbers(value, out, want_max);
  if (n < want_min || n > want_max)
    return fail(s, section, key, "expected %s, got '%s'", expected, value);
  for (int i = 0; i < n; i++)
    if (out[i] < k->min || out[i] > k->max) {
      if (k->max >= BIG)
        return fail(s, section, key, "expected a number >= %g, got '%s'", k->min, value);
      if (k->min <= -BIG)
        return fail(s, section, key, "expected a number <= %g, got '%s'", k->max, value);
      if (k->kind == V_INT || k->kind == V_UINT) /* in full: %g printed 4.29497e+09 */
        return fail(s, section, key, "expected a whole number from %.0f to %.0f, got '%s'",
                    k->min, k->max, value);
      return fail(s, section, key, "expected a number from %g to %g, got '%s'", k->min, k->max,
                  value);
    }
  return n;
}

/* Fails (0) when the resolved path would not fit. */
static int resolve_path(const parse_state *s, const char *value, char *out, size_t size) {
  int n = value[0] == '/' || !s->folder[0] ? snprintf(out, size, "%s", value)
                                           : snprintf(out, size, "%s/%s", s->folder, value);
  return n >= 0 && (size_t)n < size;
}

static int handle_key(parse_state *s, const char *section, const char *key, const char *value);

/* Keys whose presence matters beyond their value: a VDB fills the profile and the box
 * unless the file sets them (docs/config.md, [fog] vdb). */
static int handle(void *user, const char *section, const char *key, const char *value) {
  parse_state *s = user;
  int ok = handle_key(s, section, key, value);
  if (!ok || s->error_line) return ok;
  scene_config *cfg = s->cfg;
  if (!strcmp(section, "fog") && !strcmp(key, "profile")) cfg->fog.profile_set = true;
  if (!strcmp(section, "fog") && !strcmp(key, "model")) cfg->fog.model_line = s->line;
  if (!strcmp(section, "fog") && !strcmp(key, "rbf_carrier")) cfg->fog.rbf_carrier_line = s->line;
  if (!strcmp(section, "light") && !strcmp(key, "lamp_integral")) cfg->lamp_integral_line = s->line;
  if (!strcmp(section, "render") && !strcmp(key, "supersample")) cfg->supersample_line = s->line;
  if (!strcmp(section, "box")) {
    if (!strcmp(key, "origin")) cfg->box.origin_set = true;
    if (!strcmp(key, "cell_size")) cfg->box.cell_size_set = true;
    if (!strcmp(key, "floor")) cfg->box.floor_set = true, cfg->box.floor_line = s->line;
    if (!strcmp(key, "top")) cfg->box.top_set = true, cfg->box.top_line = s->line;
  }
  return ok;
}

/* Levenshtein distance of two short names (insertions, deletions, substitutions). */
static int edit_distance(const char *a, const char *b) {
  enum { MAX_NAME = 64 };
  const size_t n = strlen(a), m = strlen(b);
  if (n >= MAX_NAME || m >= MAX_NAME) return MAX_NAME; /* no key is that long: far */
  int row[MAX_NAME];
  for (size_t j = 0; j <= m; j++) row[j] = (int)j;
  for (size_t i = 1; i <= n; i++) {
    int diagonal = row[0];
    row[0] = (int)i;
    for (size_t j = 1; j <= m; j++) {
      const int above = row[j];
      const int substitute = diagonal + (a[i - 1] != b[j - 1]);
      row[j] = substitute < above + 1 ? substitute : above + 1;
      if (row[j - 1] + 1 < row[j]) row[j] = row[j - 1] + 1;
      diagonal = above;
    }
  }
  return row[m];
}

/* The spec of [section] key, or NULL after the error that says which sections or keys
 * there are. */
static const key_spec *lookup_key(parse_state *s, const char *section, const char *key) {
  bool section_known = false;
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
    if (!strcmp(keys[i].section, section)) {
      section_known = true;
      if (!strcmp(keys[i].key, key)) return &keys[i];
    }
  if (!section_known) {
    if (!section[0]) fail(s, "", key, "key outside any section; sections are %s", sections);
    else fail(s, section, key, "unknown section [%s]; sections are %s", section, sections);
    return NULL;
  }
  /* the nearest key of the section (a typo: at most a third of its letters off), and the
   * section's keys when they fit the message */
  const char *nearest = NULL;
  int nearest_distance = INT_MAX / 4, count = 0;
  char known[400] = "";
  bool cut = false;
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
    if (!strcmp(keys[i].section, section)) {
      const int d = edit_distance(key, keys[i].key);
      if (d < nearest_distance) nearest = keys[i].key, nearest_distance = d;
      size_t used = strlen(known);
      int n = snprintf(known + used, sizeof known - used, "%s%s", used ? ", " : "", keys[i].key);
      if (n < 0 || (size_t)n >= sizeof known - used) cut = true;
      count++;
    }
  char guess[96] = "";
  if (nearest && 3 * nearest_distance <= (int)strlen(nearest))
    snprintf(guess, sizeof guess, "did you mean '%s'? ", nearest);
  if (cut)
    fail(s, section, key, "unknown key; %s[%s] has %d keys (docs/config.md lists them)", guess,
         section, count);
  else
    fail(s, section, key, "unknown key; %s[%s] has %s", guess, section, known);
  return NULL;
}

/* V_ENUM: the index of value among k->names. */
static int store_enum(parse_state *s, const key_spec *k, const char *section, const char *key,
                      const char *value, int *field) {
  int index = 0;
  for (const char *p = k->names;; index++) {
    const char *bar = strchr(p, '|');
    size_t n = bar ? (size_t)(bar - p) : strlen(p);
    if (strlen(value) == n && !strncmp(p, value, n)) {
      *field = index;
      return 1;
    }
    if (!bar) break;
    p = bar + 1;
  }
  return fail(s, section, key, "expected one of %s, got '%s'", k->names, value);
}

/* V_OBJECT: box = X Z WIDTH HEIGHT DEPTH [R G B], appended. */
static int store_box(parse_state *s, const char *section, const char *key, const char *value) {
  scene_config *cfg = s->cfg;
  double v[8];
  int n = parse_numbers(value, v, 8);
  if (n != 5 && n != 8)
    return fail(s, section, key, "expected X Z WIDTH HEIGHT DEPTH [R G B], got '%s'", value);
  if (!(v[2] > 0 && v[3] > 0 && v[4] > 0))
    return fail(s, section, key, "expected positive WIDTH HEIGHT DEPTH, got '%s'", value);
  for (int i = 0; i < n; i++) {
    bool colour = i >= 5, position = i < 2;
    double lo = colour ? 0.0 : position ? -WORLD : MIN_LENGTH, hi = colour ? MAX_RADIANCE : WORLD;
    if (!(v[i] >= lo && v[i] <= hi))
      return fail(s, section, key, "number %d (%g) of X Z WIDTH HEIGHT DEPTH [R G B]: expected "
                  "%g to %g, got '%s'", i + 1, v[i], lo, hi, value);
  }
  if (cfg->object_count == SCENE_MAX_BOXES)
    return fail(s, section, key, "at most %d boxes", SCENE_MAX_BOXES);
  s->box_line[cfg->object_count] = s->line;
  scene_box_desc *b = &cfg->objects[cfg->object_count++];
  *b = (scene_box_desc){.center = {v[0], v[1]}, .size = {v[2], v[3], v[4]},
                        .colour = SCENE_BOX_GREY};
  if (n == 8)
    for (int i = 0; i < 3; i++) b->colour[i] = (float)v[5 + i];
  return 1;
}

/* V_RBF: rbf = X Y Z RADIUS DENSITY, appended. */
static int store_rbf(parse_state *s, const char *section, const char *key, const char *value) {
  scene_config *cfg = s->cfg;
  double v[5];
  int n = parse_numbers(value, v, 5);
  if (n != 5)
    return fail(s, section, key, "expected X Y Z RADIUS DENSITY (5 numbers), got '%s'", value);
  if (!(fabs(v[0]) <= WORLD && fabs(v[1]) <= WORLD && fabs(v[2]) <= WORLD))
    return fail(s, section, key, "expected X Y Z from -%g to %g, got '%s'", WORLD, WORLD, value);
  if (!(v[3] >= MIN_LENGTH && v[3] <= WORLD && v[4] >= 0 && v[4] <= MAX_EXTINCTION))
    return fail(s, section, key, "expected RADIUS from %g to %g and DENSITY from 0 to %g, "
                "got '%s'", MIN_LENGTH, WORLD, MAX_EXTINCTION, value);
  if (cfg->fog.rbf_count == SCENE_CONFIG_MAX_RBFS)
    return fail(s, section, key, "at most %d Gaussians", SCENE_CONFIG_MAX_RBFS);
  cfg->fog.rbfs[cfg->fog.rbf_count++] =
      (fog_rbf){.centre = {v[0], v[1], v[2]}, .radius = v[3], .density = v[4]};
  return 1;
}

/* V_RBF_EMITTER: rbf_emitter = X Y Z RATE LIFETIME RADIUS DENSITY SPREAD DIFFUSION WX WY WZ
 * [SEED], appended (render/fog_rbf_emitter.h). */
static int store_rbf_emitter(parse_state *s, const char *section, const char *key,
                             const char *value) {
  scene_config *cfg = s->cfg;
  double v[13];
  int n = parse_numbers(value, v, 13);
  if (n != 12 && n != 13)
    return fail(s, section, key, "expected X Y Z RATE LIFETIME RADIUS DENSITY SPREAD DIFFUSION "
                "WX WY WZ [SEED] (12 or 13 numbers), got '%s'", value);
  static const char *const names[12] = {"X", "Y", "Z", "RATE", "LIFETIME", "RADIUS", "DENSITY",
                                        "SPREAD", "DIFFUSION", "WX", "WY", "WZ"};
  for (int i = 0; i < 12; i++) {
    /* positions and wind: world; RATE, LIFETIME, RADIUS > 0; the rest >= 0 */
    double lo = i < 3 || i >= 9 ? -WORLD : i == 6 || i == 7 || i == 8 ? 0.0 : MIN_LENGTH;
    double hi = i == 6 ? MAX_EXTINCTION : WORLD;
    if (!(v[i] >= lo && v[i] <= hi))
      return fail(s, section, key, "%s (%g): expected %g to %g", names[i], v[i], lo, hi);
  }
  if (n == 13 && !(v[12] >= 0 && v[12] <= 4294967295.0 && v[12] == floor(v[12])))
    return fail(s, section, key, "SEED (%g): expected a whole number from 0 to 4294967295",
                v[12]);
  if (cfg->fog.rbf_emitter_count == SCENE_CONFIG_MAX_EMITTERS)
    return fail(s, section, key, "at most %d emitters", SCENE_CONFIG_MAX_EMITTERS);
  fog_rbf_emitter e = {.position = {v[0], v[1], v[2]}, .rate = v[3], .lifetime = v[4],
                       .radius = v[5], .density = v[6], .spread = v[7], .diffusion = v[8],
                       .wind = {v[9], v[10], v[11]},
                       /* without SEED, its place among the emitters (0 for the first): two
                        * emitters without one put every puff at the same offset, each plume
                        * a copy of the other */
                       .seed = n == 13 ? (uint64_t)v[12] : (uint64_t)cfg->fog.rbf_emitter_count};
  /* in double: RATE x LIFETIME can pass INT_MAX (1e7 x 1e7), where the count's int cast
   * is undefined and came out negative */
  double puffs = ceil(e.rate * e.lifetime - 1e-9);
  for (int i = 0; i < cfg->fog.rbf_emitter_count; i++)
    puffs += fog_rbf_emitter_count(&cfg->fog.rbf_emitters[i]);
  if (puffs + SCENE_CONFIG_MAX_RBFS > FOG_MAX_RBFS)
    return fail(s, section, key, "RATE x LIFETIME: %.6g puffs alive at once in all, expected "
                "at most %d", puffs, FOG_MAX_RBFS - SCENE_CONFIG_MAX_RBFS);
  cfg->fog.rbf_emitters[cfg->fog.rbf_emitter_count++] = e;
  return 1;
}

/* V_QUADRIC: quadric = SHAPE NUMBERS [EDGE [NOISE]], appended; the shapes' numbers
 *   (docs/config.md): sphere X Y Z R DENSITY, ellipsoid X Y Z RX RY RZ DENSITY, cylinder and
 *   cone X Y Z R HEIGHT DENSITY (upright, standing on (X, Y, Z); the cone's apex on top),
 *   general A B C D E F G H I J XMIN YMIN ZMIN XMAX YMAX ZMAX DENSITY; then EDGE, the soft
 *   edge (default 0: a hard edge; for the shapes a share of Q's range, 0..1), and NOISE, the
 *   share of the density the Perlin octaves' turbulence modulates (default 0; 0..1). */
#define QUADRIC_MAX_COEFFICIENT 1e12
enum quadric_shape { SHAPE_SPHERE, SHAPE_ELLIPSOID, SHAPE_CYLINDER, SHAPE_CONE, SHAPE_GENERAL };
static const struct {
  const char *name, *numbers;
  int count; /* without EDGE */
} shapes[] = {[SHAPE_SPHERE] = {"sphere", "X Y Z R DENSITY", 5},
              [SHAPE_ELLIPSOID] = {"ellipsoid", "X Y Z RX RY RZ DENSITY", 7},
              [SHAPE_CYLINDER] = {"cylinder", "X Y Z R HEIGHT DENSITY", 6},
              [SHAPE_CONE] = {"cone", "X Y Z R HEIGHT DENSITY", 6},
              [SHAPE_GENERAL] = {"general",
                                 "A B C D E F G H I J XMIN YMIN ZMIN XMAX YMAX ZMAX DENSITY", 17}};
static int store_quadric(parse_state *s, const char *section, const char *key, const char *value) {
  scene_config *cfg = s->cfg;
  size_t word = strcspn(value, " \t,"); /* "sphere, 0 0 0 10 0.1" as numbers are written */
  int kind = -1;
  for (int i = 0; i < (int)(sizeof shapes / sizeof shapes[0]); i++)
    if (strlen(shapes[i].name) == word && !strncmp(value, shapes[i].name, word)) kind = i;
  if (kind < 0)
    return fail(s, section, key, "expected a shape (sphere, ellipsoid, cylinder, cone or "
                "general) and its numbers, got '%s'", value);
  double v[19];
  /* parse_numbers takes the one comma after the shape ("sphere, 0 50 0 30 0.1") and
   * refuses a second */
  const int want = shapes[kind].count, n = parse_numbers(value + word, v, want + 2);
  if (n < want || n > want + 2)
    return fail(s, section, key, "expected %s %s [EDGE [NOISE]] (%d to %d numbers), got '%s'",
                shapes[kind].name, shapes[kind].numbers, want, want + 2, value);
  const double density = v[want - 1], edge = n > want ? v[want] : 0.0;
  const double noise = n > want + 1 ? v[want + 1] : 0.0;
  const bool general = kind == SHAPE_GENERAL;
  if (!(density >= 0 && density <= MAX_EXTINCTION && edge >= 0 &&
        edge <= (general ? QUADRIC_MAX_COEFFICIENT : 1.0) && noise >= 0 && noise <= 1))
    return fail(s, section, key, "expected DENSITY from 0 to %g, EDGE from 0 to %g and NOISE "
                "from 0 to 1, got '%s'", MAX_EXTINCTION, general ? QUADRIC_MAX_COEFFICIENT : 1.0,
                value);
  for (int i = 0; i < want - 1; i++) {
    /* general: coefficients, then a box; the shapes: a position, then lengths */
    bool coefficient = general && i < 10, position = general ? i >= 10 : i < 3;
    double lo = coefficient ? -QUADRIC_MAX_COEFFICIENT : position ? -WORLD : MIN_LENGTH;
    double hi = coefficient ? QUADRIC_MAX_COEFFICIENT : WORLD;
    if (!(v[i] >= lo && v[i] <= hi))
      return fail(s, section, key, "number %d (%g) of %s %s: expected %g to %g", i + 1, v[i],
                  shapes[kind].name, shapes[kind].numbers, lo, hi);
  }
  if (general && !(v[10] < v[13] && v[11] < v[14] && v[12] < v[15]))
    return fail(s, section, key, "expected XMIN < XMAX, YMIN < YMAX and ZMIN < ZMAX, got '%s'",
                value);
  if (cfg->fog.quadric_count == FOG_MAX_QUADRICS)
    return fail(s, section, key, "at most %d quadric volumes", FOG_MAX_QUADRICS);
  struct scene_quadric_line *line = &cfg->fog.quadric_lines[cfg->fog.quadric_count];
  *line = (struct scene_quadric_line){.shape = kind, .count = n};
  for (int i = 0; i < n; i++) line->numbers[i] = v[i];
  fog_quadric *q = &cfg->fog.quadrics[cfg->fog.quadric_count++];
  switch (kind) {
    case SHAPE_SPHERE: *q = fog_quadric_sphere(v, v[3], density, edge); break;
    case SHAPE_ELLIPSOID: *q = fog_quadric_ellipsoid(v, v + 3, density, edge); break;
    case SHAPE_CYLINDER: *q = fog_quadric_cylinder(v, v[3], v[4], density, edge); break;
    case SHAPE_CONE: *q = fog_quadric_cone(v, v[3], v[4], density, edge); break;
    default:
      *q = (fog_quadric){.density = density, .edge = edge};
      for (int i = 0; i < 10; i++) q->q[i] = v[i];
      for (int a = 0; a < 3; a++) q->lo[a] = v[10 + a], q->hi[a] = v[13 + a];
  }
  q->noise = noise;
  if (noise > 0 && !cfg->fog.quadric_noise_line) cfg->fog.quadric_noise_line = s->line;
  return 1;
}

/* The quadric line waiting (parse_state.quadric_text), stored with its first line's
 * number in any message. */
static int finish_quadric(parse_state *s) {
  if (!s->quadric_line) return 1;
  const int line = s->line;
  s->line = s->quadric_line;
  s->quadric_line = 0;
  int ok = store_quadric(s, "fog", "quadric", s->quadric_text);
  s->line = line;
  return ok;
}

/* quadric = ...: the line waits for its indented continuations (finish_quadric). */
static int hold_quadric(parse_state *s, const char *value) {
  if (s->continuation && strchr(value, '='))
    return fail(s, "fog", "quadric", "an indented line goes on with the volume above: unindent "
                "'%s'", value);
  if (!s->continuation) {
    s->quadric_line = s->line;
    s->quadric_text[0] = '\0';
  }
  const size_t used = strlen(s->quadric_text);
  int n = snprintf(s->quadric_text + used, sizeof s->quadric_text - used, "%s%s",
                   used ? " " : "", value);
  if (n < 0 || (size_t)n >= sizeof s->quadric_text - used) {
    s->line = s->quadric_line;
    return fail(s, "fog", "quadric", "the volume's lines hold more than %zu bytes",
                sizeof s->quadric_text - 1);
  }
  return 1;
}

/* V_LAMP: lamp = X Y Z R G B [RADIUS]; spot = X Y Z R G B DX DY DZ INNER OUTER [RADIUS]
 * (half-angles in degrees); appended. */
#define LAMP_RADIUS 0.5
static int store_lamp(parse_state *s, const char *section, const char *key, const char *value) {
  scene_config *cfg = s->cfg;
  const bool spot = !strcmp(key, "spot");
  const int want = spot ? 11 : 6;
  double v[13];
  int n = parse_numbers(value, v, 13);
  if (n != want && n != want + 1)
    return fail(s, section, key, spot ? "expected X Y Z R G B DX DY DZ INNER OUTER [RADIUS] "
                                        "(11 or 12 numbers), got '%s'"
                                      : "expected X Y Z R G B [RADIUS] (6 or 7 numbers), got '%s'",
                value);
  for (int i = 0; i < 3; i++)
    if (!(fabs(v[i]) <= WORLD))
      return fail(s, section, key, "expected a position within %g of the origin, got '%s'",
                  WORLD, value);
  for (int i = 3; i < 6; i++)
    if (!(v[i] >= 0 && v[i] <= 1e9))
      return fail(s, section, key, "expected R G B (colour x intensity) from 0 to 1e9, got '%s'",
                  value);
  double radius = n == want + 1 ? v[want] : LAMP_RADIUS;
  if (!(radius >= MIN_LENGTH && radius <= WORLD))
    return fail(s, section, key, "expected RADIUS from %g to %g, got %g", MIN_LENGTH, WORLD,
                radius);
  scene_lamp_config lamp = {.spot = spot, .position = {v[0], v[1], v[2]},
                            .colour = {v[3], v[4], v[5]}, .radius = radius};
  if (spot) {
    double len = sqrt(v[6] * v[6] + v[7] * v[7] + v[8] * v[8]);
    if (!(len > 1e-9 && len <= WORLD))
      return fail(s, section, key, "expected a direction DX DY DZ of non-zero length, got '%s'",
                  value);
    /* the cone's edge is a ramp between the cosines, which the shaders take as float: the
     * fog pass refuses cosines closer than FOG_SPOT_MIN_COSINE_GAP (10 and
     * 10.00000000000001 differ, their cosines do not; a 0.01 degree cone was dark) */
    if (!(v[9] >= 0 && v[9] < v[10] && v[10] <= 180 &&
          cos(v[9] * DEG) - cos(v[10] * DEG) >= FOG_SPOT_MIN_COSINE_GAP))
      return fail(s, section, key, "expected half-angles 0 <= INNER < OUTER <= 180 (degrees) "
                  "whose cosines differ by %g or more (an outer cone of 0.26 about an inner "
                  "0), got %.17g and %.17g", FOG_SPOT_MIN_COSINE_GAP, v[9], v[10]);
    for (int i = 0; i < 3; i++) lamp.axis[i] = v[6 + i];
    lamp.inner = v[9], lamp.outer = v[10];
  }
  if (cfg->lamp_count == FOG_MAX_LAMPS)
    return fail(s, section, key, "at most %d lamps (lamp and spot lines together)", FOG_MAX_LAMPS);
  cfg->lamps[cfg->lamp_count++] = lamp;
  return 1;
}

/* The lamp a lamp_path or lamp_flicker line names: INDEX, 1-based among the lamp and spot
 * lines above it. NULL after the error. */
static scene_lamp_config *lamp_of_index(parse_state *s, const char *section, const char *key,
                                        double index) {
  scene_config *cfg = s->cfg;
  if (!(index >= 1 && index <= cfg->lamp_count && index == floor(index))) {
    fail(s, section, key, "lamp %g: expected the number (1 to %d) of a lamp or spot line above",
         index, cfg->lamp_count);
    return NULL;
  }
  return &cfg->lamps[(int)index - 1];
}

/* V_LAMP_PATH: lamp_path = INDEX T X Y Z, times increasing per lamp. */
static int store_lamp_path(parse_state *s, const char *section, const char *key,
                           const char *value) {
  double v[6];
  if (parse_numbers(value, v, 6) != 5)
    return fail(s, section, key, "expected INDEX T X Y Z (5 numbers), got '%s'", value);
  scene_lamp_config *lamp = lamp_of_index(s, section, key, v[0]);
  if (!lamp) return 0;
  for (int i = 1; i < 5; i++)
    if (!(fabs(v[i]) <= WORLD))
      return fail(s, section, key, "expected T X Y Z within %g, got '%s'", WORLD, value);
  if (lamp->key_count == SCENE_LAMP_MAX_KEYS)
    return fail(s, section, key, "at most %d keys per lamp", SCENE_LAMP_MAX_KEYS);
  if (lamp->key_count > 0 && !(v[1] > lamp->keys[lamp->key_count - 1][0]))
    return fail(s, section, key, "time %g: expected times after the lamp's last key (%g)", v[1],
                lamp->keys[lamp->key_count - 1][0]);
  for (int i = 0; i < 4; i++) lamp->keys[lamp->key_count][i] = v[1 + i];
  lamp->key_count++;
  return 1;
}

/* V_LAMP_FLICKER: lamp_flicker = INDEX AMOUNT RATE [SEED]. */
static int store_lamp_flicker(parse_state *s, const char *section, const char *key,
                              const char *value) {
  double v[5];
  int n = parse_numbers(value, v, 5);
  if (n != 3 && n != 4)
    return fail(s, section, key, "expected INDEX AMOUNT RATE [SEED] (3 or 4 numbers), got '%s'",
                value);
  scene_lamp_config *lamp = lamp_of_index(s, section, key, v[0]);
  if (!lamp) return 0;
  if (!(v[1] >= 0 && v[1] <= 1 && v[2] > 0 && v[2] <= 1e3))
    return fail(s, section, key, "expected AMOUNT from 0 to 1 and RATE in (0, 1000] per second, "
                "got '%s'", value);
  if (n == 4 && !(v[3] >= 0 && v[3] <= 4294967295.0 && v[3] == floor(v[3])))
    return fail(s, section, key, "expected SEED an integer from 0 to 4294967295, got '%s'", value);
  /* a lamp has one flicker: a second line would replace the first without a word */
  int *line = &s->flicker_line[lamp - s->cfg->lamps];
  if (*line)
    return fail(s, section, key, "lamp %g has a flicker already (line %d)", v[0], *line);
  *line = s->line;
  lamp->flicker_amount = v[1], lamp->flicker_rate = v[2];
  lamp->flicker_seed = n == 4 ? (unsigned)v[3] : 1u;
  return 1;
}

/* V_LIST: 1 to SCENE_CONFIG_MAX_PROFILE numbers in the key's range, the count at
 * k->aux_offset. They may go on over indented lines below the key (a config line holds
 * 199 bytes; 64 coefficients take more): each such line appends. */
static int store_list(parse_state *s, const key_spec *k, const char *section, const char *key,
                      const char *value) {
  int *count = (int *)((char *)s->cfg + k->aux_offset);
  const int had = s->continuation ? *count : 0;
  /* a comma may end one line or start the next, not both (parse_numbers' one comma) */
  const char *first = value + strspn(value, " \t");
  if (had && s->list_comma_open && *first == ',')
    return fail(s, section, key, "two commas in a row (one ends the line above), got '%s'",
                value);
  const size_t length = strcspn(value, ";\r\n");
  size_t end = length;
  while (end > 0 && (value[end - 1] == ' ' || value[end - 1] == '\t')) end--;
  s->list_comma_open = end > 0 && value[end - 1] == ',';
  double *field = (double *)((char *)s->cfg + k->offset) + had;
  int n = parse_numbers(value, field, SCENE_CONFIG_MAX_PROFILE - had);
  if (n < 1)
    return fail(s, section, key, "expected 1 to %d numbers in all, got '%s'%s",
                SCENE_CONFIG_MAX_PROFILE, value, had ? " after those above" : "");
  for (int i = 0; i < n; i++)
    if (!(field[i] >= k->min && field[i] <= k->max))
      return fail(s, section, key, "expected numbers from %g to %g%s, got '%s'", k->min, k->max,
                  k->min == 0 ? " (fog density)" : "", value);
  if (k->offset == F(fog.perlin_wind) && !had) s->cfg->fog.perlin_wind_line = s->line;
  *count = had + n;
  return 1;
}

static int handle_key(parse_state *s, const char *section, const char *key, const char *value) {
  scene_config *cfg = s->cfg;
  s->after_key = true;
  /* a quadric line held is whole unless this line goes on with it: its mistakes come first */
  const bool continues_quadric = s->continuation && !strcmp(section, "fog") &&
                                 !strcmp(key, "quadric");
  if (!continues_quadric && !finish_quadric(s)) return 0;
  const key_spec *k = lookup_key(s, section, key);
  if (!k) return 0;
  /* A value key given twice is a mistake (which one did the author mean?); the appending
   * keys (boxes, RBFs, quadrics, emitters, lamps) and a list's continuation lines repeat. */
  const bool appends = k->kind == V_OBJECT || k->kind == V_RBF || k->kind == V_QUADRIC ||
                       k->kind == V_RBF_EMITTER || k->kind == V_LAMP ||
                       k->kind == V_LAMP_PATH || k->kind == V_LAMP_FLICKER;
  if (s->key_line[k - keys] && !appends && !s->continuation)
    return fail(s, section, key, "given twice (first on line %d)", s->key_line[k - keys]);
  if (!s->continuation) s->key_line[k - keys] = s->line; /* the key's own line */
  if (s->continuation && k->kind != V_LIST && k->kind != V_QUADRIC)
    /* libinih hands an indented line to the key above */
    return fail(s, section, key, "an indented line goes on with the key above, and only a list "
                "(profile_coefficients, perlin_wind) or a quadric volume goes on over lines: "
                "unindent '%s'", value);
  char *field = (char *)cfg + k->offset;
  double v[16];
  if (k->offset == F(fog.perlin_size)) cfg->fog.perlin_size_line = s->line;
  switch (k->kind) {
    case V_DOUBLE:
      if (numbers(s, k, section, key, value, v, 1, 1, "a number") != 1) return 0;
      *(double *)field = v[0];
      return 1;
    case V_DOUBLE2:
      if (numbers(s, k, section, key, value, v, 2, 2, "two numbers") != 2) return 0;
      memcpy(field, v, 2 * sizeof(double));
      return 1;
    case V_DOUBLE3:
    case V_LOOK_AT:
      if (numbers(s, k, section, key, value, v, 3, 3, "three numbers (x y z)") != 3) return 0;
      memcpy(field, v, 3 * sizeof(double));
      if (k->kind == V_LOOK_AT) cfg->camera.look_at_set = true;
      return 1;
    case V_FLOAT3:
      if (numbers(s, k, section, key, value, v, 3, 3, "three numbers (r g b)") != 3) return 0;
      for (int i = 0; i < 3; i++) ((float *)field)[i] = (float)v[i];
      return 1;
    case V_INT:
    case V_UINT:
      if (numbers(s, k, section, key, value, v, 1, 1, "an integer") != 1) return 0;
      if (v[0] != floor(v[0])) return fail(s, section, key, "expected an integer, got '%s'", value);
      if (k->kind == V_INT)
        *(int *)field = (int)v[0];
      else
        *(unsigned *)field = (unsigned)v[0];
      if (k->aux_offset) *(int *)((char *)cfg + k->aux_offset) = s->line; /* its line */
      return 1;
    case V_ENUM:
      return store_enum(s, k, section, key, value, (int *)field);
    case V_PATH:
      if (!value[0]) /* not "none": a path left empty is more likely a slip */
        return fail(s, section, key, "expected a file path, got nothing (leave the key out "
                    "for none)");
      if (!resolve_path(s, value, field, k->size))
        return fail(s, section, key, "the path resolved against the config's folder is longer "
                    "than %zu characters: '%.60s...'", k->size - 1, value);
      *(int *)((char *)cfg + k->aux_offset) = s->line;
      return 1;
    case V_STRING:
      if (strlen(value) >= k->size)
        return fail(s, section, key, "expected at most %zu characters, got '%s'", k->size - 1, value);
      /* min: the least length (vdb_grid = nothing read "density" as a fogmap and no grid
       * at all as a volume, and was dropped when written back) */
      if (strlen(value) < k->min)
        return fail(s, section, key, "expected a name, got nothing (leave the key out for "
                    "the default)");
      snprintf(field, k->size, "%s", value);
      return 1;
    case V_LIST:
      return store_list(s, k, section, key, value);
    case V_OBJECT:
      return store_box(s, section, key, value);
    case V_RBF:
      return store_rbf(s, section, key, value);
    case V_QUADRIC:
      return hold_quadric(s, value);
    case V_RBF_EMITTER:
      return store_rbf_emitter(s, section, key, value);
    case V_LAMP:
      return store_lamp(s, section, key, value);
    case V_LAMP_PATH:
      return store_lamp_path(s, section, key, value);
    case V_LAMP_FLICKER:
      return store_lamp_flicker(s, section, key, value);
  }
  return 1;
}

static int check_file(parse_state *s, const char *section, const char *key, int line,
                      const char *path) {
  FILE *f = fopen(path, "rb");
  if (f) {
    fclose(f);
    return 0;
  }
  s->line = line;
  /* the line is sound; its file is not there */
  fail_as(s, FOG_ERR_FILE_ACCESS, section, key, "cannot open '%s' (%s)", path, strerror(errno));
  return 1;
}

/* The files the config names (fogmap, sequence, VDB, heightmap) and their exclusions,
 * named by the key that was set last. */
static int check_sources(parse_state *ps) {
  parse_state s = *ps;
  const scene_config *cfg = s.cfg;
  if (cfg->fog.fogmap[0] && cfg->fog.vdb[0]) {
    bool vdb_last = cfg->fog.vdb_line > cfg->fog.fogmap_line;
    s.line = vdb_last ? cfg->fog.vdb_line : cfg->fog.fogmap_line;
    fail(&s, "fog", vdb_last ? "vdb" : "fogmap",
         "fogmap (line %d) and vdb (line %d) are mutually exclusive: set one of them",
         cfg->fog.fogmap_line, cfg->fog.vdb_line);
    return 1;
  }
  if (cfg->fog.vdb[0] && cfg->fog.model != FOG_MODEL_FOGMAP &&
      cfg->fog.model != FOG_MODEL_VOLUME) {
    /* the other models draw no VDB: it was read and ignored (and fit measured against it) */
    s.line = cfg->fog.vdb_line;
    fail(&s, "fog", "vdb", "a VDB sequence is drawn by model = fogmap (projected) or volume, "
         "not by model = %s (line %d)", fog_model_table[cfg->fog.model].name,
         cfg->fog.model_line);
    return 1;
  }
  if (cfg->fog.sequence[0] && (cfg->fog.fogmap[0] || cfg->fog.vdb[0] ||
                               cfg->fog.model != FOG_MODEL_FOGMAP)) {
    s.line = cfg->fog.sequence_line;
    fail(&s, "fog", "sequence", "a fogmap sequence plays the fogmap model alone: no fogmap, "
         "vdb or other model beside it");
    return 1;
  }
  if (cfg->fog.sequence[0] && s.no_files) {
    char first[SCENE_CONFIG_PATH_MAX + 32];
    if (!scene_config_sequence_path(cfg->fog.sequence, 1, first, sizeof first)) {
      s.line = cfg->fog.sequence_line;
      fail(&s, "fog", "sequence", "%s: expected a pattern with #s for the frame number "
           "(fog.####.exr)", cfg->fog.sequence);
      return 1;
    }
  } else if (cfg->fog.sequence[0]) {
    if (sequence_first_frame(cfg->fog.sequence) < 0) {
      s.line = cfg->fog.sequence_line;
      fail(&s, "fog", "sequence", "%s: expected a pattern with #s for the frame number "
           "whose frame 1 exists (fog.####.exr)", cfg->fog.sequence);
      return 1;
    }
    /* Frame n of a recording shows file n and the last file stays past the end: a file
     * missing inside the run would end it early and leave the later files unplayed. */
    vdb_sequence seq;
    fog_error serr = {0};
    const char *input = cfg->fog.sequence;
    if (vdb_sequence_find(&input, 1, 1, -1, &seq, &serr)) {
      /* frame 1 exists: what fails is a span too long to check (a stray fog.2000000.exr),
       * which would hide a gap; the lister's reason, on the key's line */
      s.line = cfg->fog.sequence_line;
      fail(&s, "fog", "sequence", "%s", serr.message);
      return 1;
    }
    const int missing = seq.missing_count ? seq.missing[0] : 0;
    const int last = seq.count ? seq.frames[seq.count - 1] : 0;
    vdb_sequence_destroy(&seq);
    if (missing) {
      char path[SCENE_CONFIG_PATH_MAX + 32];
      scene_config_sequence_path(cfg->fog.sequence, missing, path, sizeof path);
      s.line = cfg->fog.sequence_line;
      fail(&s, "fog", "sequence", "frame %d (%s) is missing, but the files run to frame "
           "%d: expected frames 1 to %d without a gap", missing, path, last, last);
      return 1;
    }
  }
  if (s.no_files) return 0;
  if (cfg->fog.fogmap[0] &&
      check_file(&s, "fog", "fogmap", cfg->fog.fogmap_line, cfg->fog.fogmap))
    return 1;
  if (cfg->fog.vdb[0]) {
    /* The files must exist now; their contents are read by the command (vdb_source). */
    vdb_sequence seq;
    fog_error serr = {0};
    const char *input = cfg->fog.vdb;
    if (vdb_sequence_find(&input, 1, -1, -1, &seq, &serr)) {
      s.line = cfg->fog.vdb_line;
      /* not there (file access), or a pattern it cannot take */
      fail_as(&s, serr.code ? serr.code : FOG_ERR_BAD_CONFIG, "fog", "vdb", "%s", serr.message);
      return 1;
    }
    vdb_sequence_destroy(&seq);
  }
  if (cfg->terrain.heightmap[0] &&
      check_file(&s, "terrain", "heightmap", cfg->terrain.heightmap_line, cfg->terrain.heightmap))
    return 1;
  return 0;
}

/* Where the model's K0 e^{-(y - y0)/H} is largest in view: height fog (everywhere) at the
 * lowest point a view ray reaches, the camera or the terrain's base; Perlin fog (0 outside
 * [box] floor .. top) at the box's floor, wherever the camera is. (Both used to take the
 * least of all three: a Perlin layer above the camera was refused for fog it has not, and
 * the box, which height fog ignores, decided for it.) */
static double scene_lowest_point(const scene_config *cfg) {
  if (cfg->fog.model == FOG_MODEL_PERLIN) return cfg->box.floor;
  return fmin(cfg->camera.position[1], cfg->terrain.origin[1]);
}

double scene_config_min_scale_height(const scene_config *cfg) {
  /* K0 e^{-(y - y0)/H} grows without bound below y0: down to the lowest point it must stay
   * under MAX_EXTINCTION, log K0 + (y0 - low)/H <= log MAX_EXTINCTION */
  const double rise = cfg->fog.fog_height - scene_lowest_point(cfg);
  if (!(cfg->fog.density_scale > 0) || rise <= 0) return 0.0;
  const double room = log(MAX_EXTINCTION) - log(cfg->fog.density_scale);
  return room > 0 ? rise / room : HUGE_VAL;
}

/* What each fog model needs of the other keys. */
static int check_models(parse_state *ps) {
  parse_state s = *ps;
  const scene_config *cfg = s.cfg;
  if (cfg->fog.model == FOG_MODEL_RBF && cfg->fog.rbf_count == 0 &&
      cfg->fog.rbf_emitter_count == 0) {
    s.line = cfg->fog.model_line;
    fail(&s, "fog", "model", "rbf needs at least one 'rbf = X Y Z RADIUS DENSITY' or "
         "'rbf_emitter = ...' line");
    return 1;
  }
  for (int e = 0; cfg->fog.rbf_carrier == SCENE_RBF_CARRIER_SIM &&
                  e < cfg->fog.rbf_emitter_count; e++)
    if (cfg->fog.rbf_emitters[e].lifetime > RBF_CARRIER_MAX_LIFETIME) {
      s.line = cfg->fog.rbf_carrier_line;
      fail(&s, "fog", "rbf_carrier", "sim replays the flow from minus the longest LIFETIME "
           "every time the fog is made: emitter %d's %g s is more than the %g s allowed with "
           "it (use rbf_carrier = wind, or a shorter LIFETIME)", e + 1,
           cfg->fog.rbf_emitters[e].lifetime, RBF_CARRIER_MAX_LIFETIME);
      return 1;
    }
  if (cfg->fog.model == FOG_MODEL_QUADRIC && cfg->fog.quadric_count == 0) {
    s.line = cfg->fog.model_line;
    fail(&s, "fog", "model", "quadric needs at least one 'quadric = SHAPE ...' line");
    return 1;
  }
  if ((cfg->fog.model == FOG_MODEL_LINEAR || cfg->fog.model == FOG_MODEL_EXP2) &&
      cfg->fog.quadric_count > 0) {
    s.line = cfg->fog.model_line;
    fail(&s, "fog", "model", "%s is a fog of the distance from the camera: it takes no "
         "'quadric' volumes beside it (any other model does)",
         fog_model_table[cfg->fog.model].name);
    return 1;
  }
  if (fog_quadric_noisy(cfg->fog.quadrics, cfg->fog.quadric_count) &&
      cfg->fog.model != FOG_MODEL_QUADRIC && cfg->fog.model != FOG_MODEL_PERLIN) {
    s.line = cfg->fog.quadric_noise_line;
    fail(&s, "fog", "quadric", "NOISE needs [fog] model = quadric or perlin (the turbulence is "
         "the perlin_* octaves), not %s", fog_model_table[cfg->fog.model].name);
    return 1;
  }
  if (cfg->lamp_method.integral == FOG_LAMP_FOGSHOP && cfg->fog.quadric_count > 0 &&
      cfg->fog.model == FOG_MODEL_RBF) {
    s.line = cfg->lamp_integral_line;
    fail(&s, "light", "lamp_integral", "fogshop is Fogshop's approximation for Gaussian fog "
         "alone: it does not light the 'quadric' volumes beside it (use angle or march)");
    return 1;
  }
  if (cfg->lamp_method.integral == FOG_LAMP_FOGSHOP && cfg->fog.model != FOG_MODEL_RBF) {
    s.line = cfg->lamp_integral_line;
    fail(&s, "light", "lamp_integral", "fogshop is Fogshop's approximation for Gaussian fog: "
         "it needs [fog] model = rbf");
    return 1;
  }
  if (cfg->fog.model == FOG_MODEL_VOLUME && !cfg->fog.vdb[0]) {
    s.line = cfg->fog.model_line;
    fail(&s, "fog", "model", "volume needs a 'vdb = FILE or PATTERN' line (the 3D grid)");
    return 1;
  }
  /* Keys of a model other than the scene's are checked all the same (docs/config.md): a
   * scene switched to that model later (the viewer, fit's rungs, an edit) must not meet
   * an error its config was loaded with. The one of the pair set last is named. */
  if (!(cfg->fog.fog_end > cfg->fog.fog_start)) {
    const int start = key_line(&s, "fog", "fog_start"), end = key_line(&s, "fog", "fog_end");
    s.line = end > start ? end : start;
    fail(&s, "fog", end > start ? "fog_end" : "fog_start", "linear fog needs fog_end above "
         "fog_start, got fog_start = %g and fog_end = %g", cfg->fog.fog_start,
         cfg->fog.fog_end);
    return 1;
  }
  /* the octaves: Perlin fog's, or the turbulence inside quadric volumes with NOISE */
  const int octave_size = cfg->fog.perlin_size, winds = cfg->fog.perlin_wind_count;
  if (octave_size & (octave_size - 1)) {
    s.line = cfg->fog.perlin_size_line;
    fail(&s, "fog", "perlin_size", "expected a power of two (8, 16, 32, 64 or 128), got %d",
         octave_size);
    return 1;
  }
  if (winds != 3 && (winds % 3 || winds < 3 * cfg->fog.perlin_octaves)) {
    s.line = cfg->fog.perlin_wind_line;
    fail(&s, "fog", "perlin_wind", "expected 3 numbers (one drift for every octave) or 3 per "
         "octave (%d numbers for %d octaves), got %d numbers", 3 * cfg->fog.perlin_octaves,
         cfg->fog.perlin_octaves, winds);
    return 1;
  }
  if (cfg->fog.model == FOG_MODEL_PERLIN && !(cfg->box.top > cfg->box.floor)) {
    /* the one of the two the config sets last (only floor set: top has no line) */
    const int top = key_line(&s, "box", "top"), floor_line = key_line(&s, "box", "floor");
    const char *named = floor_line > top ? "floor" : "top";
    s.line = floor_line > top ? floor_line : top;
    fail(&s, "box", named, "Perlin fog fills the terrain's footprint between [box] floor and "
         "top: expected top above floor, got floor %g and top %g", cfg->box.floor, cfg->box.top);
    return 1;
  }
  if (cfg->fog.model == FOG_MODEL_HEIGHT || cfg->fog.model == FOG_MODEL_PERLIN) {
    double low = scene_lowest_point(cfg);
    double exponent = (cfg->fog.fog_height - low) / cfg->fog.scale_height;
    if (cfg->fog.scale_height < scene_config_min_scale_height(cfg)) {
      s.line = cfg->fog.model_line;
      fail(&s, "fog", "model", "%s fog of density_scale %g, fog_height %g and "
           "scale_height %g reaches exp(%.3g) times density_scale at y = %g (%s): over %g "
           "per unit, past what float holds; raise scale_height",
           cfg->fog.model == FOG_MODEL_PERLIN ? "Perlin" : "height", cfg->fog.density_scale,
           cfg->fog.fog_height, cfg->fog.scale_height, exponent, low,
           cfg->fog.model == FOG_MODEL_PERLIN ? "[box] floor, the fog's lowest"
                                              : "the lowest the view reaches",
           MAX_EXTINCTION);
      return 1;
    }
  }
  return 0;
}

int scene_config_check(const scene_config *cfg, fog_error *err) {
  /* check_models reads the scene alone (never writes it) */
  parse_state s = {.cfg = (scene_config *)cfg, .path = cfg->path, .err = err, .in_memory = true};
  return check_models(&s);
}

static int load_stream(const char *path, FILE *file, bool no_files, scene_config *cfg,
                       fog_error *err);

/* A box farther from the terrain than the terrain's own size (on either axis) is refused:
 * the sun's shadow map is fitted around the terrain and every box, and one such box
 * stretched its texels ~200x (a box at 2e5 beside the 1000-unit default terrain took the
 * hills' shadows off the ground, with no word said). */
static int check_boxes_near_terrain(parse_state *s) {
  const scene_config *cfg = s->cfg;
  const double *o = cfg->terrain.origin, *size = cfg->terrain.size;
  for (int i = 0; i < cfg->object_count; i++) {
    const scene_box_desc *b = &cfg->objects[i];
    const double x0 = b->center[0] - 0.5 * b->size[0], x1 = b->center[0] + 0.5 * b->size[0];
    const double z0 = b->center[1] - 0.5 * b->size[2], z1 = b->center[1] + 0.5 * b->size[2];
    const double gap_x = fmax(0.0, fmax(o[0] - x1, x0 - (o[0] + size[0])));
    const double gap_z = fmax(0.0, fmax(o[2] - z1, z0 - (o[2] + size[1])));
    if (gap_x > size[0] || gap_z > size[1]) {
      s->line = s->box_line[i];
      fail(s, "objects", "box", "its footprint (x %g to %g, z %g to %g) lies %g units "
                  "beyond the terrain (x %g to %g, z %g to %g), farther than the terrain's own "
                  "size: the sun's shadow map holds the terrain and every box, and would lose "
                  "the terrain's shadows; expected a box on or near the terrain", x0, x1, z0,
                  z1, fmax(gap_x, gap_z), o[0], o[0] + size[0], o[2], o[2] + size[1]);
      return 1;
    }
  }
  return 0;
}

int scene_config_load(const char *path, scene_config *cfg, fog_error *err) {
  scene_config_init(cfg);
  /* not a regular file: refused before fopen, which waits on a FIFO for a writer forever */
  struct stat st;
  if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
    fog_fail(err, FOG_ERR_BAD_CONFIG, "%s: not a config file (%s)", path,
             S_ISDIR(st.st_mode) ? "a folder" : "not a regular file");
    return 1;
  }
  FILE *file = fopen(path, "r");
  if (!file) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot open the config (%s)", path, strerror(errno));
    return 1;
  }
  if (fstat(fileno(file), &st) != 0 || !S_ISREG(st.st_mode)) {
    bool folder = fstat(fileno(file), &st) == 0 && S_ISDIR(st.st_mode);
    fog_fail(err, FOG_ERR_BAD_CONFIG, "%s: not a config file (%s)", path,
             folder ? "a folder" : "not a regular file");
    fclose(file);
    return 1;
  }
  const int status = load_stream(path, file, false, cfg, err);
  fclose(file);
  return status;
}

/* The config in file as if read from path (its folder resolves relative paths); no_files:
 * the files it names are not looked at. */
static int load_stream(const char *path, FILE *file, bool no_files, scene_config *cfg,
                       fog_error *err) {
  scene_config_init(cfg);
  snprintf(cfg->path, sizeof cfg->path, "%s", path);
  parse_state s = {.cfg = cfg, .path = path, .err = err, .file = file, .no_files = no_files};
  const char *slash = strrchr(path, '/');
  if (slash) snprintf(s.folder, sizeof s.folder, "%.*s", (int)(slash - path), path);
  if (slash == path) snprintf(s.folder, sizeof s.folder, "/");
  int status = ini_parse_stream(read_line, &s, handle, &s);
  free(s.whole_line);
  if (!s.error_line) finish_quadric(&s); /* before a syntax error below it */
  /* libinih reads on past a line it cannot parse ("[fog" with no "]") and reports its first
   * error's line as status: when that comes before ours, it is the first mistake. */
  if (s.error_line && !(status > 0 && status < s.error_line)) return 1;
  if (status > 0) {
    fog_fail(err, FOG_ERR_BAD_CONFIG, "%s:%d: expected '[section]', 'key = value' or a comment",
             path, status);
    return 1;
  }
  if (status < 0) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot read the config", path);
    return 1;
  }
  if (check_sources(&s) || check_models(&s)) return 1;
  /* the pairs below name the key the file set last (the other may be a default) */
  const int top = key_line(&s, "box", "top"), floor_line = key_line(&s, "box", "floor");
  /* a VDB fills the one the file leaves unset (vdb_source_apply_config): the default is no
   * mistake of the file's (top = -0.01 under a VDB whose floor is -0.047 was refused
   * against the default floor 0) */
  const bool vdb_fills_one = cfg->fog.vdb[0] && !(cfg->box.floor_set && cfg->box.top_set);
  if (cfg->box.top <= cfg->box.floor && !vdb_fills_one) {
    s.line = top > floor_line ? top : floor_line;
    fail(&s, "box", top > floor_line ? "top" : "floor", "top (%g) must be above floor (%g)",
         cfg->box.top, cfg->box.floor);
    return 1;
  }
  if (check_boxes_near_terrain(&s)) return 1;
  const double *eye = cfg->camera.position, *at = cfg->camera.look_at;
  if (cfg->camera.look_at_set && eye[0] == at[0] && eye[1] == at[1] && eye[2] == at[2]) {
    s.line = key_line(&s, "camera", "look_at"); /* no direction to look in */
    fail(&s, "camera", "look_at", "(%g, %g, %g) is the camera's position: expected another "
         "point", at[0], at[1], at[2]);
    return 1;
  }
  if (cfg->fog.profile == SCENE_PROFILE_BSPLINE && cfg->fog.profile_count == 0) {
    s.line = key_line(&s, "fog", "profile");
    fail(&s, "fog", "profile", "bspline needs profile_coefficients");
    return 1;
  }
  const int near = key_line(&s, "camera", "near"), far = key_line(&s, "camera", "far");
  if (cfg->camera.near_plane >= cfg->camera.far_plane) {
    s.line = near > far ? near : far;
    fail(&s, "camera", near > far ? "near" : "far", "near (%g) must be below far (%g)",
         cfg->camera.near_plane, cfg->camera.far_plane);
    return 1;
  }
  /* The scene pass's float depth buffer holds 1 - near/d (its projection's far is at
   * infinity, camera_projection_matrix_infinite; far is a clip distance): past d = near x 3.4e7
   * it rounds to 1, the cleared depth, and surfaces vanish into the sky (near 1e-5 shredded
   * the default terrain into speckles) */
  if (cfg->camera.far_plane > SCENE_CAMERA_MAX_DEPTH_RATIO * cfg->camera.near_plane) {
    s.line = near > far ? near : far;
    fail(&s, "camera", near > far ? "near" : "far",
         "far / near = %g: the depth buffer loses surfaces past near x 3.4e7; expected at "
         "most %g (a larger near or a smaller far)",
         cfg->camera.far_plane / cfg->camera.near_plane, SCENE_CAMERA_MAX_DEPTH_RATIO);
    return 1;
  }
  return 0;
}

bool scene_config_sequence_path(const char *pattern, long n, char *out, size_t size) {
  size_t at, run; /* the run vdb_sequence_find reads as the frame number */
  if (!vdb_pattern_hash_run(pattern, &at, &run)) return false;
  const char *hash = pattern + at;
  const int digits = (int)run;
  char buffer[SCENE_CONFIG_PATH_MAX + 32];
  int length = snprintf(buffer, sizeof buffer, "%.*s%0*ld%s", (int)(hash - pattern), pattern,
                        digits, n, hash + digits);
  if (length < 0 || (size_t)length >= sizeof buffer || (size_t)length >= size) return false;
  memcpy(out, buffer, (size_t)length + 1);
  return true;
}

/* 1 when the sequence's frame 1 exists, else -1. */
static int sequence_first_frame(const char *pattern) {
  char path[SCENE_CONFIG_PATH_MAX + 32];
  struct stat st;
  if (!scene_config_sequence_path(pattern, 1, path, sizeof path)) return -1;
  return stat(path, &st) == 0 && S_ISREG(st.st_mode) ? 1 : -1;
}

/* ---- writing a config back (scene_config_write) ---- */

/* The working folder as the shell names it: $PWD when it is "." (getcwd resolves links). */
static bool logical_cwd(char *out, size_t size) {
  const char *pwd = getenv("PWD");
  struct stat a, b;
  if (pwd && pwd[0] == '/' && stat(pwd, &a) == 0 && stat(".", &b) == 0 && a.st_dev == b.st_dev &&
      a.st_ino == b.st_ino && strlen(pwd) < size) {
    snprintf(out, size, "%s", pwd);
    return true;
  }
  return getcwd(out, size) != NULL;
}

/* path made absolute as its user spells it: a relative one under the logical working folder,
 * "." dropped, and "dir/.." removed only where dir is no link (through a link, ".." leaves
 * the link's target). realpath resolved every link: a bake.ini named /mnt/nfs1/... where
 * the user typed /shared/..., which a farm node mounting /shared elsewhere lacks. False
 * when it does not fit. */
static bool logical_absolute(const char *path, char *out, size_t size) {
  char joined[2 * SCENE_CONFIG_PATH_MAX + 2], cwd[SCENE_CONFIG_PATH_MAX];
  if (path[0] == '/')
    snprintf(joined, sizeof joined, "%s", path);
  else if (logical_cwd(cwd, sizeof cwd))
    snprintf(joined, sizeof joined, "%s/%s", cwd, path);
  else
    return false;
  size_t used = 0; /* out holds "/a/b" for the components kept so far */
  out[0] = '\0';
  for (char *part = joined; *part;) {
    char *end = strchr(part, '/');
    const size_t n = end ? (size_t)(end - part) : strlen(part);
    if (n == 0 || (n == 1 && part[0] == '.')) {
    } else if (n == 2 && part[0] == '.' && part[1] == '.' && used > 0 &&
               strcmp(strrchr(out, '/') + 1, "..")) {
      struct stat st;
      if (lstat(out, &st) == 0 && !S_ISLNK(st.st_mode)) {
        used = (size_t)(strrchr(out, '/') - out);
        out[used] = '\0';
      } else if (used + 3 < size) {
        memcpy(out + used, "/..", 4), used += 3;
      } else {
        return false;
      }
    } else {
      if (used + 1 + n >= size) return false;
      out[used] = '/';
      memcpy(out + used + 1, part, n);
      used += 1 + n;
      out[used] = '\0';
    }
    if (!end) break;
    part = end + 1;
  }
  if (used == 0) snprintf(out, size, "/");
  return true;
}

static void write_path(FILE *f, const char *key, const char *path) {
  char absolute[SCENE_CONFIG_PATH_MAX + 64];
  fprintf(f, "%s = %s\n", key, logical_absolute(path, absolute, sizeof absolute) ? absolute : path);
}

/* Keys whose being set changes what the scene does (a VDB sequence places the fog and
 * gives its profile unless the config sets them): written only when the config set them. */
static bool key_unset(const scene_config *cfg, const key_spec *k) {
  const size_t o = k->offset;
  if (!strcmp(k->section, "fog") && !strcmp(k->key, "profile")) return !cfg->fog.profile_set;
  if (strcmp(k->section, "box")) return false;
  return (o == F(box.origin) && !cfg->box.origin_set) ||
         (o == F(box.cell_size) && !cfg->box.cell_size_set) ||
         (o == F(box.floor) && !cfg->box.floor_set) || (o == F(box.top) && !cfg->box.top_set);
}

/* An exponent without its '+' and leading zeros: "1e+20" as "1e20", "1.5e-05" as "1.5e-5". */
static void compact_exponent(char *number) {
  char *e = strchr(number, 'e');
  if (!e) return;
  char *digits = e + 1 + (e[1] == '+' || e[1] == '-');
  char *first = digits + strspn(digits, "0");
  if (!*first) first--; /* e+00: keep one 0 */
  memmove(e[1] == '+' ? e + 1 : digits, first, strlen(first) + 1);
}

/* x's shortest text that reads back as x (as a float with single): the fewest significant
 * digits, written as %g writes them or positionally, whichever is shorter ("50", not
 * "5e1"; "1e3", not "1000"; "100" on a tie). Lines of many numbers stay short: a written
 * line is no longer than the line it was read from unless that one wrote numbers shorter
 * still (".5", read back as 0.5). */
static void shortest_number(double x, bool single, char number[32]) {
  const int most = single ? 9 : 17;
  for (int digits = 1; digits <= most; digits++) {
    snprintf(number, 32, "%.*g", digits, x);
    const double back = strtod(number, NULL);
    if (single ? (float)back == (float)x : back == x) break;
  }
  compact_exponent(number);
  if (!strchr(number, 'e')) return;
  char plain[64];
  for (int decimals = 0; decimals <= 20; decimals++) {
    const int n = snprintf(plain, sizeof plain, "%.*f", decimals, x);
    if (n >= 32 || n >= (int)strlen(number) + 1) return; /* no shorter, or too long */
    const double back = strtod(plain, NULL);
    if (single ? (float)back == (float)x : back == x) {
      if (n <= (int)strlen(number)) memcpy(number, plain, (size_t)n + 1);
      return;
    }
  }
}

static void write_number(FILE *f, double x) {
  char number[32];
  shortest_number(x, false, number);
  fprintf(f, " %s", number);
}

/* A float in the shortest form that reads back as the same float. */
static void write_float(FILE *f, float x) {
  char number[32];
  shortest_number((double)x, true, number);
  fprintf(f, " %s", number);
}

/* `key =` and the numbers, each in its shortest exact form: a written line of many numbers
 * stays under the reader's line length (%.17g made a spot line 253 bytes). */
static void write_numbers(FILE *f, const char *key, const double *v, int n) {
  fprintf(f, "%s =", key);
  for (int i = 0; i < n; i++) write_number(f, v[i]);
  fputc('\n', f);
}

/* The quadric lines as written, each number in its shortest exact form (at most 25
 * bytes), 6 a line (a general quadric's 17 to 19, a shape's 7 to 9 with EDGE and NOISE),
 * the rest on indented lines: under the reader's 199 bytes. */
static void write_quadrics(FILE *f, const scene_config *cfg, const char *key) {
  for (int i = 0; i < cfg->fog.quadric_count; i++) {
    const struct scene_quadric_line *line = &cfg->fog.quadric_lines[i];
    fprintf(f, "%s = %s", key, shapes[line->shape].name);
    for (int c = 0; c < line->count; c++) {
      if (c > 0 && c % 6 == 0) fputs("\n   ", f);
      write_number(f, line->numbers[c]);
    }
    fputc('\n', f);
  }
}

static void write_key(FILE *f, const scene_config *cfg, const key_spec *k) {
  if (key_unset(cfg, k)) return;
  const char *field = (const char *)cfg + k->offset;
  const double *d = (const double *)field;
  const float *c = (const float *)field;
  switch (k->kind) {
    case V_DOUBLE: write_numbers(f, k->key, d, 1); break;
    case V_DOUBLE2: write_numbers(f, k->key, d, 2); break;
    case V_LOOK_AT:
      if (!cfg->camera.look_at_set) break;
      /* fall through */
    case V_DOUBLE3: write_numbers(f, k->key, d, 3); break;
    case V_FLOAT3:
      fprintf(f, "%s =", k->key);
      for (int n = 0; n < 3; n++) write_float(f, c[n]);
      fputc('\n', f);
      break;
    case V_INT: fprintf(f, "%s = %d\n", k->key, *(const int *)field); break;
    case V_UINT: fprintf(f, "%s = %u\n", k->key, *(const unsigned *)field); break;
    case V_ENUM: {
      const char *p = k->names;
      for (int i = *(const int *)field; i > 0 && p; i--) p = strchr(p, '|') ? strchr(p, '|') + 1 : NULL;
      if (p) fprintf(f, "%s = %.*s\n", k->key, (int)strcspn(p, "|"), p);
      break;
    }
    case V_PATH:
      if (field[0]) write_path(f, k->key, field);
      break;
    case V_STRING:
      if (field[0]) fprintf(f, "%s = %s\n", k->key, field);
      break;
    case V_LIST: { /* lines of at most ~120 bytes, the rest indented below (store_list) */
      int count = *(const int *)((const char *)cfg + k->aux_offset);
      if (!count) break;
      int length = fprintf(f, "%s =", k->key);
      for (int i = 0; i < count; i++) {
        char number[32];
        shortest_number(d[i], false, number); /* write_number's form */
        if (length + 1 + (int)strlen(number) > 120) length = fprintf(f, "\n   ");
        length += fprintf(f, " %s", number);
      }
      fputc('\n', f);
      break;
    }
    case V_OBJECT:
      for (int i = 0; i < cfg->object_count; i++) {
        const scene_box_desc *b = &cfg->objects[i];
        fprintf(f, "%s =", k->key);
        const double numbers[5] = {b->center[0], b->center[1], b->size[0], b->size[1], b->size[2]};
        for (int n = 0; n < 5; n++) write_number(f, numbers[n]);
        for (int n = 0; n < 3; n++) write_float(f, b->colour[n]);
        fputc('\n', f);
      }
      break;
    case V_RBF:
      for (int i = 0; i < cfg->fog.rbf_count; i++) {
        const fog_rbf *g = &cfg->fog.rbfs[i];
        const double numbers[5] = {g->centre[0], g->centre[1], g->centre[2], g->radius,
                                   g->density};
        write_numbers(f, k->key, numbers, 5);
      }
      break;
    case V_RBF_EMITTER:
      for (int i = 0; i < cfg->fog.rbf_emitter_count; i++) {
        const fog_rbf_emitter *e = &cfg->fog.rbf_emitters[i];
        const double numbers[12] = {e->position[0], e->position[1], e->position[2], e->rate,
                                    e->lifetime, e->radius, e->density, e->spread,
                                    e->diffusion, e->wind[0], e->wind[1], e->wind[2]};
        fprintf(f, "%s =", k->key);
        for (int c = 0; c < 12; c++) write_number(f, numbers[c]);
        /* SEED only where it is not the default (its place): the line stays as long as it
         * was read */
        if (e->seed != (uint64_t)i) fprintf(f, " %llu", (unsigned long long)e->seed);
        fputc('\n', f);
      }
      break;
    case V_QUADRIC: write_quadrics(f, cfg, k->key); break;
    case V_LAMP: /* every lamp at the "lamp" key, in the array's order (the order the fog
                  * sums them: a bake reads back bit for bit), each under its kind's key */
      for (int i = 0; i < cfg->lamp_count && !strcmp(k->key, "lamp"); i++) {
        const scene_lamp_config *l = &cfg->lamps[i];
        const double lamp[7] = {l->position[0], l->position[1], l->position[2], l->colour[0],
                                l->colour[1], l->colour[2], l->radius};
        const double spot[12] = {l->position[0], l->position[1], l->position[2], l->colour[0],
                                 l->colour[1], l->colour[2], l->axis[0], l->axis[1],
                                 l->axis[2], l->inner, l->outer, l->radius};
        /* RADIUS only where it is not the default: a line read without one stays as long */
        const int omitted = l->radius == LAMP_RADIUS;
        write_numbers(f, l->spot ? "spot" : "lamp", l->spot ? spot : lamp,
                      (l->spot ? 12 : 7) - omitted);
      }
      break;
    case V_LAMP_PATH: /* lamp numbers in file order: the array's, as written above */
      for (int i = 0; i < cfg->lamp_count; i++) {
        const scene_lamp_config *l = &cfg->lamps[i];
        for (int j = 0; j < l->key_count; j++)
          write_numbers(f, k->key, (const double[5]){i + 1, l->keys[j][0], l->keys[j][1],
                                                     l->keys[j][2], l->keys[j][3]}, 5);
      }
      break;
    case V_LAMP_FLICKER:
      for (int i = 0; i < cfg->lamp_count; i++) {
        const scene_lamp_config *l = &cfg->lamps[i];
        if (l->flicker_amount > 0)
          write_numbers(f, k->key, (const double[4]){i + 1, l->flicker_amount, l->flicker_rate,
                                                     l->flicker_seed}, 4);
      }
      break;
  }
}

/* The longest line the reader takes: libinih's buffer (INI_MAX_LINE, 200 in Debian's
 * build) less its terminating NUL. */
enum { SCENE_CONFIG_LINE_MAX = INI_MAX_LINE - 1 };

/* Whether the written text reads back as written: no line past the reader's 199 bytes (a
 * lamp line of long numbers can pass it once written in full, with its radius), and no
 * value that a ';' after a blank would cut short (a path through a folder "a ;b"). 0, or 1
 * naming the line. */
static int check_written_text(const char *text, const char *path, fog_error *err) {
  int number = 0;
  for (const char *line = text; *line;) {
    const size_t length = strcspn(line, "\n");
    number++;
    if (line[0] != ';') {
      const char *cut = NULL;
      for (size_t i = 1; i < length && !cut; i++)
        if (line[i] == ';' && (line[i - 1] == ' ' || line[i - 1] == '\t')) cut = line + i;
      if (length > SCENE_CONFIG_LINE_MAX)
        return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                        "%.400s: the scene cannot be written as a config: its line %d "
                        "('%.40s...') would be %zu bytes, more than a config line holds (%d)",
                        path, number, line, length, SCENE_CONFIG_LINE_MAX);
      if (cut)
        return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                        "%.400s: the scene cannot be written as a config: its line %d "
                        "('%.*s') holds ' ;', which a config reads as the start of a comment "
                        "(rename the folder)",
                        path, number, (int)(length < 300 ? length : 300), line);
    }
    line += length + (line[length] == '\n');
  }
  return 0;
}

int scene_config_write(const scene_config *cfg, const char *path, fog_error *err) {
  /* what the loader would refuse of the scene's numbers, not written (the files it names may
   * come later: bake writes its config before its frames) */
  fog_error check;
  if (scene_config_check(cfg, &check))
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "%.400s: the scene cannot be written as a config that loads: %s", path,
                    check.message);
  /* a line break in a path or name would start a line of its own */
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
    if ((keys[i].kind == V_PATH || keys[i].kind == V_STRING) &&
        strpbrk((const char *)cfg + keys[i].offset, "\r\n"))
      return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                      "%.400s: the scene cannot be written as a config: its [%s] %s holds a "
                      "line break",
                      path, keys[i].section, keys[i].key);
  /* the text first, checked, then the file */
  char *text = NULL;
  size_t text_size = 0;
  FILE *m = open_memstream(&text, &text_size);
  if (!m) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%.400s: out of memory", path);
  fprintf(m, "; written by fogpipe (scene_config_write): every key of the scene\n");
  const char *section = "";
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
    if (strcmp(keys[i].section, section)) {
      section = keys[i].section;
      fprintf(m, "%s[%s]\n", i ? "\n" : "", section);
    }
    write_key(m, cfg, &keys[i]);
  }
  if (ferror(m) | fclose(m)) {
    free(text);
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%.400s: out of memory", path);
  }
  if (check_written_text(text, path, err)) {
    free(text);
    return 1;
  }
  /* The text loads: read back as the loader reads a file (the files it names aside), so
   * that no key's own range is missed (a brush's Gaussian shrunk by '-' below the least
   * RADIUS wrote "wrote NAME.painted.ini", a file that did not load). */
  scene_config *back = malloc(sizeof *back);
  FILE *reader = back ? fmemopen(text, text_size, "r") : NULL;
  fog_error berr = {0};
  const int loads = reader && !load_stream(path, reader, true, back, &berr);
  if (reader) fclose(reader);
  free(back);
  if (!loads) {
    free(text);
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "%.400s: not written: the scene's config would not load (%s)", path,
                    reader ? berr.message : "out of memory");
  }
  /* written whole or not at all, a config written over keeping its mode
   * (sim/atomic_file.h) */
  const int failed = atomic_file_write(path, text, text_size, err);
  free(text);
  return failed;
}

bool scene_config_knows_key(const char *section, const char *key) {
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
    if (!strcmp(keys[i].section, section) && !strcmp(keys[i].key, key)) return true;
  return false;
}

bool scene_config_has_fog(const scene_config *cfg) {
  /* quadric volumes are drawn beside every model: beside a fogmap model with no fogmap
   * too (render drew the scene alone where record drew them) */
  return cfg->fog.model != FOG_MODEL_FOGMAP || cfg->fog.fogmap[0] || cfg->fog.vdb[0] ||
         cfg->fog.sequence[0] || cfg->fog.quadric_count > 0;
}

bool scene_config_draws_density_scale(const scene_config *cfg) {
  const char *keys = fog_model_table[cfg->fog.model].keys;
  const size_t n = strlen("density_scale");
  for (const char *k = strstr(keys, "density_scale"); k; k = strstr(k + 1, "density_scale"))
    if ((k == keys || k[-1] == ' ') && (k[n] == ' ' || k[n] == '\0')) return true;
  return false;
}

double scene_live_terrain_lod(double lod_error) {
  return lod_error > 0 ? fmax(2.0, 2.0 * lod_error) : 0.0;
}

scene_fog_shape scene_config_fog_shape(const scene_config *cfg) {
  return (scene_fog_shape){.extinction = cfg->fog.density_scale,
                           .profile = (fog_profile_kind)cfg->fog.profile,
                           .y0 = cfg->fog.fog_height, .scale_height = cfg->fog.scale_height};
}

int scene_config_fog_quadrics(const scene_config *cfg, fog_quadric out[FOG_MAX_QUADRICS]) {
  const scene_fog_config *f = &cfg->fog;
  for (int i = 0; i < f->quadric_count; i++) {
    out[i] = f->quadrics[i];
    out[i].density *= f->density_scale;
  }
  return f->quadric_count;
}

fog_volume scene_config_fog_volume(const scene_config *cfg, int map_width, int map_height,
                                   const scene_fog_shape *shape) {
  const scene_box_config *b = &cfg->box;
  const scene_fog_config *f = &cfg->fog;
  fog_volume v = {
      .map_width = map_width, .map_height = map_height,
      .origin_x = b->origin[0], .origin_z = b->origin[1], .cell_size = b->cell_size,
      .extinction = shape->extinction,
      .profile = {.kind = shape->profile, .y_floor = b->floor, .y_top = b->top,
                  .y0 = shape->y0, .scale_height = shape->scale_height}};
  if (shape->profile == FOG_PROFILE_BSPLINE && f->profile_count == 0) {
    v.profile.kind = FOG_PROFILE_SLAB; /* no B-spline profile in the config to show */
  } else if (shape->profile == FOG_PROFILE_BSPLINE) {
    v.profile.count = f->profile_count;
    v.profile.degree = f->profile_degree;
    v.profile.coefficients = f->profile_coefficients;
    v.profile.origin = f->profile_origin;
    v.profile.spacing = f->profile_spacing;
  }
  return v;
}

fog_lamp_method scene_live_lamp_method(fog_lamp_method method) {
  if (method.integral != FOG_LAMP_ANGLE) return method;
  method.angle_pieces = method.angle_pieces < 4 ? method.angle_pieces : 4;
  method.span_pieces = method.span_pieces < 4 ? method.span_pieces : 4;
  method.shadow_steps = method.shadow_steps < 4 ? method.shadow_steps : 4;
  return method;
}

void scene_config_live_software(scene_config *cfg) {
  cfg->terrain.lod_error = scene_live_terrain_lod(cfg->terrain.lod_error);
  cfg->lamp_method = scene_live_lamp_method(cfg->lamp_method);
}

uint64_t scene_config_sim_seed(const scene_config *cfg) { return (uint64_t)cfg->sim.seed + 1; }

display_transform scene_config_display(const scene_config *cfg) {
  return (display_transform){.exposure = cfg->exposure,
                             .tone_map = (display_tone_map)cfg->tone_map,
                             .dither = cfg->dither != 0};
}

fog_walk_settings scene_config_walk(const scene_config *cfg) {
  return (fog_walk_settings){
      .transmittance_cutoff = cfg->transmittance_cutoff,
      .skip = !cfg->empty_skip ? FOG_SKIP_NONE
              : cfg->skip_below > 0 ? FOG_SKIP_BELOW : FOG_SKIP_EMPTY,
      /* the key bounds the fog before density_scale: the fogmap's cells are that (the pass
       * applies the extinction), the volume's voxels are uploaded already scaled */
      .skip_below = (float)(cfg->skip_below *
                            (cfg->fog.model == FOG_MODEL_VOLUME ? cfg->fog.density_scale : 1.0)),
  };
}

fog_light_rule scene_config_light_rule(const scene_config *cfg) {
  /* auto: per piece where segments alias, Perlin fog's eddies; the volume's 48^3 sun
   * volume caps its error either way and per piece costs it ~1.6x (docs/light.md) */
  bool pieces = cfg->shadow.pieces == 1 ||
                (cfg->shadow.pieces == 2 && cfg->fog.model == FOG_MODEL_PERLIN);
  return (fog_light_rule){.steps = cfg->shadow.steps, .nodes = cfg->shadow.nodes,
                          .pieces = pieces, .shaft_samples = cfg->shadow.shaft_samples};
}

fog_sun scene_config_fog_sun(const scene_config *cfg) {
  const scene_light light = cfg->light;
  fog_sun sun = {.albedo = cfg->fog.albedo, .phase_g = cfg->fog.phase_g};
  scene_light_sun_direction(&light, sun.direction);
  /* A white Lambertian surface facing the sun shows sun_colour, so the irradiance the fog
   * scatters, per steradian through p(theta), is pi sun_colour. */
  for (int c = 0; c < 3; c++)
    sun.radiance[c] = SCENE_SUN_IRRADIANCE_PER_COLOUR * light.sun_colour[c];
  return sun;
}

bool scene_config_lamps_animated(const scene_config *cfg) {
  for (int i = 0; i < cfg->lamp_count; i++)
    if (cfg->lamps[i].key_count > 0 || cfg->lamps[i].flicker_amount > 0) return true;
  return false;
}

int scene_config_lamp_shadow_size(const scene_config *cfg) {
  return cfg->shadow.lamp_shadows ? cfg->shadow.lamp_shadow_size : 0;
}

/* A lamp's position at `time`: straight between its keys, held before and after. */
static void lamp_position_at(const scene_lamp_config *l, double time, double out[3]) {
  int n = l->key_count;
  if (n == 0) {
    for (int a = 0; a < 3; a++) out[a] = l->position[a];
    return;
  }
  int k = 0;
  while (k + 1 < n && l->keys[k + 1][0] <= time) k++;
  if (time <= l->keys[0][0] || k + 1 == n) {
    const double *key = l->keys[time <= l->keys[0][0] ? 0 : n - 1];
    for (int a = 0; a < 3; a++) out[a] = key[1 + a];
    return;
  }
  const double *p = l->keys[k], *q = l->keys[k + 1];
  double w = (time - p[0]) / (q[0] - p[0]);
  for (int a = 0; a < 3; a++) out[a] = p[1 + a] + w * (q[1 + a] - p[1 + a]);
}

/* Smooth value noise in [0, 1]: a hashed value per integer x, smoothstep between. */
static double lamp_hash(unsigned seed, long long i) {
  uint64_t h = (uint64_t)i * 0x9E3779B97F4A7C15ull ^ ((uint64_t)seed << 32 | seed);
  h ^= h >> 33, h *= 0xff51afd7ed558ccdull, h ^= h >> 33, h *= 0xc4ceb9fe1a85ec53ull, h ^= h >> 33;
  return (double)(h >> 11) * (1.0 / 9007199254740992.0);
}

static double lamp_flicker(const scene_lamp_config *l, double time) {
  if (!(l->flicker_amount > 0)) return 1.0;
  double x = time * l->flicker_rate, f = x - floor(x);
  long long i = (long long)floor(x);
  double s = f * f * (3.0 - 2.0 * f);
  double n = lamp_hash(l->flicker_seed, i) + s * (lamp_hash(l->flicker_seed, i + 1) -
                                                  lamp_hash(l->flicker_seed, i));
  return 1.0 - l->flicker_amount * n;
}

fog_lamps scene_config_fog_lamps(const scene_config *cfg) {
  return scene_config_fog_lamps_at(cfg, 0.0);
}

fog_lamps scene_config_fog_lamps_at(const scene_config *cfg, double time) {
  fog_lamps lamps = {.count = cfg->lamp_count, .method = cfg->lamp_method};
  for (int i = 0; i < cfg->lamp_count; i++) {
    const scene_lamp_config *l = &cfg->lamps[i];
    fog_lamp *out = &lamps.lamp[i];
    *out = (fog_lamp){.kind = l->spot ? FOG_LAMP_SPOT : FOG_LAMP_POINT, .radius = l->radius};
    lamp_position_at(l, time, out->position);
    const double flicker = lamp_flicker(l, time);
    for (int a = 0; a < 3; a++) out->intensity[a] = l->colour[a] * flicker;
    if (l->spot) {
      double len = sqrt(l->axis[0] * l->axis[0] + l->axis[1] * l->axis[1] + l->axis[2] * l->axis[2]);
      for (int a = 0; a < 3; a++) out->axis[a] = l->axis[a] / len;
      out->cos_inner = cos(l->inner * DEG), out->cos_outer = cos(l->outer * DEG);
    }
  }
  return lamps;
}

void scene_config_camera(const scene_config *cfg, camera *cam) {
  const scene_camera_config *c = &cfg->camera;
  *cam = (camera){
      .position = {c->position[0], c->position[1], c->position[2]},
      .yaw = c->yaw * DEG,
      .pitch = c->pitch * DEG,
      .fov_y = c->fov * DEG,
      .near_plane = c->near_plane,
      .far_plane = c->far_plane,
  };
  if (c->look_at_set) camera_look_at(cam, c->look_at);
}

void scene_config_scene_desc(const scene_config *cfg, const float *heights, int width,
                             int height, scene_desc *desc) {
  const scene_terrain_config *t = &cfg->terrain;
  *desc = (scene_desc){
      .terrain = {.origin = {t->origin[0], t->origin[1], t->origin[2]},
                  .size = {t->size[0], t->size[1]},
                  .height = t->height,
                  .heights = heights,
                  .heights_width = width,
                  .heights_height = height,
                  .resolution = t->resolution,
                  .octaves = t->octaves,
                  .frequency = t->frequency,
                  .persistence = t->persistence,
                  .seed = t->seed},
      .box_count = cfg->object_count,
      .light = cfg->light,
  };
  memcpy(desc->boxes, cfg->objects, sizeof cfg->objects);
}

/* ---- the fingerprint: every key's resolved value (defaults included), table by table ---- */

static uint64_t fnv(uint64_t hash, const void *bytes, size_t n) {
  const unsigned char *b = bytes;
  for (size_t i = 0; i < n; i++) hash = (hash ^ b[i]) * 1099511628211ull;
  return hash;
}

/* A file's bytes (what a fogmap or heightmap path names); its absence hashes as such. */
static uint64_t fnv_file(uint64_t hash, const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return fnv(hash, "missing", 7);
  unsigned char block[65536];
  size_t n;
  while ((n = fread(block, 1, sizeof block, f)) > 0) hash = fnv(hash, block, n);
  fclose(f);
  return hash;
}

/* A VDB or fogmap sequence by its frame numbers and file sizes (bakes run to gigabytes, too
 * much to read at every start; a re-bake of the same sizes goes unseen), and the bytes of
 * the Mantaflow configs beside VDB frames. */
static uint64_t fnv_vdb_sequence(uint64_t hash, const char *pattern) {
  vdb_sequence seq;
  fog_error serr = {0};
  if (vdb_sequence_find(&pattern, 1, -1, -1, &seq, &serr)) return fnv(hash, "missing", 7);
  for (int i = 0; i < seq.count; i++) {
    struct stat st;
    long long size = stat(seq.paths[i], &st) == 0 ? (long long)st.st_size : -1;
    hash = fnv(hash, &seq.frames[i], sizeof seq.frames[i]);
    hash = fnv(hash, &size, sizeof size);
    /* the Mantaflow config beside a frame places it (a domain moved in Blender and baked
     * again keeps its voxels' sizes): its bytes, a few hundred, count whole */
    char config[4096];
    if (!vdb_config_path_beside(seq.paths[i], config, sizeof config))
      hash = fnv_file(hash, config);
  }
  vdb_sequence_destroy(&seq);
  return hash;
}

uint64_t scene_config_fingerprint(const scene_config *cfg) {
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
    const key_spec *k = &keys[i];
    /* the display transform changes no EXR pixel: a preview's exposure may change between
     * a run and its --resume or a farm's ranges */
    if (k->offset == F(exposure) || k->offset == F(tone_map) || k->offset == F(dither)) continue;
    const char *field = (const char *)cfg + k->offset;
    h = fnv(h, k->section, strlen(k->section) + 1);
    h = fnv(h, k->key, strlen(k->key) + 1);
    switch (k->kind) {
      case V_DOUBLE: h = fnv(h, field, sizeof(double)); break;
      case V_DOUBLE2: h = fnv(h, field, 2 * sizeof(double)); break;
      case V_DOUBLE3:
      case V_LOOK_AT: h = fnv(h, field, 3 * sizeof(double)); break;
      case V_FLOAT3: h = fnv(h, field, 3 * sizeof(float)); break;
      case V_INT:
      case V_ENUM: h = fnv(h, field, sizeof(int)); break;
      case V_UINT: h = fnv(h, field, sizeof(unsigned)); break;
      case V_STRING: h = fnv(h, field, strlen(field) + 1); break;
      case V_PATH: /* what the file holds, not how the path is spelt */
        if (!field[0]) h = fnv(h, "none", 4);
        else if (k->offset == F(fog.vdb) || k->offset == F(fog.sequence))
          h = fnv_vdb_sequence(h, field);
        else h = fnv_file(h, field);
        break;
      case V_LIST: {
        int count = *(const int *)((const char *)cfg + k->aux_offset);
        h = fnv(h, &count, sizeof count);
        h = fnv(h, field, (size_t)count * sizeof(double));
        break;
      }
      case V_OBJECT: /* member by member: no padding bytes in the hash */
        h = fnv(h, &cfg->object_count, sizeof cfg->object_count);
        for (int b = 0; b < cfg->object_count; b++) {
          h = fnv(h, cfg->objects[b].center, sizeof cfg->objects[b].center);
          h = fnv(h, cfg->objects[b].size, sizeof cfg->objects[b].size);
          h = fnv(h, cfg->objects[b].colour, sizeof cfg->objects[b].colour);
        }
        break;
      case V_LAMP: /* every lamp at the "lamp" key, in the array's order (the order the fog
                    * sums them in: interleaved lamp and spot lines differ in the last bit) */
        for (int i = 0; i < cfg->lamp_count && !strcmp(k->key, "lamp"); i++) {
          const scene_lamp_config *l = &cfg->lamps[i];
          h = fnv(h, &l->spot, sizeof l->spot);
          h = fnv(h, l->position, sizeof l->position);
          h = fnv(h, l->colour, sizeof l->colour);
          h = fnv(h, &l->radius, sizeof l->radius);
          if (l->spot) {
            h = fnv(h, l->axis, sizeof l->axis);
            h = fnv(h, &l->inner, sizeof l->inner);
            h = fnv(h, &l->outer, sizeof l->outer);
          }
          h = fnv(h, &l->key_count, sizeof l->key_count);
          h = fnv(h, l->keys, (size_t)l->key_count * sizeof l->keys[0]);
          h = fnv(h, &l->flicker_amount, sizeof l->flicker_amount);
          if (l->flicker_amount > 0) {
            h = fnv(h, &l->flicker_rate, sizeof l->flicker_rate);
            h = fnv(h, &l->flicker_seed, sizeof l->flicker_seed);
          }
        }
        break;
      case V_LAMP_PATH: /* with their lamps (V_LAMP) */
      case V_LAMP_FLICKER:
        break;
      case V_RBF:
        h = fnv(h, &cfg->fog.rbf_count, sizeof cfg->fog.rbf_count);
        for (int r = 0; r < cfg->fog.rbf_count; r++) {
          h = fnv(h, cfg->fog.rbfs[r].centre, sizeof cfg->fog.rbfs[r].centre);
          h = fnv(h, &cfg->fog.rbfs[r].radius, sizeof(double));
          h = fnv(h, &cfg->fog.rbfs[r].density, sizeof(double));
        }
        break;
      case V_RBF_EMITTER:
        h = fnv(h, &cfg->fog.rbf_emitter_count, sizeof cfg->fog.rbf_emitter_count);
        for (int r = 0; r < cfg->fog.rbf_emitter_count; r++) {
          const fog_rbf_emitter *e = &cfg->fog.rbf_emitters[r];
          h = fnv(h, e->position, sizeof e->position);
          const double numbers[6] = {e->rate, e->lifetime, e->radius, e->density, e->spread,
                                     e->diffusion};
          h = fnv(h, numbers, sizeof numbers);
          h = fnv(h, e->wind, sizeof e->wind);
          h = fnv(h, &e->seed, sizeof e->seed);
        }
        break;
      case V_QUADRIC:
        h = fnv(h, &cfg->fog.quadric_count, sizeof cfg->fog.quadric_count);
        /* doubles only: no padding bytes in the hash */
        h = fnv(h, cfg->fog.quadrics, sizeof cfg->fog.quadrics[0] * cfg->fog.quadric_count);
        break;
    }
  }
  /* What the file says besides values: which of the optional settings were given. */
  const bool flags[] = {cfg->camera.look_at_set, cfg->fog.profile_set, cfg->box.origin_set,
                        cfg->box.cell_size_set,  cfg->box.floor_set,   cfg->box.top_set};
  for (size_t i = 0; i < sizeof flags / sizeof flags[0]; i++) h = fnv(h, &flags[i], 1);
  return h;
}
