/* fogpipe bench models: the analytic rungs of the fog-model ladder (DESIGN §3,
 * render/fog_models.h), each integrated exactly and by uniform ray marching, side by side
 * on one fixed scene: configs/rbf_fog_banks.ini's valley and camera (terrain, boxes, view),
 * with
 *   - homogeneous fog, K = 0.002 (exact only: marching a constant is exact at any step);
 *   - height fog, K = 0.01 exp(-(y - 40)/25);
 *   - the config's six Gaussian fog banks (RBFs, no base).
 * Rows: exact (closed form per pixel) and marching N = 8 .. 256 midpoint steps (to the
 * surface, or for the sky to where the fog ends: fog_models.glsl). Time: GL, glFinish
 * before and after, median of --frames rounds after a warm-up, rows interleaved. Error: tau
 * against the double-precision CPU model on the same rays to the scene pass's read-back
 * distances; RMSE and max over all pixels.
 * Writes models.csv and models_chart.{csv,png} (max error vs ms, log-log, a series per
 * model and method). Last line: `models: rbf_exact_ms=... rbf_march_speedup_at_matched_error=
 * ... height_exact_ms=... height_march_speedup_at_matched_error=...`, a speedup being the time
 * of the cheapest marching with max error <= 1e-3 over the exact time. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "app/render_frame.h"
#include "bench/bench.h"
#include "bench/chart.h"
#include "render/render.h"

#define ERROR_FLOOR 1e-9
#define MATCHED_ERROR 1e-3

static const int march_steps[] = {8, 16, 32, 64, 128, 256};
enum { MARCH_COUNT = 6, MODEL_COUNT = 3, MAX_ROWS = MODEL_COUNT * (1 + MARCH_COUNT) };
static const char *const model_names[MODEL_COUNT] = {"homogeneous", "height", "rbf"};

typedef struct model_row {
  int model;     /* index into model_names */
  int steps;     /* 0: exact */
  char series[48];
  fog_pass_params params;
  double *times;
  double ms, rmse, max_error;
} model_row;

static void print_help(void) {
  printf(
      "usage: fogpipe bench models [--size WxH] [--frames N] [--out DIR]\n"
      "  --size WxH   image size (default 640x360)\n"
      "  --frames N   timed rounds; each row's time is the median of N frames after one\n"
      "               warm-up frame (default 5)\n"
      "  --out DIR    where models.csv, models_chart.csv and models_chart.png go (default\n"
      "               build/bench/models; created if missing)\n"
      "Last line: models: rbf_exact_ms=A rbf_march_speedup_at_matched_error=B\n"
      "height_exact_ms=C height_march_speedup_at_matched_error=D: B and D = time of the\n"
      "cheapest ray marching with max tau error <= 1e-3 / the closed form's time.\n");
}

/* The cheapest marching row of a model within MATCHED_ERROR (else its most accurate one,
 * *matched false) over its exact row. */
static double march_speedup(const model_row *rows, int count, int model, bool *matched) {
  int exact = -1, cheapest = -1, best = -1;
  for (int i = 0; i < count; i++) {
    if (rows[i].model != model) continue;
    if (!rows[i].steps) {
      exact = i;
      continue;
    }
    if (rows[i].max_error <= MATCHED_ERROR && (cheapest < 0 || rows[i].ms < rows[cheapest].ms))
      cheapest = i;
    if (best < 0 || rows[i].max_error < rows[best].max_error) best = i;
  }
  *matched = cheapest >= 0;
  int use = cheapest >= 0 ? cheapest : best;
  return exact >= 0 && use >= 0 ? rows[use].ms / rows[exact].ms : NAN;
}

static int write_table(const char *path, const model_row *rows, int count, char *error,
                       int size) {
  FILE *f = bench_csv_open(path, error, size);
  if (!f) return 1;
  fprintf(f, "model,method,steps,ms_per_frame,rmse,max_error\n");
  for (int i = 0; i < count; i++)
    fprintf(f, "%s,%s,%d,%.6g,%.6g,%.6g\n", model_names[rows[i].model],
            rows[i].steps ? "march" : "exact", rows[i].steps, rows[i].ms, rows[i].rmse,
            rows[i].max_error);
  return bench_csv_close(f, path, error, size);
}

