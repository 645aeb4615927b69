/* fogpipe bake CONFIG --frames N --out DIR [--fps F]: the simulation of a fogmap scene,
 * run once, written as the fogmap of every frame (DIR/fog.####.exr, float) and a config
 * that plays them (DIR/bake.ini, `[fog] sequence`). The simulation is sequential; the
 * bake is not: a farm job renders any range of it with `fogpipe record DIR/bake.ini
 * --frames A-B` without simulating the frames before A (docs/farm.md). Frame n of that
 * recording equals frame n of `fogpipe record CONFIG --fps F`, bit for bit.
 *
 * A bake into a folder that holds one already replaces it whole or not at all: the frames
 * are simulated into a staging folder inside DIR and moved into place only when all are
 * written, so a failed or interrupted bake (Ctrl-C, SIGTERM: exit 130) leaves the old bake
 * as it was, never old and new frames under one bake.ini. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/cli.h"
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/config.h"
#include "app/pipeline.h"
#include "app/recorder.h"
#include "app/stop_signals.h"
#include "render/gl_context.h"
#include "sim/sim.h"

typedef struct bake_job {
  const char *config_path, *out;
  int frames;
  double fps;
} bake_job;

/* 0 to go on, CLI_HELP, or the exit status of a bad command line. */
static int parse_bake_options(int argc, char **argv, bake_job *job) {
  const cli_option options[] = {
      {.kind = CLI_INT, .name = "--frames", .value = "N", .target = &job->frames, .min = 1,
       .max = VDB_SEQUENCE_MAX_SPAN, .required = true,
       .help = "frames to bake, 1 to 1048576, the most a sequence plays (required)"},
      {.kind = CLI_TEXT, .name = "--out", .value = "DIR", .target = &job->out,
       .required = true, .help = "the bake's folder (created if missing; required)"},
      {.kind = CLI_NUMBER, .name = "--fps", .value = "F", .target = &job->fps,
       .min = 1.0 / PIPELINE_MAX_FRAME_SECONDS, .max = 1000,
       .help = "frames per second of simulated time, as record's --fps (default 24)"},
  };
  const cli_spec spec = {
      .command = "bake",
      .usage = "CONFIG --frames N --out DIR [--fps F]",
      .about = "Runs the scene's fog simulation for N frames and writes each frame's fogmap\n"
               "(DIR/fog.0001.exr ...) and DIR/bake.ini, the scene playing them. Render ranges\n"
               "of it on a farm: fogpipe record DIR/bake.ini --frames A-B --out FRAMES/",
      .operand = "CONFIG", .min_operands = 1, .max_operands = 1,
      CLI_OPTIONS(options)};
  int parsed = cli_parse_one(&spec, argc, argv, &job->config_path);
  if (parsed) return parsed;
  return 0;
}

/* The frame files' pattern: at least 4 digits, more for longer bakes. */
static void frame_pattern(const bake_job *job, char *pattern, size_t size) {
  int digits = 4;
  for (long n = 10000; n <= job->frames; n *= 10) digits++;
  snprintf(pattern, size, "%s/fog.%.*s.exr", job->out, digits, "##########");
}

/* Removes frames 1..written of pattern (a failed bake leaves nothing of its own). */
static void remove_frames(const char *pattern, int written) {
  char path[SCENE_CONFIG_PATH_MAX + 32];
  for (int n = 1; n <= written; n++)
    if (scene_config_sequence_path(pattern, n, path, sizeof path)) unlink(path);
}

/* Removes every frame an earlier bake wrote into pattern's folder that is not one of this
 * bake's: a number above frames, or another count of digits than pattern's (a rebake of 5
 * frames over one of 10001 left fog.00001 .. fog.00005 beside the new fog.0001 ..
 * fog.0005). Names no bake writes (fewer than 4 digits, frame 0) are kept. */
