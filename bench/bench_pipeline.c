/* fogpipe bench pipeline: per-stage milliseconds and frames per second of the default
 * scene rendered headless (EGL) through the whole per-frame pipeline (app/pipeline.h):
 * sim step, transform, upload, render. Measured side by side in one run: the CPU stages
 * in the worker thread (double-buffered, what the demo and `record` run) and on the GL
 * thread (synchronous), alternating in blocks of frames so machine noise hits both alike;
 * the table shows what the overlap buys.
 *
 * Summary line: `pipeline: fps=C cpu_stage_share=D fps_moving_camera=E moving_over_still=R`,
 * C from the
 * threaded pipeline's median frame time at the live setting with the camera still (the
 * pipeline then reuses the scene pass: only the fog changes), D = (sim + transform CPU
 * time + upload, medians, + the sun volume's CPU time, its mean per frame: the worker
 * computes it every LIVE_SHADOW_INTERVAL steps) / frame (the worker's wall-clock times
 * also count its waits for a core while llvmpipe's two render threads run, printed
 * beside; so is D without the volume, as it was until the fifteenth session) at the scene's fogmap
 * (256² in configs/default.ini), E the same as C with the camera turning every frame
 * (scene pass every frame, the terrain at the demo's LOD), R = fps turning / fps still
 * at the live setting, the two threaded pipelines measured in alternating blocks of one
 * fifth run (the camera swinging ±5° about the still pose). A fourth run turns with the
 * full terrain mesh (LOD off) for the side-by-side before/after.
 * Targets: C >= 30 on llvmpipe with 2 cores, D <= 0.15, R >= 0.85. */
#define _POSIX_C_SOURCE 200809L
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "app/pipeline.h"
#include "app/cli_options.h"
#include "bench/bench.h"
#include "render/gl_context.h"

typedef struct run_result {
  pipeline_timings median;
  double sun_shadow_cpu_mean; /* per frame: the volume's CPU time, spread over its steps */
  int frames;
  int grid_w, grid_h;
} run_result;

/* Per-frame samples of one mode. */
typedef struct samples {
  double *stage[PIPELINE_TIMING_FIELDS]; /* pipeline_timings_to_array's order */
  int n;
} samples;

/* moving: the camera turns by MOVING_YAW_STEP every frame (the scene pass re-runs each
 * frame, as while the user looks around), swinging to and fro within 30 steps (±5°) of the
 * still pose, so that the view, and the fog in it, stays the still camera's; otherwise it
 * stands still and the pipeline reuses the scene pass (app/pipeline.c), as while the user
 * watches the fog. */
#define MOVING_YAW_STEP 0.003 /* radians per frame */

static int record_frame(pipeline *p, const camera *still, bool moving, samples *s, fog_error *err) {
  camera cam = *still;
  const int k = (s->n + 1) % 120; /* 0 .. 30 .. 0 .. -30 .. 0: one step every frame */
  if (moving) cam.yaw += MOVING_YAW_STEP * (k < 30 ? k : k < 90 ? 60 - k : k - 120);
  if (pipeline_frame(p, &cam, true, err)) return 1;
  pipeline_timings last;
  pipeline_get_timings(p, &last);
  double v[PIPELINE_TIMING_FIELDS];
  pipeline_timings_to_array(&last, v);
  for (int k = 0; k < PIPELINE_TIMING_FIELDS; k++) s->stage[k][s->n] = v[k];
  s->n++;
  return 0;
}

static pipeline_timings medians(samples *s) {
  double medians[PIPELINE_TIMING_FIELDS];
  for (int k = 0; k < PIPELINE_TIMING_FIELDS; k++) medians[k] = app_median(s->stage[k], s->n);
  return pipeline_timings_from_array(medians);
}

/* Two pipelines side by side in the same GL context (slot m synchronous or with the
 * worker thread, its camera moving or still), measured in alternating blocks of frames so
 * that a busy machine slows both alike: threaded against synchronous with one camera, or
 * two threaded ones still against turning (moving_over_still from one run: measured in
 * two runs 20 s apart, it came out 1.003 and 1.080 where turning costs a scene pass). A
 * threaded pipeline is paused while the other block runs (its worker filled both slots
 * there, taking cores from the other's frames, and handed its next block two steps
 * ready), and its first WARM frames after each pause are not recorded: the worker is
 * back in its stride. */
