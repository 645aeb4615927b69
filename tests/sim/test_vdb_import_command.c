/* `fogpipe import` end to end: the EXR sequence and the sidecar it writes read back to the
 * same mass as the voxels (f·cell²·thickness summed = the sidecar's mass per frame, which
 * test_vdb_real_files checks against the voxel sum); bad input (a non-VDB file in the
 * sequence, missing frames, no such grid) exits non-zero, names the file and frame, and
 * leaves nothing in --out; an import into a folder that holds other frames of the same
 * name keeps them and says so; a re-import that cannot finish replaces none of the earlier
 * import's files. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sim/sim.h"
#include "test_util.h"

static char dir[256];

/* Runs a shell command; returns its exit status and its stderr (first 4 KiB). */
static int run(const char *command, char *errors, size_t size) {
  char cmd[4096], errfile[300];
  snprintf(errfile, sizeof errfile, "%s/stderr.txt", dir);
  snprintf(cmd, sizeof cmd, "%s > /dev/null 2> '%s'", command, errfile);
  int status = system(cmd);
  errors[0] = 0;
  FILE *f = fopen(errfile, "r");
  if (f) {
    size_t n = fread(errors, 1, size - 1, f);
    errors[n] = 0;
    fclose(f);
  }
  unlink(errfile);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* The value of "key = ..." in the sidecar (first occurrence). */
static int ini_value(const char *path, const char *key, char *out, size_t size) {
  FILE *f = fopen(path, "r");
  if (!f) return 1;
  char line[8192];
  int found = 0;
  while (!found && fgets(line, sizeof line, f)) {
    size_t k = strlen(key);
    if (!strncmp(line, key, k) && line[k] == ' ' && line[k + 1] == '=') {
      snprintf(out, size, "%s", line + k + 3);
      found = 1;
    }
  }
  fclose(f);
  return !found;
}

/* A Blender cache at DIR/NAME (data/ and config/) of the plume's frames whose numbers
 * match the globs (e.g. "004[68]"): its data and config globs apart. */
static void plume_cache(const char *name, const char *data_frames, const char *config_frames,
                        char *folder, size_t size) {
  char cmd[2048];
  snprintf(folder, size, "%s/%s", dir, name);
  snprintf(cmd, sizeof cmd,
           "mkdir -p '%s/data' '%s/config' && "
           "cp ../shared/data/vdb/plume/data/fluid_data_%s.vdb '%s/data/' && "
           "cp ../shared/data/vdb/plume/config/config_%s.uni '%s/config/'",
           folder, folder, data_frames, folder, config_frames, folder);
  CHECK(system(cmd) == 0, "setup failed: %s", cmd);
}

int main(void) {
  const char *bin = getenv("FOGPIPE_BIN");
  if (!bin) bin = "build/fogpipe";
  snprintf(dir, sizeof dir, "/tmp/test_vdb_import_XXXXXX");
  if (!test_scratch_folder(dir)) return 1;
  char cmd[4096], errors[4096], out[512];

  /* 1. frames 40..48 of the ground fog, resampled to 50 cells */
  snprintf(out, sizeof out, "%s/good", dir);
  snprintf(cmd, sizeof cmd,
           "'%s' import ../shared/data/vdb/groundfog/data/fluid_data_%%04d.vdb --frames 40-48 "
           "--resolution 50 --out '%s' --name gf", bin, out);
  int status = run(cmd, errors, sizeof errors);
  CHECK(status == 0, "import failed (%d): %s", status, errors);
  CHECK(test_folder_entries(out) == 10, "%d files in %s, expected 9 EXR + 1 ini",
        test_folder_entries(out), out);
  char ini[600], value[8192];
  snprintf(ini, sizeof ini, "%s/gf.ini", out);
  double cell = 0, thickness = 0;
  int width = 0;
  if (!ini_value(ini, "cell_size", value, sizeof value)) cell = atof(value);
  if (!ini_value(ini, "; thickness", value, sizeof value)) thickness = atof(value);
  if (!ini_value(ini, "width", value, sizeof value)) width = atoi(value);
  CHECK(width == 50 && fabs(cell - 6.0 / 50) < 1e-9, "sidecar: width %d, cell %g", width, cell);
  CHECK(!ini_value(ini, "mass", value, sizeof value), "sidecar has no mass line");
  char *p = value;
  for (int frame = 40; frame <= 48; frame++) {
    const double mass = strtod(p, &p);
    char exr[700];
    snprintf(exr, sizeof exr, "%s/gf.%04d.exr", out, frame);
    fogmap map;
    fog_error err = {0};
    if (fogmap_load(exr, &(fogmap_load_desc){0}, &map, &err)) {
      CHECK(0, "%s", err.message);
      continue;
    }
    double sum = 0;
    for (int n = 0; n < map.width * map.height; n++) sum += map.density[n];
    const double fm = sum * cell * cell * thickness;
    CHECK(fabs(fm - mass) < 1e-5 * mass, "frame %d: EXR mass %.8g vs sidecar mass %.8g", frame,
          fm, mass);
    fogmap_destroy(&map);
  }

  /* 2. a non-VDB file inside the sequence: non-zero, names the file and frame, nothing left */
  char bad[512];
  snprintf(bad, sizeof bad, "%s/badseq", dir);
  snprintf(cmd, sizeof cmd,
           "mkdir -p '%s' && cp ../shared/data/vdb/plume/data/fluid_data_000[1-3].vdb '%s/' && "
           "echo 'not a vdb' > '%s/fluid_data_0004.vdb' && "
           "cp ../shared/data/vdb/plume/data/fluid_data_0005.vdb '%s/'", bad, bad, bad, bad);
  CHECK(system(cmd) == 0, "setup failed: %s", cmd);
  snprintf(out, sizeof out, "%s/out_bad", dir);
  snprintf(cmd, sizeof cmd, "'%s' import '%s' --out '%s' --config none", bin, bad, out);
  status = run(cmd, errors, sizeof errors);
  CHECK(status != 0, "import of a bad sequence succeeded");
  CHECK(strstr(errors, "fluid_data_0004.vdb") && strstr(errors, "frame 4"),
        "message lacks the file or frame: %s", errors);
  CHECK(test_folder_entries(out) <= 0, "%d entries left in %s", test_folder_entries(out), out);

  /* 3. missing frames inside the range */
  snprintf(cmd, sizeof cmd, "rm '%s/fluid_data_0004.vdb'", bad);
  CHECK(system(cmd) == 0, "rm failed");
  snprintf(cmd, sizeof cmd, "'%s' import '%s/fluid_data_####.vdb' --out '%s' --config none", bin,
           bad, out);
  status = run(cmd, errors, sizeof errors);
  CHECK(status != 0 && strstr(errors, "missing: 4"), "missing frame 4 not reported (%d): %s",
        status, errors);
  CHECK(test_folder_entries(out) <= 0, "%d entries left in %s", test_folder_entries(out), out);
  snprintf(cmd, sizeof cmd,
           "'%s' import '%s/fluid_data_####.vdb' --out '%s' --config none --skip-missing", bin,
           bad, out);
  status = run(cmd, errors, sizeof errors);
  CHECK(status == 0 && strstr(errors, "missing"), "--skip-missing (%d): %s", status, errors);
  CHECK(test_folder_entries(out) == 5, "%d files after --skip-missing, expected 4 EXR + ini",
        test_folder_entries(out));

  /* 4. no such grid: the message lists the grids */
  snprintf(out, sizeof out, "%s/out_grid", dir);
  snprintf(cmd, sizeof cmd, "'%s' import '%s/fluid_data_0001.vdb' --grid smoke --out '%s'", bin,
           bad, out);
  status = run(cmd, errors, sizeof errors);
  CHECK(status != 0 && strstr(errors, "fluid_data_0001.vdb") && strstr(errors, "density, flame"),
        "no such grid (%d): %s", status, errors);
  CHECK(test_folder_entries(out) <= 0, "%d entries left in %s", test_folder_entries(out), out);

  /* 5. frame 48 alone into the folder of 1.'s frames 40..48: it says the other 8 are there,
   * kept, and not described by the new gf.ini */
  snprintf(out, sizeof out, "%s/good", dir);
  snprintf(cmd, sizeof cmd,
           "'%s' import ../shared/data/vdb/groundfog/data/fluid_data_0048.vdb --resolution 50 "
           "--out '%s' --name gf", bin, out);
  status = run(cmd, errors, sizeof errors);
  CHECK(status == 0 && strstr(errors, "also holds 8 frames of another import") &&
            strstr(errors, "gf.0040.exr .. gf.0047.exr"),
        "no word of the earlier frames (%d): %s", status, errors);
  CHECK(test_folder_entries(out) == 10, "%d files: the earlier frames must stay",
        test_folder_entries(out));
  /* 5b. an earlier --report run's report beside an import without --report: said, kept */
  {
    char report[700];
    snprintf(report, sizeof report, "%s/gf.report.csv", out);
    test_write_text(report, "an earlier import's report\n");
    status = run(cmd, errors, sizeof errors);
    CHECK(status == 0 && strstr(errors, "gf.report.csv is an earlier import's report"),
          "no word of the earlier report (%d): %s", status, errors);
    unlink(report);
  }

  /* 6. a re-import that cannot finish (a folder where its frame 44 goes) replaces nothing:
   * the earlier import's files are kept byte for byte, no replaced copy is left */
  {
    char frame44[700], sidecar_before[8192] = "", sidecar_after[8192] = "", gf40[700];
    snprintf(frame44, sizeof frame44, "%s/gf.0044.exr", out);
    snprintf(gf40, sizeof gf40, "%s/gf.0040.exr", out);
    struct stat before40, after40;
    stat(gf40, &before40);
    FILE *f = fopen(ini, "r");
    size_t n = f ? fread(sidecar_before, 1, sizeof sidecar_before - 1, f) : 0;
    sidecar_before[n] = '\0';
    if (f) fclose(f);
    snprintf(cmd, sizeof cmd, "rm '%s' && mkdir -p '%s/keep'", frame44, frame44);
    CHECK(system(cmd) == 0, "%s", cmd);
    const int entries = test_folder_entries(out);
    snprintf(cmd, sizeof cmd,
             "'%s' import ../shared/data/vdb/groundfog/data/fluid_data_%%04d.vdb --frames 40-48 "
             "--resolution 40 --out '%s' --name gf", bin, out);
    status = run(cmd, errors, sizeof errors);
    f = fopen(ini, "r");
    n = f ? fread(sidecar_after, 1, sizeof sidecar_after - 1, f) : 0;
    sidecar_after[n] = '\0';
    if (f) fclose(f);
    stat(gf40, &after40);
    CHECK(status != 0 && strstr(errors, "gf.0044.exr") && strstr(errors, "nothing"),
          "a folder in the way (%d): %s", status, errors);
    CHECK(n > 0 && !strcmp(sidecar_before, sidecar_after), "the failed import replaced gf.ini");
    CHECK(before40.st_size == after40.st_size && before40.st_mtime == after40.st_mtime &&
              before40.st_ino == after40.st_ino,
          "the failed import replaced gf.0040.exr");
    CHECK(test_folder_entries(out) == entries, "%d entries after the failed import, had %d",
          test_folder_entries(out), entries);
  }

  /* 7. a sequence where only some frames have a Mantaflow config beside them (the others
   * would be placed from the VDB transform, about a metre off): refused, naming a frame
   * without one and one with, nothing written; --config none imports it */
  {
    char mixed[512];
    plume_cache("mixed", "004[678]", "004[67]", mixed, sizeof mixed);
    snprintf(out, sizeof out, "%s/out_mixed", dir);
    snprintf(cmd, sizeof cmd, "'%s' import '%s/data/fluid_data_####.vdb' --out '%s'", bin, mixed,
             out);
    status = run(cmd, errors, sizeof errors);
    CHECK(status != 0 && strstr(errors, "fluid_data_0048.vdb") && strstr(errors, "frame 46") &&
              strstr(errors, "placed two ways"),
          "frames with and without a config (%d): %s", status, errors);
    CHECK(test_folder_entries(out) <= 0, "%d entries left in %s", test_folder_entries(out), out);
    snprintf(cmd, sizeof cmd, "'%s' import '%s/data/fluid_data_####.vdb' --out '%s' --config none",
             bin, mixed, out);
    status = run(cmd, errors, sizeof errors);
    CHECK(status == 0, "the same frames with --config none (%d): %s", status, errors);
    /* a scene's [fog] vdb reads the frames the same way: refused as well */
    char scene[600], image[600];
    snprintf(scene, sizeof scene, "%s/mixed.ini", dir);
    snprintf(image, sizeof image, "%s/mixed.png", dir);
    FILE *f = fopen(scene, "w");
    if (f) {
      fprintf(f, "[fog]\nvdb = %s/data/fluid_data_####.vdb\n", mixed);
      fclose(f);
    }
    snprintf(cmd, sizeof cmd, "'%s' render '%s' --size 32x18 --out '%s'", bin, scene, image);
    status = run(cmd, errors, sizeof errors);
    CHECK(status != 0 && strstr(errors, "fluid_data_0048.vdb") && strstr(errors, "placed two ways"),
          "a scene's [fog] vdb of frames with and without a config (%d): %s", status, errors);
    CHECK(access(image, F_OK) != 0, "the refused render left %s", image);
    /* and as a volume (model = volume plays the frames in 3D, loaded as they are shown) */
    f = fopen(scene, "w");
    if (f) {
      fprintf(f, "[fog]\nmodel = volume\nvdb = %s/data/fluid_data_####.vdb\nvdb_frame = 46\n",
              mixed);
      fclose(f);
    }
    status = run(cmd, errors, sizeof errors);
    CHECK(status != 0 && strstr(errors, "fluid_data_0048.vdb") && strstr(errors, "placed two ways"),
          "a volume's [fog] vdb of frames with and without a config (%d): %s", status, errors);
    CHECK(access(image, F_OK) != 0, "the refused render left %s", image);
  }

  /* 8. a sequence with a hole in its numbers (46, 48): a scene's [fog] vdb refuses it as a
   * fogmap and as a volume (the player steps through the files in order: 46 and 48 would
   * play as neighbours, the speed silently changed), naming the pattern and the hole */
  {
    char gap[512], scene[600], image[600];
    plume_cache("gap", "004[68]", "004[68]", gap, sizeof gap);
    snprintf(scene, sizeof scene, "%s/gap.ini", dir);
    snprintf(image, sizeof image, "%s/gap.png", dir);
    snprintf(cmd, sizeof cmd, "'%s' render '%s' --size 32x18 --out '%s'", bin, scene, image);
    for (int volume = 0; volume < 2; volume++) {
      FILE *f = fopen(scene, "w");
      if (f) {
        fprintf(f, "[fog]\n%svdb = %s/data/fluid_data_####.vdb\nvdb_frame = 46\n",
                volume ? "model = volume\n" : "", gap);
        fclose(f);
      }
      status = run(cmd, errors, sizeof errors);
      CHECK(status != 0 && strstr(errors, "fluid_data_####.vdb") &&
                strstr(errors, "1 frame missing inside 46..48 (the first: 47)"),
            "a %s's [fog] vdb with a hole in its frames (%d): %s",
            volume ? "volume" : "fogmap", status, errors);
      CHECK(access(image, F_OK) != 0, "the refused render left %s", image);
    }
  }

  test_remove_tree(dir);
  return test_finish("test_vdb_import_command");
}
