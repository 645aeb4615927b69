/* fogpipe bench import: VDB import per frame (read + project + profile + resample) over
 * the ground-fog sequence, and the time to preview one frame: fogpipe (import + project +
 * wavelet transform + headless GL render at 640x480 + PNG) against OpenVDB's own
 * vdb_render of the same frame at 640x480, measured in the same run. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/cli_options.h"
#include "bench/bench.h"
#include "render/camera.h"
#include "render/fog_pass.h"
#include "render/gl_context.h"
#include "render/gl_util.h"
#include "render/scene.h"
#include "sim/sim.h"
#include "transform/transform.h"

enum { W = 640, H = 480, max_levels = 3, max_runs = 64, parts_count = 6 };


/* Wall seconds of one vdb_render run; < 0 when it failed. */
static double time_vdb_render(const char *exe, const char *vdb, const char *png) {
  char res[32];
  snprintf(res, sizeof res, "%dx%d", W, H);
  /* The VDB's own world: the domain min corner at 0, Z up (README). Same view as ours. */
  const double t0 = app_clock_seconds();
  fflush(stdout); /* or the child would flush our buffered table a second time */
  fflush(stderr);
  pid_t pid = fork();
  if (pid == 0) {
    int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, 1);
      dup2(null, 2);
    }
    execl(exe, exe, vdb, png, "-name", "density", "-res", res, "-translate", "3,-5,3.5",
          "-lookat", "3,3,0.2", "-up", "0,0,1", "-absorb", "2,2,2", "-scatter", "4,4,4",
          "-light", "0.3,-0.5,0.8,1,1,1", (char *)NULL);
    _exit(127);
  }
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) < 0) return -1;
  const double t = app_clock_seconds() - t0;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? t : -1;
}

typedef struct preview {
  gl_context *ctx;
  scene_geometry geo;
  scene_pass *scene;
  gl_target scene_target, out_target;
  fog_pass *fog;
  transform_plan *plan;
  int map_w, map_h; /* the fogmap's size the plan was made for */
  int levels;
  float *coefficients, *approx[max_levels + 1], *detail[max_levels + 1];
  transform_grid approx_grid[max_levels + 1], detail_grid[max_levels];
  transform_grid finest; /* level J: the fogmap itself, what mu = 1 shows */
  fog_integrator integrator;
  vdb_frame_desc frame_desc;
  float *rgba, *rgb;
  double profile_coefficients[VDB_PROFILE_MAX_KNOTS];
} preview;

static const float flat_heights[4] = {0, 0, 0, 0};

/* vdb_render's camera: VDB (3,-5,3.5) looking at (3,3,0.2); our world is Blender's
 * shifted by the domain min (-3,-3,0) then (x, z, -y); 44.8 deg horizontal fov. */
static camera preview_camera(void) {
  camera cam = {.position = {0, 3.5, 8},
                .fov_y = 2 * atan(tan(0.5 * 44.8 * 3.14159265358979323846 / 180) * H / W),
                    .near_plane = CAMERA_DEFAULT_NEAR, .far_plane = CAMERA_DEFAULT_FAR};
  camera_look_at(&cam, (const double[3]){0, 0.2, 0});
  return cam;
}

