/* fogpipe record CONFIG --frames N --out DIR [--fps F] [--size WxH] [--resume]
 *                [--preview out.mp4]
 * Headless (EGL), deterministic EXR sequence recording. Ctrl-C finishes the current frame
 * and exits with 130; --resume re-runs the simulation (without rendering) up to the last
 * complete frame and continues, giving the frames an uninterrupted run gives. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <errno.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "app/commands.h"
#include "app/config.h"
#include "app/frame_exr.h"
#include "app/pipeline.h"
#include "app/player.h"
#include "app/cli.h"
#include "app/cli_options.h"
#include "app/cmd_record.h"
#include "app/recorder.h"
#include "app/stop_signals.h"
#include "sim/sim.h"

/* SIGINT and SIGTERM set the stop flag (app/stop_signals.h: the work in hand finishes or
 * stops cleanly) until the previous handlers are back. The flag is cleared once, as
 * record_run starts: one raised while the scene loads stops it before the first frame, one
 * raised during the frames still stops the preview after them. */

/* PATH with its deepest existing folder resolved (realpath) and the rest appended, without
 * "." parts, repeated or trailing slashes: two spellings of one place compare equal
 * ("./rec", "rec/", "/abs/rec"), also where folders are still to be made ("renders/shot1"
 * with no renders/ stayed relative, and never matched its resolved parent). */
static void resolved_path(const char *path, char *out, size_t size) {
  char copy[PATH_MAX], real[PATH_MAX];
  snprintf(copy, sizeof copy, "%s", path);
  for (size_t n = strlen(copy); n > 1 && copy[n - 1] == '/'; n--) copy[n - 1] = '\0';
  /* the folders from the top down: head = copy[0, cut), the part realpath resolves */
  size_t cut = strrchr(copy, '/') ? (size_t)(strrchr(copy, '/') - copy) : 0;
  for (;;) {
    char head[PATH_MAX];
    const size_t n = cut == 0 && copy[0] == '/' ? 1 : cut;
    memcpy(head, n ? copy : ".", n ? n : 1);
    head[n ? n : 1] = '\0';
    if (realpath(head, real)) break;
    if (cut == 0) { /* not even "." or "/" resolves: as written (a one-letter top folder
                       "r" is a head of length 1 too: tried, not taken for the top) */
      snprintf(out, size, "%s", copy);
      return;
    }
    while (cut > 0 && copy[cut - 1] != '/') cut--;
    if (cut > 0) cut--; /* onto the slash before the last part */
  }
  size_t used = (size_t)snprintf(out, size, "%s", real);
  for (char *part = copy + cut; *part && used < size;) {
    while (*part == '/') part++;
    const size_t length = strcspn(part, "/");
    if (length && !(length == 1 && part[0] == '.'))
      used += (size_t)snprintf(out + used, size - used, "%s%.*s",
                               used && out[used - 1] == '/' ? "" : "/", (int)length, part);
    part += length;
  }
}

/* Refuses (true, the usage message printed) a --preview that names the --out folder itself
 * (which may not exist yet, spelt any way): the video would be renamed onto the frames'
 * folder after the whole recording; or one whose folder neither exists nor is the --out
 * folder or above it. (An existing folder is cli_output_file's refusal.) */
/* ffmpeg picks the container from the name's extension: one it cannot write would fail
 * only after the whole recording, and a still image's (.png, .exr) could be one of the
 * scene's inputs or one of the frames. */
static bool refuse_preview_not_video(const char *preview) {
  static const char *const videos[] = {".mp4", ".mkv", ".mov", ".m4v", ".avi", ".webm"};
  for (size_t i = 0; i < sizeof videos / sizeof videos[0]; i++)
    if (cli_ends_with(preview, videos[i])) return false;
  cli_usage_error("record", "--preview '%s': expected a video file name ending in .mp4, .mkv, "
                  ".mov, .m4v, .avi or .webm (ffmpeg takes the format from it)", preview);
  return true;
}

