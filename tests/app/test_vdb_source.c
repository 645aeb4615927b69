/* app/vdb_source.h on the real ground-fog bake (48 Mantaflow frames): at integer frame
 * times the fogmap is exactly vdb_frame_load's fogmap of that frame (loaded on its own,
 * with the sequence's shared grid and profile passed in); halfway it is the average of
 * the two frames; mass follows the linear interpolation and matches the 3D grid's mass;
 * times outside the sequence clamp or loop as configured. Also the [fog] vdb config keys:
 * defaults, the placement/profile override rules and their errors. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/vdb_source.h"
#include "test_util.h"

#define PATTERN "../shared/data/vdb/groundfog/data/fluid_data_####.vdb"

static double map_mass(const fogmap *m, const vdb_source *s) {
  double sum = 0;
  for (size_t k = 0; k < (size_t)m->width * m->height; k++) sum += m->density[k];
  return sum * s->place.cell_size * s->place.cell_size * s->profile.thickness;
}

/* max |a - b| over the cells */
static double max_diff(const fogmap *a, const fogmap *b) {
  double d = 0;
  for (size_t k = 0; k < (size_t)a->width * a->height; k++)
    d = fmax(d, fabs((double)a->density[k] - b->density[k]));
  return d;
}

static int load_frame(const vdb_source *s, int number, fogmap *out) {
  char path[256];
  snprintf(path, sizeof path, "../shared/data/vdb/groundfog/data/fluid_data_%04d.vdb", number);
  vdb_frame frame;
  fog_error err;
  vdb_frame_desc desc = {.place = &s->place, .fixed_profile = &s->profile};
  if (vdb_frame_load(path, &desc, &frame, &err)) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  *out = frame.map;
  frame.map = (fogmap){0};
  vdb_frame_destroy(&frame);
  return 0;
}

