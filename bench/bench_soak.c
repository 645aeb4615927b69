/* fogpipe bench soak: the live pipeline (app/pipeline.h) run headless for N frames, as the
 * headless `fogpipe demo` runs it (app/cmd_record.c: the CPU stages in the worker thread,
 * pipeline_frame with wait = true so every frame steps the simulation, transforms and
 * renders, then pipeline_read_frame; the still camera of the config; 1/24 s per step), but
 * without writing the frames to disk. Memory is sampled at checkpoints: the peak resident
 * set (getrusage ru_maxrss), the current one (/proc/self/statm) and the bytes malloc has
 * handed out and not had back (glibc mallinfo2, all arenas and mmapped chunks).
 *
 * Summary line: `soak: frames=N rss_1k_mb=A rss_end_mb=B growth_mb=C
 * growth_per_1k_frames_kb=D heap_growth_per_1k_frames_kb=E`, A and B the peak RSS after
 * frame 1,000 and after frame N, C = B - A, D = C per 1,000 frames after frame 1,000 (in
 * KB), E the same for the malloc heap in use; A, C, D and E are nan in a run of 1,000
 * frames or fewer. The run fails (exit 1) when D or E exceeds
 * SOAK_MAX_GROWTH_KB_PER_1K: a leak of about 64 bytes per frame.
 *
 * Why E: after start-up the allocator holds ~25 MB of freed, still-resident chunks (the
 * shader JIT's, the config's), and a leak is served from them first, so RSS shows nothing
 * until it has used them up: a 64-byte-per-frame leak (80 with malloc's header) would take
 * ~300,000 frames to reach RSS, a 1 KB one ~25,000 (measured: neither moved RSS in 2,500
 * frames; E showed +78 and +1016 KB per 1000 frames). D catches what malloc does not see
 * (driver mmaps, GL objects in llvmpipe's own pools, stacks).
 *
 * The loop allocates nothing itself: the read-back buffers are allocated before the first
 * frame, the checkpoints are computed before it, and memory is read with open/read into a
 * stack buffer (no stdio stream), printing only at checkpoints. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <malloc.h>
#include <math.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "app/config.h"
#include "app/pipeline.h"
#include "app/cli_options.h"
#include "bench/bench.h"
#include "render/gl_context.h"

/* The memory growth that fails the run: KB of peak RSS per 1,000 frames after frame
 * 1,000 (64 bytes per frame). */
#define SOAK_MAX_GROWTH_KB_PER_1K 64.0
/* The frame after which the baseline is taken: warm-up (shader JIT, first allocations,
 * the allocator's arenas) is over by then. */
#define SOAK_BASELINE_FRAME 1000L
/* Checkpoints: frames 1, 100, the baseline, every N/10 after it, and N. */
#define SOAK_MAX_CHECKPOINTS 16

static volatile sig_atomic_t interrupted = 0;
static void on_interrupt(int sig) {
  (void)sig;
  interrupted = 1;
}

typedef struct memory_sample {
  double current_mb, max_mb; /* /proc/self/statm resident; getrusage ru_maxrss */
  long max_kb;
  double heap_kb; /* malloc'd bytes in use (glibc mallinfo2, all arenas, mmapped chunks too) */
} memory_sample;

/* Without allocating: no stdio stream, the file read into a stack buffer. */
static void sample_memory(memory_sample *m) {
  struct rusage usage;
  m->max_kb = getrusage(RUSAGE_SELF, &usage) == 0 ? usage.ru_maxrss : 0;
  m->max_mb = (double)m->max_kb / 1024.0;
  struct mallinfo2 heap = mallinfo2();
  m->heap_kb = (double)(heap.uordblks + heap.hblkhd) / 1024.0;
  m->current_mb = 0.0;
  char text[128];
  int fd = open("/proc/self/statm", O_RDONLY);
  if (fd < 0) return;
  ssize_t n = read(fd, text, sizeof text - 1);
  close(fd);
  if (n <= 0) return;
  text[n] = 0;
  long size_pages = 0, resident_pages = 0;
  if (sscanf(text, "%ld %ld", &size_pages, &resident_pages) == 2)
    m->current_mb = (double)resident_pages * (double)sysconf(_SC_PAGESIZE) / (1024.0 * 1024.0);
}

