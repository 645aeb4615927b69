/* fuzz_options.c's way into fogpipe import's option parser: this file compiles
 * app/cmd_import.c itself, so its static parse_options is callable. The command's other
 * code is compiled too but never called; the renderer and chart functions it refers to
 * are stubs here (the harness does not link the GL renderer). */
#include "app/cmd_import.c"

#include <stdlib.h>

int fuzz_import_parse(int argc, char **argv) {
  import_options o;
  int status = parse_options(argc, argv, &o);
  if (status == 0) {
    /* What parse_options promises the command on success. */
    if (o.input_count < 1 || o.input_count > max_inputs || (!o.out && !o.list)) abort();
    if (o.first > o.last || (o.first >= 0) != (o.last >= 0)) abort();
    if (o.max_voxels < 0 || o.resolution < 0 || o.resolution > 16384) abort();
    if (o.profile.knots < 0 || o.profile.knots > VDB_PROFILE_MAX_KNOTS) abort();
    for (int i = 0; i < o.input_count; i++)
      if (!o.inputs[i]) abort();
  } else if (status != 2 && status != -1) {
    abort(); /* a usage error (2) or --help (-1) */
  }
  return status;
}

/* Never called by parse_options: the import command's GPU report, chart and the
 * stale-frames warning (app/recorder.c). */
double app_clock_seconds(void) { abort(); }
int chart_write(const chart_desc *desc, const chart_point *points, int count,
                const char *csv_path, const char *png_path, char *error, int error_size) {
  abort();
}
bool chart_can_draw(char *error, int error_size) { abort(); }
gl_context *gl_context_create(const gl_context_desc *desc, fog_error *err) {
  abort();
}
void gl_context_destroy(gl_context *ctx) { abort(); }
volume_march *volume_march_create(const volume_grid_desc *grid, fog_error *err) {
  abort();
}
void volume_march_destroy(volume_march *march) { abort(); }
int volume_march_view(volume_march *march, const volume_view_desc *view, float *optical_depth,
                      fog_error *err) {
  abort();
}
int recorder_frame_number(const recorder *rec, const char *file) { abort(); }