static void remove_later_frames(const char *pattern, int frames) {
  size_t at, run;
  const char *slash = strrchr(pattern, '/');
  if (!slash || !vdb_pattern_hash_run(pattern, &at, &run)) return;
  char dir[SCENE_CONFIG_PATH_MAX];
  snprintf(dir, sizeof dir, "%.*s", (int)(slash - pattern), pattern);
  const char *prefix = slash + 1, *suffix = pattern + at + run;
  const size_t prefix_length = (size_t)(pattern + at - prefix), suffix_length = strlen(suffix);
  DIR *d = opendir(dir);
  for (struct dirent *e; d && (e = readdir(d));) {
    const char *name = e->d_name;
    const size_t n = strlen(name);
    if (n <= prefix_length + suffix_length || strncmp(name, prefix, prefix_length) ||
        strcmp(name + n - suffix_length, suffix))
      continue;
    long long number = 0;
    size_t k = prefix_length;
    for (; k < n - suffix_length && isdigit((unsigned char)name[k]) && k < prefix_length + 18;
         k++)
      number = 10 * number + (name[k] - '0');
    /* a name a bake writes (at least 4 digits, frames from 1: fog.1.exr or fog.00000.exr is
     * nobody's frame, kept) and not one of this bake's frames */
    const size_t digits = k - prefix_length;
    const bool bakes_name = digits >= 4 && number >= 1;
    if (k != n - suffix_length || !bakes_name || (number <= frames && digits == run)) continue;
    char path[SCENE_CONFIG_PATH_MAX + 300];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    unlink(path);
  }
  if (d) closedir(d);
}

/* The bake's targets (bake.ini and frames 1..frames) that exist must be files: a rename
 * onto a folder fails, and it would fail half-way through moving the bake into place. */
static int targets_are_files(const bake_job *job, const char *pattern, const char *ini) {
  struct stat st;
  if (stat(ini, &st) == 0 && !S_ISREG(st.st_mode)) /* a link to a file is replaced */
    return !cli_fail("bake", "%s is not a file: expected the bake's bake.ini or nothing there",
                     ini);
  char path[SCENE_CONFIG_PATH_MAX + 32];
  for (int n = 1; n <= job->frames; n++)
    if (scene_config_sequence_path(pattern, n, path, sizeof path) && stat(path, &st) == 0 &&
        !S_ISREG(st.st_mode))
      return !cli_fail("bake", "%s is not a file: expected frame %d of a bake or nothing "
                       "there", path, n);
  return 1;
}

/* The scene cfg with the frames (pattern, simulated on cells cell_size wide) as its fog, as
 * a config at path: 0, or 1 (printed). */
static int write_bake_ini(const scene_config *cfg, const char *pattern, double cell_size,
                          const char *path, const char *shown_path) {
  /* The same scene with the frames as its fog (density_scale, box, profile as they are). */
  scene_config baked = *cfg;
  baked.fog.fogmap[0] = baked.fog.channel[0] = '\0'; /* the frames hold one channel, Y */
  /* the frames' cells: a map simulated k times finer or coarser covers the same world */
  if (cell_size != cfg->box.cell_size) {
    baked.box.cell_size = cell_size;
    baked.box.cell_size_set = true;
  }
  snprintf(baked.fog.sequence, sizeof baked.fog.sequence, "%s", pattern);
  fog_error err = {0};
  if (!scene_config_write(&baked, path, &err)) return 0;
  /* the error names the staging folder's file: say bake.ini's own name, and why the cells
   * differ from the config's where they do */
  char message[sizeof err.message + 512] = "";
  size_t used = 0;
  for (const char *from = err.message; *from && used + 1 < sizeof message;) {
    const char *at = strstr(from, path);
    const size_t plain = at ? (size_t)(at - from) : strlen(from);
    used += (size_t)snprintf(message + used, sizeof message - used, "%.*s%s", (int)plain, from,
                             at ? shown_path : "");
    from = at ? at + strlen(path) : from + plain;
  }
  char why[160] = "";
  if (cell_size != cfg->box.cell_size && strstr(err.message, "cell_size"))
    snprintf(why, sizeof why, " (the %s map is simulated on cells %g wide, the config's %g)",
             cell_size < cfg->box.cell_size ? "small" : "large", cell_size, cfg->box.cell_size);
  return cli_fail("bake", "%s%s", message, why);
}

