/* `fogpipe bake` for a render farm: the simulation run once, each frame's fogmap written,
 * and a config that plays them. A range recorded from the bake, with no simulation before
 * it, has the pixels of the same frames of one full simulated run, every channel, bit for
 * bit. A bad bake (a model without a simulation) is refused and leaves no folder behind;
 * the bake's config loads back to the same scene but its fog. The bake's folder is named
 * "bake#1": a '#' of a folder is itself, not the frame number of the fogmaps' pattern, and
 * the closing hint quotes the path for a shell (it was pasted as two words). A re-bake
 * interrupted half-way leaves the old bake as it was; a bake over one written with another
 * count of digits (fog.00001.exr of a bake of 10001 frames) removes that one's frames. */
#include "tests/app/record_util.h"
#include "tests/test_util.h"

#include "app/config.h"
#include "sim/sim.h"

enum { FRAMES = 8, FIRST = 5 };

static int run(const char *command, const char *log) {
  const int status = record_shell(command, log);
  if (status != 0) record_print_log(log);
  return status;
}

int main(void) {
  char root[] = "/tmp/fogpipe-bake-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char bake[600], whole[600], range[600], log[600], command[3000], ini[700];
  snprintf(bake, sizeof bake, "%s/bake#1", root);
  snprintf(whole, sizeof whole, "%s/whole", root);
  snprintf(range, sizeof range, "%s/range", root);
  snprintf(log, sizeof log, "%s/log.txt", root);
  snprintf(ini, sizeof ini, "%s/bake.ini", bake);

  snprintf(command, sizeof command, "'%s' bake %s --frames %d --out '%s'", record_bin(),
           RECORD_TEST_CONFIG, FRAMES, bake);
  CHECK(run(command, log) == 0, "bake failed");
  CHECK(record_log_contains(log, "render a range: fogpipe record") &&
            !record_log_contains(log, "--fps"),
        "the default bake's hint names a rate");
  {
    char quoted[800];
    snprintf(quoted, sizeof quoted, "render a range: fogpipe record '%s' --frames A-B", ini);
    CHECK(record_log_contains(log, quoted), "the hint does not quote %s for a shell", ini);
  }
  /* a bake at another rate says to record it at that rate (bake.ini holds none, but lamps
   * on a path run on the scene's clock) */
  char slow[600];
  snprintf(slow, sizeof slow, "%s/slow", root);
  char earlier[2][700];
  CHECK(mkdir(slow, 0755) == 0, "mkdir %s", slow);
  for (int i = 0; i < 2; i++) {
    snprintf(earlier[i], sizeof earlier[i], "%s/fog.%05d.exr", slow, i ? 9 : 1);
    test_write_text(earlier[i], "an earlier bake's frame\n");
  }
  /* names no bake writes (fewer than 4 digits, frame 0): a user's, kept */
  const char *kept_names[3] = {"fog.1.exr", "fog.012.exr", "fog.00000.exr"};
  char kept[3][700];
  for (int i = 0; i < 3; i++) {
    snprintf(kept[i], sizeof kept[i], "%s/%s", slow, kept_names[i]);
    test_write_text(kept[i], "a user's file\n");
  }
  snprintf(command, sizeof command, "'%s' bake %s --frames 1 --fps 12 --out '%s'", record_bin(),
           RECORD_TEST_CONFIG, slow);
  CHECK(run(command, log) == 0 && record_log_contains(log, "bake.ini --fps 12 --frames A-B"),
        "a bake at 12 fps does not say to record it at 12");
  for (int i = 0; i < 2; i++)
    CHECK(access(earlier[i], F_OK) != 0, "%s, of an earlier bake of another count of digits, "
          "is left beside the new bake", earlier[i]);
  for (int i = 0; i < 3; i++)
    CHECK(access(kept[i], F_OK) == 0, "%s, a name no bake writes, was removed", kept[i]);
  snprintf(command, sizeof command, "'%s' record %s --frames %d --size %s --out '%s'",
           record_bin(), RECORD_TEST_CONFIG, FRAMES, RECORD_TEST_SIZE, whole);
  CHECK(run(command, log) == 0, "the full simulated record failed");
  snprintf(command, sizeof command, "'%s' record '%s' --frames %d-%d --size %s --out '%s'",
           record_bin(), ini, FIRST, FRAMES, RECORD_TEST_SIZE, range);
  CHECK(run(command, log) == 0, "the range from the bake failed");
  CHECK(!record_log_contains(log, "re-running the simulation"),
        "the range from the bake re-ran a simulation");

  for (int f = FIRST; f <= FRAMES; f++) {
    char a[700], b[700];
    record_frame_path(whole, f, a, sizeof a);
    record_frame_path(range, f, b, sizeof b);
    int wa = 0, ha = 0, wb = 0, hb = 0;
    uint64_t ha_hash = record_hash_frame(a, &wa, &ha), hb_hash = record_hash_frame(b, &wb, &hb);
    CHECK(ha_hash != 0 && ha_hash == hb_hash && wa == wb && ha == hb,
          "frame %d: the bake's pixels differ from the simulated run's", f);
  }
  /* The simulation moves: the bake is not one frame repeated. */
  char p1[700], p2[700];
  snprintf(p1, sizeof p1, "%s/fog.0001.exr", bake);
  snprintf(p2, sizeof p2, "%s/fog.%04d.exr", bake, FRAMES);
  fogmap m1 = {0}, m2 = {0};
  fog_error serr = {0};
  int loaded = !fogmap_load(p1, NULL, &m1, &serr) && !fogmap_load(p2, NULL, &m2, &serr);
  CHECK(loaded, "the bake's frames do not load: %s", serr.message);
  double change = 0.0;
  for (int i = 0; loaded && i < m1.width * m1.height; i++)
    change += fabs((double)m1.density[i] - m2.density[i]);
  CHECK(loaded && change > 0.0, "frames 1 and %d of the bake are the same", FRAMES);
  fogmap_destroy(&m1);
  fogmap_destroy(&m2);

  /* A still of the bake (render, view) shows its frame 1: fog, not an empty scene. */
  char still[700];
  snprintf(still, sizeof still, "%s/still.exr", root);
  snprintf(command, sizeof command, "'%s' render '%s' --size %s --out '%s'", record_bin(), ini,
           RECORD_TEST_SIZE, still);
  CHECK(run(command, log) == 0 && record_log_contains(log, "scene + fog"),
        "render of the bake's config failed");

  /* The bake's config is the scene with the frames as its fog. */
  scene_config original, baked;
  fog_error err = {0};
  CHECK(scene_config_load(RECORD_TEST_CONFIG, &original, &err) == 0, "%s", err.message);
  CHECK(scene_config_load(ini, &baked, &err) == 0, "%s", err.message);
  CHECK(baked.fog.sequence[0] && !baked.fog.fogmap[0] &&
            baked.fog.density_scale == original.fog.density_scale &&
            baked.box.cell_size == original.box.cell_size && baked.fog.levels == original.fog.levels,
        "bake.ini is not the scene playing its frames");

  /* Baking fewer frames into the same folder leaves no frame of the longer bake to play,
   * past a gap in them too (a stray fog.0012.exr: its bake.ini would be refused for the
   * gap at 9), and the shorter bake's config loads. */
  char stray[700], far[700];
  snprintf(stray, sizeof stray, "%s/fog.0012.exr", bake);
  snprintf(command, sizeof command, "cp '%s' '%s'", p1, stray);
  CHECK(system(command) == 0, "cannot make %s", stray);
  /* and one numbered far past 2^20 frames (the sequence lister refuses such a span: the
   * bake kept it, exit 0, and its bake.ini did not load) */
  snprintf(far, sizeof far, "%s/fog.2000000.exr", bake);
  snprintf(command, sizeof command, "cp '%s' '%s'", p1, far);
  CHECK(system(command) == 0, "cannot make %s", far);
  snprintf(command, sizeof command, "'%s' bake %s --frames 3 --out '%s'", record_bin(),
           RECORD_TEST_CONFIG, bake);
  CHECK(run(command, log) == 0, "the second, shorter bake failed");
  char stale[700];
  snprintf(stale, sizeof stale, "%s/fog.0004.exr", bake);
  CHECK(access(stale, F_OK) != 0, "the shorter bake left %s of the longer one", stale);
  CHECK(access(stray, F_OK) != 0, "the shorter bake left %s past the gap", stray);
  CHECK(access(far, F_OK) != 0, "the shorter bake left %s", far);
  CHECK(scene_config_load(ini, &baked, &err) == 0, "the shorter bake's config: %s", err.message);

  /* A re-bake interrupted (SIGTERM) once it has simulated frames (of the old frames' names:
   * 5000 frames keep 4 digits): exit 130, and the folder holds the old bake as it was: its
   * bake.ini and its frames byte for byte, no staging folder. */
  char before_ini[4096] = "", after_ini[4096] = "";
  FILE *f = fopen(ini, "r");
  size_t n = f ? fread(before_ini, 1, sizeof before_ini - 1, f) : 0;
  before_ini[n] = '\0';
  if (f) fclose(f);
  struct stat st, old_frame;
  stat(p1, &old_frame);
  const int entries = test_folder_entries(bake);
  pid_t pid = fork();
  if (pid == 0) {
    int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) dup2(fd, 1), dup2(fd, 2), close(fd);
    execl(record_bin(), record_bin(), "bake", RECORD_TEST_CONFIG, "--frames", "5000",
          "--out", bake, (char *)NULL);
    _exit(127);
  }
  /* two frames in the staging folder (or, were frames written in place, frame 1 rewritten) */
  for (int waited = 0; waited < 60000; waited += 5) {
    int staged = 0;
    DIR *d = opendir(bake);
    for (struct dirent *e; d && (e = readdir(d));)
      if (!strncmp(e->d_name, ".bake-staging.", 14)) {
        char path[1000];
        snprintf(path, sizeof path, "%s/%s", bake, e->d_name);
        staged = test_folder_entries(path);
      }
    if (d) closedir(d);
    if (staged >= 2 || (stat(p1, &st) == 0 && st.st_mtime != old_frame.st_mtime)) break;
    record_sleep_ms(5);
  }
  kill(pid, SIGTERM);
  int status = record_wait(pid);
  CHECK(status == 130 && record_log_contains(log, "interrupted"),
        "the interrupted re-bake exited %d", status);
  f = fopen(ini, "r");
  n = f ? fread(after_ini, 1, sizeof after_ini - 1, f) : 0;
  after_ini[n] = '\0';
  if (f) fclose(f);
  CHECK(n > 0 && !strcmp(before_ini, after_ini), "the interrupted re-bake changed bake.ini");
  CHECK(stat(p1, &st) == 0 && st.st_mtime == old_frame.st_mtime &&
            st.st_size == old_frame.st_size,
        "the interrupted re-bake changed %s", p1);
  CHECK(test_folder_entries(bake) == entries, "the interrupted re-bake left %d files, had %d",
        test_folder_entries(bake), entries);

  /* A bake whose bake.ini or a frame's name in the folder is a folder: refused before the
   * simulation, naming it, and nothing of the new bake stays (it used to fail at the move:
   * the whole bake was left in a hidden staging folder, or a folder without bake.ini). */
  const char *const blockers[] = {"bake.ini", "fog.0002.exr"};
  for (int b = 0; b < 2; b++) {
    char blocked[700], blocker[800];
    snprintf(blocked, sizeof blocked, "%s/blocked%d", root, b);
    snprintf(blocker, sizeof blocker, "%s/%s", blocked, blockers[b]);
    snprintf(command, sizeof command, "mkdir -p '%s'", blocker);
    CHECK(system(command) == 0, "cannot make %s", blocker);
    snprintf(command, sizeof command, "'%s' bake %s --frames 3 --out '%s'", record_bin(),
             RECORD_TEST_CONFIG, blocked);
    CHECK(run(command, log) == 1 && record_log_contains(log, "is not a file") &&
              record_log_contains(log, blockers[b]),
          "a bake onto a folder named %s was not refused naming it", blockers[b]);
    CHECK(test_folder_entries(blocked) == 1, "the refused bake left %d entries in %s, had 1",
          test_folder_entries(blocked), blocked);
  }

  /* Nothing to bake: refused, no folder made. */
  char none[600];
  snprintf(none, sizeof none, "%s/none/deeper", root);
  snprintf(command, sizeof command, "'%s' bake configs/rbf_fog_banks.ini --frames 2 --out '%s'",
           record_bin(), none);
  CHECK(run(command, log) == 1 && record_log_contains(log, "nothing to bake"),
        "a bake of an analytic model was not refused");
  snprintf(none, sizeof none, "%s/none", root);
  CHECK(stat(none, &st) != 0, "the refused bake left %s", none);
  test_remove_tree(root);
  return test_finish("test_bake");
}