static int preview_create(preview *p, int map_w, int map_h, char *error, size_t size) {
  fog_error err = {0};
  *p = (preview){.map_w = map_w, .map_h = map_h};
  p->ctx = gl_context_create(&(gl_context_desc){0}, &err);
  if (!p->ctx) goto fail;
  scene_desc sd = {.terrain = {.origin = {-20, 0, -20}, .size = {40, 40}, .height = 1,
                               .heights = flat_heights, .heights_width = 2, .heights_height = 2},
                   .light = scene_light_default()};
  if (scene_geometry_create(&p->geo, &sd, &err)) goto fail;
  if (!(p->scene = scene_pass_create(&p->geo, &err))) goto fail;
  if (scene_target_create(&p->scene_target, W, H, &err)) goto fail;
  if (gl_target_create(&p->out_target,
                       &(gl_target_desc){.width = W, .height = H,
                                         .color_formats = {GL_RGBA32F, GL_R32F}},
                       &err))
    goto fail;
  if (!(p->fog = fog_pass_create(&err))) goto fail;
  fog_error terr = {0};
  p->levels = transform_max_levels(map_w, map_h, TRANSFORM_SYMMETRIC);
  if (p->levels > max_levels) p->levels = max_levels;
  transform_desc td = {.width = map_w, .height = map_h, .levels = p->levels,
                       .basis = TRANSFORM_LINEAR, .boundary = TRANSFORM_SYMMETRIC};
  if (!(p->plan = transform_plan_create(&td, &terr))) {
    snprintf(error, size, "transform: %s", terr.message);
    return 1;
  }
  p->coefficients = transform_alloc_floats((size_t)map_w * map_h);
  if (!p->coefficients) goto out_of_memory;
  for (int l = 0; l <= p->levels; l++) {
    int w, h;
    transform_level_size(p->plan, l, &w, &h);
    p->approx[l] = transform_alloc_floats((size_t)w * h);
    p->detail[l] = transform_alloc_floats((size_t)w * h);
    if (!p->approx[l] || !p->detail[l]) goto out_of_memory;
    if (transform_grid_create_level(p->plan, l, p->approx[l], &p->approx_grid[l], &terr) ||
        (l > 0 && transform_grid_create_level(p->plan, l, p->detail[l], &p->detail_grid[l - 1],
                                              &terr))) {
      snprintf(error, size, "transform grids: %s", terr.message);
      return 1;
    }
  }
  if (transform_grid_create_level(p->plan, p->levels, p->coefficients, &p->finest, &terr)) {
    snprintf(error, size, "transform grids: %s", terr.message);
    return 1;
  }
  p->rgba = malloc((size_t)W * H * 4 * sizeof(float));
  p->rgb = malloc((size_t)W * H * 3 * sizeof(float));
  if (!p->rgba || !p->rgb) goto out_of_memory;
  return 0;
out_of_memory:
  snprintf(error, size, "out of memory for the preview's buffers");
  return 1;
fail:
  snprintf(error, size, "%s", err.message);
  return 1;
}

static void preview_destroy(preview *p) {
  for (int l = 0; l <= max_levels; l++) {
    free(p->approx[l]);
    free(p->detail[l]);
    transform_grid_destroy(&p->approx_grid[l]);
    if (l < max_levels) transform_grid_destroy(&p->detail_grid[l]);
  }
  transform_grid_destroy(&p->finest);
  free(p->coefficients);
  free(p->rgba);
  free(p->rgb);
  if (p->plan) transform_plan_destroy(p->plan);
  if (p->fog) fog_pass_destroy(p->fog);
  if (p->out_target.framebuffer) gl_target_destroy(&p->out_target);
  if (p->scene_target.framebuffer) gl_target_destroy(&p->scene_target);
  if (p->scene) scene_pass_destroy(p->scene);
  scene_geometry_destroy(&p->geo);
  if (p->ctx) gl_context_destroy(p->ctx);
}

