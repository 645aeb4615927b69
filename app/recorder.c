/* recorder: frame files (naming, writability, resume scan), EXR writing, the ffmpeg
 * preview and the progress display. See app/recorder.h for the lifecycle. */
#define _POSIX_C_SOURCE 200809L
#include "app/recorder.h"
#include "app/cli.h"

#include "app/frame_exr.h"
#include "app/out_folder.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "app/clock.h"
#include "sim/sim.h"

/* Bytes of one uncompressed frame at most: 10 float channels per pixel (R G B A go as
 * half unless a value passes half's range, frame_exr_channels). */
static double frame_bytes(int width, int height) {
  return (double)width * (double)height * (10 * 4);
}

int recorder_open(recorder *rec, const recorder_desc *desc, fog_error *err) {
  *rec = (recorder){.width = desc->width, .height = desc->height};
  if (!desc->folder || !*desc->folder)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "no output folder given (--out DIR)");
  if (desc->width <= 0 || desc->height <= 0)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "frame size %dx%d is not positive", desc->width,
                    desc->height);
  if (strlen(desc->folder) >= sizeof rec->folder)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                    "the output folder's name is %zu bytes long, more than the %zu taken: "
                    "%.60s...", strlen(desc->folder), sizeof rec->folder - 1, desc->folder);
  snprintf(rec->folder, sizeof rec->folder, "%s", desc->folder);
  /* Strip trailing slashes so paths read FOLDER/NAME.0001.exr. */
  for (size_t n = strlen(rec->folder); n > 1 && rec->folder[n - 1] == '/'; n--)
    rec->folder[n - 1] = '\0';
  snprintf(rec->name, sizeof rec->name, "%s", desc->name && *desc->name ? desc->name : "frame");
  if (out_folder_make(&rec->made, rec->folder, err)) return 1;

  /* Prove the folder is writable: access() alone is fooled by read-only mounts and full
   * disks, so create a probe file, write a block, flush it to disk and remove it. */
  char probe[1200];
  /* a name of its own (mkstemp: O_EXCL): a farm's tasks on other nodes, or in containers,
   * share the folder and may share a PID; one unlinking another's probe made its fsync
   * fail on NFS (ESTALE) and the task abort */
  snprintf(probe, sizeof probe, "%s/.fogpipe-write-probe-XXXXXX", rec->folder);
  int fd = mkstemp(probe);
  if (fd < 0)
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "the output folder %s is not writable: %s",
                    rec->folder, strerror(errno));
  static const char block[4096];
  ssize_t wrote = write(fd, block, sizeof block);
  int write_errno = wrote < 0 ? errno : 0;
  int sync_failed = wrote == (ssize_t)sizeof block && fsync(fd) != 0;
  int sync_errno = sync_failed ? errno : 0;
  close(fd);
  unlink(probe);
  if (wrote != (ssize_t)sizeof block || sync_failed) {
    int e = write_errno ? write_errno : sync_errno ? sync_errno : ENOSPC;
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "cannot write into the output folder %s: %s%s",
                    rec->folder, strerror(e), e == ENOSPC ? " (the disk is full)" : "");
  }
  struct statvfs vfs;
  if (statvfs(rec->folder, &vfs) == 0) {
    double free_bytes = (double)vfs.f_bavail * (double)vfs.f_frsize;
    if (free_bytes < frame_bytes(rec->width, rec->height))
      return fog_fail(err, FOG_ERR_FILE_ACCESS,
                      "the disk holding %s is full: %.1f MB free, one %dx%d frame needs up to "
                      "%.1f MB",
                      rec->folder, free_bytes / 1e6, rec->width, rec->height,
                      frame_bytes(rec->width, rec->height) / 1e6);
  }
  return 0;
}

void recorder_frame_path(const recorder *rec, int frame, char *path, size_t size) {
  snprintf(path, size, "%s/%s.%04d.exr", rec->folder, rec->name, frame);
}

/* What the file at PATH holds: 0 when it carries rec's identity, 1 when its header cannot
 * be read (cut short or damaged: rendered again), -1 with err set when it was recorded
 * from another scene or settings or carries no identity at all. */