static bool refuse_preview_in_out(const char *preview, const char *out) {
  char p[2 * PATH_MAX + 2], o[2 * PATH_MAX + 2];
  resolved_path(preview, p, sizeof p);
  resolved_path(out, o, sizeof o);
  if (strcmp(p, o) != 0) {
    /* the folder must be there now, not found missing by ffmpeg after the recording */
    char folder[PATH_MAX];
    snprintf(folder, sizeof folder, "%s", preview);
    char *slash = strrchr(folder, '/');
    if (!slash) return false;
    slash[slash == folder] = '\0';
    struct stat st;
    if (stat(folder, &st) == 0 && S_ISDIR(st.st_mode)) return false;
    /* the --out folder or one above it: record makes those (mkdir -p) before the video */
    char f[2 * PATH_MAX + 2];
    resolved_path(folder, f, sizeof f);
    const size_t n = strlen(f);
    if (strncmp(o, f, n) == 0 && (o[n] == '\0' || o[n] == '/')) return false;
    cli_usage_error("record", "--preview '%s': its folder %s does not exist (nor is it the "
                    "--out folder, which record makes)", preview, folder);
    return true;
  }
  cli_usage_error("record", "--preview '%s': that is the --out folder; expected a video file "
                  "name (out.mp4)", preview);
  return true;
}

int cmd_record(int argc, char **argv) {
  record_job job = {.command = "record", .fps = 24};
  int frames[3] = {0, 0, 0}, size[2] = {0, 0};
  const cli_option options[] = {
      {.kind = CLI_RANGE, .name = "--frames", .value = "N|A-B", .target = frames, .min = 1,
       .max = 9999999, .required = true,
       .help = "frames 1..N, or only A..B (required): a range renders\n"
               "exactly those frames of the full run, bit for bit, so\n"
               "ranges can go to different machines (docs/farm.md)"},
      {.kind = CLI_TEXT, .name = "--out", .value = "DIR", .target = &job.out,
       .required = true, .help = "output folder, created if missing (required)"},
      {.kind = CLI_NUMBER, .name = "--fps", .value = "F", .target = &job.fps,
       .given = &job.fps_given,
       .min = 1.0 / PIPELINE_MAX_FRAME_SECONDS, .max = 1000,
       .help = "frames per second of simulated time (default 24)"},
      {.kind = CLI_SIZE, .name = "--size", .value = "WxH", .target = size,
       .help = "image size (default: the config's [render] size)"},
      {.kind = CLI_FLAG, .name = "--resume", .target = &job.resume,
       .help = "continue after the last complete frame in DIR (the\n"
               "simulation is re-run to that frame; same frames as an\n"
               "uninterrupted run)"},
      {.kind = CLI_TEXT, .name = "--preview", .value = "FILE", .target = &job.preview,
       .help = "also encode the finished sequence to a video with ffmpeg\n"
               "(.mp4, .mkv, .mov, .m4v, .avi or .webm; skipped with a note\n"
               "if ffmpeg is missing)"},
      {.kind = CLI_FLAG, .name = "--synchronous", .target = &job.synchronous,
       .help = "run the simulation and transform on the rendering thread\n"
               "instead of the worker thread (same frames; for comparison)"},
  };
  const cli_spec spec = {
      .command = "record",
      .usage = "CONFIG --frames N --out DIR [options]",
      .about = "Renders the scene CONFIG headless (EGL, no window) for N frames and writes an\n"
               "OpenEXR sequence DIR/frame.0001.exr ... (channels R,G,B,A half, or float in a\n"
               "frame brighter than half holds; transmittance, depth, Z, inscatter.R/G/B\n"
               "float). The same config gives bit-identical pixels\n"
               "every run. Each frame is written to a temporary file and renamed, so no partial\n"
               "frame ever exists. Ctrl-C finishes the current frame and stops (exit status\n"
               "130); --resume goes on. A fogmap scene is simulated (or its [fog] vdb sequence\n"
               "played as 2.5D fogmaps); [fog] model = volume plays the VDB frames in 3D\n"
               "(blended between frames); Perlin fog, noisy quadric volumes and RBF emitters\n"
               "move with time; the other analytic models stand still.",
      .operand = "CONFIG", .min_operands = 1, .max_operands = 1,
      CLI_OPTIONS(options)};
  int parsed = cli_parse_one(&spec, argc, argv, &job.config_path);
  if (parsed) return parsed == CLI_HELP ? 0 : parsed;
  /* N (frames 1..N) or A-B (frames A..B, for a farm's job array) */
  job.first_frame = frames[2] ? 1 : frames[0], job.frames = frames[1];
  job.width = size[0], job.height = size[1];
  if (job.preview && (cli_output_file("record", "--preview", job.preview) ||
                      refuse_preview_in_out(job.preview, job.out) ||
                      refuse_preview_not_video(job.preview)))
    return 2;
  if (job.preview && job.first_frame > 1) {
    fprintf(stderr, "fogpipe record: --preview encodes a whole sequence; it takes --frames N, "
            "not a range (encode the joined ranges afterwards)\n");
    return 2;
  }
  return record_run(&job);
}

