/* fogpipe bench lights: lamps in the fog (docs/light.md, Lamps), speed against accuracy, side
 * by side in one run, on two scenes:
 *   - valley: configs/night_lamps.ini, 9 lamps (a spot among them) in the default scene's
 *     fogmap (static: the simulation's initial fog, through `render`'s fog);
 *   - tube: configs/rbf_lamp_tube.ini, Fogshop's shaft scene (59 Gaussians, a lamp inside).
 * Rows per scene: unlit (no lamps: the baseline); ours at 4+4, 8+8 (the default), 12+12,
 * 16+16 and 32+32 pieces; uniform marching at 16..1024 samples (the tube to 4096); on the
 * tube Fogshop's approximation; on the valley T's walk at 4 and 16 steps, the live demo's
 * rule (scene_live_lamp_method: 4+4, walk 4) and unlit and ours at half resolution.
 * Time: the fog pass, GL, glFinish before and after, median of --frames rounds after a
 * warm-up. A row whose loops pass the renderer's cap (llvmpipe: 65535 a pixel,
 * docs/platform.md; marching at 1024 and 4096) is not drawn: the shader would end its loops
 * early. Its error is its method's CPU twin's (equal to the GL's, test_gpu_lamps), its time
 * extrapolated linearly in the samples from the scene's drawn marching rows, marked so.
 * Error: the lamps' in-scatter (the row's in-scatter minus the unlit row's) against the CPU
 * twin converged (64+64 pieces, 64 depth and 64 shadow steps; for the tube's closed-form
 * depths that is the independent reference to 1e-15, test_lamp_accuracy) on every 16th pixel
 * of every 16th row, max and mean relative to the largest. The halo (test_lamp_accuracy's
 * scene, g 0.7): the CPU twins of ours and Fogshop's against the converged twin.
 * Writes lights.csv and lights_chart.{csv,png}. Last line:
 * `lights: ms_per_light=A march_speedup_at_matched_error=B fogshop_halo_error_ratio=C`:
 * A = (valley, ours default - unlit) / its lamps, scaled to 640x360 by pixels, without the
 * lamps' shadow cubes (on by default; the shadow rows measure them apart); B = on the
 * tube, the cheapest marching within 1e-3 of the peak / our cheapest within it; C =
 * Fogshop's max halo error / ours. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "app/cli_options.h"
#include "bench/bench.h"
#include "render/render.h"

#define ERROR_STRIDE 16
#define MATCHED_ERROR 1e-3
enum { SCENE_COUNT = 2, MAX_ROWS = 32 };
static const char *const scene_configs[SCENE_COUNT] = {"night_lamps.ini", "rbf_lamp_tube.ini"};
static const char *const scene_names[SCENE_COUNT] = {"valley", "tube"};
static const int piece_counts[] = {4, 8, 12, 16, 32};
static const int march_samples[] = {16, 64, 256, 1024, 4096};
static const fog_lamp_method converged = {.integral = FOG_LAMP_ANGLE, .angle_pieces = 64,
                                          .span_pieces = 64, .depth_steps = 64,
                                          .shadow_steps = 64};

/* The error pixels along a side of n pixels: every ERROR_STRIDE-th (bench_error_pixel). */
static int error_count(int n) { return (n + ERROR_STRIDE - 1) / ERROR_STRIDE; }

typedef struct lights_row {
  int scene;
  int divisor; /* fog_pass_params.resolution_divisor: 0 full, 2 the live demo's */
  fog_lamp_method method;
  bool unlit;
  /* Its loops pass the renderer's cap (fog_pass_lamp_loop_bound; llvmpipe): not drawn. Its
   * error from the CPU twin of its method (equal to the GL's, test_gpu_lamps), its time
   * extrapolated from the scene's drawn marching rows (linear in the samples). */
  bool beyond_cap;
  char name[32], series[48];
  double ms, max_error, mean_error;
} lights_row;

