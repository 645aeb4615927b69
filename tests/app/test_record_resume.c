/* `fogpipe record` interrupted by SIGINT finishes the frame it is on and exits with 130,
 * leaving only whole frames (every one readable in every channel, no temporary files);
 * `--resume` (the command the interrupt printed, run by a shell: the folder's name holds a
 * space and a quote) then completes the sequence, and the result has the same pixels,
 * frame by frame, as an uninterrupted recording. A resume with another --size is refused.
 * Interrupted while rendering over another scene's recording, it prints the frames left as
 * a range (--resume would refuse those frames), which finishes the same sequence. */
#include "tests/app/record_util.h"
#include "tests/test_util.h"

enum { frames = 24 };

/* The command an interrupted run printed ("to finish: fogpipe ...") from its log, into
 * hint; false when there is none. */
static bool printed_hint(const char *log, char *hint, size_t size) {
  char text[8192] = "";
  FILE *f = fopen(log, "r");
  size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
  text[n] = '\0';
  if (f) fclose(f);
  const char *at = strstr(text, "to finish: fogpipe ");
  if (!at) return false;
  snprintf(hint, size, "%.*s", (int)strcspn(at, "\n"), at);
  return true;
}

/* The hint run as printed, by a shell (the binary in place of "fogpipe"): its exit status. */
static int run_hint(const char *hint, const char *log, char *command, size_t size) {
  snprintf(command, size, "'%s'%s > '%s' 2>&1", record_bin(),
           hint + strlen("to finish: fogpipe"), log);
  const int status = system(command);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* Frames 1..frames of folders a and b that differ (or cannot be read), the first 3 named. */
static int frames_differing(const char *a_folder, const char *b_folder) {
  int differing = 0;
  for (int k = 1; k <= frames; k++) {
    char a[600], b[600];
    int w = 0, h = 0;
    record_frame_path(a_folder, k, a, sizeof a);
    record_frame_path(b_folder, k, b, sizeof b);
    const uint64_t ha = record_hash_frame(a, &w, &h), hb = record_hash_frame(b, &w, &h);
    if ((ha == 0 || ha != hb) && differing++ < 3)
      fprintf(stderr, "frame %d: %s and %s differ\n", k, a_folder, b_folder);
  }
  return differing;
}

int main(void) {
  char root[] = "/tmp/fogpipe-record-resume-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char whole[512], cut[512], log_whole[512], log_cut[512], log_resume[512];
  snprintf(whole, sizeof whole, "%s/whole", root);
  /* a folder name a shell would split or unquote: the printed resume command quotes it */
  snprintf(cut, sizeof cut, "%s/cut it's", root);
  snprintf(log_whole, sizeof log_whole, "%s/whole.log", root);
  snprintf(log_cut, sizeof log_cut, "%s/cut.log", root);
  snprintf(log_resume, sizeof log_resume, "%s/resume.log", root);

  /* Interrupt as soon as the first frame is on disk. */
  pid_t pid = record_start(cut, frames, NULL, log_cut);
  char first[600];
  record_frame_path(cut, 1, first, sizeof first);
  struct stat st;
  for (int waited = 0; waited < 60000 && stat(first, &st) != 0; waited += 2) {
    if (waitpid(pid, NULL, WNOHANG) == pid) break;
    record_sleep_ms(2);
  }
  kill(pid, SIGINT);
  int status = record_wait(pid);
  CHECK(status == 130, "interrupted record exited with %d, expected 130", status);
  CHECK(record_log_contains(log_cut, "--resume"), "the interrupt message does not say how to "
                                                  "resume");
  if (status != 130) record_print_log(log_cut);
  int done = 0;
  int others = record_count_files(cut, &done);
  CHECK(others == 0, "%d temporary or partial files left after the interrupt", others);
  CHECK(done >= 1 && done < frames, "%d frames complete after the interrupt (expected 1..%d)",
        done, frames - 1);
  for (int f = 1; f <= done; f++) {
    char path[600];
    int w = 0, h = 0;
    record_frame_path(cut, f, path, sizeof path);
    CHECK(record_hash_frame(path, &w, &h) != 0, "frame %d left by the interrupt is unreadable",
          f);
  }

  /* Resuming with another size would mix two sequences: refused, nothing written. */
  char log_mismatch[512];
  snprintf(log_mismatch, sizeof log_mismatch, "%s/mismatch.log", root);
  pid_t mismatch = fork();
  if (mismatch == 0) {
    int fd = open(log_mismatch, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    char frames_text[16];
    snprintf(frames_text, sizeof frames_text, "%d", frames);
    execl(record_bin(), record_bin(), "record", RECORD_TEST_CONFIG, "--frames", frames_text,
          "--out", cut, "--size", "32x18", "--resume", (char *)NULL);
    _exit(127);
  }
  status = record_wait(mismatch);
  int after_mismatch = 0;
  record_count_files(cut, &after_mismatch);
  CHECK(status != 0 && status < 128 && record_log_contains(log_mismatch, "cannot resume"),
        "--resume with another --size: status %d, expected a `cannot resume` error", status);
  CHECK(after_mismatch == done, "the refused resume changed the folder: %d frames, had %d",
        after_mismatch, done);

  /* The command the interrupt printed, run as printed (by a shell), resumes. */
  char hint[8192] = "", command[9000] = "";
  CHECK(printed_hint(log_cut, hint, sizeof hint), "no resume command printed");
  status = hint[0] ? run_hint(hint, log_resume, command, sizeof command) : -1;
  CHECK(status == 0, "the printed resume command exited with %d: %s", status, command);
  if (status != 0) record_print_log(log_resume);
  status = record_run(whole, frames, NULL, log_whole);
  CHECK(status == 0, "uninterrupted record exited with %d", status);
  if (status != 0) record_print_log(log_whole);

  int resumed_frames = 0, whole_frames = 0;
  CHECK(record_count_files(cut, &resumed_frames) == 0, "temporary files after --resume");
  record_count_files(whole, &whole_frames);
  CHECK(resumed_frames == frames && whole_frames == frames,
        "resumed run has %d frames, uninterrupted %d, expected %d", resumed_frames,
        whole_frames, frames);
  int differing = frames_differing(cut, whole);
  CHECK(differing == 0, "%d of %d frames differ between the resumed and the uninterrupted run",
        differing, frames);

  /* A run over another scene's recording (which a plain run rewrites), interrupted: --resume
   * refuses to render over the other scene's frames still there, so the printed command is
   * the frames left as a range; run as printed, the folder equals the uninterrupted run. */
  char over[512], other[512], log_other[512], log_over[512], log_finish[512];
  snprintf(over, sizeof over, "%s/over", root);
  snprintf(other, sizeof other, "%s/other.ini", root);
  snprintf(log_other, sizeof log_other, "%s/other.log", root);
  snprintf(log_over, sizeof log_over, "%s/over.log", root);
  snprintf(log_finish, sizeof log_finish, "%s/finish.log", root);
  FILE *f = fopen(other, "w");
  if (f) fputs("[fog]\nmodel = homogeneous\ndensity_scale = 0.01\n", f), fclose(f);
  snprintf(command, sizeof command, "'%s' record '%s' --frames %d --out '%s' --size %s > '%s' 2>&1",
           record_bin(), other, frames, over, RECORD_TEST_SIZE, log_other);
  status = system(command);
  CHECK(status == 0, "recording another scene: %s", command);
  record_frame_path(over, 1, first, sizeof first);
  struct stat theirs;
  stat(first, &theirs);
  pid = record_start(over, frames, NULL, log_over);
  for (int waited = 0; waited < 60000; waited += 2) { /* until frame 1 is this run's */
    if (stat(first, &st) == 0 && st.st_ino != theirs.st_ino) break;
    if (waitpid(pid, NULL, WNOHANG) == pid) break;
    record_sleep_ms(2);
  }
  kill(pid, SIGINT);
  status = record_wait(pid);
  CHECK(status == 130, "the run over another scene, interrupted, exited %d", status);
  hint[0] = '\0';
  CHECK(printed_hint(log_over, hint, sizeof hint) && !strstr(hint, "--resume") &&
            strstr(hint, "-24 "),
        "over another scene, the printed command: %s", hint);
  status = hint[0] ? run_hint(hint, log_finish, command, sizeof command) : -1;
  CHECK(status == 0, "the printed command over another scene exited %d: %s", status, command);
  if (status != 0) record_print_log(log_finish);
  differing = frames_differing(over, whole);
  CHECK(differing == 0, "over another scene, finished as printed: %d of %d frames differ from "
        "the uninterrupted run", differing, frames);
  test_remove_tree(root);
  return test_finish("test_record_resume");
}
