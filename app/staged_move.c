/* A command's output files written into a staging folder first, then moved into the
 * output folder all or none (app/staged_move.h). */
#define _POSIX_C_SOURCE 200809L
#include "app/staged_move.h"

#include <dirent.h>
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/cli.h"

static int compare_names(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

int staged_move_into_place(const char *command, const char *temp_dir, const char *out) {
  DIR *d = opendir(temp_dir);
  if (!d) return cli_fail(command, "%s: %s", temp_dir, strerror(errno));
  char **names = NULL;
  int count = 0, capacity = 0, status = 0;
  for (struct dirent *e; (e = readdir(d));) {
    if (e->d_name[0] == '.') continue;
    if (count == capacity) {
      char **grown = realloc(names, sizeof *names * (capacity = capacity ? 2 * capacity : 64));
      if (!grown) abort();
      names = grown;
    }
    if (!(names[count++] = strdup(e->d_name))) abort();
  }
  closedir(d);
  /* frames in order, the .ini (the one name not ending in .exr) last */
  qsort(names, count, sizeof *names, compare_names);
  for (int i = 0; i + 1 < count; i++)
    if (cli_ends_with(names[i], ".ini")) {
      char *ini = names[i];
      memmove(names + i, names + i + 1, sizeof *names * (count - i - 1));
      names[count - 1] = ini;
      break;
    }
  char from[4400], to[4400], aside[4500];
  for (int i = 0; i < count && !status; i++) {
    snprintf(to, sizeof to, "%s/%s", out, names[i]);
    struct stat st;
    if (lstat(to, &st) == 0 && !S_ISREG(st.st_mode))
      status = cli_fail(command, "%s: not a file (a folder or link is in the way); nothing "
                        "in %s was replaced", to, out);
  }
  bool *replaced = calloc(count ? count : 1, sizeof *replaced);
  if (!replaced) abort();
  int moved = 0;
  for (; moved < count && !status; moved++) {
    snprintf(from, sizeof from, "%s/%s", temp_dir, names[moved]);
    snprintf(to, sizeof to, "%s/%s", out, names[moved]);
    snprintf(aside, sizeof aside, "%s/.%s.replaced", out, names[moved]);
    if (rename(to, aside) == 0) replaced[moved] = true;
    else if (errno != ENOENT) {
      status = cli_fail(command, "%s: cannot replace it: %s", to, strerror(errno));
      break;
    }
    if (rename(from, to)) {
      const int why = errno;
      if (replaced[moved] && rename(aside, to) == 0) replaced[moved] = false;
      status = replaced[moved]
                   ? cli_fail(command, "%s: cannot move into place: %s; the file it replaces "
                              "is at %s", to, strerror(why), aside)
                   : cli_fail(command, "%s: cannot move into place: %s; %s is as it was", to,
                              strerror(why), out);
      break;
    }
  }
  /* undo (status) or finish: the replaced files back, or gone */
  for (int i = 0; i < count; i++) {
    snprintf(to, sizeof to, "%s/%s", out, names[i]);
    snprintf(aside, sizeof aside, "%s/.%s.replaced", out, names[i]);
    if (status && i < moved) {
      if (replaced[i]) rename(aside, to);
      else unlink(to);
    } else if (status && i == moved) {
      /* the file whose move failed: `to` is the original (or nothing); an original set
       * aside whose return failed above is tried once more, and else left where it is (the
       * message names it), never removed */
      if (replaced[i]) rename(aside, to);
    } else if (replaced[i]) {
      unlink(aside);
    }
    free(names[i]);
  }
  free(replaced);
  free(names);
  return status;
}

void staged_remove(const char *staging) {
  DIR *d = opendir(staging);
  if (d) {
    struct dirent *e;
    char path[4400];
    while ((e = readdir(d))) {
      if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
      snprintf(path, sizeof path, "%s/%s", staging, e->d_name);
      unlink(path);
    }
    closedir(d);
  }
  rmdir(staging);
}
