/* fogpipe fit INPUT --tolerance T [--out scene.ini] [--chart fit.png]: the cheapest model
 * of the ladder that holds the input's fog within T (app/fit.h, docs/fit.md). */
#define _XOPEN_SOURCE 700 /* realpath */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "app/chart.h"
#include "app/cli.h"
#include "app/clock.h"
#include "app/commands.h"
#include "app/config.h"
#include "app/fit.h"
#include "app/render_fog.h"
#include "sim/sim.h"

static void usage(FILE *out) {
  fprintf(out,
          "usage: fogpipe fit INPUT --tolerance T [options]\n\n"
          "Fits every model of the ladder that can represent the input's fog (homogeneous,\n"
          "height, an ellipsoid and banks of 2 to 16, banks of 1 to 64 Gaussians, the\n"
          "fogmap at three bases x three LOD factors (an analytic fog's density projected),\n"
          "the 3D volume), measures each on nine views around and inside\n"
          "the fog (max and mean |delta tau| against the input's own fog, exact integrals in\n"
          "double) and times it on the GL (headless), prints the table and picks the fastest\n"
          "within the tolerance (docs/fit.md).\n\n"
          "INPUT: a scene config (.ini), or a VDB file or sequence (a #### pattern, a folder)\n"
          "whose frame is fitted as a 3D volume.\n\n"
          "options:\n"
          "  --tolerance T[,T..]  max |delta tau| allowed on every ray (required, > 0); more\n"
          "                       values print the pick at each (the first one's is written)\n"
          "  --by max|mean        the tolerance bounds each rung's max error (default) or\n"
          "                       its mean error over the rays\n"
          "  --out FILE.ini       write the scene with the chosen model (nothing is written\n"
          "                       when none is within T); a fogmap projected from an\n"
          "                       analytic fog goes beside it as FILE.fogmap.exr\n"
          "  --chart FILE.png     error against ms, one series per family (and FILE.csv)\n"
          "VDB input:\n"
          "  --grid NAME          float grid (default density)\n"
          "  --up z|y             the file's up axis (default z: Blender/Mantaflow)\n"
          "  --frame N            frame number of a sequence (default: the last)\n"
          "sequences (a VDB INPUT, or a config's [fog] vdb):\n"
          "  --frames all|A-B[:S] fit over these frame numbers (every S-th), the worst frame\n"
          "                       deciding: the static rungs fit the frames' mean density,\n"
          "                       the fogmap and the volume play the frames (default: one\n"
          "                       frame, --frame or the config's vdb_frame)\n"
          "  --density-scale S    extinction per unit of the grid's value (default 1)\n"
          "measurement:\n"
          "  --rays N             rays per side of each view (default %d)\n"
          "  --samples N          density samples along the longest side (default %d)\n"
          "  --size WxH           timed frames (default %dx%d)\n"
          "  --timed N            timed frames per rung (default %d)\n"
          "  --help               this text\n",
          FIT_RAYS_PER_SIDE, FIT_SAMPLE_SIDE, FIT_WIDTH, FIT_HEIGHT, FIT_TIMED_FRAMES);
}

typedef struct fit_options {
  const char *input, *out, *chart, *grid;
  const char *frames; /* --frames all|A-B[:STEP] */
  double tolerance[8]; /* --tolerance T[,T...]: the first picks --out */
  int tolerance_count;
  double density_scale;
  int up, frame;
  fit_desc desc;
} fit_options;

