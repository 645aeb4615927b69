/* A config's `[fog] model` reaches the pixels as docs/config.md says: render_frame (what
 * `fogpipe render` and `view` draw) of homogeneous, height, Gaussian RBF, volume, quadric
 * and Perlin fog (its perlin_ keys, its box the terrain's footprint between [box] floor and
 * top), and the classic linear and exp2 factors, each pixel's transmittance against the CPU
 * model of the documented meaning of the keys (density_scale, fog_height, scale_height,
 * rbf_base, rbf lines, fog_start and fog_end from the camera; quadric lines as
 * test_config_quadric pins them, for model = quadric and beside the height, RBF and Perlin
 * fog, NOISE modulating them by the perlin_ keys' turbulence (K (1 - n + n T / T_mean)); for
 * the volume the VDB frame's grid where the bake put it, integrated exactly), along the
 * pixel's ray to
 * the depth render_frame reports (the sky: to infinity). Max |delta tau| <= 2e-4. `fogpipe
 * record` of an analytic model gives render's image every frame (fog that moves by itself:
 * frames that change, and a frame recorded alone equal to the run's); the live pipeline
 * (pipeline_create) refuses these models, naming the line. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/config.h"
#include "app/pipeline.h"
#include "app/render_frame.h"
#include "render/render.h"
#include "sim/sim.h"
#include "exr_channel_util.h"
#include "model_tau.h"
#include "test_util.h"

enum { W = 96, H = 54 };

/* The volume the keys describe: frame vdb_frame of the sequence, its voxels placed by the
 * VDB's own transform (sim's world map), density_scale applied. values: owned by *frame. */
static volume_grid_desc documented_volume(const scene_config *cfg, vdb_frame *frame) {
  vdb_sequence seq;
  fog_error err = {0};
  const char *input = cfg->fog.vdb;
  volume_grid_desc g = {.values = NULL};
  *frame = (vdb_frame){0};
  if (vdb_sequence_find(&input, 1, -1, -1, &seq, &err)) {
    CHECK(0, "%s", err.message);
    return g;
  }
  int index = seq.count - 1;
  for (int i = 0; i < seq.count; i++)
    if (seq.frames[i] == cfg->fog.vdb_frame) index = i;
  int failed = vdb_frame_load(seq.paths[index], &(vdb_frame_desc){.keep_grid = 1}, frame, &err);
  vdb_sequence_destroy(&seq);
  CHECK(!failed, "%s", err.message);
  if (failed) return g;
  vdb_dense_grid *d = &frame->grid;
  size_t n = (size_t)d->dim[0] * d->dim[1] * d->dim[2];
  for (size_t i = 0; i < n; i++) d->values[i] = (float)(cfg->fog.density_scale * d->values[i]);
  g = (volume_grid_desc){.dim = {d->dim[0], d->dim[1], d->dim[2]}, .values = d->values};
  for (int a = 0; a < 3; a++) { /* world axis a = base + step u along index axis c */
    int c = frame->world.index_axis[a];
    g.index_from_world[c][a] = 1.0 / frame->world.step[a];
    g.index_offset[c] = -frame->world.base[a] / frame->world.step[a] - d->index_min[c];
  }
  return g;
}

/* The model the keys describe (docs/config.md, [fog] model); for model = perlin its octaves
 * in *perlin (fog_perlin_destroy when done). */
