/* `fogpipe fit` from the command line: --out writes a scene that loads back with the chosen
 * model and its fitted parameters, --chart writes the PNG and its CSV; a fogmap projected
 * from an analytic input (Perlin fog, 15x the fogmap's time) is written beside the scene
 * as SCENE.fogmap.exr, which the scene names; bad input (a
 * missing VDB, a bad config key, no tolerance, an unwritable --out, an --out that would
 * replace an input, --chart without gnuplot) fails with a message naming the file or
 * option, and leaves no file behind; a fit stopped by SIGTERM exits 130 and removes its
 * scratch folder (in $TMPDIR). And the references:
 *  - a VDB plume beside an opaque quadric sphere is measured with the sphere: the fit's
 *    domain reaches the sphere (it was fitted, measured and written as the plume alone);
 *  - classic linear fog ending 500 units from the camera fits (infinite samples past
 *    fog_end, about the world's origin, ended the fit in an error);
 *  - a fogmap input at its own settings (lod = sum) is a rung of its own, error 0: a tight
 *    tolerance picks it (no fixed fogmap rung matched it, and nothing was written). */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/config.h"
#include "test_bin.h"

static char dir[] = "/tmp/fogpipe_fit_cli_XXXXXX";

static void read_text(const char *path, char *text, size_t size) {
  FILE *f = fopen(path, "r");
  size_t n = f ? fread(text, 1, size - 1, f) : 0;
  text[n] = '\0';
  if (f) fclose(f);
}

static bool exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

/* Runs `fogpipe fit ARGS`, stdout and stderr into DIR/out.txt and DIR/err.txt; the exit
 * status. */