static int parse(int argc, char **argv, fit_options *o) {
  *o = (fit_options){.density_scale = 1.0, .frame = -1,
                     .desc = {.rays_per_side = FIT_RAYS_PER_SIDE, .sample_side = FIT_SAMPLE_SIDE,
                              .width = FIT_WIDTH, .height = FIT_HEIGHT,
                              .timed_frames = FIT_TIMED_FRAMES}};
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      usage(stdout);
      return -1;
    }
    if (a[0] != '-' || !a[1]) {
      if (o->input) return cli_usage_error("fit", "one INPUT only, got '%s' and '%s'", o->input, a);
      o->input = a;
      continue;
    }
    static const char *const valued[] = {"--tolerance", "--by", "--out", "--chart", "--grid", "--up",
                                         "--frame", "--density-scale", "--rays", "--samples",
                                         "--size", "--timed", "--frames"};
    bool known = false;
    for (size_t k = 0; k < sizeof valued / sizeof valued[0]; k++) known |= !strcmp(a, valued[k]);
    if (!known) return cli_usage_error("fit", "unknown option '%s'", a);
    if (i + 1 >= argc) return cli_usage_error("fit", "%s needs a value", a);
    const char *v = argv[++i];
    if (!strcmp(a, "--tolerance")) {
      char list[256], *save = NULL;
      snprintf(list, sizeof list, "%s", v);
      o->tolerance_count = 0;
      for (char *t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        if (o->tolerance_count == 8) return cli_usage_error("fit", "--tolerance: at most 8 values");
        if (cli_number("fit", a, t, 1e-12, 1.0, &o->tolerance[o->tolerance_count++])) return 2;
      }
    } else if (!strcmp(a, "--by")) {
      if (strcmp(v, "max") && strcmp(v, "mean"))
        return cli_usage_error("fit", "--by '%s': expected max or mean", v);
      o->desc.by_mean = !strcmp(v, "mean");
    } else if (!strcmp(a, "--out")) {
      if (!cli_ends_with(v, ".ini")) return cli_usage_error("fit", "--out '%s': expected a .ini file", v);
      o->out = v;
    } else if (!strcmp(a, "--chart")) {
      if (!cli_ends_with(v, ".png")) return cli_usage_error("fit", "--chart '%s': expected a .png file", v);
      o->chart = v;
    } else if (!strcmp(a, "--grid")) {
      o->grid = v;
    } else if (!strcmp(a, "--up")) {
      if (strcmp(v, "z") && strcmp(v, "y")) return cli_usage_error("fit", "--up '%s': expected z or y", v);
      o->up = !strcmp(v, "y");
    } else if (!strcmp(a, "--frame")) {
      if (cli_int("fit", a, v, 0, INT_MAX, &o->frame)) return 2;
    } else if (!strcmp(a, "--density-scale")) {
      if (cli_number("fit", a, v, 1e-12, 1e12, &o->density_scale)) return 2;
    } else if (!strcmp(a, "--rays")) {
      if (cli_int("fit", a, v, 1, 1024, &o->desc.rays_per_side)) return 2;
    } else if (!strcmp(a, "--samples")) {
      if (cli_int("fit", a, v, 2, 512, &o->desc.sample_side)) return 2;
    } else if (!strcmp(a, "--size")) {
      if (cli_size("fit", a, v, &o->desc.width, &o->desc.height)) return 2;
    } else if (!strcmp(a, "--timed")) {
      if (cli_int("fit", a, v, 1, 64, &o->desc.timed_frames)) return 2;
    } else if (!strcmp(a, "--frames")) {
      o->frames = v;
    }
  }
  if (!o->input) return cli_usage_error("fit", "no INPUT given");
  if (o->tolerance_count < 1) return cli_usage_error("fit", "no --tolerance T given");
  o->desc.tolerance = o->tolerance[0];
  return 0;
}

/* The scene of the input: its config, or a VDB frame as a volume in a scene around it. */
static int load_input(const fit_options *o, scene_config *cfg) {
  if (cli_ends_with(o->input, ".ini")) {
    scene_config_error err;
    if (scene_config_load(o->input, cfg, &err)) return cli_fail("fit", "%s", err.message);
    if (o->grid || o->up || o->frame >= 0 || o->density_scale != 1.0)
      return cli_usage_error("fit", "--grid, --up, --frame and --density-scale are for a VDB "
                             "INPUT; a config sets them in [fog]");
    return 0;
  }
  scene_config_init(cfg);
  char *absolute = realpath(o->input, NULL); /* a pattern stays as written */
  snprintf(cfg->fog.vdb, sizeof cfg->fog.vdb, "%s", absolute ? absolute : o->input);
  free(absolute);
  snprintf(cfg->path, sizeof cfg->path, "%s", o->input);
  if (o->grid) snprintf(cfg->fog.vdb_grid, sizeof cfg->fog.vdb_grid, "%s", o->grid);
  cfg->fog.model = FOG_MODEL_VOLUME;
  cfg->fog.vdb_up = o->up;
  cfg->fog.vdb_frame = o->frame;
  cfg->fog.density_scale = o->density_scale;
  fit_error err;
  if (fit_scene_for_volume(cfg, &err)) return cli_fail("fit", "%s", err.message);
  return 0;
}