/* The command line that continues this recording, stopped after frame `done`: --resume,
 * unless a frame still to do was recorded from another scene (this run was rendering over
 * an older recording), which --resume refuses to render over: then the frames left as a
 * range (ranges give the frames of a whole run), or with --preview, which encodes whole
 * runs only, the whole run again. */
static void resume_hint(const record_job *job, const recorder *rec, int done, char *text,
                        size_t size) {
  char config[4 * PATH_MAX + 8], out[4 * PATH_MAX + 8];
  const char *config_word = cli_shell_word(job->config_path, config, sizeof config);
  const char *out_word = cli_shell_word(job->out, out, sizeof out);
  const bool foreign_ahead = recorder_frames_foreign(rec, done + 1, job->frames);
  const int first = foreign_ahead && !job->preview ? done + 1 : job->first_frame;
  int n = first > 1
              ? snprintf(text, size, "fogpipe record %s --frames %d-%d --out %s", config_word,
                         first, job->frames, out_word)
              : snprintf(text, size, "fogpipe record %s --frames %d --out %s", config_word,
                         job->frames, out_word);
  /* in full: the frames' identity holds the rate to the last digit */
  if (job->fps_given) n += snprintf(text + n, size - (size_t)n, " --fps %.17g", job->fps);
  if (job->width > 0)
    n += snprintf(text + n, size - (size_t)n, " --size %dx%d", job->width, job->height);
  if (job->preview) {
    char preview[4 * PATH_MAX + 8];
    n += snprintf(text + n, size - (size_t)n, " --preview %s",
                  cli_shell_word(job->preview, preview, sizeof preview));
  }
  if (!foreign_ahead) snprintf(text + n, size - (size_t)n, " --resume");
}

/* The output folder first (an unwritable folder or a full disk is reported before any
 * work, whatever else is wrong), then the config, then the folder again for the config's
 * size when the job gives none. 0 or 1 (printed). */
static int open_output(const record_job *job, recorder *rec, scene_config *config, int *width,
                       int *height) {
  const char *cmd = job->command;
  fog_error rerr = {0};
  fog_error cerr = {0};
  *width = job->width, *height = job->height;
  if (recorder_open(rec,
                    &(recorder_desc){.folder = job->out, .width = *width > 0 ? *width : 1,
                                     .height = *height > 0 ? *height : 1},
                    &rerr)) {
    fprintf(stderr, "fogpipe %s: %s\n", cmd, rerr.message);
    return 1;
  }
  if (scene_config_load(job->config_path, config, &cerr)) {
    fprintf(stderr, "fogpipe %s: %s\n", cmd, cerr.message);
    return 1;
  }
  char frames[PATH_MAX + 32];
  snprintf(frames, sizeof frames, "%s/%s.####.exr", rec->folder, rec->name);
  if (cli_sequence_not_scene_input(cmd, "--out", frames, config)) return 2;
  if (*width > 0 && *height > 0) return 0;
  /* The size comes from the config: check the free space again for that size. */
  *width = config->width;
  *height = config->height;
  const out_folder made = rec->made; /* the first open made the folders */
  int failed = recorder_open(
      rec, &(recorder_desc){.folder = job->out, .width = *width, .height = *height}, &rerr);
  rec->made = made;
  if (failed) fprintf(stderr, "fogpipe %s: %s\n", cmd, rerr.message);
  return failed;
}