/* One preview: import + project, transform, render, read back, PNG. Times in seconds. */
static int preview_frame(preview *p, const char *vdb, const char *png, double times[parts_count],
                         char *error, size_t size) {
  fog_error serr = {0};
  fog_error rerr = {0};
  double t0 = app_clock_seconds();
  vdb_frame frame;
  if (vdb_frame_load(vdb, &p->frame_desc, &frame, &serr)) {
    snprintf(error, size, "%s", serr.message);
    return 1;
  }
  double t1 = app_clock_seconds();
  if (frame.map.width != p->map_w || frame.map.height != p->map_h) {
    snprintf(error, size, "%s: a %dx%d fogmap where the plan is %dx%d", vdb, frame.map.width,
             frame.map.height, p->map_w, p->map_h);
    vdb_frame_destroy(&frame);
    return 1;
  }
  transform_forward(p->plan, frame.map.density, p->coefficients);
  fog_error perr = {0};
  if (transform_density_pyramid(p->plan, frame.map.density, p->coefficients, p->approx,
                                p->levels > 0 ? p->detail : NULL, &perr)) {
    snprintf(error, size, "%s", perr.message);
    vdb_frame_destroy(&frame);
    return 1;
  }
  fog_error terr = {0};
  for (int l = 0; l <= p->levels; l++) {
    transform_grid_export(p->plan, l, p->approx[l], &p->approx_grid[l], &terr);
    if (l > 0) transform_grid_export(p->plan, l, p->detail[l], &p->detail_grid[l - 1], &terr);
  }
  transform_grid_export(p->plan, p->levels, frame.map.density, &p->finest, &terr);
  double t2 = app_clock_seconds();
  const vdb_profile *g = &frame.profile;
  for (int k = 0; k < g->count; k++) p->profile_coefficients[k] = g->values[k];
  fog_volume volume = {
      .map_width = frame.map.width, .map_height = frame.map.height,
      .origin_x = frame.fogmap_place.origin_x, .origin_z = frame.fogmap_place.origin_z,
      .cell_size = frame.fogmap_place.cell_size,
      .extinction = 6.0, /* vdb_render's absorb 2 + scatter 4 per unit density */
      .profile = {.kind = g->kind == VDB_PROFILE_EXPONENTIAL ? FOG_PROFILE_EXPONENTIAL
                                                             : FOG_PROFILE_BSPLINE,
                  .y_floor = g->y_bottom, .y_top = g->y_top, .y0 = g->y_bottom,
                  .scale_height = g->scale_height,
                  .count = g->count, .degree = g->degree,
                  .coefficients = p->profile_coefficients, .origin = g->origin,
                  .spacing = g->spacing}};
  const camera cam = preview_camera();
  /* The full-detail fogmap (A_J, what LOD mu = 1 shows) as one grid: the pyramid above
   * is what the LOD variants would upload. */
  fog_pass_params params = {.volume = &volume, .fog_colour = {0.8f, 0.8f, 0.8f},
                            .integrator = p->integrator, .march_steps = FOG_PASS_MARCH_STEPS,
                            .walk = {.transmittance_cutoff = FOG_PASS_TRANSMITTANCE_CUTOFF}};
  int status = fog_pass_upload_grid(p->fog, 0, &p->finest, &rerr);
  double t2b = t2, t2c = t2;
  if (!status) {
    scene_pass_run(p->scene, &cam, &p->scene_target);
    fog_pass_finish(); /* glFinish: each GL stage timed on its own */
    t2b = app_clock_seconds();
    gl_target_bind(&p->out_target);
    status = fog_pass_draw(p->fog, &cam, &params, p->scene_target.color[0],
                           p->scene_target.color[1], W, H, &rerr);
    fog_pass_finish();
    t2c = app_clock_seconds();
  }
  if (!status) status = gl_target_read(&p->out_target, 0, 4, p->rgba, &rerr);
  double t3 = app_clock_seconds();
  vdb_frame_destroy(&frame);
  if (status) {
    snprintf(error, size, "render: %s", rerr.message);
    return 1;
  }
  for (int i = 0; i < W * H; i++)
    for (int c = 0; c < 3; c++) p->rgb[3 * i + c] = p->rgba[4 * i + c];
  /* rounded, as vdb_render writes its PNG: the same image work on both sides (dithering
   * costs ~4 ms more here, the deflate of a pattern with no runs) */
  if (image_write_png_srgb(png, W, H, 3, p->rgb, SRGB8_ROUND, &serr)) {
    snprintf(error, size, "%s", serr.message);
    return 1;
  }
  double t4 = app_clock_seconds();
  times[0] = t1 - t0;
  times[1] = t2 - t1;
  times[2] = t2b - t2;
  times[3] = t2c - t2b;
  times[4] = t3 - t2c;
  times[5] = t4 - t3;
  return 0;
}

/* ---- For comparison only: the 2.5D model rendered on the CPU by this bench (not the
 * product's renderer): per pixel, transmittance by a midpoint march of f (bilinear on the
 * cell centres, the linear B-spline) times g (tabulated), half a cell per step, clipped by
 * the fog box and the ground plane y = 0; 2 threads. Shows how much of the preview time
 * is the model and how much is llvmpipe. */
