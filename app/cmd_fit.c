/* fogpipe fit INPUT --tolerance T [--out scene.ini] [--chart fit.png]: the cheapest model
 * of the ladder that holds the input's fog within T (app/fit.h, docs/fit.md). */
#define _XOPEN_SOURCE 700 /* realpath */
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/chart.h"
#include "app/cli.h"
#include "app/cli_options.h"
#include "app/clock.h"
#include "app/commands.h"
#include "app/config.h"
#include "app/fit.h"
#include "app/stop_signals.h"
#include "app/render_fog.h"
#include "sim/sim.h"

typedef struct fit_options {
  const char *input, *out, *chart, *grid;
  const char *frames; /* --frames all|A|A-B[:S], read into the three below */
  long frames_first, frames_last, frames_step;
  double tolerance[8]; /* --tolerance T[,T...]: the first picks --out */
  int tolerance_count;
  double density_scale;
  int up, frame;
  bool vdb_option_given; /* --grid, --up, --frame or --density-scale (even at its default) */
  fit_desc desc;
} fit_options;

/* --frames all|A|A-B, each with an optional :S (every S-th frame), read before any work
 * (`all:2` was refused as "all", and a config input without a sequence said so before
 * the syntax). */
static int parse_frames(fit_options *o) {
  o->frames_first = 0, o->frames_last = INT_MAX, o->frames_step = 1;
  if (!o->frames) return 0;
  char text[64];
  bool ok = strlen(o->frames) < sizeof text;
  if (ok) {
    snprintf(text, sizeof text, "%s", o->frames);
    char *colon = strchr(text, ':');
    if (colon) {
      *colon = '\0';
      ok = cli_parse_long(colon + 1, 1, INT_MAX, &o->frames_step);
    }
    if (ok && strcmp(text, "all")) {
      char *dash = strchr(text, '-');
      if (dash) *dash = '\0';
      ok = dash != text && cli_parse_long(text, 0, INT_MAX, &o->frames_first);
      o->frames_last = o->frames_first;
      if (ok && dash) ok = cli_parse_long(dash + 1, o->frames_first, INT_MAX, &o->frames_last);
    }
  }
  if (!ok)
    return cli_usage_error("fit", "--frames '%s': expected all, A or A-B (whole numbers, 0 <= "
                           "A <= B <= %d), each optionally followed by :S for every S-th "
                           "frame (S >= 1)", o->frames, INT_MAX);
  return 0;
}

/* --tolerance T[,T...]: up to 8 values in (0, 1]. */
static int parse_tolerances(const char *command, const char *option, const char *text,
                            void *target) {
  fit_options *o = target;
  const size_t n = strlen(text);
  if (!n || text[0] == ',' || text[n - 1] == ',' || strstr(text, ",,")) /* strtok skips them */
    return cli_usage_error(command, "%s '%s': expected numbers separated by single commas",
                           option, text);
  char list[256], *save = NULL;
  if (n >= sizeof list) /* cut, a value changed without a word (0.25 read as 0.2) */
    return cli_usage_error(command, "%s: %zu characters; expected at most %zu", option, n,
                           sizeof list - 1);
  snprintf(list, sizeof list, "%s", text);
  o->tolerance_count = 0;
  for (char *t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
    if (o->tolerance_count == 8) return cli_usage_error(command, "%s: at most 8 values", option);
    if (cli_number(command, option, t, 1e-12, 1.0, &o->tolerance[o->tolerance_count++]))
      return 2;
  }
  return 0;
}