typedef struct lights_scene {
  scene_config *cfg;
  render_scene drawn;
  render_fog fog;
  fog_model model;
  fog_lamps lamps;
  float *unlit;      /* the unlit row's in-scatter, 3 per pixel */
  float *unlit_half; /* the same at half resolution (the live rows subtract it) */
  double *reference; /* the lamps' converged in-scatter, 3 per error pixel */
  double peak;
} lights_scene;

static int scene_create(lights_scene *s, int index, int W, int H, fog_error *err) {
  if (bench_load_source_config(scene_configs[index], &s->cfg, err)) return 1;
  if (render_scene_create(&s->drawn, s->cfg, W, H, err) || render_fog_create(&s->fog, s->cfg, err))
    return 1;
  s->model = render_fog_model(&s->fog);
  s->lamps = s->fog.params.lamps;
  return 0;
}

static void scene_destroy(lights_scene *s) {
  if (s->cfg) {
    render_fog_destroy(&s->fog);
    render_scene_destroy(&s->drawn);
  }
  free(s->unlit);
  free(s->unlit_half);
  free(s->reference);
  free(s->cfg);
}

/* The lamps' in-scatter at the error pixels by the CPU twin of `method`, with V (NULL: 1),
 * into out (3 per error pixel); returns its largest value. */
static double lamps_twin(const lights_scene *s, const fog_lamp_method *method, int W, int H,
                         fog_lamp_visibility_fn visible, const void *user, double *out) {
  const int cols = error_count(W), rows = error_count(H);
  fog_lamps lamps = s->lamps;
  lamps.method = *method;
  double peak = 0;
  for (int j = 0; j < rows; j++)
    for (int i = 0; i < cols; i++) {
      int px, py;
      bench_error_pixel(i, j, ERROR_STRIDE, W, H, &px, &py);
      size_t k = (size_t)py * W + px;
      double o[3], d[3], v[3];
      camera_ray(&s->drawn.cam, px, py, W, H, o, d);
      double ts = s->drawn.distance[k] >= 1e29f ? HUGE_VAL : (double)s->drawn.distance[k];
      fog_lamps_inscatter_shadowed(&s->model, &lamps, s->fog.params.sun.albedo,
                                   s->fog.params.sun.phase_g, o, d, ts, visible, user, v);
      for (int c = 0; c < 3; c++) {
        out[((size_t)j * cols + i) * 3 + c] = v[c];
        peak = fmax(peak, v[c]);
      }
    }
  return peak;
}

/* The converged twin (the reference). */
static double scene_reference(const lights_scene *s, int W, int H, fog_lamp_visibility_fn visible,
                              const void *user, double *out) {
  return lamps_twin(s, &converged, W, H, visible, user, out);
}

/* Row r's max and mean error: its lamps' in-scatter at the error pixels (3 each) against the
 * reference, relative to the reference's peak. */
static void set_errors(lights_row *r, const lights_scene *s, const double *lamps, int count) {
  double worst = 0, sum = 0;
  for (int k = 0; k < 3 * count; k++) {
    double e = fabs(lamps[k] - s->reference[k]);
    if (!(e == e)) e = HUGE_VAL;
    worst = fmax(worst, e);
    sum += e;
  }
  r->max_error = worst / s->peak;
  r->mean_error = sum / (3.0 * count) / s->peak;
}

/* A drawn row: its in-scatter less the unlit row's. NAN errors when out of memory. */
static void row_errors(lights_row *r, const lights_scene *s, const float *inscatter, int W, int H) {
  const float *unlit = r->divisor > 1 ? s->unlit_half : s->unlit;
  const int cols = error_count(W), rows = error_count(H);
  double *lamps = malloc((size_t)cols * rows * 3 * sizeof(double));
  r->max_error = r->mean_error = NAN;
  if (!lamps) return;
  for (int j = 0; j < rows; j++)
    for (int i = 0; i < cols; i++) {
      int px, py;
      bench_error_pixel(i, j, ERROR_STRIDE, W, H, &px, &py);
      size_t k = (size_t)py * W + px;
      for (int c = 0; c < 3; c++)
        lamps[((size_t)j * cols + i) * 3 + c] = (double)inscatter[3 * k + c] - unlit[3 * k + c];
    }
  set_errors(r, s, lamps, cols * rows);
  free(lamps);
}

