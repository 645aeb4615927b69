/* Frame ranges for a render farm, and what --resume keeps.
 * - `record --frames 1-12` and `--frames 13-24`, run at the same time in two processes into
 *   one folder, give the 24 files of one full run, byte for byte (the simulation is re-run,
 *   unrendered, up to a range's first frame).
 * - --resume with another scene (same size) is refused, naming the frame; the folder is
 *   left as it was.
 * - A frame truncated on disk (size > 0) is not counted as complete: --resume renders it
 *   again, and the folder again equals the full run byte for byte.
 * - A frame without the recording identity (an older fogpipe, another program) is refused.
 * - A plain run of another scene over part of the frames warns, naming a frame it leaves
 *   of the other recording, and leaves that frame as it was.
 * - --resume judges every frame of its range, also past a gap: another scene's frame
 *   there is refused, not rendered over.
 * - A run removes the temporaries a killed run left for its own range only. */
#include "tests/app/record_util.h"
#include "tests/test_util.h"

enum { FRAMES = 24 };

static pid_t start(const char *config, const char *frames, const char *out, const char *extra,
                   const char *log) {
  pid_t pid = fork();
  if (pid == 0) {
    int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) dup2(fd, 1), dup2(fd, 2), close(fd);
    const char *argv[] = {record_bin(), "record", config, "--frames", frames, "--out", out,
                          "--size", RECORD_TEST_SIZE, extra, NULL};
    execv(argv[0], (char *const *)argv);
    _exit(127);
  }
  return pid;
}

static unsigned char *read_all(const char *path, size_t *size) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char *bytes = malloc(n > 0 ? (size_t)n : 1);
  *size = bytes ? fread(bytes, 1, (size_t)n, f) : 0;
  fclose(f);
  return bytes;
}

/* Frames 1..FRAMES of a and b that differ in any byte. */
static int differing_files(const char *a, const char *b) {
  int differing = 0;
  for (int f = 1; f <= FRAMES; f++) {
    char pa[700], pb[700];
    record_frame_path(a, f, pa, sizeof pa);
    record_frame_path(b, f, pb, sizeof pb);
    size_t na = 0, nb = 0;
    unsigned char *ba = read_all(pa, &na), *bb = read_all(pb, &nb);
    if (!ba || !bb || na != nb || memcmp(ba, bb, na)) {
      if (differing++ < 3) fprintf(stderr, "  frame %d differs (%zu vs %zu bytes)\n", f, na, nb);
    }
    free(ba), free(bb);
  }
  return differing;
}