/* The frames' source, moved on past frame done (a simulation re-runs those frames; the
 * other sources' frames are independent). NULL on failure (printed, *status 1) or when
 * SIGINT or SIGTERM came meanwhile (said with the command that resumes, *status 130): a
 * range's catch-up may simulate thousands of frames, so it runs in parts and looks for a
 * stop between them (a farm's preemption sends SIGTERM). */
static player *start_player(const record_job *job, recorder *rec, const scene_config *config,
                            int width, int height, double fps, int first, int done,
                            int *status) {
  fog_error err = {0};
  *status = 1;
  player *src = player_create(&(player_desc){.config = config, .width = width,
                                             .height = height, .fps = fps, .play = true,
                                             .synchronous = job->synchronous},
                              &err);
  if (src && done > 0 && player_is_sequential(src)) {
    printf("%s frame %d: re-running the simulation to it\n",
           done >= first ? "resuming after" : "starting after", done);
    fflush(stdout);
  }
  enum { SKIP_PART = 8 }; /* frames simulated between looks at the stop flag */
  for (long skipped = 0; src && skipped < done; skipped += SKIP_PART) {
    const long part = done - skipped < SKIP_PART ? done - skipped : SKIP_PART;
    if (stop_signals_caught() || player_skip(src, part, &err)) {
      player_destroy(src);
      src = NULL;
    }
  }
  if (src && stop_signals_caught()) {
    player_destroy(src);
    src = NULL;
  }
  if (!src && stop_signals_caught()) {
    char hint[13 * PATH_MAX];
    resume_hint(job, rec, done, hint, sizeof hint);
    fprintf(stderr, "fogpipe %s: interrupted before frame %d: nothing new written; to "
            "finish: %s\n", job->command, done + 1, hint);
    *status = 130;
  } else if (!src) {
    fprintf(stderr, "fogpipe %s: %s\n", job->command, err.message);
  }
  return src;
}

/* After a frame failed: the frames written stay whole (as after Ctrl-C), and the command
 * that finishes the run once `when` (a full disk, a missing input). */
static void say_complete(const record_job *job, const recorder *rec, int first, int done,
                         int last, const char *when) {
  if (done < first) return;
  char hint[13 * PATH_MAX];
  resume_hint(job, rec, done, hint, sizeof hint);
  fprintf(stderr, "fogpipe %s: %d of %d frames complete in %s; to finish once %s: %s\n",
          job->command, done - first + 1, last - first + 1, rec->folder, when, hint);
}

/* Frames done+1 .. last into rec; SIGINT/SIGTERM end the frame being drawn, then stop with
 * the command that resumes. 0, 1 (printed) or 130 (interrupted). */