/* Sorted, distinct frame numbers in 1..frames; returns how many. */
static int plan_checkpoints(long frames, long out[SOAK_MAX_CHECKPOINTS]) {
  int n = 0;
  long candidates[3] = {1, 100, SOAK_BASELINE_FRAME};
  for (int k = 0; k < 3; k++)
    if (candidates[k] < frames) out[n++] = candidates[k];
  for (int k = 1; k <= 10; k++) {
    long f = frames * k / 10;
    if (f > SOAK_BASELINE_FRAME && f < frames && f > out[n - 1]) out[n++] = f;
  }
  out[n++] = frames;
  return n;
}


int bench_soak(int argc, char **argv) {
  const char *config_path = NULL;
  bench_image_options options = {.width = 160, .height = 90, .frames = 100000};
  const bench_command command = {
      .stage = "soak", .usage = "[CONFIG] [options]", .image = &options, .without_out = true,
      .frames_help = "frames",
      .about = "Runs the live pipeline headless for N frames as the headless demo does (sim step,\n"
               "transform, upload, render and read-back every frame; no files written) and\n"
               "samples memory: peak RSS (getrusage) and current RSS (/proc/self/statm) at\n"
               "frames 1, 100, 1000, every N/10 and N, with ms per frame between checkpoints.\n"
               "Also the malloc heap in use (glibc mallinfo2), which shows a leak that freed,\n"
               "still-resident memory hides from RSS. Fails (exit 1) if the peak RSS or the heap\n"
               "grows by more than " CLI_TEXT_OF(SOAK_MAX_GROWTH_KB_PER_1K) " KB per 1000 frames "
               "after frame 1000. Last line:\n"
               "soak: frames=N rss_1k_mb=A rss_end_mb=B growth_mb=C growth_per_1k_frames_kb=D\n"
               "      heap_growth_per_1k_frames_kb=E\n\n"
               "CONFIG defaults to configs/default.ini of the source tree (a fogmap scene).",
      .footer = "SIGINT/SIGTERM end the run after the current frame with the figures so far\n"
                "(exit 130).",
      .operand = "CONFIG", .operands = &config_path, .max_operands = 1};
  int exit_status = bench_parse(&command, argc, argv);
  if (exit_status >= 0) return exit_status;
  if (!config_path) config_path = FOGPIPE_SOURCE_DIR "/configs/default.ini";
  const long frames = options.frames;
  const int width = options.width, height = options.height;

  scene_config cfg;
  gl_context *gl;
  if (bench_open_scene("soak", config_path, &cfg, &gl)) return 1;
  fog_error perr = {0};
  /* As record_run builds it for the headless demo: worker thread, 1/24 s per frame, the
   * pipeline's default parameters (full-resolution fog). */
  pipeline *pipe = pipeline_create(&(pipeline_desc){.config = &cfg, .width = width,
                                                    .height = height,
                                                    .frame_seconds = 1.0 / 24.0},
                                   &perr);
  const size_t n = (size_t)width * height;
  float *buffer = pipe ? malloc(n * 6 * sizeof(float)) : NULL;
  if (!pipe || !buffer) {
    fprintf(stderr, "fogpipe bench soak: %s\n", pipe ? "out of memory" : perr.message);
    free(buffer);
    pipeline_destroy(pipe);
    gl_context_destroy(gl);
    return 1;
  }
  float *rgba = buffer, *transmittance = buffer + 4 * n, *depth = buffer + 5 * n;
  camera cam;
  scene_config_camera(&cfg, &cam);
  long checkpoints[SOAK_MAX_CHECKPOINTS];
  const int checkpoint_count = plan_checkpoints(frames, checkpoints);

  bench_print_build();
  const char *lp = getenv("LP_NUM_THREADS");
  printf("gl: %s, %s (LP_NUM_THREADS=%s)\n", gl_context_version(gl), gl_context_renderer(gl),
         lp ? lp : "unset");
  printf("scene: %s at %dx%d, %ld frames\n", config_path, width, height, frames);
  printf("per frame: sim + transform (worker thread), upload, render, read-back; camera "
         "still\n");
  printf("threshold: peak RSS and malloc heap growth after frame %ld <= %.0f KB per 1000 "
         "frames each\n\n",
         SOAK_BASELINE_FRAME, SOAK_MAX_GROWTH_KB_PER_1K);
  printf("%10s %12s %12s %10s %10s\n", "frame", "rss_mb", "max_rss_mb", "heap_mb", "ms/frame");
  fflush(stdout);

  struct sigaction action = {.sa_handler = on_interrupt}, old_int, old_term;
  sigemptyset(&action.sa_mask);
  interrupted = 0;
  sigaction(SIGINT, &action, &old_int);
  sigaction(SIGTERM, &action, &old_term);

  memory_sample base = {0}, last = {0};
  long base_frame = 0, done = 0;
  int next = 0, status = 0;
  double interval_start = app_clock_seconds(), run_start = interval_start;
  long interval_first = 1;
  for (long frame = 1; frame <= frames; frame++) {
    if (pipeline_frame(pipe, &cam, true, &perr) ||
        pipeline_read_frame(
            pipe, &(frame_pixels){.rgba = rgba, .transmittance = transmittance, .depth = depth},
            &perr)) {
      fprintf(stderr, "fogpipe bench soak: frame %ld: %s\n", frame, perr.message);
      status = 1;
      break;
    }
    done = frame;
    bool stop = interrupted != 0;
    bool checkpoint = next < checkpoint_count && frame == checkpoints[next];
    if (checkpoint || stop) {
      double now = app_clock_seconds();
      sample_memory(&last);
      printf("%10ld %12.2f %12.2f %10.3f %10.3f%s\n", frame, last.current_mb, last.max_mb,
             last.heap_kb / 1024.0,
             1000.0 * (now - interval_start) / (double)(frame - interval_first + 1),
             stop ? "  (interrupted)" : "");
      fflush(stdout);
      if (frame <= SOAK_BASELINE_FRAME) base = last, base_frame = frame;
      if (checkpoint) next++;
      interval_start = now, interval_first = frame + 1;
    }
    if (stop) {
      status = 130;
      break;
    }
  }
  double run_seconds = app_clock_seconds() - run_start;
  sigaction(SIGINT, &old_int, NULL);
  sigaction(SIGTERM, &old_term, NULL);

  if (status != 1 && done > 0) {
    double growth_mb = (double)(last.max_kb - base.max_kb) / 1024.0;
    double growth_per_1k = 0.0, heap_per_1k = 0.0;
    bool measured = done > base_frame && base_frame == SOAK_BASELINE_FRAME;
    if (measured) {
      growth_per_1k = (double)(last.max_kb - base.max_kb) * 1000.0 / (double)(done - base_frame);
      heap_per_1k = (last.heap_kb - base.heap_kb) * 1000.0 / (double)(done - base_frame);
    }
    printf("\n%ld frames in %.1f s (%.3f ms/frame overall); from frame %ld to %ld: current "
           "RSS %+.2f MB, malloc heap in use %+.1f KB\n",
           done, run_seconds, 1000.0 * run_seconds / (double)done, base_frame, done,
           last.current_mb - base.current_mb, last.heap_kb - base.heap_kb);
    bool failed = measured && (growth_per_1k > SOAK_MAX_GROWTH_KB_PER_1K ||
                               heap_per_1k > SOAK_MAX_GROWTH_KB_PER_1K);
    if (!measured)
      printf("note: no growth figures: they need more than %ld frames\n", SOAK_BASELINE_FRAME);
    else
      printf("%s: per 1000 frames after frame %ld, peak RSS %+.1f KB, malloc heap in use "
             "%+.1f KB (threshold %.0f KB each)\n",
             failed ? "FAIL" : "ok", SOAK_BASELINE_FRAME, growth_per_1k, heap_per_1k,
             SOAK_MAX_GROWTH_KB_PER_1K);
    /* figures of frame 1,000 on are nan before it: 0.0 would read as "no growth" */
    const double unmeasured = NAN;
    printf("soak: frames=%ld rss_1k_mb=%.2f rss_end_mb=%.2f growth_mb=%.2f "
           "growth_per_1k_frames_kb=%.1f heap_growth_per_1k_frames_kb=%.1f\n",
           done, measured ? base.max_mb : unmeasured, last.max_mb,
           measured ? growth_mb : unmeasured, measured ? growth_per_1k : unmeasured,
           measured ? heap_per_1k : unmeasured);
    if (!status && failed) status = 1;
  }
  free(buffer);
  pipeline_destroy(pipe);
  gl_context_destroy(gl);
  return status;
}