static int fit(const char *bin, const char *args, char *out, char *err, size_t size) {
  char command[2048], out_path[256], err_path[256];
  snprintf(out_path, sizeof out_path, "%s/out.txt", dir);
  snprintf(err_path, sizeof err_path, "%s/err.txt", dir);
  snprintf(command, sizeof command, "'%s' fit %s > '%s' 2> '%s'", bin, args, out_path, err_path);
  int status = system(command);
  read_text(out_path, out, size);
  read_text(err_path, err, size);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int main(void) {
  const char *bin = test_bin_and_folder(dir);
  if (!bin) return test_finish("test_fit_cli");
  const char *fast = "--rays 8 --samples 16 --size 64x36 --timed 1";
  char out[8192], err[8192], args[1024], ini[256], scene[256], chart[256], csv[256];
  snprintf(ini, sizeof ini, "%s/constant.ini", dir);
  snprintf(scene, sizeof scene, "%s/scene.ini", dir);
  snprintf(chart, sizeof chart, "%s/fit.png", dir);
  snprintf(csv, sizeof csv, "%s/fit.csv", dir);
  test_write_text(ini, "[fog]\nmodel = homogeneous\ndensity_scale = 0.004\n");

  /* a constant fog: homogeneous, written and charted */
  snprintf(args, sizeof args, "'%s' --tolerance 0.01,0.5 --out '%s' --chart '%s' %s", ini, scene,
           chart, fast);
  int status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 0, "exit %d: %s", status, err);
  CHECK(strstr(out, "chosen: homogeneous") != NULL, "stdout: %s", out);
  CHECK(strstr(out, "at tolerance 0.5: ") != NULL, "stdout: %s", out);
  CHECK(exists(chart) && exists(csv), "no chart %s / %s", chart, csv);
  {
    /* Gaussians over a base, above the box: the domain is theirs (the terrain's footprint
     * 0 to 50 high never sampled them, and homogeneous fog was chosen at 1e-10) */
    char tube[256], tube_scene[256];
    snprintf(tube, sizeof tube, "%s/tube.ini", dir);
    snprintf(tube_scene, sizeof tube_scene, "%s/tube_fit.ini", dir);
    test_write_text(tube, "[fog]\nmodel = rbf\nrbf_base = 0.004\nrbf = 0 300 0 7 0.25\n"
                          "rbf = 30 300 0 7 0.25\nrbf = 0 300 30 7 0.25\n");
    snprintf(args, sizeof args, "'%s' --tolerance 0.05 --out '%s' %s", tube, tube_scene, fast);
    status = fit(bin, args, out, err, sizeof out);
    double y_lo = 0, y_hi = 0;
    const char *domain = strstr(out, "domain [");
    CHECK(status == 0 && domain &&
              sscanf(domain, "domain [%*g, %*g] x [%lg, %lg]", &y_lo, &y_hi) == 2 &&
              y_lo >= 250 && y_hi <= 350 && !strstr(out, "chosen: homogeneous"),
          "Gaussians over a base at y 300: exit %d, domain y %g..%g, stdout %s", status, y_lo,
          y_hi, out);
  }
  {
    /* no fog at all (a Gaussian of density 0): refused, nothing written (every rung
     * scored 0, and a linear fog opaque past the domain was chosen and written) */
    char zero[256], zero_scene[256];
    snprintf(zero, sizeof zero, "%s/zero.ini", dir);
    snprintf(zero_scene, sizeof zero_scene, "%s/zero_fit.ini", dir);
    test_write_text(zero, "[fog]\nmodel = rbf\nrbf = 0 40 0 25 0\n");
    snprintf(args, sizeof args, "'%s' --tolerance 0.05 --out '%s' %s", zero, zero_scene, fast);
    status = fit(bin, args, out, err, sizeof out);
    CHECK(status == 1 && strstr(err, "zero.ini: the fog is zero everywhere") &&
              !exists(zero_scene) && !strstr(out, "chosen"),
          "a fit of no fog: exit %d, stderr %s, stdout %s", status, err, out);
  }
  {
    /* a rung this renderer refuses with the scene's lamps (llvmpipe's loop cap: night_lamps'
     * 9 lamps over 4 ellipsoids) is measured, marked and never chosen; the fit goes on (it
     * failed whole: "rung ellipsoids 4: fog pass: quadric fog may run 66871 loop
     * iterations") */
    snprintf(args, sizeof args, "configs/night_lamps.ini --tolerance 0.05 --rays 4 "
             "--samples 8 --size 16x9 --timed 1");
    status = fit(bin, args, out, err, sizeof out);
    const char *chosen_line = strstr(out, "chosen: ");
    CHECK(status == 0 && chosen_line && !strstr(chosen_line, "nan"),
          "night_lamps: exit %d, stderr %s", status, err);
    int refused_rows = 0;
    for (const char *line = out; (line = strstr(line, "\n")); line++) {
      const char *end = strchr(line + 1, '\n');
      const char *mark = strstr(line + 1, "(refused by this renderer");
      if (mark && (!end || mark < end)) {
        refused_rows++;
        CHECK(line[1] == ' ', "a refused rung was chosen: %.80s", line + 1);
      }
    }
    printf("night_lamps: %d rungs refused with the lamps (llvmpipe's loop cap)\n",
           refused_rows);
    /* llvmpipe's loop cap (the tests' renderer) refuses some: 12 measured */
    CHECK(refused_rows > 0, "night_lamps: no rung refused (llvmpipe's loop cap): %s", out);
  }
  {
    /* no gnuplot on PATH: --chart is refused before the fit, and nothing is written */
    char scene2[256], chart2[256], csv2[256], command[2048];
    snprintf(scene2, sizeof scene2, "%s/nochart.ini", dir);
    snprintf(chart2, sizeof chart2, "%s/nochart.png", dir);
    snprintf(csv2, sizeof csv2, "%s/nochart.csv", dir);
    snprintf(command, sizeof command,
             "env PATH=/nonexistent '%s' fit '%s' --tolerance 0.01 --out '%s' --chart '%s' %s "
             "> '%s/out.txt' 2> '%s/err.txt'",
             bin, ini, scene2, chart2, fast, dir, dir);
    const int rc = system(command);
    char path[300];
    snprintf(path, sizeof path, "%s/err.txt", dir);
    read_text(path, err, sizeof err);
    CHECK(WIFEXITED(rc) && WEXITSTATUS(rc) == 1 &&
              strstr(err, "fogpipe fit: --chart: gnuplot could not be run"),
          "without gnuplot: exit %d, stderr: %s", WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, err);
    CHECK(!exists(scene2) && !exists(chart2) && !exists(csv2),
          "without gnuplot the fit still wrote its scene or chart's CSV");
  }
  {
    /* a folder where --chart's CSV goes: refused before the fit, naming it, and the --out of
     * an earlier run kept (the fit used to run, replace --out, then fail on the CSV with
     * "disk full?") */
    char kept[256], chart3[256], csv3[256], before[64], after[64];
    snprintf(kept, sizeof kept, "%s/kept.ini", dir);
    snprintf(chart3, sizeof chart3, "%s/blocked.png", dir);
    snprintf(csv3, sizeof csv3, "%s/blocked.csv", dir);
    test_write_text(kept, "; an earlier fit\n");
    CHECK(mkdir(csv3, 0755) == 0, "mkdir %s", csv3);
    snprintf(args, sizeof args, "'%s' --tolerance 0.01 --out '%s' --chart '%s' %s", ini, kept,
             chart3, fast);
    status = fit(bin, args, out, err, sizeof out);
    read_text(kept, after, sizeof after);
    snprintf(before, sizeof before, "; an earlier fit\n");
    CHECK(status != 0 && strstr(err, "blocked.csv") && strstr(err, "a folder of that name") &&
              !strcmp(before, after) && !exists(chart3) && !strstr(out, "chosen:"),
          "a folder at the chart's CSV: exit %d, stderr %s, --out '%s'", status, err, after);
    rmdir(csv3);
  }
  {
    /* the chart failing at gnuplot's drawing (a gnuplot on PATH that answers --version
     * and fails to draw): exit 1, and neither the scene nor the chart's CSV (written
     * before gnuplot ran, it was left) */
    char scene5[256], chart5[256], csv5[256], fake[256], command[2048];
    snprintf(scene5, sizeof scene5, "%s/late.ini", dir);
    snprintf(chart5, sizeof chart5, "%s/late.png", dir);
    snprintf(csv5, sizeof csv5, "%s/late.csv", dir);
    snprintf(fake, sizeof fake, "%s/fakebin", dir);
    snprintf(command, sizeof command, "%s/gnuplot", fake);
    CHECK(mkdir(fake, 0755) == 0, "mkdir %s", fake);
    test_write_text(command, "#!/bin/sh\n[ \"$1\" = --version ] && { echo 'gnuplot 5.4'; "
                             "exit 0; }\necho 'cannot draw' >&2\nexit 1\n");
    CHECK(chmod(command, 0755) == 0, "chmod %s", command);
    snprintf(command, sizeof command,
             "env PATH='%s':\"$PATH\" '%s' fit '%s' --tolerance 0.01 --out '%s' --chart '%s' %s "
             "> '%s/out.txt' 2> '%s/err.txt'",
             fake, bin, ini, scene5, chart5, fast, dir, dir);
    const int rc = system(command);
    status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    char path[300];
    snprintf(path, sizeof path, "%s/err.txt", dir);
    read_text(path, err, sizeof err);
    CHECK(status != 0 && strstr(err, "gnuplot failed") && !exists(scene5) && !exists(chart5) &&
              !exists(csv5),
          "a chart that failed at gnuplot: exit %d, scene %d, chart %d, CSV %d; stderr %s",
          status, exists(scene5), exists(chart5), exists(csv5), err);
    snprintf(path, sizeof path, "%s/gnuplot", fake);
    unlink(path);
    rmdir(fake);
  }
  {
    /* a folder where a projected rung's fogmap goes beside --out (OUT.fogmap.exr): refused
     * before the fit, naming it (it was found after the whole fit, the chart left behind) */
    char blocked_out[256], blocked_map[256], chart4[256];
    snprintf(blocked_out, sizeof blocked_out, "%s/q.ini", dir);
    snprintf(blocked_map, sizeof blocked_map, "%s/q.fogmap.exr", dir);
    snprintf(chart4, sizeof chart4, "%s/q.png", dir);
    CHECK(mkdir(blocked_map, 0755) == 0, "mkdir %s", blocked_map);
    snprintf(args, sizeof args, "configs/perlin_fog.ini --tolerance 0.04 --by mean --out '%s' "
             "--chart '%s' %s", blocked_out, chart4, fast);
    status = fit(bin, args, out, err, sizeof out);
    CHECK(status != 0 && strstr(err, "q.fogmap.exr") && strstr(err, "a folder of that name") &&
              !strstr(out, "chosen:") && !exists(blocked_out) && !exists(chart4),
          "a folder at --out's fogmap: exit %d, stdout %s, stderr %s", status, out, err);
    rmdir(blocked_map);
  }
  scene_config cfg;
  fog_error cerr;
  CHECK(scene_config_load(scene, &cfg, &cerr) == 0, "%s", cerr.message);
  CHECK(cfg.fog.model == FOG_MODEL_HOMOGENEOUS && fabs(cfg.fog.density_scale - 0.004) < 1e-12,
        "loaded model %d, K %.9g", (int)cfg.fog.model, cfg.fog.density_scale);

  /* Perlin fog: a fogmap projected from it holds it within 0.04 on average (the height
   * fog does not), in a twentieth of the time: its file goes beside the scene */
  char perlin_scene[256], perlin_map[256];
  snprintf(perlin_scene, sizeof perlin_scene, "%s/perlin.ini", dir);
  snprintf(perlin_map, sizeof perlin_map, "%s/perlin.fogmap.exr", dir);
  snprintf(args, sizeof args, "configs/perlin_fog.ini --tolerance 0.04 --by mean --out '%s' %s",
           perlin_scene, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 0 && strstr(out, "chosen: fogmap"), "Perlin: exit %d: %s%s", status, out, err);
  CHECK(scene_config_load(perlin_scene, &cfg, &cerr) == 0, "%s", cerr.message);
  CHECK(cfg.fog.model == FOG_MODEL_FOGMAP && !strcmp(cfg.fog.fogmap, perlin_map) &&
            cfg.fog.profile == SCENE_PROFILE_BSPLINE && cfg.fog.profile_count > 8,
        "loaded model %d, fogmap '%s', profile %d of %d knots", (int)cfg.fog.model,
        cfg.fog.fogmap, (int)cfg.fog.profile, cfg.fog.profile_count);
  /* lit per piece as the Perlin fog was (its auto), not by the fogmap's segments */
  CHECK(scene_config_light_rule(&cfg).pieces, "the fitted fogmap is lit by segments");

  /* a missing VDB: the file named, nothing written */
  char missing_out[256];
  snprintf(missing_out, sizeof missing_out, "%s/missing.ini", dir);
  snprintf(args, sizeof args, "'%s/none_0001.vdb' --tolerance 0.1 --out '%s' %s", dir,
           missing_out, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status != 0, "a missing VDB: exit 0");
  CHECK(strstr(err, "none_0001.vdb") != NULL, "stderr does not name the file: %s", err);
  CHECK(!exists(missing_out), "%s written", missing_out);

  /* a VDB INPUT's own errors name the file and what it holds, not a config line nobody
   * wrote ("x.vdb:0: [fog] vdb: x.vdb: no grid named ..."), nor the file twice */
  snprintf(args, sizeof args, "../shared/data/vdb/groundfog/data/fluid_data_0048.vdb "
           "--tolerance 0.1 --grid nosuch --out '%s' %s", missing_out, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 1 && strstr(err, "fluid_data_0048.vdb: no grid named 'nosuch'; the file has") &&
            !strstr(err, ":0:") && !strstr(err, "[fog]") && !exists(missing_out),
        "--grid nosuch: exit %d, stderr %s", status, err);
  snprintf(args, sizeof args, "'../shared/data/vdb/groundfog/data/fluid_data_####.vdb' "
           "--tolerance 0.1 --frame 999 --out '%s' %s", missing_out, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 1 &&
            strstr(err, "fluid_data_####.vdb: no frame 999 in the sequence (frames 1..48)") &&
            !strstr(err, ":0:") && !exists(missing_out),
        "--frame 999: exit %d, stderr %s", status, err);
  {
    char nofog[256], twice[600];
    snprintf(nofog, sizeof nofog, "%s/nofog.ini", dir);
    test_write_text(nofog, "[fog]\nmodel = fogmap\n");
    snprintf(args, sizeof args, "'%s' --tolerance 0.1 %s", nofog, fast);
    status = fit(bin, args, out, err, sizeof out);
    snprintf(twice, sizeof twice, "%s: %s", nofog, nofog);
    CHECK(status == 1 && strstr(err, "nofog.ini: the scene has no fog to fit") &&
              !strstr(err, twice),
          "no fog: exit %d, stderr %s", status, err);
  }

  /* a bad config key: FILE:LINE named */
  char bad[256];
  snprintf(bad, sizeof bad, "%s/bad.ini", dir);
  test_write_text(bad, "[fog]\nmodel = homogeneous\ndensity_scael = 0.004\n");
  snprintf(args, sizeof args, "'%s' --tolerance 0.1 --out '%s' %s", bad, missing_out, fast);
  status = fit(bin, args, out, err, sizeof out);
  char want[300];
  snprintf(want, sizeof want, "%s:3", bad);
  CHECK(status != 0 && strstr(err, want) && strstr(err, "density_scael"),
        "a bad key: exit %d, stderr %s", status, err);
  CHECK(!exists(missing_out), "%s written", missing_out);

  /* no tolerance: a usage error */
  snprintf(args, sizeof args, "'%s' %s", ini, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 2 && strstr(err, "--tolerance"), "no tolerance: exit %d, %s", status, err);

  /* --frames without a sequence */
  snprintf(args, sizeof args, "'%s' --tolerance 0.1 --frames all %s", ini, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 2 && strstr(err, "--frames") && strstr(err, "no VDB sequence"),
        "--frames without a sequence: exit %d, %s", status, err);

  /* --frames' syntax read before the input: a malformed range is named as such (it said
   * "no VDB sequence"), and all:S is every S-th frame (it was refused as "all") */
  snprintf(args, sizeof args, "'%s' --tolerance 0.1 --frames x %s", ini, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 2 && strstr(err, "--frames 'x': expected all, A or A-B"),
        "--frames x: exit %d, %s", status, err);
  snprintf(args, sizeof args, "'../shared/data/vdb/groundfog/data/fluid_data_####.vdb' "
           "--tolerance 0.1 --frames all:24 %s", fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 0 && strstr(out, "2 frames (1..25;"), "--frames all:24: exit %d, %s %s",
        status, out, err);
  /* the chosen rung plays the sequence: its config shows the last frame fitted, not the
   * input's default -1 (the sequence's last, 48, which the fit never looked at) */
  {
    char played[256], text[8192];
    snprintf(played, sizeof played, "%s/played.ini", dir);
    snprintf(args, sizeof args, "'../shared/data/vdb/groundfog/data/fluid_data_####.vdb' "
             "--tolerance 1e-9 --frames 1-25:24 --out '%s' %s", played, fast);
    status = fit(bin, args, out, err, sizeof out);
    read_text(played, text, sizeof text);
    CHECK(status == 0 && strstr(out, "chosen: volume") && strstr(text, "\nvdb_frame = 25\n"),
          "--frames 1-25:24: exit %d, the config's frame: %s", status,
          strstr(text, "vdb_frame") ? strstr(text, "vdb_frame") : "(none)");
  }

  /* an --out that cannot be written: the path named, nothing left */
  char unwritable[256];
  snprintf(unwritable, sizeof unwritable, "%s/no/such/folder/scene.ini", dir);
  snprintf(args, sizeof args, "'%s' --tolerance 0.1 --out '%s' %s", ini, unwritable, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status != 0 && strstr(err, unwritable), "unwritable --out: exit %d, %s", status, err);

  /* --out the INPUT itself, spelt otherwise: refused before the fit, the input kept */
  char before[8192], after[8192], same[300];
  read_text(ini, before, sizeof before);
  snprintf(same, sizeof same, "%s/./constant.ini", dir);
  snprintf(args, sizeof args, "'%s' --tolerance 0.5 --out '%s' %s", ini, same, fast);
  status = fit(bin, args, out, err, sizeof out);
  read_text(ini, after, sizeof after);
  CHECK(status == 2 && strstr(err, "is the INPUT") && !strstr(out, "chosen"),
        "--out the input: exit %d, %s%s", status, out, err);
  CHECK(!strcmp(before, after), "the input was rewritten:\n%s", after);
  /* --out whose fogmap beside it (OUT.fogmap.exr) would be the scene's fogmap: the same */
  char map[300], cp[700];
  snprintf(map, sizeof map, "%s/other.fogmap.exr", dir);
  snprintf(cp, sizeof cp, "cp data/fogmap_sample.exr '%s'", map);
  CHECK(system(cp) == 0, "%s", cp);
  snprintf(same, sizeof same, "%s/map.ini", dir);
  test_write_text(same, "[fog]\nmodel = fogmap\nfogmap = other.fogmap.exr\n");
  snprintf(args, sizeof args, "'%s' --tolerance 0.5 --out '%s/other.ini' %s", same, dir, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 2 && strstr(err, "is the config's [fog] fogmap"),
        "--out beside the scene's fogmap: exit %d, %s%s", status, out, err);

  /* the VDB reference with the quadric volumes beside it */
  char plume[300], text[16384];
  snprintf(plume, sizeof plume, "%s/plume_sphere.ini", dir);
  snprintf(text, sizeof text,
           "[camera]\nposition = 0 1.5 6\nlook_at = 0 1.2 0\n"
           "[fog]\nmodel = volume\nvdb = %s/../shared/data/vdb/plume/data/fluid_data_0048.vdb\n"
           "density_scale = 6\nquadric = sphere 3 1.5 0 0.6 5\n",
           FOGPIPE_SOURCE_DIR);
  test_write_text(plume, text);
  snprintf(args, sizeof args, "'%s' --tolerance 0.5 --by mean --rays 4 --samples 8 --size 32x18 "
           "--timed 1", plume);
  status = fit(bin, args, out, err, sizeof out);
  const char *domain = strstr(out, "domain [");
  double x_lo = 0.0, x_hi = 0.0;
  CHECK(status == 0 && domain && sscanf(domain, "domain [%lf, %lf]", &x_lo, &x_hi) == 2 &&
            x_hi >= 3.6 - 1e-9,
        "plume beside a sphere at x 2.4..3.6: exit %d, domain x to %g: %s%s", status, x_hi, out,
        err);
  /* and the volume rung draws it too: exact against the reference */
  const char *volume_row = strstr(out, " volume ");
  double volume_max = -1.0;
  CHECK(volume_row && sscanf(volume_row, " volume %lf", &volume_max) == 1 && volume_max == 0.0,
        "plume beside a sphere: the volume rung's max error %g, expected 0", volume_max);

  /* classic linear fog: its samples about the camera, opaque past fog_end */
  char classic[300];
  snprintf(classic, sizeof classic, "%s/classic.ini", dir);
  test_write_text(classic, "[camera]\nposition = 0 120 400\nlook_at = 0 20 -100\n"
                           "[terrain]\nsize = 1000 1000\nheight = 120\n"
                           "[fog]\nmodel = linear\nfog_start = 100\nfog_end = 500\n");
  snprintf(args, sizeof args, "'%s' --tolerance 0.05 %s", classic, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 0 && strstr(out, "linear as given"), "classic fog ending at 500: exit %d, %s%s",
        status, out, err);

  /* a fogmap input at its own settings */
  char summed[300], summed_pick[300];
  snprintf(summed, sizeof summed, "%s/summed.ini", dir);
  snprintf(summed_pick, sizeof summed_pick, "%s/summed_pick.ini", dir);
  snprintf(text, sizeof text,
           "[fog]\nfogmap = %s/data/fogmap_sample.png\ndensity_scale = 0.02\nlevels = 2\n"
           "lod = sum\nmu = 0.7\nprofile = exponential\nfog_height = 50\nscale_height = 25\n"
           "[box]\norigin = -512 -512\ncell_size = 4\n",
           FOGPIPE_SOURCE_DIR);
  test_write_text(summed, text);
  snprintf(args, sizeof args, "'%s' --tolerance 0.0001 --by mean --out '%s' %s", summed,
           summed_pick, fast);
  status = fit(bin, args, out, err, sizeof out);
  CHECK(status == 0 && strstr(out, "chosen: fogmap as given") && exists(summed_pick),
        "a fogmap at its own settings: exit %d, %s%s", status, out, err);

  /* SIGTERM while the rungs are measured: exit 130, the scratch folder of the projected
   * fogmap (in $TMPDIR) removed. The signal goes once that folder exists. */
  char tmp[300], stopped[4096];
  snprintf(tmp, sizeof tmp, "%s/tmp", dir);
  CHECK(mkdir(tmp, 0777) == 0, "cannot make %s", tmp);
  snprintf(stopped, sizeof stopped,
           "TMPDIR='%s' '%s' fit configs/perlin_fog.ini --tolerance 0.01 > '%s/out.txt' "
           "2> '%s/err.txt' & pid=$!; i=0; while [ $i -lt 1000 ] && ! ls '%s' | grep -q "
           "fogpipe-fit; do sleep 0.01; i=$((i+1)); done; kill -TERM $pid; wait $pid; "
           "exit $?",
           tmp, bin, dir, dir, tmp);
  status = system(stopped);
  status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  snprintf(args, sizeof args, "%s/err.txt", dir);
  read_text(args, err, sizeof err);
  CHECK(status == 130 && strstr(err, "interrupted") && test_folder_entries(tmp) == 0,
        "SIGTERM during the fit: exit %d, %d files left in TMPDIR, %s", status,
        test_folder_entries(tmp), err);

  char command[512];
  snprintf(command, sizeof command, "rm -rf '%s'", dir);
  if (system(command)) fprintf(stderr, "could not remove %s\n", dir);
  return test_finish("test_fit_cli");
}