static int record_frames(const record_job *job, recorder *rec, player *src, int width,
                         int height, int first, int done, int last) {
  const char *cmd = job->command;
  const size_t n = (size_t)width * height;
  /* rgba 4 + transmittance 1 + depth 1 + inscatter 3, then the recorder's planes. */
  float *buffer = malloc(n * (9 + RECORDER_PLANES) * sizeof(float));
  if (!buffer) {
    fprintf(stderr, "fogpipe %s: out of memory\n", cmd);
    return 1;
  }
  float *rgba = buffer, *transmittance = buffer + 4 * n, *depth = buffer + 5 * n;
  float *inscatter = buffer + 6 * n, *scratch = buffer + 9 * n;
  const frame_pixels out = {.rgba = rgba, .transmittance = transmittance, .depth = depth,
                            .inscatter = inscatter};
  fog_error perr = {0};
  fog_error rerr = {0};
  recorder_progress progress;
  int status = 0, float_frames = 0, first_float = 0;
  if (!job->quiet) recorder_progress_begin(&progress, stdout, done - first + 1, last - first + 1);
  for (int frame = done + 1; frame <= last && !status; frame++) {
    recorder_frame pixels = {.rgba = rgba, .transmittance = transmittance, .depth = depth,
                             .inscatter = inscatter};
    bool beauty_float = false;
    camera_exr_matrices(player_camera(src), width, height, pixels.world_to_camera,
                        pixels.world_to_ndc);
    pixels.view = *player_camera(src);
    int drawn = player_frame(src, frame, &out, &perr), written = 0;
    if (!drawn) {
      /* SIGINT and SIGTERM held while the frame's file is written and renamed into place:
       * a second one (which ends the process at once) killed it mid-write and left a
       * partial .frame.N.exr.tmp.PID.N no later run of another range removes */
      stop_signals held;
      stop_signals_hold(&held);
      written = recorder_write_frame(rec, frame, &pixels, scratch, &beauty_float, &rerr);
      stop_signals_release(&held);
    }
    if (drawn) {
      if (!job->quiet) recorder_progress_end(&progress);
      fprintf(stderr, "fogpipe %s: frame %d: %s\n", cmd, frame, perr.message);
      say_complete(job, rec, first, done, last, "the frame can be made");
      status = 1;
    } else if (written) {
      if (!job->quiet) recorder_progress_end(&progress);
      fprintf(stderr, "fogpipe %s: %s\n", cmd, rerr.message);
      say_complete(job, rec, first, done, last, "the frame can be written");
      status = 1;
    } else {
      if (beauty_float && !float_frames++) first_float = frame;
      done = frame;
      if (!job->quiet) recorder_progress_update(&progress, done - first + 1);
      if (stop_signals_caught() && done < last) {
        if (!job->quiet) recorder_progress_end(&progress);
        char hint[13 * PATH_MAX];
        resume_hint(job, rec, done, hint, sizeof hint);
        fprintf(stderr,
                "fogpipe %s: interrupted: %d of %d frames complete in %s; to finish: %s\n",
                cmd, done - first + 1, last - first + 1, rec->folder, hint);
        status = 130;
      }
    }
  }
  if (!status && !job->quiet) recorder_progress_end(&progress);
  if (float_frames)
    fprintf(stderr, "fogpipe %s: %d frame%s (the first: %d) written with R G B A as 32-bit "
            "float: some pixels are brighter than half-float holds (%g)\n", cmd, float_frames,
            float_frames == 1 ? "" : "s", first_float, (double)FRAME_EXR_HALF_MAX);
  free(buffer);
  return status;
}

/* The summary line, and the preview video when asked for. 0, 1 (printed) or 130 (the
 * encode interrupted: no video, the frames kept). */
static int finish_output(const record_job *job, const recorder *rec, const scene_config *config,
                         int width, int height, double fps, int first, int last) {
  char first_path[1200], last_path[1200];
  recorder_frame_path(rec, first, first_path, sizeof first_path);
  recorder_frame_path(rec, last, last_path, sizeof last_path);
  printf("%d frame%s (%dx%d) in %s: %s .. %s\n", last - first + 1, last == first ? "" : "s",
         width, height, rec->folder, strrchr(first_path, '/') + 1, strrchr(last_path, '/') + 1);
  if (!job->preview) return 0;
  fog_error rerr = {0};
  if (!recorder_have_ffmpeg()) {
    printf("note: ffmpeg is not installed, so no preview video was written "
           "(apt-get install ffmpeg)\n");
  } else if (stop_signals_caught()) { /* during the last frame: the frames are whole, no encode */
    fprintf(stderr, "fogpipe %s: interrupted: all frames are complete in %s; no preview "
            "video written\n", job->command, rec->folder);
    return 130;
  } else {
    stop_signals stop;
    stop_signals_catch(&stop, false);
    const display_transform display = scene_config_display(config);
    const int failed = recorder_write_preview(rec, job->frames, fps, job->preview, &display,
                                              stop_signals_flag(), &rerr);
    stop_signals_restore(&stop);
    if (failed && stop_signals_caught()) {
      fprintf(stderr, "fogpipe %s: interrupted while encoding the preview: no video written "
              "(the frames in %s are kept)\n", job->command, rec->folder);
      return 130;
    }
    if (failed) {
      fprintf(stderr, "fogpipe %s: %s\n", job->command, rerr.message);
      return 1;
    }
    printf("preview: %s\n", job->preview);
  }
  return 0;
}