static fog_model documented_model(const scene_config *cfg, fog_rbf *rbfs,
                                   fog_quadric *quadrics, fog_perlin *perlin) {
  const scene_fog_config *f = &cfg->fog;
  *perlin = (fog_perlin){0};
  bool noisy = false; /* quadric volumes with NOISE: the perlin_ keys' turbulence */
  for (int i = 0; i < f->quadric_count; i++) noisy = noisy || f->quadrics[i].noise > 0;
  if (f->model == FOG_MODEL_PERLIN || noisy) {
    /* the perlin_ keys; the box: the terrain's footprint between [box] floor and top; one
     * wind triple per octave (or one for all) */
    fog_perlin_desc d = fog_perlin_desc_default();
    d.seed = f->perlin_seed, d.octaves = f->perlin_octaves, d.size = f->perlin_size;
    d.feature_size = f->perlin_feature;
    for (int i = 0; i < d.octaves; i++)
      for (int a = 0; a < 3; a++)
        d.wind[i][a] = f->perlin_wind[f->perlin_wind_count == 3 ? a : 3 * i + a];
    for (int a = 0; a < 3; a += 2) {
      d.lo[a] = cfg->terrain.origin[a];
      d.hi[a] = cfg->terrain.origin[a] + cfg->terrain.size[a / 2];
    }
    d.lo[1] = cfg->box.floor, d.hi[1] = cfg->box.top;
    fog_error e = {0};
    CHECK(fog_perlin_create(perlin, &d, &e) == 0, "perlin: %s", e.message);
  }
  for (int i = 0; i < f->rbf_count; i++) {
    rbfs[i] = f->rbfs[i];
    rbfs[i].density *= f->density_scale;
  }
  for (int i = 0; i < f->quadric_count; i++) {
    quadrics[i] = f->quadrics[i]; /* the shapes' coefficients: test_config_quadric */
    quadrics[i].density *= f->density_scale;
  }
  /* the classic factors: distances from the camera, fog_start and fog_end (linear), the
   * density density_scale (exp2) */
  return (fog_model){.kind = f->model,
                     .extinction = f->model == FOG_MODEL_RBF ? f->rbf_base : f->density_scale,
                     .y0 = f->fog_height, .scale_height = f->scale_height, .rbfs = rbfs,
                     .rbf_count = f->rbf_count, .quadrics = quadrics,
                     .quadric_count = f->quadric_count,
                     .eye = {cfg->camera.position[0], cfg->camera.position[1],
                             cfg->camera.position[2]},
                     .fog_start = f->fog_start, .fog_end = f->fog_end,
                     .perlin = perlin->texels ? perlin : NULL,
                     .time = 0.0, .perlin_integral = (fog_perlin_integral)f->perlin_integral};
}

static void check_config(const char *path, const char *label) {
  scene_config cfg;
  fog_error cerr;
  CHECK(scene_config_load(path, &cfg, &cerr) == 0, "%s: %s", label, cerr.message);
  float *tau = malloc(sizeof(float) * W * H), *depth = malloc(sizeof(float) * W * H);
  render_frame_info info;
  fog_error err;
  if (render_frame(&cfg, W, H, &(frame_pixels){.transmittance = tau, .depth = depth}, &info,
                   &err)) {
    CHECK(0, "%s: render_frame: %s", label, err.message);
    free(tau), free(depth);
    return;
  }
  CHECK(info.has_fog, "%s: rendered without fog", label);
  camera cam;
  scene_config_camera(&cfg, &cam);
  fog_rbf rbfs[FOG_MAX_RBFS];
  fog_quadric quadrics[FOG_MAX_QUADRICS];
  fog_perlin perlin;
  fog_model m = documented_model(&cfg, rbfs, quadrics, &perlin);
  vdb_frame frame = {0};
  volume_grid_desc grid;
  if (cfg.fog.model == FOG_MODEL_VOLUME) {
    grid = documented_volume(&cfg, &frame);
    m.grid3d = &grid;
  }
  const model_tau_error e = model_tau_compare(&m, &cam, tau, depth, W, H);
  const double worst = e.worst, min_tau = e.lowest, max_tau = e.highest;
  printf("%s: max |dtau| %.2e over %dx%d, tau from %.3f to %.3f\n", label, worst, W, H, min_tau,
         max_tau);
  CHECK(worst <= 2e-4, "%s: max |dtau| %.3e", label, worst);
  CHECK(max_tau - min_tau > 0.2, "%s: tau %.3f..%.3f: the fog barely varies in view", label,
        min_tau, max_tau);
  vdb_frame_destroy(&frame);
  fog_perlin_destroy(&perlin);
  free(tau), free(depth);
}