enum { g_table_size = 1024 };

typedef struct cpu_render {
  const vdb_frame *frame;
  const camera *cam;
  double right[3], up[3], forward[3];
  double box_lo[3], box_hi[3];
  float g_table[g_table_size + 1];
  double g_y0, g_scale;
  float *rgb;
  int row_begin, row_end;
} cpu_render;

static double cpu_transmittance(const cpu_render *c, const double d[3]) {
  const double *o = c->cam->position;
  double t0, t1;
  if (!ray_box_clip(o, d, c->box_lo, c->box_hi, &t0, &t1)) return 1;
  t0 = fmax(t0, 0.0); /* the ray starts at the camera */
  if (d[1] < 0) t1 = fmin(t1, -o[1] / d[1]); /* the ground */
  if (!(t1 > t0)) return 1;
  const vdb_fogmap_place *pl = &c->frame->fogmap_place;
  const fogmap *m = &c->frame->map;
  const double step = 0.5 * pl->cell_size;
  const int n = (int)ceil((t1 - t0) / step);
  const double dt = (t1 - t0) / n;
  const double inv_cell = 1.0 / pl->cell_size;
  double tau = 0;
  for (int s = 0; s < n; s++) {
    const double t = t0 + (s + 0.5) * dt;
    const double gy = (o[1] + t * d[1] - c->g_y0) * c->g_scale;
    if (!(gy >= 0 && gy < g_table_size)) continue;
    const int gi = (int)gy;
    const double g = c->g_table[gi] + (gy - gi) * (c->g_table[gi + 1] - c->g_table[gi]);
    if (g <= 0) continue;
    const double u = (o[0] + t * d[0] - pl->origin_x) * inv_cell - 0.5;
    const double v = (o[2] + t * d[2] - pl->origin_z) * inv_cell - 0.5;
    const int i0 = (int)floor(u), j0 = (int)floor(v);
    const double wu = u - i0, wv = v - j0;
    double f = 0;
    for (int dj = 0; dj < 2; dj++) {
      const int j = j0 + dj;
      if (j < 0 || j >= m->height) continue;
      const float *row = m->density + (size_t)j * m->width;
      const double w = dj ? wv : 1 - wv;
      if (i0 >= 0 && i0 < m->width) f += w * (1 - wu) * row[i0];
      if (i0 + 1 >= 0 && i0 + 1 < m->width) f += w * wu * row[i0 + 1];
    }
    tau += f * g;
    if (tau * dt > 2.0) break; /* exp(-6·2) ~ 6e-6: opaque */
  }
  return exp(-6.0 * tau * dt); /* extinction 6: vdb_render's absorb 2 + scatter 4 */
}

static void *cpu_render_rows(void *arg) {
  const cpu_render *c = arg;
  for (int py = c->row_begin; py < c->row_end; py++)
    for (int px = 0; px < W; px++) {
      const double nx = 2 * (px + 0.5) / W - 1, ny = 1 - 2 * (py + 0.5) / H;
      double d[3];
      for (int a = 0; a < 3; a++) d[a] = c->forward[a] + nx * c->right[a] + ny * c->up[a];
      const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (int a = 0; a < 3; a++) d[a] /= len;
      const double tr = cpu_transmittance(c, d);
      const float ground[3] = {0.38f, 0.52f, 0.28f}, sky[3] = {0.75f, 0.8f, 0.85f};
      const float *bg = d[1] < 0 ? ground : sky;
      for (int k = 0; k < 3; k++)
        c->rgb[3 * ((size_t)py * W + px) + k] = (float)(tr * bg[k] + (1 - tr) * 0.8);
    }
  return NULL;
}

