/* `fogpipe record --preview VIDEO` hands ffmpeg exactly the recorded frames: a stand-in
 * ffmpeg first on PATH keeps its arguments and the raw rgb24 stream, which must be the
 * frames' R, G, B channels through the sRGB transfer function (IEC 61966-2-1) and the
 * ordered dither (tests/reference/srgb8_dither_reference.h), frame after frame, at the
 * size and rate asked for; the video appears under its own name only when ffmpeg
 * succeeded. A failing ffmpeg makes record fail with a message naming ffmpeg's exit code,
 * leaves no video (nor its temporary), and keeps the frames; so does a SIGTERM during the
 * encode (exit 130). The temporary is the run's own (NAME.partial.PID.N.EXT, created
 * exclusively): a user's NAME.partial.EXT beside the video is left as it was (it was
 * written over, and removed with a failed encode). Where a real ffmpeg is installed
 * (/usr/bin/ffmpeg), it also encodes a playable file. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "tests/app/record_util.h" /* first: it sets _POSIX_C_SOURCE */

#include <dirent.h>
#include <limits.h>
#include <math.h>

#include "tests/app/exr_channel_util.h"
#include "tests/reference/srgb8_dither_reference.h"
#include "tests/test_util.h"

enum { frames = 3, width = 64, height = 36 };

static int write_script(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  if (!f) return 0;
  fputs(text, f);
  fclose(f);
  return chmod(path, 0755) == 0;
}

/* Entries of folder whose name starts with prefix. */
static int entries_starting(const char *folder, const char *prefix) {
  DIR *d = opendir(folder);
  if (!d) return -1;
  int n = 0;
  for (struct dirent *e; (e = readdir(d));) n += !strncmp(e->d_name, prefix, strlen(prefix));
  closedir(d);
  return n;
}

static long file_size(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* Starts record with ffmpeg looked up first in bin_dir; its pid. */
static pid_t start_with_path(const char *bin_dir, const char *out, const char *video,
                             const char *log) {
  const char *old = getenv("PATH");
  char path[4096];
  snprintf(path, sizeof path, "%s:%s", bin_dir, old ? old : "/usr/bin:/bin");
  char *saved = old ? strdup(old) : NULL;
  setenv("PATH", path, 1);
  pid_t pid = fork();
  if (pid == 0) {
    int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) dup2(fd, 1), dup2(fd, 2), close(fd);
    const char *argv[] = {record_bin(), "record", RECORD_TEST_CONFIG, "--frames", "3",
                          "--out", out, "--size", RECORD_TEST_SIZE, "--fps", "12",
                          "--preview", video, NULL};
    execv(argv[0], (char *const *)argv);
    _exit(127);
  }
  if (saved) setenv("PATH", saved, 1);
  free(saved);
  return pid;
}

/* Runs record with ffmpeg looked up first in bin_dir; its exit status. */
static int record_with_path(const char *bin_dir, const char *out, const char *video,
                            const char *log) {
  return record_wait(start_with_path(bin_dir, out, video, log));
}

