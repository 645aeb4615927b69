/* `fogpipe import --report` marches the 3D reference twice, on the CPU in double and on the
 * GL as a 3D texture (render/volume_march.h), over the same rays: on a real Mantaflow frame
 * the two agree to 1e-3 in transmittance at every elevation (they share rays and sample
 * points, so what is left is float rounding and the hardware's trilinear weights). Without
 * gnuplot, --report is refused before any work. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "tests/test_util.h"

int main(void) {
  const char *bin = getenv("FOGPIPE_BIN");
  char command[2048];
  snprintf(command, sizeof command,
           "out=$(mktemp -d /tmp/fogpipe-report-XXXXXX) && %s import "
           "../shared/data/vdb/groundfog/data/fluid_data_####.vdb --frames 40-41 "
           "--out \"$out/fog\" --report --report-rays 24 2>&1; status=$?; rm -rf \"$out\"; "
           "exit $status",
           bin && *bin ? bin : "build/fogpipe");
  FILE *p = popen(command, "r");
  CHECK(p != NULL, "cannot run: %s", command);
  if (!p) return test_finish("test_import_report_gl");
  char line[512];
  int rows = 0, header = 0;
  double worst = 0;
  while (fgets(line, sizeof line, p)) {
    if (strstr(line, "GL 3D-texture march of the same rays")) header = 1;
    double el, mean, max, t, rel, agreement;
    int rays;
    char degree[8];
    /* "      30°     1520      0.04262 ... 2.7e-04" */
    if (sscanf(line, "%lf%7s %d %lf %lf %lf %lf %lf", &el, degree, &rays, &mean, &max, &t, &rel,
               &agreement) == 8) {
      rows++;
      if (agreement > worst) worst = agreement;
    }
  }
  int status = pclose(p);
  CHECK(status == 0, "import --report exited with %d", status);
  CHECK(header, "the report does not say it ran the GL march");
  CHECK(rows == 9, "%d report rows with a GL agreement, expected 9", rows);
  CHECK(worst <= 1e-3, "GL vs CPU 3D march: max |dT| = %.3g", worst);
  printf("GL vs CPU 3D march over 9 elevations: max |dT| %.2g\n", worst);

  /* Without gnuplot on PATH --report is refused before the import: exit 1, the option
   * named, no output folder made. */
  snprintf(command, sizeof command,
           "out=$(mktemp -d /tmp/fogpipe-report-XXXXXX) && env PATH=/nonexistent %s import "
           "../shared/data/vdb/groundfog/data/fluid_data_####.vdb --frames 41 "
           "--out \"$out/fog\" --report 2>&1; status=$?; "
           "if [ -e \"$out/fog\" ]; then echo LEFT; fi; rm -rf \"$out\"; exit $status",
           bin && *bin ? bin : "build/fogpipe");
  p = popen(command, "r");
  char text[2048] = "";
  size_t n = p ? fread(text, 1, sizeof text - 1, p) : 0;
  text[n] = '\0';
  status = p ? pclose(p) : -1;
  CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 1 &&
            strstr(text, "fogpipe import: --report: gnuplot could not be run") &&
            !strstr(text, "LEFT"),
        "import --report without gnuplot: status %d, output: %s", status, text);
  return test_finish("test_import_report_gl");
}