int bench_models(int argc, char **argv) {
  bench_image_options options = {.width = 640, .height = 360, .frames = 5,
                                 .out_dir = "build/bench/models"};
  for (int i = 1; i < argc; i++) {
    int common = bench_image_option("models", argc, argv, &i, &options);
    if (common < 0) return 2;
    if (common) continue;
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      print_help();
      return 0;
    }
    fprintf(stderr, "fogpipe bench models: unknown option '%s' (or it lacks its value)\n",
            argv[i]);
    print_help();
    return 2;
  }
  const int W = options.width, H = options.height, frames = options.frames;
  const char *out_dir = options.out_dir;
  char error[1024] = "";
  if (bench_make_folder(out_dir, error, sizeof error)) {
    fprintf(stderr, "fogpipe bench models: %s\n", error);
    return 1;
  }
  const char *config_path = FOGPIPE_SOURCE_DIR "/configs/rbf_fog_banks.ini";
  scene_config *cfg = malloc(sizeof *cfg);
  scene_config_error cerr;
  if (!cfg || scene_config_load(config_path, cfg, &cerr)) {
    fprintf(stderr, "fogpipe bench models: %s\n", cfg ? cerr.message : "out of memory");
    free(cfg);
    return 1;
  }
  /* The three models; the RBFs are the config's (density_scale applied, as render does). */
  fog_rbf rbfs[FOG_MAX_RBFS];
  for (int i = 0; i < cfg->fog.rbf_count; i++) {
    rbfs[i] = cfg->fog.rbfs[i];
    rbfs[i].density *= cfg->fog.density_scale;
  }
  const fog_model models[MODEL_COUNT] = {
      {.kind = FOG_MODEL_HOMOGENEOUS, .extinction = 0.002},
      {.kind = FOG_MODEL_HEIGHT, .extinction = 0.01, .y0 = 40.0, .scale_height = 25.0},
      {.kind = FOG_MODEL_RBF, .extinction = cfg->fog.rbf_base, .rbfs = rbfs,
       .rbf_count = cfg->fog.rbf_count}};

  int status = 1;
  size_t pixels = (size_t)W * H;
  render_error rerr = {{0}};
  gl_context *ctx = NULL;
  scene_geometry geo = {0};
  bool have_geo = false;
  scene_pass *spass = NULL;
  fog_pass *pass = NULL;
  gl_target scene_target = {0}, fog_target = {0};
  float *distance = malloc(pixels * sizeof(float)), *gpu_tau = malloc(pixels * sizeof(float));
  double *references[MODEL_COUNT] = {0};
  model_row rows[MAX_ROWS] = {{0}};
  int row_count = 0;
  camera cam;
  scene_config_camera(cfg, &cam);
  if (!distance || !gpu_tau) goto out_of_memory;

  ctx = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &rerr);
  if (!ctx) goto gl_failed;
  scene_desc sdesc;
  scene_config_scene_desc(cfg, NULL, 0, 0, &sdesc); /* the config's terrain is procedural */
  if (scene_geometry_create(&geo, &sdesc, &rerr)) goto gl_failed;
  have_geo = true;
  spass = scene_pass_create(&geo, &rerr);
  if (!spass || scene_target_create(&scene_target, W, H, &rerr) ||
      gl_target_create(&fog_target, &(gl_target_desc){.width = W, .height = H,
                                                      .color_formats = {GL_RGBA32F, GL_R32F}},
                       &rerr) ||
      fog_pass_create(&pass, &rerr))
    goto gl_failed;
  scene_pass_run(spass, &cam, &scene_target);
  if (gl_target_read(&scene_target, 1, 1, distance, &rerr)) goto gl_failed;

  /* The CPU references: tau of each model along every pixel's ray to its surface. */
  for (int m = 0; m < MODEL_COUNT; m++) {
    references[m] = malloc(pixels * sizeof(double));
    if (!references[m]) goto out_of_memory;
    for (int py = 0; py < H; py++)
      for (int px = 0; px < W; px++) {
        double o[3], d[3];
        size_t k = (size_t)py * W + px;
        camera_ray(&cam, px, py, W, H, o, d);
        double ts = distance[k] >= 1e29f ? HUGE_VAL : (double)distance[k];
        references[m][k] = fog_transmittance(fog_model_optical_depth(&models[m], o, d, ts));
      }
  }

  for (int m = 0; m < MODEL_COUNT; m++)
    for (int s = -1; s < (m == 0 ? 0 : MARCH_COUNT); s++) {
      model_row *r = &rows[row_count++];
      r->model = m;
      r->steps = s < 0 ? 0 : march_steps[s];
      snprintf(r->series, sizeof r->series, "%s %s", model_names[m], s < 0 ? "exact" : "march");
      r->params = (fog_pass_params){
          .model = models[m].kind, .model_extinction = models[m].extinction,
          .model_y0 = models[m].y0, .model_scale_height = models[m].scale_height,
          .model_rbfs = models[m].rbfs, .model_rbf_count = models[m].rbf_count,
          .fog_colour = {0.75f, 0.78f, 0.82f},
          .integrator = s < 0 ? FOG_INTEGRATOR_EXACT : FOG_INTEGRATOR_MARCH,
          .march_steps = r->steps};
      r->times = malloc((size_t)frames * sizeof(double));
      if (!r->times) goto out_of_memory;
    }
  /* Warm-up (shader JIT) with the error read-back, then the timed rounds interleaved. */
  for (int i = 0; i < row_count; i++) {
    model_row *r = &rows[i];
    size_t where;
    gl_target_bind(&fog_target);
    if (fog_pass_draw(pass, &cam, &r->params, scene_target.color[0], scene_target.color[1], W,
                      H, &rerr) ||
        gl_target_read(&fog_target, 1, 1, gpu_tau, &rerr))
      goto gl_failed;
    bench_tau_errors(gpu_tau, references[r->model], pixels, &r->rmse, &r->max_error, &where);
  }
  for (int f = 0; f < frames; f++)
    for (int i = 0; i < row_count; i++) {
      gl_target_bind(&fog_target);
      fog_pass_finish();
      double t0 = app_clock_seconds();
      if (fog_pass_draw(pass, &cam, &rows[i].params, scene_target.color[0],
                        scene_target.color[1], W, H, &rerr))
        goto gl_failed;
      fog_pass_finish();
      rows[i].times[f] = app_clock_seconds() - t0;
    }
  for (int i = 0; i < row_count; i++) rows[i].ms = 1e3 * bench_median(rows[i].times, frames);

  bench_print_build();
  printf("GL: %s, %s, %s; %dx%d, median of %d frames after 1 warm-up (glFinish before and after)\n",
         gl_context_platform(ctx), gl_context_version(ctx), gl_context_renderer(ctx), W, H,
         frames);
  printf("scene: %s (terrain, boxes, camera); homogeneous K = %g; height K = %g exp(-(y - %g)/%g);"
         "\nrbf: the config's %d Gaussians; errors: tau vs the double-precision CPU model on the"
         "\nsame rays, over all pixels\n\n",
         config_path, models[0].extinction, models[1].extinction, models[1].y0,
         models[1].scale_height, models[2].rbf_count);
  printf("%-12s %-7s %6s %10s %10s %10s\n", "model", "method", "steps", "ms/frame", "RMSE",
         "max err");
  chart_point points[MAX_ROWS];
  for (int i = 0; i < row_count; i++) {
    const model_row *r = &rows[i];
    printf("%-12s %-7s %6d %10.2f %10.2e %10.2e\n", model_names[r->model],
           r->steps ? "march" : "exact", r->steps, r->ms, r->rmse, r->max_error);
    points[i] = (chart_point){.series = r->series, .x = r->ms,
                              .y = r->max_error > ERROR_FLOOR ? r->max_error : ERROR_FLOOR};
  }
  char table[4200], chart_csv[4200], chart_png[4200], title[128];
  snprintf(table, sizeof table, "%s/models.csv", out_dir);
  snprintf(chart_csv, sizeof chart_csv, "%s/models_chart.csv", out_dir);
  snprintf(chart_png, sizeof chart_png, "%s/models_chart.png", out_dir);
  snprintf(title, sizeof title, "analytic fog models %dx%d: max tau error vs GL time", W, H);
  chart_desc chart = {.title = title, .x_label = "GL time per frame (ms)",
                      .y_label = "max |tau - CPU reference|", .log_x = true, .log_y = true};
  if (write_table(table, rows, row_count, error, sizeof error) ||
      chart_write(&chart, points, row_count, chart_csv, chart_png, error, sizeof error)) {
    fprintf(stderr, "fogpipe bench models: %s\n", error);
    goto done;
  }
  printf("\nCSV: %s, %s; PNG: %s\n", table, chart_csv, chart_png);
  double exact_ms[MODEL_COUNT] = {0}, speedup[MODEL_COUNT] = {0};
  for (int m = 1; m < MODEL_COUNT; m++) {
    bool matched;
    speedup[m] = march_speedup(rows, row_count, m, &matched);
    for (int i = 0; i < row_count; i++)
      if (rows[i].model == m && !rows[i].steps) exact_ms[m] = rows[i].ms;
    if (!matched)
      printf("note: no marching of %s reached max error <= %g; its speedup uses the most "
             "accurate one\n", model_names[m], MATCHED_ERROR);
  }
  printf("models: rbf_exact_ms=%.3f rbf_march_speedup_at_matched_error=%.2f "
         "height_exact_ms=%.3f height_march_speedup_at_matched_error=%.2f\n",
         exact_ms[2], speedup[2], exact_ms[1], speedup[1]);
  status = 0;
  goto done;

out_of_memory:
  fprintf(stderr, "fogpipe bench models: out of memory\n");
  goto done;
gl_failed:
  fprintf(stderr, "fogpipe bench models: %s\n", rerr.message);
done:
  for (int i = 0; i < row_count; i++) free(rows[i].times);
  for (int m = 0; m < MODEL_COUNT; m++) free(references[m]);
  if (pass) fog_pass_destroy(pass);
  if (fog_target.framebuffer) gl_target_destroy(&fog_target);
  if (scene_target.framebuffer) gl_target_destroy(&scene_target);
  if (spass) scene_pass_destroy(spass);
  if (have_geo) scene_geometry_destroy(&geo);
  if (ctx) gl_context_destroy(ctx);
  free(distance);
  free(gpu_tau);
  free(cfg);
  return status;
}
