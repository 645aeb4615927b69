/* Every kind of config error names FILE:LINE: [section] key and what was expected: the
 * exact prefix is checked for each, on files where the offending line is not the first
 * (comments and blank lines before it count). */
#define _XOPEN_SOURCE 700 /* realpath */
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/config.h"
#include "app/render_fog.h"
#include "test_util.h"

static char dir[] = "/tmp/fogpipe_config_errors_XXXXXX";

/* Writes text to DIR/bad.ini (path), loads it into cfg and removes it: the load's status. */
static int load_text(const char *text, char path[256], scene_config *cfg, fog_error *err) {
  snprintf(path, 256, "%s/bad.ini", dir);
  FILE *f = fopen(path, "w");
  CHECK(f != NULL, "cannot write %s", path);
  if (!f) return -1;
  fputs(text, f);
  fclose(f);
  int status = scene_config_load(path, cfg, err);
  unlink(path);
  return status;
}

/* Loads text from DIR/bad.ini and checks the message starts with "DIR/bad.ini:<prefix>" and
 * contains `detail`. */
static void expect_error(const char *text, const char *prefix, const char *detail) {
  char path[256], want[512];
  scene_config cfg;
  fog_error err = {0};
  int status = load_text(text, path, &cfg, &err);
  snprintf(want, sizeof want, "%s:%s", path, prefix);
  CHECK(status != 0, "accepted: %s", text);
  CHECK(strncmp(err.message, want, strlen(want)) == 0, "message '%s' does not start with '%s'",
        err.message, want);
  CHECK(strstr(err.message, detail) != NULL, "message '%s' lacks '%s'", err.message, detail);
  /* a sound line naming a file that is not there is an access failure; the rest, the
   * config's own fault */
  const fog_result want_code =
      !strncmp(detail, "cannot open '", 13) ? FOG_ERR_FILE_ACCESS : FOG_ERR_BAD_CONFIG;
  CHECK(err.code == want_code, "'%s': code %d (%s), expected %s", err.message, err.code,
        fog_result_text(err.code), fog_result_text(want_code));
}