static int frame_identity(const recorder *rec, const char *path, fog_error *err) {
  char identity[sizeof rec->identity] = "";
  fog_error serr = {0};
  if (image_read_exr_string(path, RECORDER_IDENTITY_ATTRIBUTE, identity, sizeof identity,
                            &serr) == 0) {
    if (strcmp(identity, rec->identity) == 0) return 0;
    fog_fail(err, FOG_ERR_BAD_FILE,
             "%s was recorded from another scene or settings (%s; this run: %s)", path, identity,
             rec->identity);
    return -1;
  }
  if (strstr(serr.message, "no string attribute")) {
    fog_fail(err, FOG_ERR_BAD_FILE,
             "%s carries no recording identity (made by an older fogpipe or another "
             "program): cannot tell it belongs to this scene",
             path);
    return -1;
  }
  return 1;
}

int recorder_complete_frames(const recorder *rec, int first, int last, fog_error *err) {
  int done = first - 1;
  bool run = true; /* still inside the consecutive run of complete frames */
  char path[1200];
  for (int frame = first; frame <= last; frame++) {
    recorder_frame_path(rec, frame, path, sizeof path);
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size == 0) {
      run = false;
      continue;
    }
    /* Every frame of the range is judged, also past a gap: resuming rewrites those. */
    const int identity = frame_identity(rec, path, err);
    if (identity < 0) return -1;
    if (!run) continue;
    /* Every chunk decodes: loading one channel decodes them all. */
    fogmap probe = {0};
    fog_error serr = {0};
    if (identity > 0 || fogmap_load(path, &(fogmap_load_desc){.channel = "A"}, &probe, &serr)) {
      run = false; /* damaged: rendered again */
      continue;
    }
    const bool size_ok = probe.width == rec->width && probe.height == rec->height;
    fogmap_destroy(&probe);
    if (size_ok) done = frame;
    else run = false;
  }
  return done;
}

bool recorder_frames_foreign(const recorder *rec, int first, int last) {
  char path[1200];
  for (int frame = first; frame <= last; frame++) {
    recorder_frame_path(rec, frame, path, sizeof path);
    struct stat st;
    fog_error ignored = {0};
    if (stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0 &&
        frame_identity(rec, path, &ignored) < 0)
      return true;
  }
  return false;
}

/* The frame number of a file name NAME.NNNN.exr (4 digits or more), or -1. */
int recorder_frame_number(const recorder *rec, const char *file) {
  const size_t n = strlen(rec->name);
  if (strncmp(file, rec->name, n) != 0 || file[n] != '.') return -1;
  const char *digits = file + n + 1;
  size_t count = strspn(digits, "0123456789");
  if (count < 4 || count > 9 || strcmp(digits + count, ".exr") != 0) return -1;
  if (count > 4 && digits[0] == '0') return -1; /* frame.00002.exr: not a name %04d writes */
  return atoi(digits);
}

int recorder_read_rgb(const recorder *rec, int frame, float *rgb, fog_error *err) {
  static const char *const names[3] = {"R", "G", "B"};
  char path[1200];
  recorder_frame_path(rec, frame, path, sizeof path);
  /* the raw channels (fogmap_load refused a lamp-lit pixel past 1e12 as a fog density) */
  for (int c = 0; c < 3; c++) {
    int width = 0, height = 0;
    float *plane = NULL;
    if (image_read_exr_channel(path, names[c], &width, &height, &plane, err)) return 1;
    if (width != rec->width || height != rec->height) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "frame %s is %dx%d, expected %dx%d", path, width,
               height, rec->width, rec->height);
      free(plane);
      return 1;
    }
    const size_t n = (size_t)width * height;
    for (size_t i = 0; i < n; i++) rgb[3 * i + c] = plane[i];
    free(plane);
  }
  return 0;
}