int main(void) {
  char root[] = "/tmp/fogpipe-record-preview-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  char bin[600], out[600], video[600], log[600], script[700];
  snprintf(bin, sizeof bin, "%s/bin", root);
  mkdir(bin, 0755);
  snprintf(script, sizeof script, "%s/ffmpeg", bin);

  /* 1. The stand-in: arguments one per line beside it, stdin into the output (last arg). */
  CHECK(write_script(script, "#!/bin/sh\n"
                             "for a in \"$@\"; do out=\"$a\"; done\n"
                             "printf '%s\\n' \"$@\" > \"$(dirname \"$0\")/args\"\n"
                             "cat > \"$out\"\n"),
        "cannot write %s", script);
  snprintf(out, sizeof out, "%s/frames", root);
  snprintf(video, sizeof video, "%s/preview.mp4", root);
  snprintf(log, sizeof log, "%s/record.log", root);
  int status = record_with_path(bin, out, video, log);
  CHECK(status == 0, "record --preview with the stand-in ffmpeg exited %d", status);
  if (status) record_print_log(log);
  long expected = (long)frames * width * height * 3;
  CHECK(file_size(video) == expected, "%s: %ld bytes, expected %ld (3 frames of 64x36 rgb24)",
        video, file_size(video), expected);
  CHECK(entries_starting(root, "preview.partial") == 0, "a temporary preview.partial* was left "
        "behind");

  char args_path[700], args[4096] = "";
  snprintf(args_path, sizeof args_path, "%s/args", bin);
  FILE *f = fopen(args_path, "r");
  if (f) {
    size_t n = fread(args, 1, sizeof args - 1, f);
    args[n] = '\0';
    fclose(f);
  }
  CHECK(strstr(args, "\n-s\n64x36\n") && strstr(args, "\n-pix_fmt\nrgb24\n") &&
            strstr(args, "\n-r\n12\n") && strstr(args, "\n-i\n-\n"),
        "ffmpeg arguments lack the raw input description:\n%s", args);

  unsigned char *stream = malloc((size_t)expected);
  f = fopen(video, "rb");
  size_t got = f ? fread(stream, 1, (size_t)expected, f) : 0;
  if (f) fclose(f);
  CHECK(got == (size_t)expected, "read %zu of %ld bytes of %s", got, expected, video);
  long mismatches = 0;
  for (int k = 0; k < frames && got == (size_t)expected; k++) {
    char frame[700];
    record_frame_path(out, k + 1, frame, sizeof frame);
    static const char *const names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; c++) {
      float *plane = load_exr_channel(frame, names[c], width, height);
      if (!plane) continue;
      for (int i = 0; i < width * height; i++)
        mismatches += stream[((size_t)k * width * height + i) * 3 + c] !=
                      reference_srgb8_dithered(plane[i], i % width, i / width);
      free(plane);
    }
  }
  CHECK(mismatches == 0, "%ld stream bytes differ from sRGB(frame R, G, B), dithered",
        mismatches);
  free(stream);

  /* 2. A failing ffmpeg: record fails, says so, leaves no video; the frames stay; a user's
   * broken.partial.mp4 beside it stays as it was. */
  CHECK(write_script(script, "#!/bin/sh\ncat > /dev/null\necho 'no encoder' >&2\nexit 3\n"),
        "cannot write %s", script);
  char out2[600], video2[600];
  snprintf(out2, sizeof out2, "%s/frames2", root);
  snprintf(video2, sizeof video2, "%s/broken.mp4", root);
  char users[700];
  snprintf(users, sizeof users, "%s/broken.partial.mp4", root);
  test_write_text(users, "a user's own file\n");
  status = record_with_path(bin, out2, video2, log);
  CHECK(status != 0, "record succeeded although ffmpeg failed");
  char text[4096] = "";
  f = fopen(log, "r");
  if (f) {
    size_t n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    fclose(f);
  }
  CHECK(strstr(text, "ffmpeg failed (exit status 3)"),
        "no 'ffmpeg failed (exit status 3)' message (its own exit code):\n%s", text);
  CHECK(file_size(video2) < 0 && entries_starting(root, "broken.partial.") == 1,
        "a video or a temporary was left after a failure");
  CHECK(file_size(users) == 18, "the user's %s was written over or removed (%ld bytes)", users,
        file_size(users));
  int frame_files = 0;
  record_count_files(out2, &frame_files);
  CHECK(frame_files == frames, "%d frames kept after the failed preview, expected %d",
        frame_files, frames);

  /* 3. SIGTERM while ffmpeg encodes: exit 130 saying so, no video nor its temporary; the
   * frames stay. The stand-in writes part of its output, says so, and takes its time. */
  char started[700];
  snprintf(started, sizeof started, "%s/started", bin);
  CHECK(write_script(script, "#!/bin/sh\n"
                             "for a in \"$@\"; do out=\"$a\"; done\n"
                             "head -c 100 > \"$out\"\n"
                             "touch \"$(dirname \"$0\")/started\"\n"
                             "sleep 1\n"
                             "cat >> \"$out\"\n"),
        "cannot write %s", script);
  char out4[600], video4[600];
  snprintf(out4, sizeof out4, "%s/frames4", root);
  snprintf(video4, sizeof video4, "%s/cut.mp4", root);
  pid_t pid = start_with_path(bin, out4, video4, log);
  struct stat st;
  for (int waited = 0; waited < 60000 && stat(started, &st) != 0; waited += 5) {
    if (waitpid(pid, NULL, WNOHANG) == pid) break;
    record_sleep_ms(5);
  }
  kill(pid, SIGTERM);
  status = record_wait(pid);
  f = fopen(log, "r");
  size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
  text[n] = '\0';
  if (f) fclose(f);
  CHECK(status == 130 && strstr(text, "interrupted while encoding the preview"),
        "SIGTERM during the encode: exit %d:\n%s", status, text);
  CHECK(file_size(video4) < 0 && entries_starting(root, "cut.partial") == 0,
        "an interrupted encode left %s (%ld bytes) or its temporary", video4,
        file_size(video4));
  record_count_files(out4, &frame_files);
  CHECK(frame_files == frames, "%d frames kept after the interrupted preview, expected %d",
        frame_files, frames);

  /* 4. The video inside the --out folder record is to make (it does not exist yet): taken,
   * as record makes the folder before the video. */
  CHECK(write_script(script, "#!/bin/sh\nfor a in \"$@\"; do out=\"$a\"; done\ncat > \"$out\"\n"),
        "cannot write %s", script);
  char out5[600], video5[700];
  snprintf(out5, sizeof out5, "%s/new/frames5", root);
  snprintf(video5, sizeof video5, "%s/preview.mp4", out5);
  status = record_with_path(bin, out5, video5, log);
  CHECK(status == 0 && file_size(video5) == expected,
        "a preview inside the --out folder to be made: exit %d, %ld bytes", status,
        file_size(video5));

  /* 4b. The same, spelt relative to the working folder and two new folders deep
   * (new2/shot and new2/shot.mp4): the --out stayed relative while the video's folder was
   * resolved, and the preview was refused as "its folder does not exist". */
  char cwd[PATH_MAX], up[PATH_MAX] = "", out6[PATH_MAX + 700], video6[PATH_MAX + 800];
  CHECK(getcwd(cwd, sizeof cwd) != NULL, "getcwd");
  for (const char *c = cwd; *c; c++)
    if (*c == '/' && c[1]) strcat(up, "../");
  snprintf(out6, sizeof out6, "%s%s/new2/shot", up, root + 1);
  snprintf(video6, sizeof video6, "%s.mp4", out6);
  status = record_with_path(bin, out6, video6, log);
  CHECK(status == 0 && file_size(video6) == expected,
        "a preview beside the --out folder, both two new folders deep, relative: exit %d, "
        "%ld bytes", status, file_size(video6));
  if (status) record_print_log(log);

  /* 4c. The same from the folder itself, the first missing folder a one-letter name (r/shot
   * and r/shot.mp4): "r" was taken for the top it could not resolve, as written */
  {
    char *abs_bin = realpath(record_bin(), NULL), *abs_config = realpath(RECORD_TEST_CONFIG, NULL);
    char command[3000], video7[700];
    snprintf(command, sizeof command,
             "cd '%s' && PATH='%s':\"$PATH\" '%s' record '%s' --frames 3 --out r/shot --size %s "
             "--fps 12 --preview r/shot.mp4 > '%s' 2>&1",
             root, bin, abs_bin ? abs_bin : "", abs_config ? abs_config : "", RECORD_TEST_SIZE,
             log);
    const int rc = system(command);
    snprintf(video7, sizeof video7, "%s/r/shot.mp4", root);
    CHECK(abs_bin && abs_config && WIFEXITED(rc) && WEXITSTATUS(rc) == 0 &&
              file_size(video7) == expected,
          "a preview beside --out r/shot, relative, r/ missing: exit %d, %ld bytes",
          WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, file_size(video7));
    if (!(WIFEXITED(rc) && WEXITSTATUS(rc) == 0)) record_print_log(log);
    free(abs_bin), free(abs_config);
  }

  /* 5. The real ffmpeg, where installed. */
  if (access("/usr/bin/ffmpeg", X_OK) == 0) {
    char out3[600], video3[600];
    snprintf(out3, sizeof out3, "%s/frames3", root);
    snprintf(video3, sizeof video3, "%s/real.mp4", root);
    status = record_with_path("/usr/bin", out3, video3, log);
    CHECK(status == 0 && file_size(video3) > 0, "real ffmpeg: exit %d, %s %ld bytes", status,
          video3, file_size(video3));
  } else {
    printf("(no /usr/bin/ffmpeg: the real encoder is not exercised)\n");
  }
  test_remove_tree(root);
  return test_finish("test_record_preview");
}