static int measure(const scene_config *cfg, int width, int height, int fog_divisor,
                   const bool synchronous_slot[2], const bool moving[2], int warmup, int frames,
                   double max_seconds, run_result out[2]) {
  enum { block = 8, warm = 2 };
  fog_error err = {0};
  pipeline *p[2] = {NULL, NULL};
  double *storage = malloc(sizeof(double) * 2 * PIPELINE_TIMING_FIELDS * (size_t)frames);
  samples s[2] = {{.n = 0}, {.n = 0}};
  int status = 1;
  if (!storage) {
    fog_fail(&err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    goto done;
  }
  for (int m = 0; m < 2; m++) {
    for (int k = 0; k < PIPELINE_TIMING_FIELDS; k++)
      s[m].stage[k] = storage + (size_t)(PIPELINE_TIMING_FIELDS * m + k) * frames;
    p[m] = pipeline_create(&(pipeline_desc){.config = cfg, .width = width, .height = height,
                                            .frame_seconds = 1.0 / 24.0,
                                            .synchronous = synchronous_slot[m],
                                            .time_passes = true,
                                            .live = true},
                           &err);
    if (!p[m]) goto done;
    pipeline_params params = pipeline_get_params(p[m]);
    params.fog_resolution_divisor = fog_divisor;
    pipeline_set_params(p[m], &params);
  }
  camera cam;
  scene_config_camera(cfg, &cam);
  double cx, cz, cell;
  pipeline_fog_extent(p[0], &out[0].grid_w, &out[0].grid_h, &cx, &cz, &cell);
  out[1].grid_w = out[0].grid_w, out[1].grid_h = out[0].grid_h;
  /* Warm-up: shader compilation (JIT on llvmpipe) and first allocations. */
  for (int m = 0; m < 2; m++)
    for (int i = 0; i < warmup; i++)
      if (pipeline_frame(p[m], &cam, true, &err)) goto done;
  double start = app_clock_seconds();
  while (s[1].n < frames && (s[1].n < 5 || app_clock_seconds() - start < 2.0 * max_seconds)) {
    for (int m = 0; m < 2; m++) {
      if (!synchronous_slot[m]) { /* the worker on again, and back in its stride */
        pipeline_params params = pipeline_get_params(p[m]);
        params.paused = false;
        pipeline_set_params(p[m], &params);
        for (int i = 0; i < warm; i++)
          if (pipeline_frame(p[m], &cam, true, &err)) goto done;
      }
      for (int i = 0; i < block && s[m].n < frames; i++)
        if (record_frame(p[m], &cam, moving[m], &s[m], &err)) goto done;
      if (!synchronous_slot[m]) { /* idle while the other block runs */
        pipeline_params params = pipeline_get_params(p[m]);
        params.paused = true;
        pipeline_set_params(p[m], &params);
      }
    }
  }
  for (int m = 0; m < 2; m++) out[m].frames = s[m].n, out[m].median = medians(&s[m]);
  for (int m = 0; m < 2; m++) { /* a mean: 0 on the steps that reuse the volume */
    run_result *r = &out[m];
    double sum = 0.0;
    for (int i = 0; i < s[m].n; i++) sum += s[m].stage[9][i];
    r->sun_shadow_cpu_mean = s[m].n ? sum / s[m].n : 0.0;
  }
  status = 0;
done:
  if (status) fprintf(stderr, "fogpipe bench pipeline: %s\n", err.message);
  pipeline_destroy(p[0]);
  pipeline_destroy(p[1]);
  free(storage);
  return status;
}


int bench_pipeline(int argc, char **argv) {
  const char *config_path = FOGPIPE_SOURCE_DIR "/configs/default.ini";
  bench_image_options image = {.width = 640, .height = 360, .frames = 60};
  static const char *const divisor_names[] = {"1", "2", "4", NULL};
  int divisor_index = -1; /* -1: as the demo chooses (2 on software GL, else 1) */
  const cli_option options[] = {
      {.kind = CLI_TEXT, .name = "--config", .value = "PATH", .target = &config_path,
       .help = "scene (default: configs/default.ini of the source tree)"},
      {.kind = CLI_CHOICE, .name = "--fog-resolution", .value = "D", .target = &divisor_index,
       .choices = divisor_names,
       .help = "fog pass at 1/D resolution for the live row (1, 2 or 4;\n"
               "default: as the demo, 2 on a software renderer, 1 on a GPU)"},
  };
  const bench_command command = {
      .stage = "pipeline", .usage = "[options]", .image = &image, .without_out = true,
      .frames_help = "measured frames per mode (at least 5; at most ~20 s each)", .frames_min = 5,
      .about = "Per-stage ms (sim, transform, upload, render, frame; medians) and fps of a scene\n"
               "rendered headless through the whole pipeline, with the CPU stages in the worker\n"
               "thread and on the GL thread, with the camera still and turning. Last line:\n"
               "pipeline: fps=C cpu_stage_share=D fps_moving_camera=E moving_over_still=R\n"
               "(R = fps turning / fps still at the live setting, the two measured in\n"
               "alternating blocks of one run; target >= 0.85).",
      CLI_OPTIONS(options)};
  int exit_status = bench_parse(&command, argc, argv);
  if (exit_status >= 0) return exit_status;
  const int width = image.width, height = image.height;
  const int frames = image.frames;
  int live_divisor = divisor_index < 0 ? 0 : 1 << divisor_index;
  scene_config cfg;
  gl_context *gl;
  if (bench_open_scene("pipeline", config_path, &cfg, &gl)) return 1;
  bench_print_build();
  const char *lp = getenv("LP_NUM_THREADS");
  printf("gl: %s, %s (LP_NUM_THREADS=%s)\n", gl_context_version(gl), gl_context_renderer(gl),
         lp ? lp : "unset");
  printf("scene: %s at %dx%d\n", config_path, width, height);
  fflush(stdout);

  if (!live_divisor) live_divisor = gl_context_is_software(gl) ? 2 : 1;
  /* The live runs take the demo's settings on software GL too: the terrain LOD at 2x the
   * pixel error and the lamps' live rule (the fourth run the full mesh with that rule). */
  scene_config live_cfg = cfg;
  if (gl_context_is_software(gl)) scene_config_live_software(&live_cfg);
  scene_config full_mesh_cfg = live_cfg;
  full_mesh_cfg.terrain.lod_error = 0.0;
  /* Four runs: full-resolution fog (what `record` renders) and the live demo's setting,
   * with the camera still (the scene pass reused), then the live setting with the camera
   * turning every frame (the scene pass every frame), with the terrain LOD and with the
   * full mesh. Each with the CPU stages in the worker thread and on the GL thread: two
   * warm-up frames (the first compiles the shaders), then up to `frames` frames or 20 s
   * per mode, at least 5, the two modes alternating in blocks of 8 frames. */
  enum { RUNS = 4 };
  const int divisors[RUNS] = {1, live_divisor, live_divisor, live_divisor};
  const bool moving[RUNS] = {false, false, true, true};
  /* the fourth: turning with the full terrain mesh (no LOD), what it cost before */
  const scene_config *configs[RUNS] = {&cfg, &live_cfg, &live_cfg, &full_mesh_cfg};
  run_result threaded[RUNS] = {{.frames = 0}}, synchronous[RUNS] = {{.frames = 0}};
  int status = 0;
  for (int r = 0; r < RUNS && !status; r++) {
    if (r == 1 && live_divisor == 1) { /* the live setting is the full-resolution run */
      threaded[r] = threaded[0], synchronous[r] = synchronous[0];
      continue;
    }
    run_result pair[2];
    status = measure(configs[r], width, height, divisors[r], (const bool[2]){false, true},
                     (const bool[2]){moving[r], moving[r]}, 2, frames, 20.0, pair);
    threaded[r] = pair[0], synchronous[r] = pair[1];
  }
  /* R: the live setting's threaded pipeline still and turning, in alternating blocks */
  run_result still_turning[2] = {{.frames = 0}};
  if (!status)
    status = measure(&live_cfg, width, height, live_divisor, (const bool[2]){false, false},
                     (const bool[2]){false, true}, 2, frames, 20.0, still_turning);
  for (int r = 0; r < RUNS && !status; r++) {
    if (r == 1 && live_divisor == 1) continue;
    const run_result *t = &threaded[r], *y = &synchronous[r];
    printf("\nfog at %s resolution%s, terrain LOD %g px%s, camera %s; fogmap %dx%d, %d frames "
           "per mode (medians, ms)\n",
           divisors[r] == 1 ? "full" : divisors[r] == 2 ? "1/2" : "1/4",
           divisors[r] == live_divisor ? " (the live demo's setting here)" : "",
           configs[r]->terrain.lod_error, configs[r]->terrain.lod_error > 0 ? "" : " (full mesh)",
           moving[r] ? "turning every frame (scene pass every frame)"
                     : "still (scene pass reused)",
           t->grid_w, t->grid_h, t->frames);
    printf("%-12s %14s %14s\n", "stage", "worker thread", "synchronous");
    const char *names[5] = {"sim", "transform", "upload", "render", "frame"};
    double a[PIPELINE_TIMING_FIELDS], b[PIPELINE_TIMING_FIELDS]; /* sim .. frame first */
    pipeline_timings_to_array(&t->median, a);
    pipeline_timings_to_array(&y->median, b);
    for (int s = 0; s < 4; s++) {
      printf("%-12s %14.3f %14.3f\n", names[s], a[s], b[s]);
      if (s == 0) printf("%-12s %14.3f %14.3f\n", " CPU time", t->median.sim_cpu, y->median.sim_cpu);
      if (s == 1)
        printf("%-12s %14.3f %14.3f\n", " CPU time", t->median.transform_cpu,
               y->median.transform_cpu);
    }
    /* synchronous: the volume runs on 2 threads, and the GL thread's CPU clock sees its
     * own share only */
    printf("%-12s %14.3f %14.3f (GL thread's share)\n", " sun volume", t->sun_shadow_cpu_mean,
           y->sun_shadow_cpu_mean);
    printf("%-12s %14.3f %14.3f\n", " scene pass", t->median.scene, y->median.scene);
    printf("%-12s %14.3f %14.3f\n", " fog pass", t->median.render - t->median.scene,
           y->median.render - y->median.scene);
    printf("%-12s %14.3f %14.3f\n", names[4], a[4], b[4]);
    printf("%-12s %14.2f %14.2f\n", "fps", t->median.frame > 0 ? 1000.0 / t->median.frame : 0.0,
           y->median.frame > 0 ? 1000.0 / y->median.frame : 0.0);
  }
  if (!status) {
    const run_result *live = &threaded[1], *turning = &threaded[2];
    double fps = live->median.frame > 0 ? 1000.0 / live->median.frame : 0.0;
    double fps_moving = turning->median.frame > 0 ? 1000.0 / turning->median.frame : 0.0;
    /* D from the stages' own CPU time: in the worker their wall time also counts the
     * waits for a core while llvmpipe's render threads run (both shown above). */
    /* ... and the sun's volume, which the worker computes every LIVE_SHADOW_INTERVAL steps
     * (its CPU time's mean per frame; until the fifteenth session D left it out) */
    double share = live->median.frame > 0 ? (live->median.sim_cpu + live->median.transform_cpu +
                                             live->sun_shadow_cpu_mean + live->median.upload) /
                                                live->median.frame
                                          : 0.0;
    double share_without_volume =
        live->median.frame > 0 ? (live->median.sim_cpu + live->median.transform_cpu +
                                  live->median.upload) / live->median.frame
                               : 0.0;
    double share_wall = live->median.frame > 0 ? (live->median.sim + live->median.transform +
                                                  live->median.upload) / live->median.frame
                                               : 0.0;
    printf("\nsummary: the live setting (fog at 1/%d), worker thread; fps with the camera "
           "still,\nfps_moving_camera with it turning every frame; cpu_stage_share = (sim + "
           "transform + sun volume\nCPU time + upload) / frame (%.3f without the sun volume; "
           "%.3f with the worker's wall-clock\ntimes, without it)\n",
           live_divisor, share_without_volume, share_wall);
    const run_result *full_mesh = &threaded[3];
    double fps_full_mesh = full_mesh->median.frame > 0 ? 1000.0 / full_mesh->median.frame : 0.0;
    const double fps_pair_still =
                     still_turning[0].median.frame > 0 ? 1000.0 / still_turning[0].median.frame
                                                       : 0.0,
                 fps_pair_turning =
                     still_turning[1].median.frame > 0 ? 1000.0 / still_turning[1].median.frame
                                                       : 0.0;
    printf("moving_over_still = fps turning %.2f / fps still %.2f, the two measured in "
           "alternating blocks\n(%d frames each; in the separate runs above %.2f / %.2f); with "
           "the full terrain mesh turning: %.2f fps (%.3f of the still run's), scene pass "
           "%.2f -> %.2f ms\n",
           fps_pair_turning, fps_pair_still, still_turning[1].frames, fps_moving, fps,
           fps_full_mesh, fps > 0 ? fps_full_mesh / fps : 0.0, full_mesh->median.scene,
           turning->median.scene);
    printf("pipeline: fps=%.2f cpu_stage_share=%.3f fps_moving_camera=%.2f "
           "moving_over_still=%.3f\n",
           fps, share, fps_moving, fps_pair_still > 0 ? fps_pair_turning / fps_pair_still : 0.0);
  }
  gl_context_destroy(gl);
  return status;
}