/* A row past the loop cap: its method's CPU twin at the error pixels. */
static void row_errors_twin(lights_row *r, const lights_scene *s, int W, int H) {
  const int cols = error_count(W), rows = error_count(H);
  double *lamps = malloc((size_t)cols * rows * 3 * sizeof(double));
  r->max_error = r->mean_error = NAN;
  if (!lamps) return;
  lamps_twin(s, &r->method, W, H, NULL, NULL, lamps);
  set_errors(r, s, lamps, cols * rows);
  free(lamps);
}

/* Whether row r's loops pass what the renderer allows (fog_pass.h, fog_pass_loops_allowed). */
static bool row_beyond_cap(const lights_scene *s, const lights_row *r) {
  fog_pass_params p = s->fog.params;
  p.lamps = s->lamps;
  p.lamps.method = r->method;
  return !r->unlit &&
         fog_pass_loop_bound(&p, p.model_rbf_count) > fog_pass_loops_allowed(s->fog.pass);
}

/* The drawn marching rows' time, ms = a + b N by least squares, at the rows beyond the cap
 * (NAN where fewer than two were drawn, and for any other method); a and b into fit. */
static void extrapolate_march_times(lights_row *rows, int count, int scene, double fit[2]) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < count; i++) {
    const lights_row *r = &rows[i];
    if (r->scene != scene || r->beyond_cap || r->method.integral != FOG_LAMP_MARCH) continue;
    double x = r->method.march_steps;
    n++, sx += x, sy += r->ms, sxx += x * x, sxy += x * r->ms;
  }
  double b = n >= 2 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : NAN, a = (sy - b * sx) / n;
  for (int i = 0; i < count; i++) {
    lights_row *r = &rows[i];
    if (r->scene != scene || !r->beyond_cap) continue;
    const bool march = r->method.integral == FOG_LAMP_MARCH;
    r->ms = march ? a + b * r->method.march_steps : NAN; /* others: not timed */
    snprintf(r->series, sizeof r->series, "%s %s (time extrapolated)", scene_names[scene],
             march ? "marching" : r->name);
  }
  fit[0] = a, fit[1] = b;
}

static int draw_row(lights_scene *s, const lights_row *r, const gl_target *out, fog_error *err) {
  s->fog.params.lamps = s->lamps;
  s->fog.params.lamps.count = r->unlit ? 0 : s->lamps.count;
  s->fog.params.lamps.method = r->method;
  s->fog.params.resolution_divisor = r->divisor;
  return render_fog_draw(&s->fog, &s->drawn.cam, &s->drawn.target, out, err);
}

/* bench_time_rows' callbacks: the row's draw timed. */
typedef struct timing_user {
  lights_scene *scenes;
  lights_row *rows;
  const gl_target *out;
} timing_user;
static int timing_draw(void *user, int row, fog_error *err) {
  timing_user *u = user;
  if (u->rows[row].beyond_cap) return 0;
  return draw_row(&u->scenes[u->rows[row].scene], &u->rows[row], u->out, err);
}

static lights_row *add_row(lights_row *rows, int *count, int scene, const char *kind, int n) {
  lights_row *r = &rows[(*count)++];
  *r = (lights_row){.scene = scene,
                    .method = {.integral = FOG_LAMP_ANGLE, .angle_pieces = n, .span_pieces = n,
                               .depth_steps = FOG_LAMP_DEPTH_STEPS,
                               .shadow_steps = FOG_LAMP_SHADOW_STEPS, .march_steps = n}};
  r->unlit = !strcmp(kind, "unlit");
  if (!strcmp(kind, "march")) r->method.integral = FOG_LAMP_MARCH;
  if (!strcmp(kind, "fogshop")) {
    r->method.integral = FOG_LAMP_FOGSHOP;
    r->method.angle_pieces = FOG_LAMP_ANGLE_PIECES, r->method.span_pieces = FOG_LAMP_SPAN_PIECES;
  }
  if (!strcmp(kind, "ours")) snprintf(r->name, sizeof r->name, "ours %d+%d", n, n);
  else if (!strcmp(kind, "march")) snprintf(r->name, sizeof r->name, "march %d", n);
  else snprintf(r->name, sizeof r->name, "%s", kind);
  snprintf(r->series, sizeof r->series, "%s %s", scene_names[scene],
           !strcmp(kind, "ours")    ? "ours 4+4..32+32"
           : !strcmp(kind, "march") ? "marching (timed)"
                                    : kind);
  return r;
}

