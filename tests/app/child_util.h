/* A fogpipe child process for the tests that stop or disturb a run midway: started with
 * its output in a log, waited for until its log says something or a path appears. */
#ifndef FOGPIPE_TEST_CHILD_UTIL_H
#define FOGPIPE_TEST_CHILD_UTIL_H

#include <dirent.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* Whether a line of the file at path holds text. */
static inline bool child_log_says(const char *path, const char *text) {
  FILE *f = fopen(path, "r");
  char line[4096];
  bool found = false;
  while (f && fgets(line, sizeof line, f)) found = found || strstr(line, text);
  if (f) fclose(f);
  return found;
}

/* argv[0] run with stdout and stderr into log; its pid. */
static inline pid_t child_run(const char *log, char *const argv[]) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (!freopen(log, "w", stdout) || dup2(fileno(stdout), 2) < 0) _exit(126);
    execv(argv[0], argv);
    _exit(127);
  }
  return pid;
}

/* Waits up to seconds until the log says text (text not NULL) or path exists (else); false
 * when the child ended first or the time ran out. */
static inline bool child_wait_for(pid_t pid, const char *log, const char *text,
                                  const char *path, double seconds) {
  struct stat st;
  for (long waited = 0; waited < (long)(seconds * 1000); waited++) {
    if (text ? child_log_says(log, text) : stat(path, &st) == 0) return true;
    if (waitpid(pid, NULL, WNOHANG) != 0) return false;
    nanosleep(&(struct timespec){.tv_nsec = 1000000}, NULL);
  }
  return false;
}

/* Whether folder holds a file whose name starts with prefix. */
static inline bool child_folder_has(const char *folder, const char *prefix) {
  DIR *d = opendir(folder);
  bool found = false;
  for (struct dirent *e; d && !found && (e = readdir(d));)
    found = !strncmp(e->d_name, prefix, strlen(prefix));
  if (d) closedir(d);
  return found;
}

/* Whether the process catches SIGTERM (its SigCgt mask in /proc), i.e. past its set-up. */
static inline bool child_catches_term(pid_t pid) {
  char path[64], line[256];
  snprintf(path, sizeof path, "/proc/%d/status", (int)pid);
  FILE *f = fopen(path, "r");
  unsigned long long mask = 0;
  while (f && fgets(line, sizeof line, f))
    if (!strncmp(line, "SigCgt:", 7)) mask = strtoull(line + 7, NULL, 16);
  if (f) fclose(f);
  return mask & (1ULL << (SIGTERM - 1));
}

/* The exit code of a waitpid status, -1 when the child was killed by a signal. */
static inline int child_exit_code(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

#endif