/* The frame numbers of --frames in the input's sequence (malloc'd into *out). */
static int sequence_frames(const fit_options *o, const scene_config *cfg, int **out, int *count) {
  *out = NULL, *count = 0;
  if (!o->frames) return 0;
  if (!cfg->fog.vdb[0])
    return cli_usage_error("fit", "--frames: the input has no VDB sequence ([fog] vdb)");
  int first = INT_MIN, last = INT_MAX, step = 1;
  if (strcmp(o->frames, "all")) {
    char range[64];
    snprintf(range, sizeof range, "%s", o->frames);
    char *colon = strchr(range, ':');
    if (colon) {
      *colon = '\0';
      if (cli_int("fit", "--frames' step", colon + 1, 1, INT_MAX, &step)) return 2;
    }
    bool single;
    if (cli_range("fit", "--frames", range, 0, INT_MAX, &first, &last, &single)) return 2;
  }
  vdb_sequence seq;
  render_error rerr = {{0}};
  if (render_fog_volume_sequence(cfg, &seq, &rerr)) return cli_fail("fit", "%s", rerr.message);
  int *list = malloc(sizeof *list * (size_t)seq.count);
  int n = 0, seen = 0;
  for (int i = 0; list && i < seq.count; i++)
    if (seq.frames[i] >= first && seq.frames[i] <= last && seen++ % step == 0)
      list[n++] = seq.frames[i];
  vdb_sequence_destroy(&seq);
  if (!list) return cli_fail("fit", "out of memory");
  if (n == 0) {
    free(list);
    return cli_fail("fit", "--frames %s: no such frames in %s", o->frames, cfg->fog.vdb);
  }
  *out = list, *count = n;
  return 0;
}

static int write_chart(const fit_result *r, const char *png) {
  chart_point points[FIT_MAX_RUNGS];
  for (int i = 0; i < r->count; i++)
    points[i] = (chart_point){.series = r->rungs[i].family, .x = r->rungs[i].ms,
                              .y = fmax(r->rungs[i].max_error, 1e-4)};
  char csv[PATH_MAX], error[512];
  snprintf(csv, sizeof csv, "%.*s.csv", (int)(strlen(png) - 4), png);
  chart_desc desc = {.title = "fogpipe fit: each rung's error against its GL time",
                     .x_label = "GL ms per frame", .y_label = "max |delta tau| (an exact rung at 1e-4)",
                     .log_y = true};
  if (chart_write(&desc, points, r->count, csv, png, error, sizeof error))
    return cli_fail("fit", "%s", error);
  return 0;
}

/* The folder FILE goes into exists (checked before the fit, which takes seconds). */
static bool folder_exists(const char *file) {
  char folder[PATH_MAX];
  snprintf(folder, sizeof folder, "%s", file);
  char *slash = strrchr(folder, '/');
  if (!slash) return true;
  *(slash == folder ? slash + 1 : slash) = '\0';
  struct stat st;
  return stat(folder, &st) == 0 && S_ISDIR(st.st_mode);
}

/* The chosen rung's scene to `out`; a fogmap projected into the fit's scratch folder goes
 * beside it first, as OUT.fogmap.exr (without .ini), and the scene names that copy. On
 * failure neither file is left. */
static int write_scene(const fit_result *r, const fit_rung *g, const char *out) {
  const char *map = g->config->fog.fogmap;
  const size_t n = strlen(r->scratch);
  scene_config_error werr;
  if (!(n && g->config->fog.model == FOG_MODEL_FOGMAP && !strncmp(map, r->scratch, n))) {
    if (scene_config_write(g->config, out, &werr)) return cli_fail("fit", "%s", werr.message);
    return 0;
  }
  scene_config *c = malloc(sizeof *c);
  if (!c) return cli_fail("fit", "out of memory");
  *c = *g->config;
  snprintf(c->fog.fogmap, sizeof c->fog.fogmap, "%.*s.fogmap.exr",
           (int)(strlen(out) - strlen(".ini")), out);
  fogmap copy = {0};
  sim_error serr = {{0}};
  int status = 0;
  if (fogmap_load(map, &(fogmap_load_desc){0}, &copy, &serr) ||
      fogmap_save_exr(c->fog.fogmap, &copy, &serr)) {
    status = cli_fail("fit", "%s", serr.message);
  } else if (scene_config_write(c, out, &werr)) {
    remove(c->fog.fogmap);
    status = cli_fail("fit", "%s", werr.message);
  } else {
    printf("wrote %s (the scene's fogmap)\n", c->fog.fogmap);
  }
  fogmap_destroy(&copy);
  free(c);
  return status;
}