/* C: the halo of test_lamp_accuracy (a Gaussian of radius 2, the lamp 0.5 radii off its
 * centre, g 0.7), 25 rays sweeping past, the CPU twins against the converged twin. */
static double halo_ratio(double *ours_error, double *fogshop_error) {
  fog_rbf g = {.centre = {0, 0, 0}, .radius = 2.0, .density = 0.6};
  fog_model m = {.kind = FOG_MODEL_RBF, .rbfs = &g, .rbf_count = 1};
  fog_lamp lamp = {.kind = FOG_LAMP_POINT, .position = {1, 0, 0}, .intensity = {1, 1, 1},
                   .radius = 0.05};
  fog_lamp_method ours = {.integral = FOG_LAMP_ANGLE, .angle_pieces = FOG_LAMP_ANGLE_PIECES,
                          .span_pieces = FOG_LAMP_SPAN_PIECES,
                          .depth_steps = FOG_LAMP_DEPTH_STEPS,
                          .shadow_steps = FOG_LAMP_SHADOW_STEPS},
                  fogshop = ours;
  fogshop.integral = FOG_LAMP_FOGSHOP;
  const double o[3] = {0.3, 0.2, 20.0};
  double peak = 0, eo = 0, ef = 0;
  for (int k = 0; k < 25; k++) {
    double d[3] = {-4.0 + 8.0 * k / 24 - o[0], 0.05 - o[1], -o[2]};
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int a = 0; a < 3; a++) d[a] /= len;
    double want = fog_lamp_inscatter_unit(&m, &lamp, &converged, 0.7, o, d, 40.0);
    peak = fmax(peak, want);
    eo = fmax(eo, fabs(fog_lamp_inscatter_unit(&m, &lamp, &ours, 0.7, o, d, 40.0) - want));
    ef = fmax(ef, fabs(fog_lamp_inscatter_unit(&m, &lamp, &fogshop, 0.7, o, d, 40.0) - want));
  }
  *ours_error = eo / peak, *fogshop_error = ef / peak;
  return ef / eo;
}

/* V by an exact ray cast from x to lamp i against the scene's terrain and boxes. */
typedef struct exact_lamps {
  const scene_geometry *geo;
  const fog_lamps *lamps;
} exact_lamps;
static double exact_visible(const void *user, int i, const double x[3]) {
  const exact_lamps *e = user;
  double w[3], dist = 0, s;
  for (int a = 0; a < 3; a++) w[a] = e->lamps->lamp[i].position[a] - x[a], dist += w[a] * w[a];
  dist = sqrt(dist);
  if (!(dist > 0)) return 1.0;
  for (int a = 0; a < 3; a++) w[a] /= dist;
  return scene_geometry_intersect(e->geo, x, w, dist, &s, NULL) ? 0.0 : 1.0;
}

/* The lamps' shadow cubes on the valley: the time to render all of them (every lamp nudged
 * by a micron, so each cube is drawn again), the fog pass with and without them, and both
 * against the twin converged with V by exact ray casts. Returns 0, or 1 on a GL error. */
