/* `fogpipe fit` stopped by SIGTERM once the rungs are measured, while it writes its
 * outputs (FOGPIPE_BIN): gnuplot drawing the chart is slowed here by a wrapper first on
 * PATH, and the signal comes while it sleeps. The outputs finish first: the chart, its CSV
 * and the scene are there, whole, no temporary beside them, the scratch folder (TMPDIR)
 * removed, and the run exits 130 saying so. The default action used to end the process
 * there (the handlers were put back once the rungs were done): the chart's CSV, gnuplot's
 * temporaries and the scratch folder were left, the scene not written. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdlib.h>
#include <string.h>

#include "child_util.h"
#include "test_bin.h"

/* Entries of folder whose name starts with prefix. */
static int entries_starting(const char *folder, const char *prefix) {
  DIR *d = opendir(folder);
  if (!d) return -1;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)))
    if (!strncmp(e->d_name, prefix, strlen(prefix)) && strcmp(e->d_name, ".") &&
        strcmp(e->d_name, ".."))
      n++;
  closedir(d);
  return n;
}

int main(void) {
  char root[] = "/tmp/fogpipe_fit_stop_XXXXXX";
  const char *bin = test_bin_and_folder(root);
  if (!bin) return test_finish("test_fit_interrupt");
  char wrappers[300], wrapper[320], marker[300], scratch[300], out[300], scene[320], chart[320],
      csv[320], log[300], path[4400];
  snprintf(wrappers, sizeof wrappers, "%s/bin", root);
  snprintf(wrapper, sizeof wrapper, "%s/gnuplot", wrappers);
  snprintf(marker, sizeof marker, "%s/gnuplot_started", root);
  snprintf(scratch, sizeof scratch, "%s/tmp", root);
  snprintf(out, sizeof out, "%s/out", root);
  snprintf(scene, sizeof scene, "%s/k.ini", out);
  snprintf(chart, sizeof chart, "%s/k.png", out);
  snprintf(csv, sizeof csv, "%s/k.csv", out);
  snprintf(log, sizeof log, "%s.log", root);
  CHECK(mkdir(wrappers, 0755) == 0 && mkdir(scratch, 0755) == 0 && mkdir(out, 0755) == 0,
        "mkdir under %s", root);
  /* `gnuplot --version` (asked before the fit) at once; a chart's script after 3 s */
  char script[1200];
  snprintf(script, sizeof script,
           "#!/bin/sh\nif [ \"$1\" != --version ]; then touch '%s'; sleep 3; fi\n"
           "exec /usr/bin/gnuplot \"$@\"\n", marker);
  test_write_text(wrapper, script);
  CHECK(chmod(wrapper, 0755) == 0, "chmod %s", wrapper);
  const char *old_path = getenv("PATH");
  snprintf(path, sizeof path, "%s:%s", wrappers, old_path ? old_path : "/usr/bin:/bin");
  setenv("PATH", path, 1);
  setenv("TMPDIR", scratch, 1);

  char *const argv[] = {(char *)bin, "fit", "configs/quadric_volumes.ini", "--tolerance",
                        "0.02", "--rays", "8", "--samples", "16", "--size", "64x36",
                        "--timed", "1", "--out", scene, "--chart", chart, NULL};
  const pid_t child = child_run(log, argv);
  bool started = false;
  for (long waited = 0; waited < 240000 && !started; waited++) {
    started = access(marker, F_OK) == 0;
    if (!started && waitpid(child, NULL, WNOHANG) != 0) break;
    if (!started) nanosleep(&(struct timespec){.tv_nsec = 500000}, NULL);
  }
  if (started) kill(child, SIGTERM);
  int status = 0;
  waitpid(child, &status, 0);
  const int code = child_exit_code(status);
  CHECK(started, "gnuplot never ran (exit %d; /usr/bin/gnuplot installed?)", code);
  CHECK(code == 130 && child_log_says(log, "interrupted after the fit"),
        "SIGTERM while the outputs are written: exit %d (-1: killed by the signal)", code);
  struct stat st;
  CHECK(stat(scene, &st) == 0 && st.st_size > 100, "the scene %s is not there", scene);
  CHECK(stat(chart, &st) == 0 && st.st_size > 1000, "the chart %s is not there", chart);
  CHECK(stat(csv, &st) == 0 && st.st_size > 10, "the chart's CSV %s is not there", csv);
  CHECK(entries_starting(out, ".") == 0, "%d temporaries left in %s",
        entries_starting(out, "."), out);
  CHECK(entries_starting(scratch, "") == 0, "%d entries left in the scratch folder %s",
        entries_starting(scratch, ""), scratch);
  unlink(log);
  test_remove_tree(root);
  return test_finish("test_fit_interrupt");
}