int recorder_check_other_frames(const recorder *rec, int first, int last, fog_error *err) {
  DIR *dir = opendir(rec->folder);
  if (!dir) return 0; /* a new folder: nothing in it */
  int status = 0;
  struct dirent *entry;
  while (!status && (entry = readdir(dir))) {
    const int frame = recorder_frame_number(rec, entry->d_name);
    if (frame <= 0 || (frame >= first && frame <= last)) continue;
    char path[1400], identity[sizeof rec->identity] = "";
    snprintf(path, sizeof path, "%s/%s", rec->folder, entry->d_name);
    fog_error serr = {0};
    const int read = image_read_exr_string(path, RECORDER_IDENTITY_ATTRIBUTE, identity,
                                           sizeof identity, &serr);
    const bool other = read == 0 ? strcmp(identity, rec->identity) != 0
                                 : strstr(serr.message, "no string attribute") != NULL;
    if (other) {
      fog_fail(err, FOG_ERR_BAD_FILE,
               "%s, outside frames %d-%d, was recorded from %s: it stays beside this "
               "run's frames, two recordings in one folder (remove the old frames if that is "
               "not meant)",
               path, first, last, identity[0] ? "another scene or settings" : "another program");
      status = -1;
    }
  }
  closedir(dir);
  return status;
}

int recorder_remove_frames(const recorder *rec) {
  DIR *dir = opendir(rec->folder);
  if (!dir) return 0;
  int removed = 0;
  struct dirent *entry;
  while ((entry = readdir(dir))) {
    if (recorder_frame_number(rec, entry->d_name) <= 0) continue;
    char path[1400];
    snprintf(path, sizeof path, "%s/%s", rec->folder, entry->d_name);
    removed += unlink(path) == 0;
  }
  closedir(dir);
  return removed;
}

int recorder_remove_stale_temporaries(const recorder *rec, int first, int last) {
  DIR *dir = opendir(rec->folder);
  if (!dir) return 0;
  char prefix[160];
  snprintf(prefix, sizeof prefix, ".%s.", rec->name);
  const size_t n = strlen(prefix);
  int removed = 0;
  struct dirent *entry;
  while ((entry = readdir(dir))) {
    /* .NAME.NNNN.exr.tmp.PID.N, NNNN (4 to 9 digits) in first..last */
    const char *name = entry->d_name;
    if (strncmp(name, prefix, n) != 0) continue;
    const size_t digits = strspn(name + n, "0123456789");
    if (digits < 4 || digits > 9 || strncmp(name + n + digits, ".exr.tmp.", 9) != 0) continue;
    const int frame = atoi(name + n);
    if (frame < first || frame > last) continue;
    char path[1400];
    snprintf(path, sizeof path, "%s/%s", rec->folder, name);
    removed += unlink(path) == 0;
  }
  closedir(dir);
  return removed;
}

int recorder_write_frame(const recorder *rec, int frame, const recorder_frame *pixels,
                         float *scratch, bool *beauty_float, fog_error *err) {
  const int w = rec->width, h = rec->height;
  image_channel channels[FRAME_EXR_CHANNELS];
  const bool as_float = frame_exr_channels(pixels->rgba, pixels->transmittance, pixels->depth,
                                           pixels->inscatter, &pixels->view, w, h,
                                           pixels->bottom_up, scratch, channels);
  if (beauty_float) *beauty_float = as_float;
  char path[1200];
  recorder_frame_path(rec, frame, path, sizeof path);
  /* The folder again, should it be gone: a farm's ranges share it, and a range that failed
   * or stopped before its first frame removes the empty folders it made while another
   * range is still catching up to its own (mkdir -p; nothing when it is there). */
  out_folder again = {0};
  fog_error ferr = {0};
  if (out_folder_make(&again, rec->folder, &ferr)) return fog_error_pass(err, &ferr);
  fog_error serr = {0};
  const image_exr_string identity = {RECORDER_IDENTITY_ATTRIBUTE, rec->identity};
  image_exr_matrix camera[2] = {{.name = "worldToCamera"}, {.name = "worldToNDC"}};
  memcpy(camera[0].m, pixels->world_to_camera, sizeof camera[0].m);
  memcpy(camera[1].m, pixels->world_to_ndc, sizeof camera[1].m);
  const image_exr_header header = {.strings = &identity,
                                   .string_count = rec->identity[0] ? 1 : 0,
                                   .matrices = camera,
                                   .matrix_count = 2};
  if (image_write_exr_with(path, w, h, channels, FRAME_EXR_CHANNELS, &header, &serr)) {
    struct statvfs vfs;
    int full = statvfs(rec->folder, &vfs) == 0 &&
               (double)vfs.f_bavail * (double)vfs.f_frsize < frame_bytes(w, h);
    /* the writer's code (a full disk, or pixels no EXR may hold), the hint after its text */
    return fog_fail(err, full || !serr.code ? FOG_ERR_FILE_ACCESS : serr.code,
                    "cannot write frame %d: %s%s", frame, serr.message,
                    full ? " (the disk is full)" : "");
  }
  return 0;
}