int cmd_fit(int argc, char **argv) {
  fit_options o;
  int status = parse(argc, argv, &o);
  if (status) return status < 0 ? 0 : status;
  const char *outputs[2] = {o.out, o.chart};
  for (int i = 0; i < 2; i++)
    if (outputs[i] && !folder_exists(outputs[i]))
      return cli_fail("fit", "%s: cannot write: its folder does not exist", outputs[i]);
  scene_config *cfg = malloc(sizeof *cfg);
  if (!cfg) return cli_fail("fit", "out of memory");
  if ((status = load_input(&o, cfg))) {
    free(cfg);
    return status;
  }
  o.desc.input = cfg;
  int *frames = NULL;
  if ((status = sequence_frames(&o, cfg, &frames, &o.desc.frame_count))) {
    free(cfg);
    return status;
  }
  o.desc.frames = frames;
  fit_result r;
  fit_error err;
  double t0 = app_clock_seconds();
  if (fit_run(&o.desc, &r, &err)) {
    free(cfg), free(frames);
    return cli_fail("fit", "%s: %s", o.input, err.message);
  }
  printf("fogpipe fit: %s, tolerance %g on the %s |dtau|\n", o.input, o.tolerance[0],
         o.desc.by_mean ? "mean" : "max");
  printf("domain [%.4g, %.4g] x [%.4g, %.4g] x [%.4g, %.4g]; %d rays on %d views", r.lo[0],
         r.hi[0], r.lo[1], r.hi[1], r.lo[2], r.hi[2], r.rays, 9);
  if (frames)
    printf(", %d frames (%d..%d; the worst decides)", r.frame_count, frames[0],
           frames[r.frame_count - 1]);
  printf("\n\n");
  printf("  %-24s %12s %12s %10s %s %s\n", "rung", "max|dtau|", "mean|dtau|", "GL ms",
         r.lit ? "  light err" : "", " parameters");
  for (int i = 0; i < r.count; i++) {
    const fit_rung *g = &r.rungs[i];
    char light[24] = "";
    if (r.lit) snprintf(light, sizeof light, " %10.3e", g->light_error);
    printf("%c %-24s %12.3e %12.3e %10.2f%s  %s\n", i == r.chosen ? '*' : ' ', g->name,
           g->max_error, g->mean_error, g->ms, light, g->params);
  }
  if (r.lit)
    printf("(light err: the lit in-scatter's max error, relative to the reference's brightest "
           "ray)\n");
  printf("\n");
  for (int t = 1; t < o.tolerance_count; t++) {
    int pick = fit_choose(&r, o.tolerance[t], o.desc.by_mean);
    printf("at tolerance %g: %s\n", o.tolerance[t], pick < 0 ? "none" : r.rungs[pick].name);
  }
  status = 0;
  if (r.chosen < 0) {
    printf("no rung within %g: nothing written\n", o.tolerance[0]);
  } else {
    const fit_rung *g = &r.rungs[r.chosen];
    printf("chosen: %s (%s |dtau| %.3g <= %g, %.2f GL ms)\n", g->name,
           o.desc.by_mean ? "mean" : "max", o.desc.by_mean ? g->mean_error : g->max_error,
           o.tolerance[0], g->ms);
    if (o.out && !(status = write_scene(&r, g, o.out))) printf("wrote %s\n", o.out);
  }
  if (!status && o.chart) {
    status = write_chart(&r, o.chart);
    if (!status) printf("chart %s\n", o.chart);
  }
  printf("fit: %.1f s\n", app_clock_seconds() - t0);
  fit_result_destroy(&r);
  free(cfg), free(frames);
  return status;
}