/* Writes bake.ini at ini (the scene playing final_pattern, on the cells of the simulated
 * grid: the config's, or the pipeline's own for a map it simulates finer or coarser), then
 * simulates frame after frame and writes each density at pattern; *written counts the
 * files. */
static int bake_frames(const bake_job *job, const scene_config *cfg, const char *pattern,
                       const char *final_pattern, const char *ini, const char *shown_ini,
                       int *written) {
  fog_error gerr = {0};
  gl_context *gl = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &gerr);
  if (!gl) return cli_fail("bake", "%s", gerr.message);
  fog_error perr = {0};
  /* The pipeline the recording runs (its sim set-up, steps per frame), drawing nothing. */
  pipeline *p = pipeline_create(&(pipeline_desc){.config = cfg, .width = 16, .height = 16,
                                                 .frame_seconds = 1.0 / job->fps,
                                                 .synchronous = true},
                                &perr);
  int status = p ? 0 : cli_fail("bake", "%s", perr.message);
  if (p) {
    /* bake.ini before the frames, naming them where they will be, on the cells the
     * pipeline simulates: a scene that cannot be written as a config (a line too long, a
     * folder whose name a config cuts short, a map simulated finer whose cells fall below
     * the least [box] cell_size) fails before the simulation, not after it */
    int cells_x, cells_z;
    double origin_x, origin_z, cell_size;
    pipeline_fog_extent(p, &cells_x, &cells_z, &origin_x, &origin_z, &cell_size);
    status = write_bake_ini(cfg, final_pattern, cell_size, ini, shown_ini);
  }
  for (int n = 1; !status && n <= job->frames; n++) {
    if (stop_signals_caught()) {
      status = 130;
      break;
    }
    if (pipeline_skip(p, 1, &perr)) {
      status = cli_fail("bake", "frame %d: %s", n, perr.message);
      break;
    }
    const fogmap *density = pipeline_sim_density(p);
    char path[SCENE_CONFIG_PATH_MAX + 32];
    scene_config_sequence_path(pattern, n, path, sizeof path);
    image_channel y = {.name = "Y", .pixels = density->density, .as_half = 0};
    fog_error serr = {0};
    if (image_write_exr(path, density->width, density->height, &y, 1, &serr)) {
      status = cli_fail("bake", "%s", serr.message);
      break;
    }
    *written = n;
  }
  pipeline_destroy(p);
  gl_context_destroy(gl);
  return status;
}