static int shadow_rows(lights_scene *s, const lights_row *plain, int W, int H, int frames,
                       float *inscatter, const gl_target *out, fog_error *err) {
  const int cols = error_count(W), rows = error_count(H);
  double *times = malloc((size_t)frames * sizeof(double));
  if (!times) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    return 1;
  }
  /* the reference with V, in place of the row's (restored below) */
  double *unshadowed = s->reference, peak = s->peak;
  double *shadowed = malloc((size_t)cols * rows * 3 * sizeof(double));
  if (!shadowed) {
    free(times);
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    return 1;
  }
  const exact_lamps exact = {&s->drawn.geo, &s->lamps};
  s->peak = scene_reference(s, W, H, exact_visible, &exact, shadowed);
  s->reference = shadowed;
  lights_row with = *plain, without = *plain;
  int failed = 0;
  /* the cubes */
  fog_lamps nudged = s->lamps;
  for (int f = 0; f < frames && !failed; f++) {
    for (int i = 0; i < nudged.count; i++) nudged.lamp[i].position[1] += (f & 1 ? -1e-6 : 1e-6);
    fog_pass_finish();
    double t0 = app_clock_seconds();
    failed = scene_pass_set_lamps(s->drawn.pass, &nudged, err);
    fog_pass_finish();
    times[f] = app_clock_seconds() - t0;
  }
  const double cube_ms = 1e3 * app_median(times, frames);
  failed = failed || scene_pass_set_lamps(s->drawn.pass, &s->lamps, err);
  const lamp_shadow_maps *maps = scene_pass_lamp_shadows(s->drawn.pass);
  /* the fog pass with the cubes, then without, against the shadowed reference */
  for (int pass = 0; pass < 2 && !failed && maps; pass++) {
    lights_row *r = pass == 0 ? &with : &without;
    s->fog.lamp_shadows = pass == 0 ? maps : NULL;
    failed = draw_row(s, r, out, err) || gl_target_read(out, 2, 3, inscatter, err);
    if (failed) break;
    row_errors(r, s, inscatter, W, H);
    for (int f = 0; f < frames && !failed; f++) {
      fog_pass_finish();
      double t0 = app_clock_seconds();
      failed = draw_row(s, r, out, err);
      fog_pass_finish();
      times[f] = app_clock_seconds() - t0;
    }
    r->ms = 1e3 * app_median(times, frames);
  }
  s->fog.lamp_shadows = NULL;
  s->reference = unshadowed, s->peak = peak;
  if (!failed && maps) {
    const double scale = 640.0 * 360.0 / ((double)W * H);
    printf("\nlamp shadow cubes on the valley (%d lamps, %d texels a face side):\n", s->lamps.count,
           maps->size);
    printf("  rendering every lamp's cube: %.2f ms (%.2f ms a lamp)\n", cube_ms,
           cube_ms / s->lamps.count);
    printf("  fog pass (ours %d+%d) with the cubes %.2f ms, without %.2f ms: %+.2f ms a lamp at "
           "640x360\n", plain->method.angle_pieces, plain->method.span_pieces, with.ms,
           without.ms, (with.ms - without.ms) / s->lamps.count * scale);
    printf("  against the twin converged with V by exact ray casts: with the cubes max %.2e "
           "(mean %.2e), without %.2e (mean %.2e)\n", with.max_error, with.mean_error,
           without.max_error, without.mean_error);
  }
  free(times);
  free(shadowed);
  return failed;
}

static int write_table(const char *path, const lights_row *rows, int count, char *error, int size) {
  chart_table table;
  if (chart_table_open(&table, path, error, size)) return 1;
  FILE *f = table.stream;
  fprintf(f, "scene,method,ms_per_frame,max_error,mean_error,timed\n");
  for (int i = 0; i < count; i++) {
    char errors[64] = ","; /* an unlit row has no lamps' error: empty, not a perfect 0 */
    if (!rows[i].unlit)
      snprintf(errors, sizeof errors, "%.6g,%.6g", rows[i].max_error, rows[i].mean_error);
    fprintf(f, "%s,%s,%.6g,%s,%s\n", scene_names[rows[i].scene], rows[i].name, rows[i].ms,
            errors, rows[i].beyond_cap ? "extrapolated" : "measured");
  }
  return chart_table_write(&table, error, size);
}