static int parse(int argc, char **argv, fit_options *o) {
  *o = (fit_options){.density_scale = 1.0, .frame = -1,
                     .desc = {.rays_per_side = FIT_RAYS_PER_SIDE, .sample_side = FIT_SAMPLE_SIDE,
                              .width = FIT_WIDTH, .height = FIT_HEIGHT,
                              .timed_frames = FIT_TIMED_FRAMES}};
  static const char *const by[] = {"max", "mean", NULL}, *const up[] = {"z", "y", NULL};
  int by_mean = 0, size[2] = {FIT_WIDTH, FIT_HEIGHT};
  const cli_option options[] = {
      {.kind = CLI_CUSTOM, .name = "--tolerance", .value = "T[,T..]", .target = o,
       .parse = parse_tolerances, .required = true,
       .help = "the |delta tau| allowed (required, 1e-12 to 1): on every ray,\n"
               "or on average with --by mean; more values print the pick\n"
               "at each (the first one's is written)"},
      {.kind = CLI_CHOICE, .name = "--by", .value = "max|mean", .target = &by_mean, .choices = by,
       .help = "the tolerance bounds each rung's max error (default) or\n"
               "its mean error over the rays"},
      {.kind = CLI_OUTPUT, .name = "--out", .value = "FILE.ini", .target = &o->out,
       .extensions = (const char *const[]){".ini", NULL},
       .help = "write the scene with the chosen model (nothing is written\n"
               "when none is within T); a fogmap projected from an\n"
               "analytic fog goes beside it as FILE.fogmap.exr"},
      {.kind = CLI_OUTPUT, .name = "--chart", .value = "FILE.png", .target = &o->chart,
       .extensions = (const char *const[]){".png", NULL},
       .help = "error against ms, one series per family (and FILE.csv)"},
      {.kind = CLI_SECTION, .name = "VDB input:"},
      {.kind = CLI_TEXT, .name = "--grid", .value = "NAME", .target = &o->grid,
       .given = &o->vdb_option_given, .help = "float grid (default density)"},
      {.kind = CLI_CHOICE, .name = "--up", .value = "z|y", .target = &o->up, .choices = up,
       .given = &o->vdb_option_given,
       .help = "the file's up axis (default z: Blender/Mantaflow)"},
      {.kind = CLI_INT, .name = "--frame", .value = "N", .target = &o->frame, .min = 0,
       .max = INT_MAX, .given = &o->vdb_option_given,
       .help = "frame number of a sequence (default: the last)"},
      {.kind = CLI_NUMBER, .name = "--density-scale", .value = "S", .target = &o->density_scale,
       .min = 1e-12, .max = 1e12, .given = &o->vdb_option_given,
       .help = "extinction per unit of the grid's value (default 1)"},
      {.kind = CLI_SECTION, .name = "sequences (a VDB INPUT, or a config's [fog] vdb):"},
      {.kind = CLI_TEXT, .name = "--frames", .value = "all|A|A-B[:S]", .target = &o->frames,
       .help = "fit over these frame numbers (every S-th), the worst frame\n"
               "deciding: the static rungs fit the frames' mean density,\n"
               "the fogmap and the volume play the frames (default: one\n"
               "frame, --frame or the config's vdb_frame)"},
      {.kind = CLI_SECTION, .name = "measurement:"},
      {.kind = CLI_INT, .name = "--rays", .value = "N", .target = &o->desc.rays_per_side,
       .min = 1, .max = 1024,
       .help = "rays per side of each view (default " CLI_TEXT_OF(FIT_RAYS_PER_SIDE) ")"},
      {.kind = CLI_INT, .name = "--samples", .value = "N", .target = &o->desc.sample_side,
       .min = 2, .max = 512,
       .help = "density samples along the longest side (default " CLI_TEXT_OF(FIT_SAMPLE_SIDE) ")"},
      {.kind = CLI_SIZE, .name = "--size", .value = "WxH", .target = size,
       .help = "timed frames (default " CLI_TEXT_OF(FIT_WIDTH) "x" CLI_TEXT_OF(FIT_HEIGHT) ")"},
      {.kind = CLI_INT, .name = "--timed", .value = "N", .target = &o->desc.timed_frames,
       .min = 1, .max = 64,
       .help = "timed frames per rung (default " CLI_TEXT_OF(FIT_TIMED_FRAMES) ")"},
  };
  const cli_spec spec = {
      .command = "fit",
      .usage = "INPUT --tolerance T [options]",
      .about = "Fits every model of the ladder that can represent the input's fog (homogeneous,\n"
               "the classic linear and exp2 factors fitted on the views,\n"
               "height, an ellipsoid and banks of 2 to 16, banks of 1 to 16 cylinders and of\n"
               "1 to 16 oriented ellipsoids, banks of 1 to 64 Gaussians, the\n"
               "fogmap at three bases x three LOD factors (an analytic fog's density projected),\n"
               "the 3D volume, the input as given), measures each on nine views around and inside\n"
               "the fog (max and mean |delta tau| against the input's own fog, exact integrals in\n"
               "double) and times it on the GL (headless), prints the table and picks the fastest\n"
               "within the tolerance (docs/fit.md).\n\n"
               "INPUT: a scene config (.ini), or a VDB file or sequence (a #### pattern, a folder)\n"
               "whose frame is fitted as a 3D volume.",
      .operand = "INPUT", .min_operands = 1, .max_operands = 1,
      CLI_OPTIONS(options)};
  int parsed = cli_parse_one(&spec, argc, argv, &o->input);
  if (parsed) return parsed;
  if (parse_frames(o)) return 2;
  if (o->frames && o->frame >= 0) /* --frame defaults to -1 (the last); it was ignored */
    return cli_usage_error("fit", "--frame fits one frame and --frames a range: give one of "
                           "them");
  o->desc.by_mean = by_mean;
  o->desc.width = size[0], o->desc.height = size[1];
  o->desc.tolerance = o->tolerance[0];
  return 0;
}