int cmd_bake(int argc, char **argv) {
  bake_job job = {.fps = 24.0};
  int parsed = parse_bake_options(argc, argv, &job);
  if (parsed) return parsed == CLI_HELP ? 0 : parsed;
  scene_config cfg;
  fog_error cerr = {0};
  if (scene_config_load(job.config_path, &cfg, &cerr)) return cli_fail("bake", "%s", cerr.message);
  if (cfg.fog.model != FOG_MODEL_FOGMAP || cfg.fog.vdb[0] || cfg.fog.sequence[0])
    return cli_fail("bake", "%s: nothing to bake: %s", job.config_path,
                    cfg.fog.sequence[0] ? "it plays a bake already"
                    : cfg.fog.vdb[0]    ? "a [fog] vdb sequence is per frame already (record "
                                          "its ranges directly)"
                                        : "its model has no simulation (record its ranges "
                                          "directly)");
  char pattern[SCENE_CONFIG_PATH_MAX], ini[SCENE_CONFIG_PATH_MAX + 16];
  frame_pattern(&job, pattern, sizeof pattern);
  snprintf(ini, sizeof ini, "%s/bake.ini", job.out);
  /* the frames, a longer bake's later frames it removes, and bake.ini: none an input */
  if (cli_sequence_not_scene_input("bake", "--out", pattern, &cfg) ||
      cli_output_not_scene_input("bake", "--out", ini, &cfg))
    return 2;
  out_folder folders;
  fog_error rerr = {0};
  if (out_folder_make(&folders, job.out, &rerr))
    return cli_fail("bake", "%s", rerr.message);
  if (!targets_are_files(&job, pattern, ini)) { /* before the simulation, not after it */
    out_folder_undo(&folders);
    return 1;
  }
  /* The frames go to DIR/.bake-staging.XXXXXX first (same file system: moved by rename). */
  char staging[SCENE_CONFIG_PATH_MAX], staged[SCENE_CONFIG_PATH_MAX + 32];
  snprintf(staging, sizeof staging, "%s/.bake-staging.XXXXXX", job.out);
  if (!mkdtemp(staging)) {
    out_folder_undo(&folders);
    return cli_fail("bake", "%s: cannot make a staging folder in it: %s", job.out,
                    strerror(errno));
  }
  snprintf(staged, sizeof staged, "%s%s", staging, pattern + strlen(job.out));
  stop_signals stop;
  stop_signals_clear();
  stop_signals_catch(&stop, false);
  int written = 0;
  /* The new bake.ini into the staging folder too (bake_frames writes it first) */
  char staged_ini[SCENE_CONFIG_PATH_MAX + 16];
  snprintf(staged_ini, sizeof staged_ini, "%s/bake.ini", staging);
  int status = bake_frames(&job, &cfg, staged, pattern, staged_ini, ini, &written);
  if (status) {
    stop_signals_restore(&stop);
    remove_frames(staged, written);
    unlink(staged_ini);
    rmdir(staging);
    out_folder_undo(&folders);
    if (status == 130)
      fprintf(stderr, "fogpipe bake: interrupted after %d of %d frames: nothing of this bake "
              "kept%s\n", written, job.frames, folders.any ? "" : " (the folder is as "
              "it was)");
    return status;
  }
  /* Into place, with SIGINT and SIGTERM held until it is done (renames: moments): the old
   * bake.ini goes first, so that until the new one is in the folder is no bake at all
   * rather than a mix of two; the new bake.ini last. */
  stop_signals_hold(&stop);
  if (unlink(ini) != 0 && errno != ENOENT) {
    status = cli_fail("bake", "%s: cannot replace it: %s; the old bake is as it was", ini,
                      strerror(errno));
    remove_frames(staged, written); /* the new one goes: nothing of it is in place */
    unlink(staged_ini);
    rmdir(staging);
  }
  int moved = 0;
  for (int n = 1; !status && n <= job.frames; n++, moved++) {
    char from[SCENE_CONFIG_PATH_MAX + 32], to[SCENE_CONFIG_PATH_MAX + 32];
    scene_config_sequence_path(staged, n, from, sizeof from);
    scene_config_sequence_path(pattern, n, to, sizeof to);
    if (rename(from, to) != 0)
      status = cli_fail("bake", "cannot move %s to %s: %s; %s holds no bake now (its frames "
                        "1-%d are the new bake's, the rest of it is in %s with its bake.ini)",
                        from, to, strerror(errno), job.out, moved, staging);
  }
  /* A longer bake made here before must not play on past this one's end: every later file
   * the pattern matches goes, past any gap in them too (the config refuses a gap) and
   * however far its number (the sequence lister refuses spans past 2^20: a stray
   * fog.2000000.exr was kept, and the new bake.ini would not load), before the new
   * bake.ini names the pattern. */
  if (!status) remove_later_frames(pattern, job.frames);
  if (!status && rename(staged_ini, ini) != 0)
    status = cli_fail("bake", "cannot move %s to %s: %s; the new bake's frames are in place",
                      staged_ini, ini, strerror(errno));
  if (!status) rmdir(staging);
  stop_signals_release(&stop); /* one held now only sets the flag */
  stop_signals_restore(&stop);
  if (status) return status;
  /* bake.ini holds no rate (file n plays at frame n), but the scene's own clock (lamps on
   * a path, flicker) runs at record's --fps: the hint names the bake's */
  char rate[64] = "";
  if (job.fps != 24.0) snprintf(rate, sizeof rate, " --fps %.17g", job.fps);
  char quoted[4 * sizeof ini + 3];
  printf("baked %d frame%s of %s: %s and %s; render a range: fogpipe record %s%s --frames A-B "
         "--out FRAMES/\n", job.frames, job.frames == 1 ? "" : "s", job.config_path, pattern, ini,
         cli_shell_word(ini, quoted, sizeof quoted), rate);
  return 0;
}
