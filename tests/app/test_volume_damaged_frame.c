/* A `model = volume` scene whose VDB sequence holds a damaged frame is refused as it loads,
 * naming the frame, before anything is drawn or written (FOGPIPE_BIN): `render` of another
 * frame, and `record`, which used to write the frames before the damaged one and then fail
 * (the fogmap's source, which reads every frame at once, refused it up front already). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "test_bin.h"

/* Runs a shell command; its exit status, its stderr into err. */
static int run(const char *command, const char *err_path, char *err, size_t size) {
  const int rc = system(command);
  FILE *f = fopen(err_path, "r");
  size_t n = f ? fread(err, 1, size - 1, f) : 0;
  err[n] = '\0';
  if (f) fclose(f);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

int main(void) {
  char root[] = "/tmp/fogpipe_volume_damaged_XXXXXX";
  const char *bin = test_bin_and_folder(root);
  if (!bin) return test_finish("test_volume_damaged_frame");
  char command[4096], ini[300], err_path[300], err[4096], out[300], folder[300];
  const char *source = "../shared/data/vdb/plume/data";
  snprintf(command, sizeof command,
           "cp %s/fluid_data_0046.vdb %s/fluid_data_0048.vdb '%s' && "
           "head -c 30000 %s/fluid_data_0047.vdb > '%s/fluid_data_0047.vdb'",
           source, source, root, source, root);
  CHECK(system(command) == 0, "%s", command);
  snprintf(ini, sizeof ini, "%s/volume.ini", root);
  test_write_text(ini, "[fog]\nmodel = volume\nvdb = fluid_data_####.vdb\nvdb_frame = 46\n");
  snprintf(err_path, sizeof err_path, "%s/err.txt", root);
  snprintf(out, sizeof out, "%s/frame.exr", root);
  snprintf(command, sizeof command, "'%s' render '%s' --size 32x18 --out '%s' > /dev/null 2> '%s'",
           bin, ini, out, err_path);
  int status = run(command, err_path, err, sizeof err);
  struct stat st;
  CHECK(status == 1 && strstr(err, "volume.ini:3: [fog] vdb: frame 47") &&
            strstr(err, "fluid_data_0047.vdb") && stat(out, &st) != 0,
        "render of frame 46: exit %d, stderr %s", status, err);
  snprintf(folder, sizeof folder, "%s/frames", root);
  snprintf(command, sizeof command,
           "'%s' record '%s' --frames 3 --size 32x18 --out '%s' > /dev/null 2> '%s'", bin, ini,
           folder, err_path);
  status = run(command, err_path, err, sizeof err);
  CHECK(status == 1 && strstr(err, "frame 47") && stat(folder, &st) != 0,
        "record: exit %d, the folder %s, stderr %s", status,
        stat(folder, &st) == 0 ? "left" : "not made", err);
  test_remove_tree(root);
  return test_finish("test_volume_damaged_frame");
}