/* The scene of the input: its config, or a VDB frame as a volume in a scene around it. */
static int load_input(const fit_options *o, scene_config *cfg) {
  if (cli_ends_with(o->input, ".ini")) {
    fog_error err;
    if (scene_config_load(o->input, cfg, &err)) return cli_fail("fit", "%s", err.message);
    if (o->vdb_option_given)
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
  return 0; /* its scene once the frames are known (place_input_scene) */
}

/* A VDB input's scene around the frames to fit that hold fog. */
static int place_input_scene(const fit_options *o, scene_config *cfg, const int *frames,
                             int frame_count) {
  if (cli_ends_with(o->input, ".ini")) return 0;
  fog_error err;
  if (fit_scene_for_volume(cfg, frames, frame_count, &err))
    return cli_fail("fit", "%s", err.message);
  return 0;
}

/* The frame numbers of --frames in the input's sequence (malloc'd into *out). */
static int sequence_frames(const fit_options *o, const scene_config *cfg, int **out, int *count) {
  *out = NULL, *count = 0;
  if (!o->frames) return 0;
  if (!cfg->fog.vdb[0])
    return cli_usage_error("fit", "--frames: the input has no VDB sequence ([fog] vdb)");
  vdb_sequence seq;
  fog_error rerr = {0};
  if (render_fog_volume_sequence(cfg, &seq, &rerr)) return cli_fail("fit", "%s", rerr.message);
  int *list = malloc(sizeof *list * (size_t)seq.count);
  int n = 0, seen = 0;
  for (int i = 0; list && i < seq.count; i++)
    if (seq.frames[i] >= o->frames_first && seq.frames[i] <= o->frames_last &&
        seen++ % o->frames_step == 0)
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

/* Each rung's error (the one --by chose by) against its time. */
static int write_chart(const fit_result *r, bool by_mean, const char *png) {
  chart_point points[FIT_MAX_RUNGS];
  int count = 0;
  for (int i = 0; i < r->count; i++) {
    const double error = by_mean ? r->rungs[i].mean_error : r->rungs[i].max_error;
    /* a rung that measured nothing (fmax would draw it exact), or was not timed */
    if (isnan(error) || isnan(r->rungs[i].ms)) continue;
    points[count++] = (chart_point){.series = r->rungs[i].family, .x = r->rungs[i].ms,
                                    .y = fmax(error, 1e-4)};
  }
  char csv[PATH_MAX], error[512];
  snprintf(csv, sizeof csv, "%.*s.csv", (int)(strlen(png) - 4), png);
  chart_desc desc = {.title = "fogpipe fit: each rung's error against its GL time",
                     .x_label = "GL ms per frame",
                     .y_label = by_mean ? "mean |delta tau| (an exact rung at 1e-4)"
                                        : "max |delta tau| (an exact rung at 1e-4)",
                     .log_y = true};
  const int charted = chart_write(&desc, points, count, csv, png, error, sizeof error);
  if (charted) {
    /* written before gnuplot ran: a failed run leaves none of its outputs */
    if (charted == CHART_CSV_WRITTEN) remove(csv);
    return cli_fail("fit", "%s", error);
  }
  return 0;
}

/* Why FILE cannot be written into its folder, or NULL: checked before the fit, which takes
 * seconds to minutes, not found out at its end. */
static const char *folder_problem(const char *file) {
  char folder[PATH_MAX];
  snprintf(folder, sizeof folder, "%s", file);
  char *slash = strrchr(folder, '/');
  if (!slash) snprintf(folder, sizeof folder, ".");
  else *(slash == folder ? slash + 1 : slash) = '\0';
  struct stat st;
  if (stat(folder, &st) != 0 || !S_ISDIR(st.st_mode)) return "its folder does not exist";
  if (access(folder, W_OK | X_OK) != 0) return "its folder is not writable";
  if (stat(file, &st) == 0 && S_ISDIR(st.st_mode)) return "a folder of that name is in the way";
  return NULL;
}

/* The chosen rung's scene to `out`; a fogmap projected into the fit's scratch folder goes
 * beside it first, as OUT.fogmap.exr (without .ini), and the scene names that copy. On
 * failure neither file is left. */
/* The chosen rung's config at out. fitted_frame >= 0: the last frame the fit measured (and
 * timed), written as its vdb_frame: the rung's own was the input's, -1 (the sequence's
 * last), and `render` drew a frame the fit never looked at. */
static int write_scene(const fit_result *r, const fit_rung *g, const char *out,
                       int fitted_frame) {
  const char *map = g->config->fog.fogmap;
  const size_t n = strlen(r->scratch);
  const bool projected = n && g->config->fog.model == FOG_MODEL_FOGMAP &&
                         !strncmp(map, r->scratch, n);
  scene_config *c = malloc(sizeof *c);
  if (!c) return cli_fail("fit", "out of memory");
  *c = *g->config;
  if (fitted_frame >= 0 && c->fog.vdb[0]) c->fog.vdb_frame = fitted_frame;
  fog_error werr;
  if (!projected) {
    const int status = scene_config_write(c, out, &werr) ? cli_fail("fit", "%s", werr.message)
                                                         : 0;
    free(c);
    return status;
  }
  snprintf(c->fog.fogmap, sizeof c->fog.fogmap, "%.*s.fogmap.exr",
           (int)(strlen(out) - strlen(".ini")), out);
  fogmap copy = {0};
  fog_error serr = {0};
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

/* An output (the scene, the fogmap beside it, the chart and its CSV) that is one of the
 * fit's inputs (the INPUT, the files its scene reads): refused (2) before the fit
 * instead of replacing it at its end. */
static int refuse_output_input(const fit_options *o, const scene_config *cfg) {
  char beside[PATH_MAX] = "", csv[PATH_MAX] = "";
  if (o->out)
    snprintf(beside, sizeof beside, "%.*s.fogmap.exr", (int)(strlen(o->out) - 4), o->out);
  if (o->chart) snprintf(csv, sizeof csv, "%.*s.csv", (int)(strlen(o->chart) - 4), o->chart);
  const struct {
    const char *option, *path;
  } outputs[] = {{"--out", o->out}, {"--out", beside}, {"--chart", o->chart}, {"--chart", csv}};
  /* INPUT first (it is also the scene's config: the message names what was given), then
   * what the scene reads, as render, record and view guard theirs */
  for (size_t i = 0; i < sizeof outputs / sizeof *outputs; i++) {
    if (!outputs[i].path || !outputs[i].path[0]) continue;
    if (cli_output_not_input("fit", outputs[i].option, outputs[i].path, o->input, "the INPUT") ||
        cli_output_not_scene_input("fit", outputs[i].option, outputs[i].path, cfg))
      return 2;
  }
  return 0;
}

int cmd_fit(int argc, char **argv) {
  fit_options o;
  int status = parse(argc, argv, &o);
  if (status) return status < 0 ? 0 : status;
  /* every file the run writes, checked before the fit (--chart's CSV beside its PNG, and
   * the fogmap a projected rung writes beside --out: a folder in its way was found after
   * the whole fit) */
  char chart_csv[PATH_MAX] = "", out_map[PATH_MAX] = "";
  if (o.chart)
    snprintf(chart_csv, sizeof chart_csv, "%.*s.csv", (int)(strlen(o.chart) - 4), o.chart);
  if (o.out)
    snprintf(out_map, sizeof out_map, "%.*s.fogmap.exr", (int)(strlen(o.out) - 4), o.out);
  const char *outputs[4] = {o.out, o.out ? out_map : NULL, o.chart, o.chart ? chart_csv : NULL};
  for (int i = 0; i < 4; i++) {
    const char *problem = outputs[i] ? folder_problem(outputs[i]) : NULL;
    if (problem) return cli_fail("fit", "%s: cannot write: %s", outputs[i], problem);
  }
  char chart_error[256];
  if (o.chart && !chart_can_draw(chart_error, sizeof chart_error)) /* before the fit */
    return cli_fail("fit", "--chart: %s", chart_error);
  scene_config *cfg = malloc(sizeof *cfg);
  if (!cfg) return cli_fail("fit", "out of memory");
  if ((status = load_input(&o, cfg)) || (status = refuse_output_input(&o, cfg))) {
    free(cfg);
    return status;
  }
  o.desc.input = cfg;
  int *frames = NULL;
  if ((status = sequence_frames(&o, cfg, &frames, &o.desc.frame_count)) ||
      (status = place_input_scene(&o, cfg, frames, o.desc.frame_count))) {
    free(frames);
    free(cfg);
    return status;
  }
  o.desc.frames = frames;
  fit_result r;
  fog_error err;
  double t0 = app_clock_seconds();
  /* Ctrl-C or SIGTERM: the fit stops after the rung it is measuring and removes its
   * scratch folder (a projected fogmap), then exits 130 */
  /* a second signal ends the process at once; an ignored one stays so */
  stop_signals stop;
  stop_signals_clear();
  stop_signals_catch(&stop, true);
  o.desc.stop = stop_signals_flag();
  status = fit_run(&o.desc, &r, &err);
  if (stop_signals_caught()) { /* during the last rung too: its result is not what was asked for */
    stop_signals_restore(&stop);
    if (!status) fit_result_destroy(&r);
    free(cfg), free(frames);
    fprintf(stderr, "fogpipe fit: interrupted%s%s%s: nothing written\n", status ? " (" : "",
            status ? err.message : "", status ? ")" : "");
    return 130;
  }
  if (status) {
    stop_signals_restore(&stop);
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
    /* three digits: the tie rule (FIT_TIE) can be checked on the printed times */
    char ms[16] = "refused"; /* not drawn by this renderer (the parameters say why) */
    if (!isnan(g->ms)) snprintf(ms, sizeof ms, "%.3g", g->ms);
    printf("%c %-24s %12.3e %12.3e %10s%s  %s\n", i == r.chosen ? '*' : ' ', g->name,
           g->max_error, g->mean_error, ms, light, g->params);
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
    bool refused_within = false; /* within T but not drawn here with the scene's lamps */
    for (int i = 0; i < r.count; i++)
      refused_within |= isnan(r.rungs[i].ms) &&
                        fit_within(&r.rungs[i], o.tolerance[0], o.desc.by_mean);
    printf("no rung within %g%s: nothing written\n", o.tolerance[0],
           refused_within ? " that this renderer draws with the scene's lamps" : "");
  } else {
    const fit_rung *g = &r.rungs[r.chosen];
    printf("chosen: %s (%s |dtau| %.3g <= %g, %.3g GL ms)\n", g->name,
           o.desc.by_mean ? "mean" : "max", o.desc.by_mean ? g->mean_error : g->max_error,
           o.tolerance[0], g->ms);
  }
  /* SIGINT and SIGTERM held while the outputs are written (gnuplot, the scene, its fogmap):
   * the default action ended the process there and left the chart's CSV, gnuplot's
   * temporaries and the scratch folder behind. The outputs finish, then a held signal acts
   * (a second one ends the process; one alone only sets the flag: the fit is done). */
  stop_signals_hold(&stop);
  /* the chart first: a chart that cannot be written leaves --out as it was */
  if (o.chart) {
    status = write_chart(&r, o.desc.by_mean, o.chart);
    if (!status) printf("chart %s\n", o.chart);
  }
  if (!status && r.chosen >= 0 && o.out) {
    const int fitted_frame = frames ? frames[r.frame_count - 1] : -1;
    if (!(status = write_scene(&r, &r.rungs[r.chosen], o.out, fitted_frame))) {
      printf("wrote %s\n", o.out);
    } else if (o.chart) { /* a failed run leaves none of its outputs */
      remove(o.chart);
      remove(chart_csv);
      printf("chart %s removed: the scene was not written\n", o.chart);
    }
  }
  printf("fit: %.1f s\n", app_clock_seconds() - t0);
  fit_result_destroy(&r); /* removes the scratch folder */
  stop_signals_release(&stop);
  stop_signals_restore(&stop);
  free(cfg), free(frames);
  if (!status && stop_signals_caught()) { /* the outputs are whole; the run was stopped */
    fprintf(stderr, "fogpipe fit: interrupted after the fit: its outputs are complete\n");
    return 130;
  }
  return status;
}