static void test_sequence(void) {
  vdb_source s;
  fog_error err = {0};
  /* a playback rate is given, never "0 means 24" */
  CHECK(vdb_source_open(&s, &(vdb_source_desc){.path = PATTERN, .fps = 0}, &err) != 0 &&
            strstr(err.message, "expected a positive rate"),
        "fps 0: %s", err.message);
  int status = vdb_source_open(&s, &(vdb_source_desc){.path = PATTERN, .fps = 24}, &err);
  CHECK(status == 0, "open: %s", err.message);
  if (status) return;
  CHECK(s.count == 48 && s.frame_numbers[0] == 1 && s.frame_numbers[47] == 48,
        "48 frames 1..48, got %d", s.count);
  fogmap f10 = {0}, f11 = {0}, f1 = {0}, f48 = {0}, got = {0};
  if (load_frame(&s, 10, &f10) || load_frame(&s, 11, &f11) || load_frame(&s, 1, &f1) ||
      load_frame(&s, 48, &f48)) {
    CHECK(0, "vdb_frame_load");
    goto done;
  }
  /* frame number 10 is index 9: t = 9 / fps */
  CHECK(vdb_source_fogmap_at(&s, 9.0 / 24.0, &got, &err) == 0, "%s", err.message);
  CHECK(got.width == f10.width && got.height == f10.height, "size %dx%d vs %dx%d", got.width,
        got.height, f10.width, f10.height);
  CHECK(max_diff(&got, &f10) == 0, "frame 10 differs by %g", max_diff(&got, &f10));
  CHECK(vdb_source_fogmap_at(&s, 10.0 / 24.0, &got, &err) == 0, "%s", err.message);
  CHECK(max_diff(&got, &f11) == 0, "frame 11 differs by %g", max_diff(&got, &f11));
  /* halfway: exactly the average (0.5·a + 0.5·b is exact in float barring underflow) */
  CHECK(vdb_source_fogmap_at(&s, 9.5 / 24.0, &got, &err) == 0, "%s", err.message);
  double worst = 0;
  for (size_t k = 0; k < (size_t)got.width * got.height; k++)
    worst = fmax(worst, fabs(got.density[k] - 0.5 * ((double)f10.density[k] + f11.density[k])));
  CHECK(worst <= 1e-7, "halfway differs from the average by %g", worst);
  double m10 = map_mass(&f10, &s), m11 = map_mass(&f11, &s);
  CHECK(m10 != m11, "frames 10 and 11 have the same mass %g: weak test", m10);
  /* the fogmap conserves the 3D grid's mass (Σ ρ·voxel volume) */
  CHECK(fabs(m10 - s.mass[9]) <= 1e-4 * s.mass[9], "frame 10 mass %g vs grid %g", m10, s.mass[9]);
  for (int q = 1; q < 4; q++) {
    double w = q / 4.0;
    CHECK(vdb_source_fogmap_at(&s, (9 + w) / 24.0, &got, &err) == 0, "%s", err.message);
    double want = (1 - w) * m10 + w * m11;
    CHECK(fabs(map_mass(&got, &s) - want) <= 1e-5 * want, "mass at w=%g: %g, want %g", w,
          map_mass(&got, &s), want);
  }
  /* clamped: before the start is frame 1, after the end frame 48 */
  CHECK(vdb_source_fogmap_at(&s, -3.0, &got, &err) == 0, "%s", err.message);
  CHECK(max_diff(&got, &f1) == 0, "t < 0 is not frame 1 (%g)", max_diff(&got, &f1));
  CHECK(vdb_source_fogmap_at(&s, 100.0, &got, &err) == 0, "%s", err.message);
  CHECK(max_diff(&got, &f48) == 0, "t past the end is not frame 48 (%g)", max_diff(&got, &f48));
  CHECK(vdb_source_index_of(&s, -1) == 47 && vdb_source_index_of(&s, 10) == 9 &&
            vdb_source_index_of(&s, 99) == -1,
        "index_of");
  /* looped: one period (48 frames / 24 fps = 2 s) later is the same frame; the last
   * interval blends frame 48 into frame 1 */
  s.loop = 1;
  CHECK(fabs(vdb_source_duration(&s) - 2.0) < 1e-12, "duration %g", vdb_source_duration(&s));
  CHECK(vdb_source_fogmap_at(&s, 2.0 + 9.0 / 24.0, &got, &err) == 0, "%s", err.message);
  CHECK(max_diff(&got, &f10) == 0, "loop: t + period is not frame 10");
  CHECK(vdb_source_fogmap_at(&s, -2.0 + 10.0 / 24.0, &got, &err) == 0, "%s", err.message);
  CHECK(max_diff(&got, &f11) == 0, "loop: t - period is not frame 11");
  CHECK(vdb_source_fogmap_at(&s, 47.5 / 24.0, &got, &err) == 0, "%s", err.message);
  worst = 0;
  for (size_t k = 0; k < (size_t)got.width * got.height; k++)
    worst = fmax(worst, fabs(got.density[k] - 0.5 * ((double)f48.density[k] + f1.density[k])));
  CHECK(worst <= 1e-7, "loop: 47.5 is not the average of frames 48 and 1 (%g)", worst);
  /* a fogmap of the wrong size is refused, not overrun */
  fogmap small = {0};
  fogmap_create(&small, 3, 3, &err);
  CHECK(vdb_source_fogmap_at(&s, 0, &small, &err) != 0, "wrong size accepted");
  fogmap_destroy(&small);
done:
  fogmap_destroy(&f10), fogmap_destroy(&f11), fogmap_destroy(&f1), fogmap_destroy(&f48);
  fogmap_destroy(&got);
  vdb_source_destroy(&s);
}

static char dir[] = "/tmp/fogpipe_vdb_source_XXXXXX";

static int load_text(const char *text, scene_config *cfg, fog_error *err) {
  char path[256];
  snprintf(path, sizeof path, "%s/scene.ini", dir);
  FILE *f = fopen(path, "w");
  fputs(text, f);
  fclose(f);
  int status = scene_config_load(path, cfg, err);
  unlink(path);
  return status;
}