static int record_into(const record_job *job, recorder *rec) {
  scene_config config;
  int width, height;
  const int opened = open_output(job, rec, &config, &width, &height);
  if (opened) return opened;
  /* What every frame carries in its header, and --resume checks frame by frame. */
  const double fps = job->fps;
  snprintf(rec->identity, sizeof rec->identity, "scene %016llx size %dx%d fps %.17g",
           (unsigned long long)scene_config_fingerprint(&config), width, height, fps);
  const int first = job->first_frame > 0 ? job->first_frame : 1, last = job->frames;
  fog_error oerr = {0};
  if (!job->replace_earlier && recorder_check_other_frames(rec, first, last, &oerr))
    fprintf(stderr, "fogpipe %s: warning: %s\n", job->command, oerr.message); /* see h */
  int done = first - 1; /* the last frame on disk of the range */
  if (job->resume) {
    fog_error rerr = {0};
    done = recorder_complete_frames(rec, first, last, &rerr);
    if (done < 0) {
      fprintf(stderr, "fogpipe %s: cannot resume: %s (use the same config and settings, or "
              "another --out folder)\n", job->command, rerr.message);
      return 1;
    }
    if (done == last)
      printf("all %d frames are already complete in %s\n", last - first + 1, rec->folder);
  }
  /* What a killed run of this range left; other ranges' temporaries may be live. */
  recorder_remove_stale_temporaries(rec, first, last);
  if (done < last) {
    int started = 0;
    player *src = start_player(job, rec, &config, width, height, fps, first, done, &started);
    if (!src) return started;
    if (job->replace_earlier) {
      const int cleared = recorder_remove_frames(rec);
      if (cleared > 0)
        printf("fogpipe %s: removed %d frame%s of an earlier run from %s\n", job->command,
               cleared, cleared == 1 ? "" : "s", rec->folder);
    }
    int status = record_frames(job, rec, src, width, height, first, done, last);
    player_destroy(src);
    if (status) return status;
  }
  return finish_output(job, rec, &config, width, height, fps, first, last);
}

int record_run(const record_job *job) {
  recorder rec = {.folder = ""};
  /* SIGINT and SIGTERM from the start: caught while the scene loads and a range's
   * simulation catches up too (they used to end the process there, leaving its folders).
   * The load looks at the flag only once it is done: a second signal ends the process at
   * once (a long load need not be waited for); while a frame's file is written it waits
   * for the file (record_frames). */
  stop_signals stop;
  stop_signals_clear();
  stop_signals_catch(&stop, true);
  int status = record_into(job, &rec);
  /* stopped during the last frame (or after it): nothing is missing, but the run was
   * interrupted, as its status says (it exited 0 as if no signal had come) */
  if (status == 0 && stop_signals_caught()) {
    fprintf(stderr, "fogpipe %s: interrupted after the last frame: every frame asked for is "
            "complete in %s\n", job->command, rec.folder);
    status = 130;
  }
  stop_signals_restore(&stop);
  /* A run that failed or stopped before writing a frame leaves no folder of its own making
   * behind (only empty ones go, innermost first: written frames stay). */
  if (status == 1 || status == 2 || status == 130) out_folder_undo(&rec.made);
  return status;
}