int bench_lights(int argc, char **argv) {
  bench_image_options options = {.width = 320, .height = 180, .frames = 3,
                                 .out_dir = "build/bench/lights"};
  const bench_command command = {
      .stage = "lights", .usage = "[--size WxH] [--frames N] [--out DIR]", .image = &options,
      .out_help = "lights.csv, lights_chart.csv, lights_chart.png; A is scaled to 640x360 by "
                  "pixels",
      .about = "Last line: lights: ms_per_light=A march_speedup_at_matched_error=B\n"
               "fogshop_halo_error_ratio=C (see the header of bench/bench_lights.c)."};
  int exit_status = bench_parse(&command, argc, argv);
  if (exit_status >= 0) return exit_status;
  const int W = options.width, H = options.height, frames = options.frames;
  int status = 1, row_count = 0, live_rows[2] = {0, 0};
  size_t pixels = (size_t)W * H;
  const int cols = error_count(W), rows_e = error_count(H);
  fog_error rerr = {0};
  lights_scene scenes[SCENE_COUNT] = {{0}};
  lights_row rows[MAX_ROWS] = {{0}};
  gl_target out = {0};
  float *inscatter = malloc(3 * pixels * sizeof(float));
  gl_context *ctx = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &rerr);
  if (!inscatter) goto out_of_memory;
  if (!ctx || gl_target_create(&out, &(gl_target_desc){.width = W, .height = H,
                                                       .color_formats = {GL_RGBA32F, GL_R32F,
                                                                         GL_RGBA32F}},
                               &rerr))
    goto done;
  for (int s = 0; s < SCENE_COUNT; s++) {
    if (scene_create(&scenes[s], s, W, H, &rerr)) goto done;
    scenes[s].unlit = malloc(3 * pixels * sizeof(float));
    scenes[s].reference = malloc((size_t)cols * rows_e * 3 * sizeof(double));
    if (!scenes[s].unlit || !scenes[s].reference) goto out_of_memory;
    add_row(rows, &row_count, s, "unlit", 8);
    for (size_t q = 0; q < sizeof piece_counts / sizeof piece_counts[0]; q++)
      add_row(rows, &row_count, s, "ours", piece_counts[q]);
    for (size_t q = 0; q < sizeof march_samples / sizeof march_samples[0] - (s == 0); q++)
      add_row(rows, &row_count, s, "march", march_samples[q]);
    if (s == 1) add_row(rows, &row_count, s, "fogshop", 8);
    if (s == 0) /* T's walk to the lamp (the fogmap's): 4 and 16 steps beside the default 8 */
      for (int q = 0; q < 2; q++) {
        lights_row *r = add_row(rows, &row_count, s, "ours", FOG_LAMP_ANGLE_PIECES);
        r->method.shadow_steps = q ? 16 : 4;
        snprintf(r->name, sizeof r->name, "ours 8+8 walk %d", r->method.shadow_steps);
        snprintf(r->series, sizeof r->series, "valley ours 8+8 walk 4 and 16 steps");
      }
    if (s == 0) { /* the live demo's rule on a software renderer (scene_live_lamp_method) */
      lights_row *r = add_row(rows, &row_count, s, "ours", FOG_LAMP_ANGLE_PIECES);
      r->method = scene_live_lamp_method(r->method);
      snprintf(r->name, sizeof r->name, "ours live %d+%d walk %d", r->method.angle_pieces,
               r->method.span_pieces, r->method.shadow_steps);
      snprintf(r->series, sizeof r->series, "valley ours live rule");
    }
    if (s == 0) { /* the live demo's setting: the fog at half resolution */
      scenes[s].unlit_half = malloc(3 * pixels * sizeof(float));
      if (!scenes[s].unlit_half) goto out_of_memory;
      for (int live = 0; live < 2; live++) {
        lights_row *r = add_row(rows, &row_count, s, live ? "ours" : "unlit",
                                FOG_LAMP_ANGLE_PIECES);
        r->divisor = 2;
        live_rows[live] = row_count - 1;
        snprintf(r->name, sizeof r->name, "%s 1/2", live ? "ours 8+8" : "unlit");
        snprintf(r->series, sizeof r->series, "valley ours 8+8 at 1/2 resolution");
      }
    }
    scenes[s].peak = scene_reference(&scenes[s], W, H, NULL, NULL, scenes[s].reference);
  }
  /* Warm-up and errors (the unlit row first: the others subtract its in-scatter), then the
   * timed rounds, rows interleaved. */
  for (int i = 0; i < row_count; i++) {
    lights_row *r = &rows[i];
    lights_scene *s = &scenes[r->scene];
    float *into = !r->unlit ? inscatter : r->divisor > 1 ? s->unlit_half : s->unlit;
    if ((r->beyond_cap = row_beyond_cap(s, r))) {
      row_errors_twin(r, s, W, H);
      continue;
    }
    if (draw_row(s, r, &out, &rerr) || gl_target_read(&out, 2, 3, into, &rerr))
      goto done;
    if (!r->unlit) row_errors(r, s, inscatter, W, H);
  }
  timing_user user = {scenes, rows, &out};
  if (bench_time_rows(&(bench_timed_rows){.count = row_count, .frames = frames, .user = &user,
                                          .draw = timing_draw, .ms = &rows[0].ms,
                                          .ms_stride = sizeof rows[0]},
                      &rerr))
    goto done;
  double fits[SCENE_COUNT][2];
  for (int s = 0; s < SCENE_COUNT; s++) extrapolate_march_times(rows, row_count, s, fits[s]);

  bench_print_gl(ctx, W, H, frames);
  printf("error: the lamps' in-scatter vs the CPU twin converged (64+64 pieces, 64 depth and\n"
         "shadow steps) on every %dth pixel of every %dth row (moved up to 3 within its cell,\n"
         "onto every phase of the reduced passes' blocks), relative to its largest value\n\n",
         ERROR_STRIDE, ERROR_STRIDE);
  printf("%-8s %-12s %10s %10s %10s\n", "scene", "method", "ms/frame", "max err", "mean err");
  chart_point points[MAX_ROWS];
  int point_count = 0;
  for (int i = 0; i < row_count; i++) {
    const lights_row *r = &rows[i];
    if (r->unlit) {
      printf("%-8s %-12s %10.2f %10s %10s\n", scene_names[r->scene], r->name, r->ms, "-", "-");
      continue;
    }
    printf("%-8s %-12s %10.2f%s %10.2e %10.2e\n", scene_names[r->scene], r->name, r->ms,
           r->beyond_cap ? "*" : " ", r->max_error, r->mean_error);
    if (isfinite(r->ms))
      points[point_count++] = (chart_point){.series = r->series, .x = r->ms,
                                            .y = chart_floor(r->max_error, 1e-7)};
  }
  char title[128];
  bench_outputs files;
  bench_outputs_in(&files, options.out_dir, "lights");
  snprintf(title, sizeof title, "lamps in the fog %dx%d: max in-scatter error vs fog pass ms", W, H);
  chart_desc chart = {.title = title, .x_label = "fog pass per frame (ms)",
                      .y_label = "max |lamp in-scatter - reference| / max", .log_x = true,
                      .log_y = true};
  /* a file that fails costs the stage its status, not its figures */
  bench_files_written written;
  bench_write_files(&written,
                    write_table(files.table, rows, row_count, written.error,
                                 sizeof written.error),
                    &chart, points, point_count, &files);
  for (int s = 0; s < SCENE_COUNT; s++)
    for (int i = 0; i < row_count; i++)
      if (rows[i].scene == s && rows[i].beyond_cap) {
        printf("* %s: the rows marked run more loop iterations a pixel than this renderer "
               "allows (%ld, render/fog_pass.h): not drawn; their error from the CPU twin of "
               "their method, their time extrapolated from the drawn marching rows (%.2f + "
               "%.4f ms a sample)\n", scene_names[s], fog_pass_loop_cap(scenes[s].fog.pass),
               fits[s][0], fits[s][1]);
        break;
      }
  printf("\nCSV: %s, %s; PNG: %s\n", files.table, files.chart_csv,
         written.drawn ? files.chart_png : "not drawn");
  /* A: the valley's default (row 2: ours 8+8) over its unlit row (0), per lamp, at 640x360:
   * the lamps' work is per pixel, so scaled from W x H by the pixel count. */
  const double per_light = (rows[2].ms - rows[0].ms) / scenes[0].lamps.count *
                           (640.0 * 360.0) / ((double)W * H);
  printf("A: (%.2f - %.2f) ms / %d lamps at %dx%d, x %.2f to 640x360\n", rows[2].ms, rows[0].ms,
         scenes[0].lamps.count, W, H, 640.0 * 360.0 / ((double)W * H));
  /* A at the live setting: the same at half resolution (the demo's fog), per lamp at
   * 640x360 */
  const lights_row *live_unlit = &rows[live_rows[0]], *live = &rows[live_rows[1]];
  printf("A at the live setting (the fog at 1/2 resolution): (%.2f - %.2f) ms / %d lamps: "
         "%.2f ms a lamp at 640x360 (max error %.2e of the peak, mean %.2e)\n", live->ms,
         live_unlit->ms, scenes[0].lamps.count,
         (live->ms - live_unlit->ms) / scenes[0].lamps.count * (640.0 * 360.0) / ((double)W * H),
         live->max_error, live->mean_error);
  /* B: on each scene the cheapest marching within MATCHED_ERROR over our cheapest. */
  double b[SCENE_COUNT];
  bool b_extrapolated[SCENE_COUNT]; /* the matched march's time fitted, not drawn */
  for (int s = 0; s < SCENE_COUNT; s++) {
    double march_ms = NAN, ours_ms = NAN;
    b_extrapolated[s] = false;
    for (int i = 0; i < row_count; i++) {
      const lights_row *r = &rows[i];
      if (r->scene != s || r->unlit || r->divisor > 1 || r->method.integral == FOG_LAMP_FOGSHOP ||
          !(r->max_error <= MATCHED_ERROR) || !isfinite(r->ms))
        continue;
      const bool march = r->method.integral == FOG_LAMP_MARCH;
      double *best = march ? &march_ms : &ours_ms;
      if (!(*best <= r->ms)) {
        *best = r->ms;
        if (march) b_extrapolated[s] = r->beyond_cap;
      }
    }
    b[s] = march_ms / ours_ms;
    printf("%s: cheapest within %g: marching %.2f ms%s, ours %.2f ms (%s)\n", scene_names[s],
           MATCHED_ERROR, march_ms,
           b_extrapolated[s] ? " (extrapolated: past llvmpipe's loop cap)" : "", ours_ms,
           b[s] == b[s] ? "ratio below" : "nan: one of them never gets there");
  }
  if (shadow_rows(&scenes[0], &rows[2], W, H, frames, inscatter, &out, &rerr)) goto done;
  double halo_ours, halo_fogshop;
  double c = halo_ratio(&halo_ours, &halo_fogshop);
  printf("halo (g 0.7, CPU twins): ours max error %.2e, Fogshop's %.2e of the peak\n", halo_ours,
         halo_fogshop);
  /* march_time_extrapolated=1: B's marching time is the fit of the drawn rows' times (its
   * loops pass llvmpipe's cap), not a measurement */
  printf("lights: ms_per_light=%.2f march_speedup_at_matched_error=%.2f "
         "fogshop_halo_error_ratio=%.0f march_time_extrapolated=%d\n", per_light, b[1], c,
         b_extrapolated[1] ? 1 : 0);
  status = bench_files_report(&written, &rerr);
  goto done;

out_of_memory:
  fog_fail(&rerr, FOG_ERR_OUT_OF_MEMORY, "out of memory");
done:
  for (int s = 0; s < SCENE_COUNT; s++) scene_destroy(&scenes[s]);
  if (out.framebuffer) gl_target_destroy(&out);
  if (ctx) gl_context_destroy(ctx);
  free(inscatter);
  return bench_report("lights", status, &rerr);
}