int main(void) {
  char root[] = "/tmp/fogpipe-record-ranges-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char whole[600], split[600], log[4][700];
  snprintf(whole, sizeof whole, "%s/whole", root);
  snprintf(split, sizeof split, "%s/split", root);
  for (int i = 0; i < 4; i++) snprintf(log[i], sizeof log[i], "%s/log%d", root, i);

  int status = record_wait(start(RECORD_TEST_CONFIG, "24", whole, NULL, log[0]));
  CHECK(status == 0, "full run exited %d", status);
  pid_t a = start(RECORD_TEST_CONFIG, "1-12", split, NULL, log[1]);
  pid_t b = start(RECORD_TEST_CONFIG, "13-24", split, NULL, log[2]);
  int sa = record_wait(a), sb = record_wait(b);
  CHECK(sa == 0 && sb == 0, "ranges 1-12 and 13-24 exited %d and %d", sa, sb);
  if (sa) record_print_log(log[1]);
  if (sb) record_print_log(log[2]);
  int frames = 0, others = record_count_files(split, &frames);
  CHECK(frames == FRAMES && others == 0, "the two ranges left %d frames and %d other files",
        frames, others);
  int differing = differing_files(whole, split);
  CHECK(differing == 0, "%d of %d frames of the two ranges differ from the full run", differing,
        FRAMES);

  /* Another scene, same size: its --resume over these frames is refused. */
  char other[700];
  snprintf(other, sizeof other, "%s/other.ini", root);
  FILE *f = fopen(other, "w");
  fprintf(f, "[fog]\nmodel = homogeneous\ndensity_scale = 0.01\n");
  fclose(f);
  char frame5[700];
  record_frame_path(split, 5, frame5, sizeof frame5);
  struct stat before, after;
  stat(frame5, &before);
  status = record_wait(start(other, "24", split, "--resume", log[3]));
  CHECK(status == 1 && record_log_contains(log[3], "cannot resume") &&
            record_log_contains(log[3], "frame.0001.exr was recorded from another scene"),
        "--resume with another scene: exit %d", status);
  if (status != 1) record_print_log(log[3]);
  stat(frame5, &after);
  CHECK(before.st_mtime == after.st_mtime && before.st_size == after.st_size,
        "the refused resume touched the frames");

  /* A frame cut short on disk is rendered again by --resume. */
  CHECK(truncate(frame5, before.st_size / 2) == 0, "truncate");
  status = record_wait(start(RECORD_TEST_CONFIG, "24", split, "--resume", log[3]));
  CHECK(status == 0 && record_log_contains(log[3], "after frame 4"),
        "--resume over a truncated frame 5: exit %d", status);
  if (status) record_print_log(log[3]);
  differing = differing_files(whole, split);
  CHECK(differing == 0, "after resuming over a truncated frame, %d frames differ", differing);

  /* A frame with no identity in its header cannot be told apart: refused. */
  char legacy[600];
  snprintf(legacy, sizeof legacy, "%s/legacy", root);
  mkdir(legacy, 0755);
  char frame1[700];
  record_frame_path(legacy, 1, frame1, sizeof frame1);
  float pixels[64 * 36] = {0};
  image_channel y = {.name = "A", .pixels = pixels, .as_half = 1};
  fog_error err;
  CHECK(image_write_exr(frame1, 64, 36, &y, 1, &err) == 0, "%s", err.message);
  status = record_wait(start(RECORD_TEST_CONFIG, "2", legacy, "--resume", log[3]));
  CHECK(status == 1 && record_log_contains(log[3], "carries no recording identity"),
        "--resume over a frame without identity: exit %d", status);

  /* Another scene over frames 1-12 of the full run: a warning names a frame it leaves. */
  char frame20[700];
  record_frame_path(whole, 20, frame20, sizeof frame20);
  stat(frame20, &before);
  status = record_wait(start(other, "1-12", whole, NULL, log[3]));
  CHECK(status == 0 && record_log_contains(log[3], "warning: ") &&
            record_log_contains(log[3], ", outside frames 1-12, was recorded from another "
                                        "scene or settings"),
        "another scene over frames 1-12 of 24: exit %d, or no warning", status);
  if (status) record_print_log(log[3]);
  stat(frame20, &after);
  CHECK(before.st_mtime == after.st_mtime && before.st_size == after.st_size,
        "a run of frames 1-12 touched frame 20");
  /* A frame of another scene after a gap in the range: --resume would render over it.
   * Refused, naming it, and the gap stays (nothing is rendered). */
  char frame6[700], frame9[700];
  record_frame_path(split, 6, frame6, sizeof frame6);
  record_frame_path(split, 9, frame9, sizeof frame9);
  CHECK(unlink(frame6) == 0, "unlink %s", frame6);
  status = record_wait(start(other, "9-9", split, NULL, log[3]));
  CHECK(status == 0, "another scene's frame 9 into the split folder: exit %d", status);
  stat(frame9, &before);
  status = record_wait(start(RECORD_TEST_CONFIG, "24", split, "--resume", log[3]));
  CHECK(status == 1 && record_log_contains(log[3], "cannot resume") &&
            record_log_contains(log[3], "frame.0009.exr was recorded from another scene"),
        "--resume over a gap, then another scene's frame 9: exit %d", status);
  if (status != 1) record_print_log(log[3]);
  stat(frame9, &after);
  CHECK(before.st_mtime == after.st_mtime && before.st_size == after.st_size &&
            stat(frame6, &after) != 0,
        "the refused resume rendered frames");

  /* A killed run's temporary of this range is removed; another range's (a farm's other
   * job, writing now) is left alone. */
  char temps[600], mine[700], theirs[700];
  snprintf(temps, sizeof temps, "%s/temps", root);
  snprintf(mine, sizeof mine, "%s/.frame.0002.exr.tmp.AbC123", temps);
  snprintf(theirs, sizeof theirs, "%s/.frame.0007.exr.tmp.XyZ789", temps);
  mkdir(temps, 0755);
  fclose(fopen(mine, "w"));
  fclose(fopen(theirs, "w"));
  status = record_wait(start(RECORD_TEST_CONFIG, "1-3", temps, "--resume", log[3]));
  CHECK(status == 0, "--resume of 1-3 beside temporaries: exit %d", status);
  if (status) record_print_log(log[3]);
  CHECK(stat(mine, &after) != 0, "the stale temporary of frame 2 stayed");
  CHECK(stat(theirs, &after) == 0, "frame 7's temporary, another range's, was removed");

  test_remove_tree(root);
  return test_finish("test_record_frame_ranges");
}