static void test_config(void) {
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  char cwd[512], text[1400];
  CHECK(getcwd(cwd, sizeof cwd) != NULL, "getcwd");
  scene_config cfg;
  fog_error err = {0};
  /* defaults */
  snprintf(text, sizeof text, "[fog]\nvdb = %s/" PATTERN "\n", cwd);
  CHECK(load_text(text, &cfg, &err) == 0, "%s", err.message);
  CHECK(cfg.fog.vdb_fps == 24 && cfg.fog.vdb_frame == -1 && cfg.fog.vdb_loop == 0 &&
            cfg.fog.vdb_resolution == 0 && cfg.fog.vdb_up == 0 &&
            !strcmp(cfg.fog.vdb_grid, "density") && cfg.fog.vdb_line == 2,
        "vdb defaults");
  vdb_source s;
  CHECK(vdb_source_open_config(&s, &cfg, &err) == 0, "%s", err.message);
  scene_config applied = cfg;
  CHECK(vdb_source_apply_config(&s, &applied, &err) == 0, "apply: %s", err.message);
  CHECK(applied.box.origin[0] == s.place.origin_x && applied.box.origin[1] == s.place.origin_z &&
            applied.box.cell_size == s.place.cell_size,
        "box not from the VDB");
  CHECK(applied.fog.profile == SCENE_PROFILE_BSPLINE && applied.fog.profile_count == s.profile.count &&
            applied.fog.profile_spacing == s.profile.spacing,
        "profile not from the VDB");
  CHECK(applied.box.floor < applied.box.top && applied.box.floor <= s.profile.origin,
        "box floor/top %g %g", applied.box.floor, applied.box.top);
  /* the groundfog domain is 6 m wide: the fogmap spans it */
  CHECK(fabs(s.place.width * s.place.cell_size - 6.0) < 0.2, "width %g m",
        s.place.width * s.place.cell_size);
  vdb_source_destroy(&s);
  /* what the file sets stays */
  snprintf(text, sizeof text,
           "[fog]\nvdb = %s/" PATTERN "\nprofile = exponential\nvdb_resolution = 32\n"
           "vdb_fps = 12\nvdb_loop = 1\nvdb_frame = 7\n[box]\norigin = 5 6\nfloor = -1\n",
           cwd);
  CHECK(load_text(text, &cfg, &err) == 0, "%s", err.message);
  CHECK(vdb_source_open_config(&s, &cfg, &err) == 0, "%s", err.message);
  applied = cfg;
  CHECK(vdb_source_apply_config(&s, &applied, &err) == 0, "apply: %s", err.message);
  CHECK(applied.box.origin[0] == 5 && applied.box.origin[1] == 6 && applied.box.floor == -1,
        "explicit [box] overridden");
  CHECK(applied.fog.profile == SCENE_PROFILE_EXPONENTIAL, "explicit profile overridden");
  CHECK(s.place.width == 32 || s.place.height == 32, "resolution %dx%d", s.place.width,
        s.place.height);
  CHECK(s.fps == 12 && s.loop == 1 && cfg.fog.vdb_frame == 7, "fps/loop/frame");
  vdb_source_destroy(&s);
  /* errors */
  snprintf(text, sizeof text, "[fog]\nfogmap = %s/data/fogmap_sample.png\n\nvdb = %s/" PATTERN "\n",
           cwd, cwd);
  CHECK(load_text(text, &cfg, &err) != 0, "fogmap + vdb accepted");
  CHECK(strstr(err.message, ":4: [fog] vdb: ") && strstr(err.message, "fogmap") &&
            strstr(err.message, "mutually exclusive"),
        "message: %s", err.message);
  CHECK(load_text("[fog]\nbasis = haar\nvdb = nothere/fluid_####.vdb\n", &cfg, &err) != 0,
        "missing pattern accepted");
  char want[300];
  snprintf(want, sizeof want, "%s/nothere/fluid_####.vdb", dir);
  CHECK(strstr(err.message, ":3: [fog] vdb: ") && strstr(err.message, want) &&
            err.code == FOG_ERR_FILE_ACCESS,
        "message: %s (code %s)", err.message, fog_result_text(err.code));
  CHECK(load_text("[fog]\nvdb = gone.vdb\n", &cfg, &err) != 0, "missing file accepted");
  CHECK(strstr(err.message, ":2: [fog] vdb: ") && strstr(err.message, "gone.vdb") &&
            err.code == FOG_ERR_FILE_ACCESS,
        "message: %s (code %s)", err.message, fog_result_text(err.code));
  CHECK(load_text("[fog]\nvdb_up = x\n", &cfg, &err) != 0 && strstr(err.message, "z|y"),
        "vdb_up: %s", err.message);
  CHECK(load_text("[fog]\nvdb_loop = 2\n", &cfg, &err) != 0, "vdb_loop = 2 accepted");
  CHECK(load_text("[fog]\nvdb_fps = 0\n", &cfg, &err) != 0, "vdb_fps = 0 accepted");
  rmdir(dir);
}

int main(void) {
  test_sequence();
  test_config();
  return test_finish("test_vdb_source");
}