bool recorder_have_ffmpeg(void) {
  const char *path = getenv("PATH");
  if (!path) return false;
  char dir[1024];
  while (*path) {
    size_t len = strcspn(path, ":");
    if (len > 0 && len < sizeof dir - 8) {
      memcpy(dir, path, len);
      snprintf(dir + len, sizeof dir - len, "/ffmpeg");
      if (access(dir, X_OK) == 0) return true;
    }
    path += len;
    if (*path == ':') path++;
  }
  return false;
}

int recorder_write_preview(const recorder *rec, int frame_count, double fps, const char *video_path,
                           const display_transform *display, const volatile sig_atomic_t *stop,
                           fog_error *err) {
  if (!recorder_have_ffmpeg())
    return fog_fail(err, FOG_ERR_UNSUPPORTED,
                    "ffmpeg is not installed: no preview written (apt-get install ffmpeg)");
  /* ffmpeg picks the container from the extension, so the temporary name keeps it; made
   * unique and created here, O_EXCL (NAME.partial.PID.N.EXT): a fixed NAME.partial.EXT wrote
   * over (and on a failure removed) a user's file of that name, and two runs shared it. */
  char temp[1200];
  const char *dot = strrchr(video_path, '.');
  const char *slash = strrchr(video_path, '/');
  const char *extension = dot && (!slash || dot > slash) ? dot : "";
  int reserved = -1, why = 0;
  for (unsigned serial = 0; serial < 100 && reserved < 0; serial++) {
    const int length = snprintf(temp, sizeof temp, "%.*s.partial.%ld.%u%s",
                                (int)(strlen(video_path) - strlen(extension)), video_path,
                                (long)getpid(), serial, extension);
    if (length < 0 || (size_t)length >= sizeof temp)
      return fog_fail(err, FOG_ERR_FILE_ACCESS, "preview %s: the path is too long", video_path);
    /* 0666: the kernel takes the umask off, as for any new file */
    reserved = open(temp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    why = reserved < 0 ? errno : 0;
    if (reserved < 0 && why != EEXIST) break;
  }
  if (reserved < 0)
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "preview %s: cannot create its temporary %s: %s",
                    video_path, temp, strerror(why));
  close(reserved); /* ffmpeg -y writes it */
  const int w = rec->width, h = rec->height;
  char cmd[8192]; /* the quoted temporary takes up to 4 x its 1200 bytes */
  /* yuv420p needs even sizes: pad odd ones by one pixel. */
  snprintf(cmd, sizeof cmd,
           "ffmpeg -y -loglevel error -f rawvideo -pix_fmt rgb24 -s %dx%d -r %.17g -i - "
           "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -pix_fmt yuv420p ",
           w, h, fps > 0 ? fps : 24.0);
  char word[4 * sizeof temp + 8];
  strncat(cmd, cli_shell_word(temp, word, sizeof word), sizeof cmd - strlen(cmd) - 1);
  size_t n = (size_t)w * (size_t)h;
  uint8_t *rgb = malloc(n * 3);
  float *linear = malloc(n * 3 * sizeof *linear);
  const srgb8_encoder *encoder = srgb8_encoder_shared(); /* linear frames -> 8-bit video */
  if (!rgb || !linear) {
    free(rgb), free(linear);
    unlink(temp);
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory for the preview");
  }
  struct sigaction ignore = {.sa_handler = SIG_IGN}, previous;
  sigaction(SIGPIPE, &ignore, &previous); /* a dying ffmpeg must not kill us */
  FILE *pipe = popen(cmd, "w");
  int status = 0;
  if (!pipe)
    status = fog_fail(err, FOG_ERR_FILE_ACCESS, "cannot start ffmpeg: %s", strerror(errno));
  for (int frame = 1; frame <= frame_count && !status; frame++) {
    if (stop && *stop) {
      status = fog_fail(err, FOG_ERR_FILE_ACCESS, "preview: stopped before frame %d", frame);
      break;
    }
    fog_error serr = {0};
    if (recorder_read_rgb(rec, frame, linear, &serr)) {
      status = fog_error_wrap(err, &serr, "preview: cannot read back frame %d: ", frame);
      break;
    }
    display_map_values(display, linear, linear, 3 * n);
    size_t i = 0;
    for (int y = 0; y < h; y++)
      for (int x = 0; x < w; x++)
        for (int c = 0; c < 3; c++, i++)
          rgb[i] = display->dither ? srgb8_encode_dithered(encoder, linear[i], x, y)
                                   : srgb8_encode(encoder, linear[i]);
    if (!status && fwrite(rgb, 3, n, pipe) != n)
      status = fog_fail(err, FOG_ERR_FILE_ACCESS,
                        "preview: ffmpeg stopped reading frames (see its message above)");
  }
  if (pipe) {
    int rc = pclose(pipe); /* a wait status: ffmpeg's exit code, or the signal it died of */
    if (!status && rc != 0) {
      if (rc > 0 && WIFEXITED(rc))
        status = fog_fail(err, FOG_ERR_FILE_ACCESS, "preview %s: ffmpeg failed (exit status %d)",
                          video_path, WEXITSTATUS(rc));
      else if (rc > 0 && WIFSIGNALED(rc))
        status = fog_fail(err, FOG_ERR_FILE_ACCESS, "preview %s: ffmpeg was killed (signal %d)",
                          video_path, WTERMSIG(rc));
      else
        status = fog_fail(err, FOG_ERR_FILE_ACCESS, "preview %s: ffmpeg failed (%s)",
                          video_path, rc < 0 ? strerror(errno) : "unknown wait status");
    }
  }
  sigaction(SIGPIPE, &previous, NULL);
  free(rgb);
  free(linear);
  if (!status && stop && *stop) /* during ffmpeg's last writes */
    status = fog_fail(err, FOG_ERR_FILE_ACCESS, "preview: stopped while ffmpeg finished");
  if (!status && rename(temp, video_path) != 0)
    status = fog_fail(err, FOG_ERR_FILE_ACCESS, "preview: cannot rename %s to %s: %s", temp,
                      video_path, strerror(errno));
  if (status) unlink(temp);
  return status;
}

