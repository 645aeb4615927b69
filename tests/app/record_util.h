/* Helpers shared by the tests/app/test_record_*.c tests: run the fogpipe binary
 * ($FOGPIPE_BIN) in a child process, and hash the pixel data of an EXR sequence channel by
 * channel (pixels, not file bytes, so header details cannot make equal images differ). */
#ifndef FOGPIPE_TESTS_APP_RECORD_UTIL_H
#define FOGPIPE_TESTS_APP_RECORD_UTIL_H

#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <dirent.h>
#include <math.h>
#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "sim/sim.h"
#include "test_util.h"

/* Small and short, so the tests stay fast on llvmpipe. */
#define RECORD_TEST_CONFIG "configs/default.ini"
#define RECORD_TEST_SIZE "64x36"

static inline const char *record_bin(void) {
  const char *bin = getenv("FOGPIPE_BIN");
  return bin && *bin ? bin : "build/fogpipe";
}

/* Starts `fogpipe record CONFIG --frames N --out DIR --size 64x36 [extra]` with stdout and
 * stderr to log_path; returns the child's pid. */
static inline pid_t record_start(const char *out, int frames, const char *extra, const char *log_path) {
  char frames_text[16];
  snprintf(frames_text, sizeof frames_text, "%d", frames);
  pid_t pid = fork();
  if (pid == 0) {
    int fd = open(log_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    const char *argv[] = {record_bin(), "record", RECORD_TEST_CONFIG, "--frames", frames_text,
                          "--out", out, "--size", RECORD_TEST_SIZE, extra, NULL};
    execv(argv[0], (char *const *)argv);
    perror("execv");
    _exit(127);
  }
  return pid;
}

/* Exit status of the child (128 + signal if it was killed). */
static inline int record_wait(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1; /* reaped already (a WNOHANG poll), or no such child */
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

static inline int record_run(const char *out, int frames, const char *extra, const char *log_path) {
  return record_wait(record_start(out, frames, extra, log_path));
}

/* Runs a shell command line, its output into log_path: its exit status (-1 where it did
 * not exit). */
static inline int record_shell(const char *command, const char *log_path) {
  char line[4096];
  snprintf(line, sizeof line, "%s >'%s' 2>&1", command, log_path);
  const int status = system(line);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static inline void record_print_log(const char *log_path) {
  FILE *f = fopen(log_path, "r");
  if (!f) return;
  char line[1024];
  while (fgets(line, sizeof line, f)) fprintf(stderr, "  | %s", line);
  fclose(f);
}

static inline int record_log_contains(const char *log_path, const char *text) {
  FILE *f = fopen(log_path, "r");
  if (!f) return 0;
  static char buffer[1 << 16];
  size_t n = fread(buffer, 1, sizeof buffer - 1, f);
  fclose(f);
  buffer[n] = '\0';
  return strstr(buffer, text) != NULL;
}

static inline void record_frame_path(const char *out, int frame, char *path, size_t size) {
  snprintf(path, size, "%s/frame.%04d.exr", out, frame);
}

/* FNV-1a over the pixels of every channel of one frame; 0 with a message if a channel is
 * missing or unreadable. */
static inline uint64_t record_hash_frame(const char *path, int *width, int *height) {
  static const char *const channels[] = {"R", "G", "B", "A", "transmittance", "depth"};
  uint64_t hash = 1469598103934665603ull;
  for (size_t c = 0; c < sizeof channels / sizeof channels[0]; c++) {
    fogmap plane = {0};
    fog_error err = {0};
    if (fogmap_load(path, &(fogmap_load_desc){.channel = channels[c]}, &plane, &err)) {
      fprintf(stderr, "cannot read channel %s: %s\n", channels[c], err.message);
      return 0;
    }
    *width = plane.width;
    *height = plane.height;
    const unsigned char *bytes = (const unsigned char *)plane.density;
    size_t n = (size_t)plane.width * (size_t)plane.height * sizeof(float);
    for (size_t i = 0; i < n; i++) hash = (hash ^ bytes[i]) * 1099511628211ull;
    fogmap_destroy(&plane);
  }
  return hash ? hash : 1;
}

/* Number of entries in a folder that are not frame files named frame.NNNN.exr (temporary
 * or partial files), and the count of frame files. */
static inline int record_count_files(const char *out, int *frames) {
  *frames = 0;
  int others = 0;
  DIR *dir = opendir(out);
  if (!dir) return -1;
  struct dirent *e;
  while ((e = readdir(dir))) {
    if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
    int number = 0;
    char tail[8] = "";
    if (sscanf(e->d_name, "frame.%4d.%3s", &number, tail) == 2 && !strcmp(tail, "exr") &&
        strlen(e->d_name) == strlen("frame.0000.exr"))
      (*frames)++;
    else
      others++;
  }
  closedir(dir);
  return others;
}

static inline void record_sleep_ms(int ms) {
  struct timespec ts = {.tv_sec = ms / 1000, .tv_nsec = (long)(ms % 1000) * 1000000L};
  nanosleep(&ts, NULL);
}

#endif
