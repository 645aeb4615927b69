/* scene_config_write (what `fogpipe bake` writes its bake.ini with) gives a config that
 * loads back into the same scene: for every shipped config, write, load again, and the
 * scene's fingerprint (every key's value, the files' contents) is the same, and so is a
 * second write's text. A list of 64 numbers (a B-spline profile, fit's projected fogmap)
 * is more than a config line holds: it is written over indented lines and reads back bit
 * for bit; indented lines append to a list, past 64 numbers an error names the line. A
 * folder that cannot be written is an error naming the file, with nothing left behind. */
#define _XOPEN_SOURCE 700
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/config.h"
#include "test_util.h"

static char *read_text(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  static char buffer[1 << 16];
  size_t n = fread(buffer, 1, sizeof buffer - 1, f);
  fclose(f);
  buffer[n] = '\0';
  return strdup(buffer);
}

/* The config `text` written to path and loaded into *cfg: scene_config_load's status. */
static int load_text(const char *path, const char *text, scene_config *cfg, fog_error *err) {
  FILE *f = fopen(path, "w");
  if (f) fputs(text, f), fclose(f);
  return scene_config_load(path, cfg, err);
}

int main(void) {
  char dir[] = "/tmp/fogpipe-config-write-XXXXXX";
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  DIR *d = opendir("configs");
  CHECK(d != NULL, "no configs/ folder (run from the source tree)");
  int checked = 0;
  struct dirent *e;
  while (d && (e = readdir(d))) {
    size_t n = strlen(e->d_name);
    if (n < 5 || strcmp(e->d_name + n - 4, ".ini")) continue;
    char path[600], first[700], second[700];
    snprintf(path, sizeof path, "configs/%s", e->d_name);
    snprintf(first, sizeof first, "%s/first.ini", dir);
    snprintf(second, sizeof second, "%s/second.ini", dir);
    scene_config a, b, c;
    fog_error err = {0};
    if (scene_config_load(path, &a, &err)) {
      CHECK(0, "%s: %s", path, err.message);
      continue;
    }
    CHECK(scene_config_write(&a, first, &err) == 0, "%s: write: %s", path, err.message);
    CHECK(scene_config_load(first, &b, &err) == 0, "%s written: %s", path, err.message);
    CHECK(scene_config_fingerprint(&a) == scene_config_fingerprint(&b),
          "%s: the written config is another scene", path);
    /* the display keys, which the fingerprint leaves out, written too */
    CHECK(a.exposure == b.exposure && a.tone_map == b.tone_map,
          "%s: exposure or tone_map lost in writing", path);
    /* ... left out: another exposure or tone map is the same scene for --resume; another
     * image size is not */
    scene_config shown = a;
    shown.exposure += 1.5, shown.tone_map = (shown.tone_map + 1) % 3;
    CHECK(scene_config_fingerprint(&shown) == scene_config_fingerprint(&a),
          "%s: the display transform changes the fingerprint", path);
    shown.width += 2;
    CHECK(scene_config_fingerprint(&shown) != scene_config_fingerprint(&a),
          "%s: the image size does not change the fingerprint", path);
    CHECK(scene_config_write(&b, second, &err) == 0, "%s: second write: %s", path, err.message);
    CHECK(scene_config_load(second, &c, &err) == 0 &&
              scene_config_fingerprint(&c) == scene_config_fingerprint(&a),
          "%s: the second write is another scene", path);
    char *t1 = read_text(first), *t2 = read_text(second);
    CHECK(t1 && t2 && !strcmp(t1, t2), "%s: writing the written config changed its text", path);
    free(t1), free(t2);
    unlink(first), unlink(second);
    checked++;
  }
  if (d) closedir(d);
  CHECK(checked >= 5, "only %d configs checked", checked);
  /* A VDB sequence's Mantaflow configs (config/config_####.uni beside data/) place its
   * frames: one changed byte is another scene for --resume (a domain moved in Blender and
   * baked again keeps its voxels' sizes, which alone were hashed) */
  {
    char copy[900], scene[800], uni[900];
    snprintf(copy, sizeof copy, "cp -r ../shared/data/vdb/groundfog '%s/gf'", dir);
    CHECK(system(copy) == 0, "%s", copy);
    snprintf(scene, sizeof scene, "%s/gf.ini", dir);
    FILE *f = fopen(scene, "w");
    if (f) fputs("[fog]\nvdb = gf/data/fluid_data_####.vdb\n", f), fclose(f);
    scene_config one;
    fog_error err;
    CHECK(scene_config_load(scene, &one, &err) == 0, "%s", err.message);
    const uint64_t before = scene_config_fingerprint(&one); /* it reads the files now */
    snprintf(uni, sizeof uni, "%s/gf/config/config_0012.uni", dir);
    FILE *u = fopen(uni, "r+b");
    CHECK(u != NULL, "cannot open %s", uni);
    if (u) {
      fseek(u, -5, SEEK_END); /* inside the gzip member's data or its CRC: bytes differ */
      int c = fgetc(u);
      fseek(u, -5, SEEK_END);
      fputc(c ^ 0x5a, u);
      fclose(u);
    }
    CHECK(before != scene_config_fingerprint(&one),
          "a changed Mantaflow config left the scene's fingerprint as it was");
    snprintf(copy, sizeof copy, "rm -rf '%s/gf' '%s'", dir, scene);
    CHECK(system(copy) == 0, "%s", copy);
  }

  scene_config cfg;
  fog_error err = {0};
  scene_config_init(&cfg);
  /* 64 coefficients, each needing 17 digits */
  char written[700];
  snprintf(written, sizeof written, "%s/long.ini", dir);
  cfg.fog.profile = SCENE_PROFILE_BSPLINE, cfg.fog.profile_set = true;
  cfg.fog.profile_degree = 1, cfg.fog.profile_spacing = 1.0 / 3.0;
  cfg.fog.profile_count = SCENE_CONFIG_MAX_PROFILE;
  /* 17 significant digits and an exponent: the longest numbers there are */
  for (int k = 0; k < SCENE_CONFIG_MAX_PROFILE; k++)
    cfg.fog.profile_coefficients[k] = (1.0 / (k + 3)) * pow(10.0, -(k % 19));
  scene_config back;
  /* a scene the loader would refuse is not written (fit wrote a height fog overflowing
   * float below it), and no file is left */
  {
    scene_config height;
    scene_config_init(&height);
    height.fog.model = FOG_MODEL_HEIGHT, height.fog.density_scale = 0.05;
    height.fog.fog_height = 1000.0, height.fog.scale_height = 7.0; /* least: ~32 */
    char refused[700];
    snprintf(refused, sizeof refused, "%s/refused.ini", dir);
    CHECK(scene_config_write(&height, refused, &err) != 0 &&
              strstr(err.message, "refused.ini") && strstr(err.message, "scale_height"),
          "an unloadable height fog written: %s", err.message);
    CHECK(access(refused, F_OK) != 0, "%s left behind", refused);
    height.fog.scale_height = 1.01 * scene_config_min_scale_height(&height);
    CHECK(scene_config_write(&height, refused, &err) == 0 &&
              scene_config_load(refused, &back, &err) == 0,
          "the least H the scene holds: %s", err.message);
    unlink(refused);
    /* a key out of its own range (a brush's Gaussian shrunk by '-' past the least RADIUS,
     * 1e-4): refused naming the key, no file (it was written, and did not load) */
    scene_config small;
    scene_config_init(&small);
    small.fog.model = FOG_MODEL_RBF, small.fog.rbf_count = 1;
    small.fog.rbfs[0] = (fog_rbf){.centre = {0, 10, 0}, .radius = 1e-5, .density = 0.1};
    CHECK(scene_config_write(&small, refused, &err) != 0 && strstr(err.message, "refused.ini") &&
              strstr(err.message, "[fog] rbf") && strstr(err.message, "RADIUS"),
          "a Gaussian of radius 1e-5 written: %s", err.message);
    CHECK(access(refused, F_OK) != 0, "%s left behind", refused);
  }
  CHECK(scene_config_write(&cfg, written, &err) == 0, "write: %s", err.message);
  CHECK(scene_config_load(written, &back, &err) == 0, "64 coefficients read back: %s", err.message);
  CHECK(back.fog.profile_count == SCENE_CONFIG_MAX_PROFILE &&
            !memcmp(back.fog.profile_coefficients, cfg.fog.profile_coefficients,
                    sizeof cfg.fog.profile_coefficients),
        "%d coefficients read back, not the 64 written", back.fog.profile_count);
  CHECK(load_text(written, "[fog]\nprofile = bspline\nprofile_coefficients = 1 2\n  3, 4\n\t5\n",
                  &back, &err) == 0 &&
            back.fog.profile_count == 5 && back.fog.profile_coefficients[4] == 5.0,
        "indented lines: %d numbers (%s)", back.fog.profile_count, err.message);
  /* an indented key right after a section line is a key, as libinih reads it: it replaces */
  CHECK(load_text(written, "[fog]\nmodel = perlin\n[fog]\n  perlin_wind = 1 2 3\n", &back,
                  &err) == 0 &&
            back.fog.perlin_wind_count == 3 && back.fog.perlin_wind[2] == 3.0,
        "an indented first key: %d numbers (%s)", back.fog.perlin_wind_count, err.message);
  char text[512] = "[fog]\nprofile = bspline\nprofile_coefficients =";
  for (int k = 0; k < 65; k++) strcat(text, k % 10 == 9 ? " 1\n  " : " 1");
  strcat(text, "\n");
  CHECK(load_text(written, text, &back, &err) != 0 && strstr(err.message, "long.ini:9") &&
            strstr(err.message, "64"),
        "65 numbers: %s", err.message);
  /* a spot lamp of numbers that need 17 digits each: %.17g made the line 253 bytes and the
   * written config did not load (as a bake writes its scene) */
  CHECK(load_text(written,
                  "[light]\nspot = -0.1 -0.1 -0.1 0.1 0.1 0.1 -0.1 -0.1 -0.1 0.1 0.7 0.3\n"
                  "[objects]\nbox = 0.1 -0.3 0.7 0.1 0.3 0.55 0.25 0.18\n",
                  &back, &err) == 0, "a spot lamp: %s", err.message);
  scene_config again;
  CHECK(scene_config_write(&back, written, &err) == 0 &&
            scene_config_load(written, &again, &err) == 0 &&
            scene_config_fingerprint(&again) == scene_config_fingerprint(&back),
        "a spot lamp written and read back: %s", err.message);
  /* lamp and spot lines interleaved, with a path and a flicker: written back in the same
   * order (the fog sums the lamps in it; a bake that wrote lamps, then spots, renumbering
   * the paths, gave frames a last bit off), and the fingerprint sees the order */
  CHECK(load_text(written,
                  "[light]\nspot = 0 50 0 1 1 1 0 -1 0 20 30 1\nlamp = 10 20 30 1 0.5 0.2 2\n"
                  "spot = 5 60 5 0.5 1 1 0 -1 0 15 25 1\nlamp = -10 20 -30 0.2 0.5 1 2\n"
                  "lamp_path = 2 0 10 20 30\nlamp_path = 2 4 12 20 30\n"
                  "lamp_flicker = 3 0.5 2 7\n",
                  &back, &err) == 0, "interleaved lamps: %s", err.message);
  CHECK(scene_config_write(&back, written, &err) == 0 &&
            scene_config_load(written, &again, &err) == 0,
        "interleaved lamps written and read back: %s", err.message);
  bool same_order = again.lamp_count == back.lamp_count;
  for (int i = 0; same_order && i < back.lamp_count; i++)
    same_order = again.lamps[i].spot == back.lamps[i].spot &&
                 !memcmp(again.lamps[i].position, back.lamps[i].position,
                         sizeof back.lamps[i].position) &&
                 again.lamps[i].key_count == back.lamps[i].key_count &&
                 again.lamps[i].flicker_amount == back.lamps[i].flicker_amount;
  CHECK(same_order && back.lamp_count == 4 && back.lamps[1].key_count == 2 &&
            back.lamps[2].flicker_amount == 0.5,
        "interleaved lamps, their paths and flickers not read back in order");
  scene_config swapped = back;
  swapped.lamps[0] = back.lamps[1], swapped.lamps[1] = back.lamps[0];
  CHECK(scene_config_fingerprint(&swapped) != scene_config_fingerprint(&back),
        "the fingerprint does not see the lamps' order");
  /* exponents written short ("1.23456789012e-5", not e-05): a spot line of eleven such
   * numbers (the last e+1: a cone's cosines 1e-5 apart), 193 bytes, stays under 199 once
   * written with its radius (it took 208) */
  char spot[300] = "[light]\nspot =";
  for (int k = 0; k < 10; k++) strcat(spot, " 1.23456789012e-5");
  strcat(spot, " 2.23456789012e+1\n"); /* OUTER > INNER, cosines 1e-5 apart or more */
  CHECK(load_text(written, spot, &back, &err) == 0, "eleven short numbers: %s", err.message);
  CHECK(scene_config_write(&back, written, &err) == 0 &&
            scene_config_load(written, &again, &err) == 0 &&
            scene_config_fingerprint(&again) == scene_config_fingerprint(&back),
        "a spot of eleven 1.23456789012e-5 written and read back: %s", err.message);
  /* a spot line of 198 bytes without a radius, each number in its shortest form: written
   * back no longer (the writer added the default radius, 202 bytes, and refused the scene:
   * bake, fit --out and the viewer's save could not write a config that loads) */
  strcpy(spot, "[light]\nspot = -1234.56789012345 -1234.56789012345 -1234.56789012345 "
               "1.23456789012345 1.23456789012345 1.23456789012345 0.12345678901234 "
               "0.12345678901234 0.12345678901234 1.23456789012e-5 22.345678901234567\n");
  CHECK(strlen(spot) - strlen("[light]\n\n") == 198, "the spot line is %zu bytes",
        strlen(spot) - strlen("[light]\n\n"));
  CHECK(load_text(written, spot, &back, &err) == 0, "a 198-byte spot: %s", err.message);
  CHECK(scene_config_write(&back, written, &err) == 0 &&
            scene_config_load(written, &again, &err) == 0 &&
            scene_config_fingerprint(&again) == scene_config_fingerprint(&back),
        "a 198-byte spot without a radius written and read back: %s", err.message);
  /* numbers in their shortest text: 50 as 50 (not 5e1), 1000 as 1e3, 100 as 100 */
  {
    scene_config numbers = back;
    numbers.fog.fog_height = 50.0, numbers.fog.fog_end = 1000.0, numbers.fog.fog_start = 100.0;
    numbers.fog.perlin_wind[0] = 50.0; /* a list's numbers too (they were %g's: 5e+01) */
    CHECK(scene_config_write(&numbers, written, &err) == 0, "%s", err.message);
    FILE *w = fopen(written, "r");
    char line[512];
    int found = 0;
    while (w && fgets(line, sizeof line, w))
      found += !strcmp(line, "fog_height = 50\n") + !strcmp(line, "fog_end = 1e3\n") +
               !strcmp(line, "fog_start = 100\n") + !strncmp(line, "perlin_wind = 50 ", 17);
    if (w) fclose(w);
    CHECK(found == 4, "%d of fog_height = 50, fog_end = 1e3, fog_start = 100, perlin_wind = 50 "
          "... written so", found);
  }
  /* a spot line of 192 bytes that takes 204 once written (each .12345678901234 as
   * 0.12345678901234, and its radius .25 as 0.25): refused, naming the line, and nothing
   * written (a config that would not load again) */
  strcpy(spot, "[light]\nspot = -.12345678901234 -.12345678901234 -.12345678901234 "
               ".12345678901234 .12345678901234 .12345678901234 -.12345678901234 "
               "-.12345678901234 -.12345678901234 .12345678901234 .92345678901234 .25\n");
  CHECK(strlen(spot) - strlen("[light]\n\n") <= 199, "the spot line is %zu bytes", strlen(spot));
  CHECK(load_text(written, spot, &back, &err) == 0, "eleven long numbers: %s", err.message);
  unlink(written);
  CHECK(scene_config_write(&back, written, &err) != 0 &&
            strstr(err.message, "more than a config line holds") && access(written, F_OK) != 0,
        "a spot line past 199 bytes once written: %s", err.message);
  /* a path through a folder "a ;b": a config would cut it at the ';' */
  unlink(written);
  snprintf(back.fog.fogmap, sizeof back.fog.fogmap, "%s/a ;b/m.exr", dir);
  back.lamp_count = 0;
  CHECK(scene_config_write(&back, written, &err) != 0 && strstr(err.message, "' ;'") &&
            access(written, F_OK) != 0,
        "a fogmap path with ' ;' written: %s", err.message);
  /* and through a folder "a\nb": its second half would be a line of its own */
  snprintf(back.fog.fogmap, sizeof back.fog.fogmap, "%s/a\nb/m.exr", dir);
  CHECK(scene_config_write(&back, written, &err) != 0 && strstr(err.message, "line break") &&
            access(written, F_OK) != 0,
        "a fogmap path with a line break written: %s", err.message);
  unlink(written);
  /* a path through a link is written through the link, as its user spelt it, not through
   * the link's target (realpath wrote /mnt/nfs1/... for /shared/...: a farm node that
   * mounts /shared elsewhere lacks that path); "folder/.." collapsed */
  {
    static char text[65536];
    char real[700], link[700], map[800], original[800], rewritten[800];
    snprintf(real, sizeof real, "%s/real", dir);
    snprintf(link, sizeof link, "%s/link", dir);
    snprintf(map, sizeof map, "%s/real/fog.png", dir);
    snprintf(original, sizeof original, "%s/linked.ini", dir);
    snprintf(rewritten, sizeof rewritten, "%s/relinked.ini", dir);
    snprintf(text, sizeof text, "cp data/fogmap_sample.png '%s'", map);
    CHECK(mkdir(real, 0755) == 0 && symlink("real", link) == 0 && system(text) == 0,
          "cannot make %s and %s", real, link);
    scene_config linked;
    CHECK(load_text(original, "[fog]\nfogmap = real/../link/./fog.png\n", &linked, &err) == 0,
          "a fogmap through a link: %s", err.message);
    CHECK(scene_config_write(&linked, rewritten, &err) == 0, "write: %s", err.message);
    FILE *f = fopen(rewritten, "r");
    size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    text[n] = '\0';
    if (f) fclose(f);
    char expected[800];
    snprintf(expected, sizeof expected, "fogmap = %s/link/fog.png\n", dir);
    CHECK(strstr(text, expected) != NULL, "the fogmap is not written through the link: "
          "expected '%s' in the config", expected);
    unlink(rewritten), unlink(original), unlink(map), unlink(link), rmdir(real);
  }
  /* onto a folder of that name: the reason said (it was "write failed (disk full?)") */
  char folder[700];
  snprintf(folder, sizeof folder, "%s/taken.ini", dir);
  CHECK(mkdir(folder, 0755) == 0, "mkdir %s", folder);
  CHECK(scene_config_write(&cfg, folder, &err) != 0 && strstr(err.message, "taken.ini") &&
            strstr(err.message, "folder"),
        "a config written onto a folder: %s", err.message);
  rmdir(folder);
  char bad[700];
  snprintf(bad, sizeof bad, "%s/missing/x.ini", dir);
  CHECK(scene_config_write(&cfg, bad, &err) != 0 && strstr(err.message, bad),
        "an unwritable path: %s", err.message);
  /* the temporary is the write's own: a user's NAME.tmp beside it is left as it was (it
   * was the temporary, and replaced); a config written over keeps its mode (it became
   * 0644), a new one takes the umask as any new file */
  {
    char target[700], user_tmp[720];
    snprintf(target, sizeof target, "%s/moded.ini", dir);
    snprintf(user_tmp, sizeof user_tmp, "%s.tmp", target);
    test_write_text(user_tmp, "a user's own file\n");
    test_write_text(target, "[fog]\n");
    CHECK(chmod(target, 0600) == 0, "chmod %s", target);
    CHECK(scene_config_write(&cfg, target, &err) == 0, "write over %s: %s", target, err.message);
    struct stat st;
    CHECK(stat(target, &st) == 0 && (st.st_mode & 07777) == 0600,
          "a config of mode 0600 written over: mode %o", (unsigned)(st.st_mode & 07777));
    char *kept = read_text(user_tmp);
    CHECK(kept && !strcmp(kept, "a user's own file\n"), "%s was replaced: '%s'", user_tmp,
          kept ? kept : "(gone)");
    free(kept);
    unlink(target);
    const mode_t old_mask = umask(027);
    CHECK(scene_config_write(&cfg, target, &err) == 0, "write %s: %s", target, err.message);
    umask(old_mask);
    CHECK(stat(target, &st) == 0 && (st.st_mode & 07777) == 0640,
          "a new config under umask 027: mode %o, expected 640", (unsigned)(st.st_mode & 07777));
    unlink(target), unlink(user_tmp);
    CHECK(test_folder_entries(dir) == 0, "the writes left %d entries in %s",
          test_folder_entries(dir), dir);
  }
  rmdir(dir);
  return test_finish("test_config_write");
}