/* import + project + CPU render + PNG; times[0] import, [1] render, [2] PNG. */
static int cpu_preview(const char *vdb, const camera *cam, float *rgb, const char *png,
                       double times[3], char *error, size_t size) {
  fog_error serr = {0};
  const double t0 = app_clock_seconds();
  vdb_frame frame;
  if (vdb_frame_load(vdb, &(vdb_frame_desc){0}, &frame, &serr)) {
    snprintf(error, size, "%s", serr.message);
    return 1;
  }
  const double t1 = app_clock_seconds();
  cpu_render c[2];
  c[0] = (cpu_render){.frame = &frame, .cam = cam, .rgb = rgb};
  camera_basis(cam, W, H, c[0].right, c[0].up, c[0].forward);
  const vdb_fogmap_place *pl = &frame.fogmap_place;
  const vdb_profile *g = &frame.profile;
  c[0].box_lo[0] = pl->origin_x;
  c[0].box_hi[0] = pl->origin_x + pl->width * pl->cell_size;
  c[0].box_lo[1] = g->y_bottom;
  c[0].box_hi[1] = g->y_top;
  c[0].box_lo[2] = pl->origin_z;
  c[0].box_hi[2] = pl->origin_z + pl->height * pl->cell_size;
  c[0].g_y0 = g->y_bottom;
  c[0].g_scale = g_table_size / (g->y_top - g->y_bottom);
  for (int k = 0; k <= g_table_size; k++)
    c[0].g_table[k] = (float)vdb_profile_eval(g, g->y_bottom + k / c[0].g_scale);
  c[1] = c[0];
  c[0].row_begin = 0;
  c[0].row_end = c[1].row_begin = H / 2;
  c[1].row_end = H;
  pthread_t worker;
  const int threaded = pthread_create(&worker, NULL, cpu_render_rows, &c[1]) == 0;
  cpu_render_rows(&c[0]);
  if (threaded)
    pthread_join(worker, NULL);
  else
    cpu_render_rows(&c[1]);
  const double t2 = app_clock_seconds();
  vdb_frame_destroy(&frame);
  if (image_write_png_srgb(png, W, H, 3, rgb, SRGB8_ROUND, &serr)) { /* as preview_frame */
    snprintf(error, size, "%s", serr.message);
    return 1;
  }
  times[0] = t1 - t0;
  times[1] = t2 - t1;
  times[2] = app_clock_seconds() - t2;
  return 0;
}