void recorder_progress_begin(recorder_progress *p, FILE *out, int first, int total) {
  *p = (recorder_progress){.out = out,
                           .terminal = isatty(fileno(out)) != 0,
                           .total = total,
                           .first = first,
                           .start = app_clock_seconds()};
}

static void format_duration(double seconds, char *buf, size_t size) {
  long s = (long)(seconds + 0.5);
  if (s >= 3600)
    snprintf(buf, size, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    snprintf(buf, size, "%ld:%02ld", s / 60, s % 60);
}

void recorder_progress_update(recorder_progress *p, int done) {
  double elapsed = app_clock_seconds() - p->start;
  int rendered = done - p->first;
  double per_frame = rendered > 0 ? elapsed / rendered : 0.0;
  double eta = per_frame * (p->total - done);
  char eta_text[32];
  format_duration(eta, eta_text, sizeof eta_text);
  int percent = p->total > 0 ? (int)(100.0 * done / p->total) : 100;
  if (p->terminal) {
    enum { bar_width = 30 };
    char bar[bar_width + 1];
    int filled = p->total > 0 ? bar_width * done / p->total : bar_width;
    for (int i = 0; i < bar_width; i++) bar[i] = i < filled ? '#' : '.';
    bar[bar_width] = '\0';
    fprintf(p->out, "\r  [%s] %d/%d %3d%%  %.2f s/frame  ETA %s   ", bar, done, p->total,
            percent, per_frame, eta_text);
  } else {
    fprintf(p->out, "frame %d/%d (%d%%), %.2f s/frame, ETA %s\n", done, p->total, percent,
            per_frame, eta_text);
  }
  fflush(p->out);
}

void recorder_progress_end(recorder_progress *p) {
  if (p->terminal) {
    fputc('\n', p->out);
    fflush(p->out);
  }
}