int main(void) {
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  expect_error("; scene\n\n[fgo]\ndensity_scale = 1\n", "4: [fgo] density_scale: ",
               "unknown section [fgo]; sections are fog, box");
  /* a typo gets the nearest key; a section's keys are listed when they fit the message */
  expect_error("[fog]\nbasis = linear\ndensty_scale = 2\n", "3: [fog] densty_scale: ",
               "unknown key; did you mean 'density_scale'? [fog] has ");
  expect_error("[fog]\nwhatever = 2\n", "2: [fog] whatever: ",
               "unknown key; [fog] has ");
  expect_error("[fog]\nwhatever = 2\n", "2: [fog] whatever: ", "keys (docs/config.md lists them)");
  expect_error("[fog]\nxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx = 2\n",
               "2: [fog] xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx: ",
               "unknown key; [fog] has "); /* longer than any key: no guess */
  expect_error("[camera]\nfovv = 50\n", "2: [camera] fovv: ",
               "unknown key; did you mean 'fov'? [camera] has position, yaw, pitch, fov, look_at, "
               "near, far");
  expect_error("[camera]\n# a comment\nfov = 50\n\nyaw = 1O\n", "5: [camera] yaw: ",
               "expected a number, got '1O'");
  expect_error("[fog]\nmu = 1.5\n", "2: [fog] mu: ", "expected a number from 0 to 1, got '1.5'");
  expect_error("[fog]\nlevels = 2.5\n", "2: [fog] levels: ", "expected an integer, got '2.5'");
  expect_error("[render]\nwidth = 64\n[fog]\nbasis = cubic\n", "4: [fog] basis: ",
               "expected one of haar|linear|quadratic, got 'cubic'");
  expect_error("[fog]\nlod = sometimes\n", "2: [fog] lod: ", "expected one of sum|switch");
  expect_error("[fog]\nprofile = gaussian\n", "2: [fog] profile: ",
               "expected one of slab|exponential|bspline");
  expect_error("[camera]\n\nposition = 1 2\n", "3: [camera] position: ",
               "expected three numbers (x y z), got '1 2'");
  expect_error("[fog]\ncolour = 0.5 0.5 0.5 0.5\n", "2: [fog] colour: ", "expected three numbers");
  expect_error("[objects]\nbox = 1 2 3\n", "2: [objects] box: ", "expected X Z WIDTH HEIGHT DEPTH");
  expect_error("density_scale = 1\n", "1: [] density_scale: ", "key outside any section");
  expect_error("[fog]\nbasis = linear\nthis line has no equals sign\n", "3: ",
               "expected '[section]', 'key = value' or a comment");
  /* Missing files are reported at the line that named them. */
  char missing[300];
  snprintf(missing, sizeof missing, "cannot open '%s/nothere.png'", dir);
  expect_error("[fog]\nbasis = haar\n\nfogmap = nothere.png\nmu = 0.5\n", "4: [fog] fogmap: ",
               missing);
  snprintf(missing, sizeof missing, "cannot open '%s/hills.png'", dir);
  expect_error("[render]\n[terrain]\nheightmap = hills.png\n", "3: [terrain] heightmap: ", missing);
  /* The fog models of the ladder and their Gaussians. */
  expect_error("[fog]\nmodel = clouds\n", "2: [fog] model: ",
               "expected one of fogmap|homogeneous|height|rbf|volume|quadric|linear|exp2|perlin, got "
               "'clouds'");
  /* The linear fog factor ends after it starts. */
  expect_error("[fog]\nfog_start = 500\nmodel = linear\nfog_end = 400\n", "4: [fog] fog_end: ",
               "linear fog needs fog_end above fog_start, got fog_start = 500 and fog_end = 400");
  /* ':' is not a key's separator (libinih takes it), and '[]' names no section */
  expect_error("[fog]\ndensity_scale: 0.5\n", "2: expected KEY = VALUE, got 'density_scale: 0.5'",
               "");
  expect_error("[]\ndensity_scale = 0.5\n", "1: expected '[section]', got '[]'", "");
  /* two commas in a row: an error, not a number left out (a list lost one silently) */
  expect_error("[fog]\ndensity_scale = 0.5,,\n", "2: [fog] density_scale: ", "");
  expect_error("[camera]\nposition = 0,,150, 480\n", "2: [camera] position: ", "");
  expect_error("[fog]\nmodel = quadric\nquadric = sphere,,0 50 0 30 0.1\n",
               "3: [fog] quadric: ", "");
  expect_error("[fog]\nperlin_wind = 10, 0, 3,\n  , -7, 0.5, 11\n", "3: [fog] perlin_wind: ",
               "two commas in a row");
  {
    /* one comma between numbers, after a quadric's shape, and ending a list's line */
    char path[256];
    scene_config cfg;
    fog_error err = {0};
    CHECK(load_text("[fog]\nmodel = quadric\nquadric = sphere, 0, 50, 0, 30, 0.1\n"
                    "profile = bspline\nprofile_degree = 1\nprofile_coefficients = 1, 2,\n"
                    "  3, 4\n", path, &cfg, &err) == 0 &&
              cfg.fog.quadric_count == 1 && cfg.fog.profile_count == 4 &&
              cfg.fog.profile_coefficients[3] == 4.0,
          "commas as documented: %s (quadrics %d, coefficients %d)", err.message,
          cfg.fog.quadric_count, cfg.fog.profile_count);
  }
  {
    /* emitters without SEED: each its place among them (the same seed made every puff of
     * the second a copy of the first's, moved) */
    char path[256];
    scene_config cfg;
    fog_error err = {0};
    CHECK(load_text("[fog]\nmodel = rbf\nrbf_emitter = 0 10 0 2 3 1 0.1 4 0 1 0 0\n"
                    "rbf_emitter = 100 10 0 2 3 1 0.1 4 0 1 0 0\n"
                    "rbf_emitter = 50 10 0 2 3 1 0.1 4 0 1 0 0 9\n", path, &cfg, &err) == 0 &&
              cfg.fog.rbf_emitter_count == 3 && cfg.fog.rbf_emitters[0].seed == 0 &&
              cfg.fog.rbf_emitters[1].seed == 1 && cfg.fog.rbf_emitters[2].seed == 9,
          "emitters' seeds: %s (%d emitters)", err.message, cfg.fog.rbf_emitter_count);
  }
  /* a model's keys are checked whatever the scene's model (docs/config.md): a switch to it
   * later must not meet an error the config loaded with */
  expect_error("[fog]\nfog_end = 100\nmodel = homogeneous\nfog_start = 500\n",
               "4: [fog] fog_start: ", "linear fog needs fog_end above fog_start");
  expect_error("[fog]\nmodel = homogeneous\nperlin_size = 48\n", "3: [fog] perlin_size: ",
               "expected a power of two");
  expect_error("[fog]\nmodel = homogeneous\nperlin_wind = 1 2 3 4 5\n",
               "3: [fog] perlin_wind: ", "expected 3 numbers");
  expect_error("[fog]\nmodel = linear\nfog_start = -1\n", "3: [fog] fog_start: ", "");
  expect_error("[fog]\nmodel = rbf\nrbf = 0 10 0 50\n", "3: [fog] rbf: ",
               "expected X Y Z RADIUS DENSITY (5 numbers), got '0 10 0 50'");
  expect_error("[fog]\nmodel = rbf\nrbf = 0 10 0 50 0.1\nrbf = 0 10 0 0 0.1\n", "4: [fog] rbf: ",
               "expected RADIUS from 0.0001 to 1e+07 and DENSITY from 0 to 1e+12");
  expect_error("[fog]\nrbf = 0 10 0 5 -0.1\n", "2: [fog] rbf: ", "DENSITY from 0 to 1e+12");
  /* Quadric volumes: the shape, its count of numbers, each number's range, the box. */
  expect_error("[fog]\nmodel = quadric\nquadric = torus 0 0 0 5 1\n", "3: [fog] quadric: ",
               "expected a shape (sphere, ellipsoid, cylinder, cone or general)");
  expect_error("[fog]\nmodel = quadric\n\nquadric = sphere 0 10 0 50\n", "4: [fog] quadric: ",
               "expected sphere X Y Z R DENSITY [EDGE [NOISE]] (5 to 7 numbers), got 'sphere 0 10 0 50'");
  expect_error("[fog]\nquadric = cone 0 0 0 5 0 0.1\n", "2: [fog] quadric: ",
               "number 5 (0) of cone X Y Z R HEIGHT DENSITY: expected 0.0001 to 1e+07");
  expect_error("[fog]\nquadric = sphere 0 0 0 5 0.1 1.5\n", "2: [fog] quadric: ",
               "expected DENSITY from 0 to 1e+12, EDGE from 0 to 1 and NOISE from 0 to 1");
  expect_error("[fog]\nquadric = general 1 1 1 0 0 0 0 0 0 -1 -1 -1 -1 1 -1 1 0.1\n",
               "2: [fog] quadric: ", "expected XMIN < XMAX, YMIN < YMAX and ZMIN < ZMAX");
  expect_error("[fog]\nquadric = general 1e13 1 1 0 0 0 0 0 0 -1 -1 -1 -1 1 1 1 0.1\n",
               "2: [fog] quadric: ", "number 1 (1e+13) of general");
  expect_error("; volumes\n[fog]\nmodel = quadric\n", "3: [fog] model: ",
               "quadric needs at least one 'quadric = SHAPE ...' line");
  /* Values the parser used to take and the renderer turned into NaN pixels (float
   * overflow): each is refused naming its key. */
  expect_error("[fog]\ndensity_scale = 1e39\n", "2: [fog] density_scale: ",
               "expected a number from 0 to 1e+12, got '1e39'");
  expect_error("[fog]\nscale_height = 1e-9\n", "2: [fog] scale_height: ",
               "expected a number from 0.0001 to 1e+07, got '1e-9'");
  expect_error("[fog]\nmodel = rbf\nrbf = 0 10 0 1e-300 1\n", "3: [fog] rbf: ",
               "expected RADIUS from 0.0001");
  expect_error("[light]\nsun_colour = 1e300 1 1\n", "2: [light] sun_colour: ",
               "expected a number from 0 to 10000");
  expect_error("[camera]\nposition = 0 1e30 0\n", "2: [camera] position: ",
               "expected a number from -1e+07 to 1e+07");
  expect_error("[fog]\nmodel = height\nfog_height = 30\nscale_height = 0.001\n",
               "2: [fog] model: ", "raise scale_height");
  /* a FIFO named as the config: refused at once (fopen waited for a writer forever) */
  {
    char fifo[300];
    snprintf(fifo, sizeof fifo, "%s/pipe.ini", dir);
    CHECK(mkfifo(fifo, 0644) == 0, "mkfifo %s", fifo);
    scene_config cfg;
    fog_error err = {0};
    CHECK(scene_config_load(fifo, &cfg, &err) != 0 && strstr(err.message, "not a regular file"),
          "a FIFO as the config: %s", err.message);
    unlink(fifo);
  }
  /* Where each model's fog is densest in view decides it: Perlin fog at its box's floor
   * (a layer high above the camera is fine, one reaching below it is not), height fog at
   * the camera or the terrain's base, whatever [box] says. */
  {
    static const char *const accepted[] = {
        "[camera]\nposition = 0 55 0\n[box]\nfloor = 400\ntop = 480\n"
        "[fog]\nmodel = perlin\nfog_height = 400\nscale_height = 12\ndensity_scale = 0.15\n",
        "[camera]\nposition = 0 1250 0\n[terrain]\norigin = -500 1000 -500\n[fog]\n"
        "model = height\nfog_height = 1100\nscale_height = 30\ndensity_scale = 0.02\n"};
    for (int i = 0; i < 2; i++) {
      char path[256];
      scene_config cfg;
      fog_error err = {0};
      CHECK(load_text(accepted[i], path, &cfg, &err) == 0, "case %d refused: %s", i,
            err.message);
    }
  }
  /* A VDB scene that sets [box] top alone, under the default floor 0 but above the VDB's
   * floor (-0.047 on the ground fog), which fills the floor: no mistake of the file's (it was
   * refused, "top (-0.01) must be above floor (0)"); with both set the pair is checked. */
  {
    char data[PATH_MAX], text[PATH_MAX + 128], path[256];
    if (!realpath("../shared/data/vdb/groundfog/data", data)) snprintf(data, sizeof data, "?");
    scene_config cfg;
    fog_error err = {0};
    snprintf(text, sizeof text, "[fog]\nvdb = %s/fluid_data_####.vdb\n[box]\ntop = -0.01\n",
             data);
    CHECK(load_text(text, path, &cfg, &err) == 0, "a VDB scene with top alone: %s",
          err.message);
    snprintf(text, sizeof text,
             "[fog]\nvdb = %s/fluid_data_####.vdb\n[box]\nfloor = 0\ntop = -0.01\n", data);
    expect_error(text, "5: [box] top: ", "top (-0.01) must be above floor (0)");
  }
  expect_error("[camera]\nposition = 0 55 0\n[box]\nfloor = 100\ntop = 480\n"
               "[fog]\nmodel = perlin\nfog_height = 400\nscale_height = 3\n",
               "7: [fog] model: ", "at y = 100 ([box] floor, the fog's lowest)");
  /* Lines past libinih's 200-byte buffer: a long comment is a comment (its tail used to be
   * parsed as a key, and every later line number was off by one); a long key line is an
   * error naming its line. */
  {
    char text[1024];
    snprintf(text, sizeof text, "[fog]\n; %0300d density_scale = 5\nbogus = 1\n", 0);
    expect_error(text, "3: [fog] bogus: ", "unknown key");
    snprintf(text, sizeof text, "[fog]\n; %0300d\n[camera]\nfov = 40\n", 0);
    char path[256];
    scene_config cfg;
    fog_error err = {0};
    CHECK(load_text(text, path, &cfg, &err) == 0, "a long comment: %s", err.message);
    CHECK(cfg.fog.density_scale == 1.0 && cfg.camera.fov == 40.0,
          "a long comment changed the scene: density_scale %g, fov %g", cfg.fog.density_scale,
          cfg.camera.fov);
    snprintf(text, sizeof text, "[fog]\nfog_height = %0250d\n", 1);
    expect_error(text, "2: the line is 263 bytes long", "at most 199");
    /* 199 bytes hold, whatever ends the line (\n, \r\n or the file); 200 do not */
    const char *ends[3] = {"\n", "\r\n", ""};
    for (int e = 0; e < 3; e++) {
      snprintf(text, sizeof text, "[fog]\nfog_height = %0186d%s", 7, ends[e]);
      CHECK(load_text(text, path, &cfg, &err) == 0 && cfg.fog.fog_height == 7.0,
            "a line of 199 bytes ending %d: %s", e, err.message);
    }
    snprintf(text, sizeof text, "[fog]\nfog_height = %0187d\r\n", 7);
    expect_error(text, "2: the line is 200 bytes long", "at most 199");
    /* below double's normal range (strtod: ERANGE), inside the key's: a number */
    CHECK(load_text("[fog]\nmodel = homogeneous\ndensity_scale = 1e-320\n", path, &cfg,
                    &err) == 0 && cfg.fog.density_scale > 0 && cfg.fog.density_scale < 1e-319,
          "density_scale = 1e-320: %s", err.message);
  }
  expect_error("; banks\n[fog]\nmodel = rbf\nrbf_base = 0.01\n", "3: [fog] model: ",
               "rbf needs at least one 'rbf = X Y Z RADIUS DENSITY' or 'rbf_emitter = ...' line");
  expect_error("[fog]\nmodel = rbf\nrbf_emitter = 0 10 0 40 25 5 0.06 4 25 -7 1\n",
               "3: [fog] rbf_emitter: ", "(12 or 13 numbers), got '0 10 0 40 25 5 0.06 4 25 -7 1'");
  expect_error("[fog]\nrbf_emitter = 0 10 0 0 25 5 0.06 4 25 -7 1 0\n", "2: [fog] rbf_emitter: ",
               "RATE (0): expected 0.0001 to 1e+07");
  expect_error("[fog]\nrbf_emitter = 0 10 0 40 25 5 0.06 4 25 -7 1 0 1.5\n",
               "2: [fog] rbf_emitter: ", "SEED (1.5): expected a whole number");
  expect_error("[fog]\nrbf_emitter = 0 10 0 400 25 5 0.06 4 25 -7 1 0\n", "2: [fog] rbf_emitter: ",
               "RATE x LIFETIME: 10000 puffs alive at once in all, expected at most 3072");
  /* 1e14 puffs: past INT_MAX, where an int count came out negative and was let through */
  expect_error("[fog]\nrbf_emitter = 0 20 -50 1e7 1e7 5 0.01 1 0 0 0 0\n",
               "2: [fog] rbf_emitter: ",
               "RATE x LIFETIME: 1e+14 puffs alive at once in all, expected at most 3072");
  expect_error("[fog]\n\nmodel = volume\n", "3: [fog] model: ",
               "volume needs a 'vdb = FILE or PATTERN' line");
  {
    static char text[32768] = "[fog]\nmodel = rbf\n";
    for (int i = 0; i <= SCENE_CONFIG_MAX_RBFS; i++) strcat(text, "rbf = 1 2 3 4 0.5\n");
    char prefix[64];
    snprintf(prefix, sizeof prefix, "%d: [fog] rbf: ", 3 + SCENE_CONFIG_MAX_RBFS);
    expect_error(text, prefix, "at most 1024 Gaussians");
  }
  /* A quadric volume may go on over indented lines, so it is stored at the next key: its
   * mistake still comes before a later line's (an unknown key, a line that is no line), and
   * an indented key after it is told to unindent. */
  expect_error("[fog]\nmodel = quadric\nquadric = sphere 0 0 0 5\nbogus = 1\n",
               "3: [fog] quadric: ", "(5 to 7 numbers)");
  expect_error("[fog]\nmodel = quadric\nquadric = sphere 0 0 0 5\nthis is not a line\n",
               "3: [fog] quadric: ", "(5 to 7 numbers)");
  expect_error("[fog]\nmodel = quadric\nquadric = sphere 0 0 0 5 0.1\n  density_scale = 2\n",
               "4: [fog] quadric: ", "unindent 'density_scale = 2'");
  /* The first error wins when there are several. */
  expect_error("[fog]\nmu = x\nbasis = y\n", "2: [fog] mu: ", "expected a number");

  /* A config that cannot be opened at all. */
  scene_config cfg;
  fog_error err = {0};
  CHECK(scene_config_load("/nonexistent/scene.ini", &cfg, &err) != 0 &&
            strstr(err.message, "/nonexistent/scene.ini: cannot open the config") == err.message &&
            err.code == FOG_ERR_FILE_ACCESS,
        "%s (code %d)", err.message, err.code);

  /* A file the config names and that is not there is an access failure, at the config's
   * line; one that is there but no image fails when read (no GL is needed to get there: the
   * map is read before anything is uploaded), as a bad file, with the config's line. */
  const char *fogmaps[2] = {"missing.png", "notes.png"};
  const fog_result codes[2] = {FOG_ERR_FILE_ACCESS, FOG_ERR_BAD_FILE};
  char notes[300], ini[300];
  snprintf(notes, sizeof notes, "%s/notes.png", dir);
  FILE *text = fopen(notes, "w");
  fputs("not an image\n", text);
  fclose(text);
  snprintf(ini, sizeof ini, "%s/scene.ini", dir);
  for (int k = 0; k < 2; k++) {
    FILE *f = fopen(ini, "w");
    fprintf(f, "[fog]\n; the map\nfogmap = %s\n", fogmaps[k]);
    fclose(f);
    fog_error ferr = {0};
    char want[400];
    if (k == 0) {
      CHECK(scene_config_load(ini, &cfg, &ferr) != 0, "%s accepted", fogmaps[k]);
      snprintf(want, sizeof want, "%s:3: [fog] fogmap: cannot open '%s/%s'", ini, dir,
               fogmaps[k]);
    } else {
      CHECK(scene_config_load(ini, &cfg, &ferr) == 0, "%s", ferr.message);
      render_fog fog;
      CHECK(render_fog_create(&fog, &cfg, &ferr) != 0, "%s accepted", fogmaps[k]);
      snprintf(want, sizeof want, "%s:3: [fog] fogmap: %s/%s", ini, dir, fogmaps[k]);
    }
    CHECK(strstr(ferr.message, want) == ferr.message && ferr.code == codes[k],
          "'%s' (code %s), expected '%s...' and %s", ferr.message, fog_result_text(ferr.code),
          want, fog_result_text(codes[k]));
  }
  unlink(notes);
  unlink(ini);
  rmdir(dir);
  return test_finish("test_config_errors");
}