int bench_import(int argc, char **argv) {
  int runs = 3, preview_runs = 5, knots = 0, resolution = 0;
  bool march_flag = false, exponential_flag = false;
  const char *exe = "/usr/bin/vdb_render", *images = NULL;
  const cli_option options[] = {
      {.kind = CLI_INT, .name = "--runs", .value = "N", .target = &runs, .min = 1,
       .max = max_runs, .help = "import runs after a warm-up (default 3)"},
      {.kind = CLI_INT, .name = "--preview-runs", .value = "N", .target = &preview_runs,
       .min = 1, .max = max_runs, .help = "preview runs after a warm-up (default 5)"},
      {.kind = CLI_TEXT, .name = "--vdb-render", .value = "PATH", .target = &exe,
       .help = "the vdb_render to time (default /usr/bin/vdb_render)"},
      {.kind = CLI_TEXT, .name = "--images", .value = "DIR", .target = &images,
       .help = "keep both preview images there (fogpipe.png, vdb_render.png; the\n"
               "folder is created if missing)"},
      {.kind = CLI_SECTION,
       .name = "preview variants (default: native 64x64 fogmap, B-spline profile with one knot\n"
               "per layer, exact integral):"},
      {.kind = CLI_INT, .name = "--resolution", .value = "N", .target = &resolution, .min = 1,
       .max = 4096, .help = "fogmap cells along the longer side"},
      {.kind = CLI_INT, .name = "--profile-knots", .value = "N", .target = &knots, .min = 1,
       .max = VDB_PROFILE_MAX_KNOTS, .help = "B-spline profile coefficients"},
      {.kind = CLI_FLAG, .name = "--exponential", .target = &exponential_flag,
       .help = "exponential profile"},
      {.kind = CLI_FLAG, .name = "--march", .target = &march_flag,
       .help = "the summary's B from the fog pass's 64-step ray march\n"
               "(default: the exact integral; both are measured)"},
  };
  const bench_command command = {
      .stage = "import",
      .usage = "[--runs N] [--preview-runs N] [--vdb-render PATH]\n"
               "                            [--images DIR] [preview variants]",
      .about = "Import: every frame of ../shared/data/vdb/groundfog (read + project + profile +\n"
               "resample), N runs after a warm-up, median ms per frame.\n"
               "Preview of frame 48 at 640x480, median of --preview-runs after a warm-up:\n"
               "fogpipe = import + project + transform + headless GL render + readback + PNG, with\n"
               "the GL context and shaders made once before (an open viewer's situation; the cold\n"
               "first frame is printed too); vdb_render = the whole command (its own read, ray\n"
               "march with lighting, PNG) with -light given all 6 numbers.",
      CLI_OPTIONS(options)};
  int exit_status = bench_parse(&command, argc, argv);
  if (exit_status >= 0) return exit_status;
  const int march = march_flag, exponential = exponential_flag;

  bench_print_build();
  const char *pattern = FOGPIPE_SOURCE_DIR "/../shared/data/vdb/groundfog/data/fluid_data_####.vdb";
  const char *inputs[] = {pattern};
  vdb_sequence seq;
  fog_error err = {0};
  if (vdb_sequence_find(inputs, 1, -1, -1, &seq, &err)) {
    fprintf(stderr, "fogpipe bench import: %s\n", err.message);
    return 1;
  }
  char folder_error[512];
  if (images && bench_make_folder(images, folder_error, sizeof folder_error)) {
    /* refused before the work, not found out as a failed preview after it */
    fprintf(stderr, "fogpipe bench import: --images: %s\n", folder_error);
    vdb_sequence_destroy(&seq);
    return 1;
  }
  /* 1. Import per frame: read alone, and the whole frame load. */
  const int n = seq.count;
  double *read_ms = malloc((size_t)n * runs * sizeof(double));
  double *frame_ms = malloc((size_t)n * runs * sizeof(double));
  if (!read_ms || !frame_ms) {
    fprintf(stderr, "fogpipe bench import: out of memory for %d x %d timings\n", n, runs);
    free(read_ms);
    free(frame_ms);
    vdb_sequence_destroy(&seq);
    return 1;
  }
  double mass_sum = 0;
  int status = 0;
  for (int r = -1; r < runs && !status; r++) { /* r = -1: warm-up (file cache, OpenVDB init) */
    for (int i = 0; i < n && !status; i++) {
      vdb_dense_grid g;
      double t0 = app_clock_seconds();
      if (vdb_read_dense(seq.paths[i], NULL, &g, &err)) {
        status = 1;
        break;
      }
      double t1 = app_clock_seconds();
      vdb_dense_grid_destroy(&g);
      vdb_frame f;
      double t2 = app_clock_seconds();
      if (vdb_frame_load(seq.paths[i], &(vdb_frame_desc){0}, &f, &err)) {
        status = 1;
        break;
      }
      double t3 = app_clock_seconds();
      if (r == 0) mass_sum += f.columns.mass;
      vdb_frame_destroy(&f);
      if (r >= 0) {
        read_ms[r * n + i] = 1e3 * (t1 - t0);
        frame_ms[r * n + i] = 1e3 * (t3 - t2);
      }
    }
  }
  if (status) {
    fprintf(stderr, "fogpipe bench import: %s\n", err.message);
    free(read_ms);
    free(frame_ms);
    vdb_sequence_destroy(&seq);
    return 1;
  }
  const double read_median = app_median(read_ms, n * runs);
  const double frame_median = app_median(frame_ms, n * runs);
  printf("\nimport of %s: %d frames x %d runs (after a warm-up), 64x64x16 half-float BLOSC\n",
         pattern, n, runs);
  printf("%-44s %10s\n", "stage", "median ms");
  printf("%-44s %10.3f\n", "read density -> dense (OpenVDB)", read_median);
  printf("%-44s %10.3f\n", "frame: read + config + project + profile + fogmap", frame_median);
  printf("(total mass of the %d frames: %.6g)\n", n, mass_sum);
  free(read_ms);
  free(frame_ms);

  /* 2. Preview of the last frame. */
  const char *vdb = seq.paths[n - 1];
  char dir[512];
  if (images) {
    snprintf(dir, sizeof dir, "%s", images); /* made once the data was found */
  } else {
    snprintf(dir, sizeof dir, "/tmp/fogpipe_bench_import_XXXXXX");
    if (!mkdtemp(dir)) {
      fprintf(stderr, "fogpipe bench import: cannot make a temporary folder\n");
      vdb_sequence_destroy(&seq);
      return 1;
    }
  }
  char ours_png[700], theirs_png[700];
  snprintf(ours_png, sizeof ours_png, "%s/fogpipe.png", dir);
  snprintf(theirs_png, sizeof theirs_png, "%s/vdb_render.png", dir);
  preview p;
  char error[1024] = "";
  double cold = 0, warm[max_runs], parts[parts_count][max_runs];
  const vdb_frame_desc frame_desc = {
      .profile = {.kind = exponential ? VDB_PROFILE_EXPONENTIAL : VDB_PROFILE_BSPLINE,
                  .knots = knots},
      .resolution = resolution};
  /* The fogmap's size at this --resolution sizes the transform plan (not timed). */
  int map_w = 0, map_h = 0;
  {
    vdb_frame probe;
    if (vdb_frame_load(vdb, &frame_desc, &probe, &err)) {
      fprintf(stderr, "fogpipe bench import: %s\n", err.message);
      vdb_sequence_destroy(&seq);
      return 1;
    }
    map_w = probe.map.width, map_h = probe.map.height;
    vdb_frame_destroy(&probe);
  }
  const double t_cold = app_clock_seconds();
  int gl_ok = !preview_create(&p, map_w, map_h, error, sizeof error);
  p.integrator = march ? FOG_INTEGRATOR_MARCH : FOG_INTEGRATOR_EXACT;
  p.frame_desc = frame_desc;
  double times[parts_count];
  if (gl_ok && !preview_frame(&p, vdb, ours_png, times, error, sizeof error)) {
    cold = app_clock_seconds() - t_cold;
    for (int r = 0; r < preview_runs && gl_ok; r++) {
      if (preview_frame(&p, vdb, ours_png, times, error, sizeof error)) {
        gl_ok = 0;
        break;
      }
      warm[r] = 0;
      for (int k = 0; k < parts_count; k++) {
        warm[r] += times[k];
        parts[k][r] = times[k];
      }
    }
  } else {
    gl_ok = 0;
  }
  /* The other fog-pass integrator, same frame, same run (totals only). */
  double other[max_runs];
  int other_ok = gl_ok;
  if (gl_ok) {
    p.integrator = march ? FOG_INTEGRATOR_EXACT : FOG_INTEGRATOR_MARCH;
    other_ok = !preview_frame(&p, vdb, ours_png, times, error, sizeof error); /* JIT */
    for (int r = 0; r < preview_runs && other_ok; r++) {
      other_ok = !preview_frame(&p, vdb, ours_png, times, error, sizeof error);
      other[r] = 0;
      for (int k = 0; k < parts_count; k++) other[r] += times[k];
    }
    p.integrator = march ? FOG_INTEGRATOR_MARCH : FOG_INTEGRATOR_EXACT;
    preview_frame(&p, vdb, ours_png, times, error, sizeof error); /* the image kept */
    printf("\npreview of %s at %dx%d (GL: %s, %s)\n", vdb, W, H, gl_context_renderer(p.ctx),
           gl_context_version(p.ctx));
  }
  preview_destroy(&p);
  if (!gl_ok)
    printf("\npreview of %s at %dx%d: the GL path failed (%s); the summary's B comes from\n"
           "this bench's CPU march of f*g instead\n", vdb, W, H, error);
  /* The same frame through this bench's own CPU march of f·g (for comparison). */
  char cpu_png[700];
  snprintf(cpu_png, sizeof cpu_png, "%s/fogpipe_cpu.png", dir);
  float *cpu_rgb = malloc((size_t)W * H * 3 * sizeof(float));
  double cpu_total[max_runs], cpu_render_s[max_runs], cpu_times[3];
  const camera cam = preview_camera();
  int cpu_ok = cpu_rgb && !cpu_preview(vdb, &cam, cpu_rgb, cpu_png, cpu_times, error, sizeof error);
  for (int r = 0; r < preview_runs && cpu_ok; r++) {
    cpu_ok = !cpu_preview(vdb, &cam, cpu_rgb, cpu_png, cpu_times, error, sizeof error);
    cpu_total[r] = cpu_times[0] + cpu_times[1] + cpu_times[2];
    cpu_render_s[r] = cpu_times[1];
  }
  free(cpu_rgb);
  double theirs[max_runs];
  int theirs_ok = time_vdb_render(exe, vdb, theirs_png) >= 0; /* warm-up */
  for (int r = 0; r < preview_runs && theirs_ok; r++) {
    theirs[r] = time_vdb_render(exe, vdb, theirs_png);
    if (theirs[r] < 0) theirs_ok = 0;
  }
  double ours_median = NAN;
  printf("%-52s %10s\n", "fogpipe preview (median of runs)", "ms");
  if (gl_ok) {
    ours_median = app_median(warm, preview_runs);
    const char *const part_names[parts_count] = {
        "  import + project + profile (vdb_frame_load)", "  wavelet transform (linear, 3 levels)",
        "  upload + scene pass (GL, terrain + sky)",
        march ? "  fog pass (GL, ray march, 64 steps per pixel)"
              : "  fog pass (GL, exact integral per pixel)",
        "  readback (RGBA32F)", "  PNG write"};
    for (int k = 0; k < parts_count; k++)
      printf("%-52s %10.2f\n", part_names[k], 1e3 * app_median(parts[k], preview_runs));
    printf("%-52s %10.2f\n", "  total, warm (context + shaders made before)", 1e3 * ours_median);
    printf("%-52s %10.2f\n", "  first frame, cold (context + shader JIT included)", 1e3 * cold);
    if (other_ok)
      printf("%-52s %10.2f\n",
             march ? "  total, warm, with the exact fog pass instead"
                   : "  total, warm, with the 64-step ray-march fog pass",
             1e3 * app_median(other, preview_runs));
  }
  double cpu_median = NAN;
  if (cpu_ok) {
    cpu_median = app_median(cpu_total, preview_runs);
    printf("%-52s %10.2f\n", "for comparison: this bench's CPU march of f*g, total",
           1e3 * cpu_median);
    printf("%-52s %10.2f\n", "  of which the march (2 threads, half-cell steps)",
           1e3 * app_median(cpu_render_s, preview_runs));
  }
  double speedup = NAN;
  if (theirs_ok) {
    const double theirs_median = app_median(theirs, preview_runs);
    printf("%-52s %10.2f\n", "vdb_render (whole command, lit ray march, PNG)", 1e3 * theirs_median);
    if (gl_ok) {
      speedup = theirs_median / ours_median;
      printf("speedup vs vdb_render: %.1fx warm, %.1fx cold (GL fog pass, %s: the summary's B);\n"
             "  with the %s fog pass: %.1fx; with the CPU march of f*g: %.1fx\n",
             speedup, theirs_median / cold, march ? "ray march" : "exact",
             march ? "exact" : "ray-march", other_ok ? theirs_median / app_median(other, preview_runs) : NAN,
             theirs_median / cpu_median);
    } else {
      speedup = theirs_median / cpu_median;
      printf("speedup vs vdb_render: %.1fx (CPU march of f*g; GL path unavailable)\n", speedup);
    }
  } else {
    printf("vdb_render (%s) failed or is missing: no speedup measured\n", exe);
  }
  if (images)
    printf("images: %s, %s, %s\n", ours_png, cpu_png, theirs_png);
  else {
    unlink(cpu_png);
    unlink(ours_png);
    unlink(theirs_png);
    rmdir(dir);
  }
  vdb_sequence_destroy(&seq);
  printf("import: ms_per_frame=%.3f preview_speedup_vs_vdb_render=%.1f\n", frame_median, speedup);
  return 0;
}