int main(void) {
  char dir[] = "/tmp/fogpipe_models_XXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  static const char *const scene =
      "[camera]\nposition = 0 120 400\nlook_at = 0 20 -100\nfov = 55\n"
      "[terrain]\nsize = 1000 1000\nheight = 120\nresolution = 65\n";
  static const char *const fogs[8][2] = {
      {"homogeneous", "\n[fog]\nmodel = homogeneous\ndensity_scale = 0.003\n"},
      {"height", "\n[fog]\nmodel = height\ndensity_scale = 0.02\nfog_height = 30\n"
                 "scale_height = 25\n"},
      {"rbf", "\n[fog]\nmodel = rbf\nrbf_base = 0.0005\ndensity_scale = 2\n"
              "rbf = -50 20 -50 80 0.01\nrbf = 100 0 0 40 0.02\n"},
      {"linear", "\n[fog]\nmodel = linear\nfog_start = 250\nfog_end = 900\n"},
      {"exp2", "\n[fog]\nmodel = exp2\ndensity_scale = 0.0025\n"},
      /* quadric volumes beside another model's fog: their depth adds (on its density_scale) */
      {"height + quadrics", "\n[fog]\nmodel = height\ndensity_scale = 0.01\nfog_height = 0\n"
                            "scale_height = 25\nquadric = sphere -60 80 -100 70 2 0.5\n"
                            "quadric = cylinder 120 0 -60 30 160 3\n"},
      {"rbf + quadrics", "\n[fog]\nmodel = rbf\nrbf = -50 20 -50 80 0.01\n"
                         "quadric = ellipsoid 100 40 0 90 30 60 0.02 0.3\n"},
      /* thin Perlin fog (K < 1) of three octaves around the camera: the opacity budget of
       * the finer octaves once dropped them (5.8e-2 in tau) */
      {"perlin, thin", "\n[fog]\nmodel = perlin\ndensity_scale = 0.012\nfog_height = 0\n"
                       "scale_height = 30\nperlin_feature = 30\n[box]\nfloor = 0\ntop = 200\n"}};
  for (int k = 0; k < 8; k++) {
    char path[256];
    snprintf(path, sizeof path, "%s/fog%d.ini", dir, k);
    FILE *f = fopen(path, "w");
    fputs(scene, f);
    fputs(fogs[k][1], f);
    fclose(f);
    check_config(path, fogs[k][0]);
    unlink(path);
  }
  /* a sheet 0.34 thick seen from 900 units: Q's matrix in float (6e-8 relative) grew by
   * (distance/size)^2 once re-centred, and the GL drew tau 0.39 where the ray misses it */
  char sheet[256];
  snprintf(sheet, sizeof sheet, "%s/sheet.ini", dir);
  CHECK(test_write_text(sheet, "[camera]\nposition = 0 2400 800\nlook_at = 0 2000 0\nfov = 60\n"
                               "[fog]\nmodel = quadric\n"
                               "quadric = ellipsoid 0 2000 0 300 0.342 300 2\n"),
        "%s", sheet);
  check_config(sheet, "quadric, a thin sheet far off");
  unlink(sheet);
  check_config("configs/rbf_fog_banks.ini", "rbf (configs/rbf_fog_banks.ini)");
  check_config("configs/vdb_plume_volume.ini", "volume (configs/vdb_plume_volume.ini)");
  check_config("configs/quadric_volumes.ini", "quadric (configs/quadric_volumes.ini)");
  check_config("configs/perlin_fog.ini", "perlin (configs/perlin_fog.ini)");
  /* noise inside quadric volumes beside the Perlin fog (its [fog] section is the file's last:
   * the lines append to it): both read its octaves */
  char beside[256];
  snprintf(beside, sizeof beside, "%s/perlin_beside.ini", dir);
  FILE *in = fopen("configs/perlin_fog.ini", "r"), *out = fopen(beside, "w");
  CHECK(in && out, "copy configs/perlin_fog.ini");
  if (in && out) {
    for (int c; (c = fgetc(in)) != EOF;) fputc(c, out);
    fputs("\nquadric = sphere -20 100 -60 45 0.3 0.5 1\n"
          "quadric = cylinder 90 0 -40 20 160 0.4 0 0.6\n", out);
  }
  if (in) fclose(in);
  if (out) fclose(out);
  check_config(beside, "perlin + noisy quadrics");
  unlink(beside);

  /* `fogpipe record` of an analytic model: every frame is render's image (it stands still). */
  const char *bin = getenv("FOGPIPE_BIN");
  CHECK(bin != NULL, "FOGPIPE_BIN is not set (run through ctest)");
  if (bin) {
    char command[1024], still[300], frame[300];
    snprintf(still, sizeof still, "%s/still.exr", dir);
    snprintf(command, sizeof command,
             "'%s' record configs/rbf_fog_banks.ini --frames 2 --size 48x27 --out '%s/rec' > "
             "/dev/null && '%s' render configs/rbf_fog_banks.ini --size 48x27 --out '%s' > "
             "/dev/null",
             bin, dir, bin, still);
    CHECK(system(command) == 0, "%s", command);
    float *want = load_exr_channel(still, "transmittance", 48, 27);
    for (int n = 1; n <= 2; n++) {
      snprintf(frame, sizeof frame, "%s/rec/frame.%04d.exr", dir, n);
      float *got = load_exr_channel(frame, "transmittance", 48, 27);
      double worst = 0.0;
      for (int k = 0; got && want && k < 48 * 27; k++)
        worst = fmax(worst, fabs((double)got[k] - want[k]));
      CHECK(got && want && worst == 0.0, "recorded frame %d differs from render by %g", n, worst);
      free(got);
      unlink(frame);
    }
    free(want);
    unlink(still);
    snprintf(command, sizeof command, "rm -rf '%s/rec'", dir);
    CHECK(system(command) == 0, "cleanup");
  }

  /* Fog that moves by itself (configs/rbf_emitter.ini: puffs from an emitter in the wind;
   * configs/perlin_fog.ini: octaves of turbulence drifting; configs/rbf_steam_eddies.ini:
   * puffs carried by the simulation's flow): the frames change, and frame 3 recorded alone
   * (a farm's range) is frame 3 of the whole run, bit for bit (each frame a closed form of
   * its time, or the flow replayed from its start up to it), and so is `render --time 1`. */
  static const char *const moving[3] = {"rbf_emitter", "perlin_fog", "rbf_steam_eddies"};
  for (int c = 0; bin && c < 3; c++) {
    char command[1024], path[300];
    snprintf(command, sizeof command,
             "'%s' record configs/%s.ini --frames 3 --fps 2 --size 48x27 --out "
             "'%s/all' > /dev/null && '%s' record configs/%s.ini --frames 3-3 --fps 2 "
             "--size 48x27 --out '%s/one' > /dev/null && '%s' render configs/%s.ini "
             "--time 1 --size 48x27 --out '%s/one/still.exr' > /dev/null",
             bin, moving[c], dir, bin, moving[c], dir, bin, moving[c], dir);
    CHECK(system(command) == 0, "%s", command);
    float *frames[3], *alone, *still;
    for (int n = 1; n <= 3; n++) {
      snprintf(path, sizeof path, "%s/all/frame.%04d.exr", dir, n);
      frames[n - 1] = load_exr_channel(path, "transmittance", 48, 27);
    }
    snprintf(path, sizeof path, "%s/one/frame.0003.exr", dir);
    alone = load_exr_channel(path, "transmittance", 48, 27);
    snprintf(path, sizeof path, "%s/one/still.exr", dir);
    still = load_exr_channel(path, "transmittance", 48, 27); /* render --time 1: frame 3's */
    double moved = 0.0, range = 0.0, rendered = 0.0;
    for (int k = 0; frames[0] && frames[2] && alone && still && k < 48 * 27; k++) {
      moved = fmax(moved, fabs((double)frames[2][k] - frames[0][k]));
      range = fmax(range, fabs((double)alone[k] - frames[2][k]));
      rendered = fmax(rendered, fabs((double)still[k] - frames[2][k]));
    }
    printf("%s: frame 3 differs from frame 1 by up to %.3f; recorded alone, by %g; rendered "
           "at its time, by %g\n", moving[c], moved, range, rendered);
    CHECK(frames[0] && frames[2] && alone && still, "%s: the frames were not written",
          moving[c]);
    CHECK(moved > 1e-3, "%s: the fog did not move (%.3e)", moving[c], moved);
    CHECK(range == 0.0, "%s: frame 3 alone differs from frame 3 of the run by %g", moving[c],
          range);
    CHECK(rendered == 0.0, "%s: render --time 1 differs from frame 3 (time 1) by %g",
          moving[c], rendered);
    for (int n = 0; n < 3; n++) free(frames[n]);
    free(alone);
    free(still);
    snprintf(command, sizeof command, "rm -rf '%s/all' '%s/one'", dir, dir);
    CHECK(system(command) == 0, "cleanup");
  }

  /* The flow carries the puffs: the same scene carried by the wind alone looks otherwise. */
  if (bin) {
    char wind[300], command[1200];
    snprintf(wind, sizeof wind, "%s/steam_wind.ini", dir);
    FILE *from = fopen("configs/rbf_steam_eddies.ini", "r"), *to = fopen(wind, "w");
    CHECK(from && to, "copy configs/rbf_steam_eddies.ini");
    char line[512];
    while (from && to && fgets(line, sizeof line, from))
      fputs(strncmp(line, "rbf_carrier", 11) ? line : "rbf_carrier = wind\n", to);
    if (from) fclose(from);
    if (to) fclose(to);
    /* the copy's paths resolve against its own folder: the scene has none */
    snprintf(command, sizeof command,
             "'%s' render configs/rbf_steam_eddies.ini --time 1 --size 48x27 --out '%s/sim.exr' "
             "> /dev/null && '%s' render '%s' --time 1 --size 48x27 --out '%s/wind.exr' > "
             "/dev/null", bin, dir, bin, wind, dir);
    CHECK(system(command) == 0, "%s", command);
    char path[300];
    snprintf(path, sizeof path, "%s/sim.exr", dir);
    float *sim = load_exr_channel(path, "transmittance", 48, 27);
    snprintf(path, sizeof path, "%s/wind.exr", dir);
    float *by_wind = load_exr_channel(path, "transmittance", 48, 27);
    double apart = 0.0;
    for (int k = 0; sim && by_wind && k < 48 * 27; k++)
      apart = fmax(apart, fabs((double)sim[k] - by_wind[k]));
    printf("rbf_steam_eddies at 1 s: carried by the flow, up to %.3f from the wind alone\n",
           apart);
    CHECK(sim && by_wind && apart > 1e-2, "the flow carried the puffs as the wind alone does "
          "(%.3e)", apart);
    free(sim);
    free(by_wind);
    snprintf(command, sizeof command, "rm -f '%s' '%s/sim.exr' '%s/wind.exr'", wind, dir, dir);
    CHECK(system(command) == 0, "cleanup");
  }

  /* The live animation has nothing to simulate in an analytic model. */
  scene_config cfg;
  fog_error cerr;
  CHECK(scene_config_load("configs/rbf_fog_banks.ini", &cfg, &cerr) == 0, "%s", cerr.message);
  fog_error perr = {0};
  pipeline *p = pipeline_create(
      &(pipeline_desc){.config = &cfg, .width = 32, .height = 18, .frame_seconds = 1.0 / 24.0},
      &perr);
  CHECK(p == NULL, "the pipeline accepted model = rbf");
  if (p) pipeline_destroy(p);
  char want[128];
  snprintf(want, sizeof want, "configs/rbf_fog_banks.ini:%d: [fog] model = rbf: ",
           cfg.fog.model_line);
  CHECK(cfg.fog.model_line > 0 && strstr(perr.message, want) == perr.message,
        "pipeline error '%s' does not start with '%s'", perr.message, want);
  /* A frame's simulated time has no "0 means the default": 0 and past the most are refused. */
  CHECK(scene_config_load("configs/default.ini", &cfg, &cerr) == 0, "%s", cerr.message);
  const double bad_seconds[2] = {0.0, 2.0 * PIPELINE_MAX_FRAME_SECONDS};
  for (int k = 0; k < 2; k++) {
    p = pipeline_create(&(pipeline_desc){.config = &cfg, .width = 32, .height = 18,
                                         .frame_seconds = bad_seconds[k]},
                        &perr);
    CHECK(p == NULL && perr.code == FOG_ERR_INVALID_ARGUMENT &&
              strstr(perr.message, "expected more than 0 and at most"),
          "frame_seconds %g: %s", bad_seconds[k], p ? "accepted" : perr.message);
    if (p) pipeline_destroy(p);
  }
  rmdir(dir);
  return test_finish("test_render_fog_models");
}
