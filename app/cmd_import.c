/* fogpipe import: OpenVDB smoke (one file or a sequence) -> a fogmap sequence
 * NAME.####.exr + a profile sidecar NAME.ini (placement and g(y)); --report compares the
 * 2.5D model with a ray march of the original 3D grid. Everything is written into a
 * temporary folder inside --out and renamed into place only when every frame worked. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdbool.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "app/out_folder.h"
#include "app/cli.h"
#include "app/staged_move.h"
#include "app/stop_signals.h"
#include "app/cli_options.h"
#include "app/clock.h"
#include "app/commands.h"
#include "app/chart.h"
#include "app/recorder.h"
#include "render/render.h"
#include "sim/sim.h"

enum { max_inputs = 256, report_rows = 9 };
static const double report_elevations[report_rows] = {5, 10, 15, 20, 30, 45, 60, 75, 90};

typedef struct import_options {
  const char *inputs[max_inputs];
  int input_count;
  const char *out, *name, *grid, *config;
  int first, last;
  bool skip_missing, list, verbose;
  long long max_voxels;
  vdb_up_axis up;
  double scale, offset[3];
  int resolution;
  double cell;
  vdb_profile_desc profile;
  int profile_per_frame;
  bool report;
  int report_frame, report_rays;
} import_options;

/* The exit status of an import stopped by SIGINT or SIGTERM (128 + SIGINT, as the shells). */
enum { IMPORT_INTERRUPTED = 130 };

/* --name: the files' base name. Not hidden ('.': the frames would be dot files, which the
 * move into place and every folder listing pass over), no '#' or '%', which the sidecar's
 * `files` pattern and every frame pattern reader take for the frame number, no ';', which
 * the sidecar's lines (a config) read after a blank as a comment, and no control character
 * (a line break split the sidecar's lines). */
static int parse_name(const char *command, const char *option, const char *text, void *target) {
  bool control = false;
  for (const char *c = text; *c; c++) control = control || (unsigned char)*c < 0x20 || *c == 0x7f;
  if (!*text || strchr(text, '/') || text[0] == '.' || strpbrk(text, "#%;") || control)
    return cli_usage_error(command, "%s '%s': expected a plain file name (no '/', '#', '%%', "
                           "';' or control characters, not starting with '.')", option, text);
  *(const char **)target = text;
  return 0;
}

/* --max-voxels N: a count; past long long, no limit. */
static int parse_voxels(const char *command, const char *option, const char *text, void *target) {
  double m;
  if (cli_number(command, option, text, 1, 1e300, &m)) return 2;
  if (m != floor(m)) /* a count: 1.9 is not taken as 1 */
    return cli_usage_error(command, "%s '%s': expected a whole number of voxels", option, text);
  *(long long *)target = m < 0x1p62 ? (long long)m : 1LL << 62;
  return 0;
}

/* The bounds a scene config holds for world positions and cell sizes (app/config.c's
 * WORLD and MIN_LENGTH): a sidecar past them would not load. */
enum { SIDECAR_WORLD = 10000000 };
static const double sidecar_min_cell = 1e-4;

/* --offset X,Y,Z: three decimal numbers, each as cli_number reads one */
static int parse_offset(const char *command, const char *option, const char *text, void *target) {
  double *v = target;
  char part[3][64];
  const char *at = text;
  for (int k = 0; k < 3; k++) {
    const size_t n = strcspn(at, ",");
    if ((k < 2 && at[n] != ',') || (k == 2 && at[n] != '\0'))
      return cli_usage_error(command, "%s '%s': expected X,Y,Z", option, text);
    /* blanks around a number ("1, 2, 3"), not inside it */
    const size_t lead = strspn(at, " \t");
    size_t end = n;
    while (end > lead && (at[end - 1] == ' ' || at[end - 1] == '\t')) end--;
    if (end - lead >= sizeof part[k])
      return cli_usage_error(command, "%s '%s': expected X,Y,Z (numbers of at most %zu "
                             "characters)", option, text, sizeof part[k] - 1);
    snprintf(part[k], sizeof part[k], "%.*s", (int)(end - lead), at + lead);
    if (cli_number(command, option, part[k], -SIDECAR_WORLD, SIDECAR_WORLD, &v[k])) return 2;
    at += n + 1;
  }
  return 0;
}

static int parse_options(int argc, char **argv, import_options *o) {
  *o = (import_options){.name = "fog", .first = -1, .last = -1, .report_frame = -1};
  /* either case, as the Z-up / Y-up convention is written both ways */
  static const char *const up[] = {"z", "y", "Z", "Y", NULL};
  static const char *const profiles[] = {"bspline", "exponential", NULL};
  static const char *const degrees[] = {"1", "0", NULL}, *const per[] = {"sequence", "frame", NULL};
  int frames[3] = {-1, -1, 0}, up_axis = VDB_UP_Z, profile = VDB_PROFILE_BSPLINE;
  int degree = -1; /* -1: not given (hats) */
  bool import_given = false; /* an option of the import itself, which --list does not read */
  const cli_option options[] = {
      {.kind = CLI_SECTION, .name = "input:"},
      {.kind = CLI_TEXT, .name = "--grid",
       .given = &import_given, .value = "NAME", .target = &o->grid,
       .help = "float grid to read (default density)"},
      {.kind = CLI_RANGE, .name = "--frames", .value = "A-B | A", .target = frames, .min = 0,
       .max = INT_MAX,
       .help = "frame range (default: all found); frames missing inside\n"
               "the range are an error"},
      {.kind = CLI_FLAG, .name = "--skip-missing",
       .given = &import_given, .target = &o->skip_missing,
       .help = "warn about missing frames instead of failing"},
      {.kind = CLI_FLAG, .name = "--list", .target = &o->list,
       .help = "list every grid of every input file and exit"},
      {.kind = CLI_CUSTOM, .name = "--max-voxels",
       .given = &import_given, .value = "N", .target = &o->max_voxels,
       .parse = parse_voxels,
       .help = "refuse grids whose dense box is larger (default 268435456)"},
      {.kind = CLI_SECTION, .name = "placement:"},
      {.kind = CLI_CHOICE, .name = "--up",
       .given = &import_given, .value = "z|y", .target = &up_axis, .choices = up,
       .help = "the file's up axis: z = Blender/Mantaflow (default),\n"
               "y = Houdini/EmberGen. Z-up maps (x,y,z) to (x, z, -y)"},
      {.kind = CLI_NUMBER, .name = "--scale",
       .given = &import_given, .value = "S", .target = &o->scale, .min = 1e-12,
       .max = 1e12, .help = "world scale of the source (default 1)"},
      {.kind = CLI_CUSTOM, .name = "--offset",
       .given = &import_given, .value = "X,Y,Z", .target = o->offset,
       .parse = parse_offset, .help = "fogpipe-world offset added last (default 0,0,0)"},
      {.kind = CLI_TEXT, .name = "--config",
       .given = &import_given, .value = "FILE|none", .target = &o->config,
       .help = "Mantaflow config_####.uni (default: ../config/config_####.uni\n"
               "beside each data/ file when present; it places the domain\n"
               "and replaces adaptive domains' wrong VDB voxel size)"},
      {.kind = CLI_SECTION, .name = "fogmap and profile:"},
      {.kind = CLI_INT, .name = "--resolution",
       .given = &import_given, .value = "N", .target = &o->resolution,
       .min = 1, .max = CLI_MAX_SIZE,
       .help = "fogmap cells along the longer side (default: one per voxel)"},
      {.kind = CLI_NUMBER, .name = "--cell",
       .given = &import_given, .value = "SIZE", .target = &o->cell, .min = 1e-4,
       .max = SIDECAR_WORLD, .help = "or a world cell size"},
      {.kind = CLI_CUSTOM, .name = "--name",
       .given = &import_given, .value = "NAME", .target = &o->name,
       .parse = parse_name, .help = "output base name (default fog)"},
      {.kind = CLI_CHOICE, .name = "--profile",
       .given = &import_given, .value = "bspline|exponential",
       .target = &profile, .choices = profiles,
       .help = "g(y): centred B-spline of the mean vertical density\n"
               "(default) or a moment-fitted exponential"},
      {.kind = CLI_INT, .name = "--profile-knots",
       .given = &import_given, .value = "N", .target = &o->profile.knots,
       .min = 1, .max = VDB_PROFILE_MAX_KNOTS,
       .help = "B-spline coefficients (default one per voxel layer, max 64)"},
      {.kind = CLI_CHOICE, .name = "--profile-degree",
       .given = &import_given, .value = "0|1",
       .target = &degree, .choices = degrees,
       .help = "B-spline degree (default 1: hats; 0: the layer histogram)"},
      {.kind = CLI_CHOICE, .name = "--profile-per",
       .given = &import_given, .value = "sequence|frame",
       .target = &o->profile_per_frame, .choices = per,
       .help = "one g for the whole sequence (default) or one per\n"
               "frame ([fog.####] sections in NAME.ini)"},
      {.kind = CLI_SECTION, .name = "report:"},
      {.kind = CLI_FLAG, .name = "--report",
       .given = &import_given, .target = &o->report,
       .help = "also compare the 2.5D model with a CPU ray march of the 3D\n"
               "grid: transmittance error per view elevation 5..90 deg, as\n"
               "a table, DIR/NAME.report.csv and DIR/NAME.report.png"},
      {.kind = CLI_INT, .name = "--report-frame",
       .given = &import_given, .value = "N", .target = &o->report_frame,
       .min = 0, .max = INT_MAX, .help = "the frame to report on (default: the last)"},
      {.kind = CLI_INT, .name = "--report-rays",
       .given = &import_given, .value = "N", .target = &o->report_rays,
       .min = 1, .max = 1024, .help = "rays per side of each view (default 48)"},
      {.kind = CLI_SECTION, .name = "other:"},
      {.kind = CLI_TEXT, .name = "--out",
       .given = &import_given, .value = "DIR", .target = &o->out,
       .help = "the output folder (required, but for --list)"},
      {.kind = CLI_FLAG, .name = "--verbose",
       .given = &import_given, .target = &o->verbose,
       .help = "one line per frame (mass, voxels)"},
  };
  const cli_spec spec = {
      .command = "import",
      .usage = "INPUT... --out DIR [options]",
      .about = "Projects OpenVDB fog (Blender/Mantaflow, Houdini, EmberGen caches) to a 2D fogmap\n"
               "f(x,z) per frame and a vertical profile g(y): K(x,y,z) = f(x,z)*g(y), where g has\n"
               "max 1, T = integral of g dy, and f = (column integral of the density) / T, so the\n"
               "column optical depth is kept exactly. fogpipe's world is Y-up; the fogmap spans X\n"
               "(columns) and Z (rows). Writes DIR/NAME.####.exr (one float channel Y, #### = the\n"
               "source frame number) and DIR/NAME.ini (placement: origin, cell size; the profile).\n"
               "Nothing is left in DIR when any frame fails.\n\n"
               "INPUT: a .vdb file, a folder (every *.vdb), a #### or printf pattern\n"
               "       (data/fluid_data_####.vdb, data/fluid_data_%04d.vdb) or a glob ('data/*.vdb').",
      .operand = "INPUT", .min_operands = 1, .max_operands = max_inputs,
      CLI_OPTIONS(options)};
  int parsed = cli_parse(&spec, argc, argv, o->inputs, &o->input_count);
  if (parsed) return parsed;
  o->first = frames[0], o->last = frames[1];
  o->up = (vdb_up_axis)(up_axis % 2);
  o->profile.kind = (vdb_profile_kind)profile;
  if (!o->out && !o->list) return cli_usage_error("import", "--out DIR is required");
  if (o->list && import_given) /* they would be dropped without a word */
    return cli_usage_error("import", "--list only lists the inputs' grids (of --frames): "
                           "the other options are for an import");
  if (o->resolution && o->cell) /* one would be dropped without a word */
    return cli_usage_error("import", "--resolution and --cell are alternatives: give one");
  /* options of a mode that is off would be dropped without a word too */
  if ((o->report_frame >= 0 || o->report_rays > 0) && !o->report)
    return cli_usage_error("import", "--report-frame and --report-rays set up --report: give "
                           "--report too");
  if (o->profile.kind == VDB_PROFILE_EXPONENTIAL && (o->profile.knots > 0 || degree >= 0))
    return cli_usage_error("import", "--profile-knots and --profile-degree shape the B-spline "
                           "profile: not with --profile exponential");
  o->profile.degree_box = degree == 1;
  return 0;
}

static int list_grids(const import_options *o) {
  vdb_sequence seq;
  fog_error err = {0};
  if (vdb_sequence_find(o->inputs, o->input_count, o->first, o->last, &seq, &err))
    return cli_fail("import", "%s", err.message);
  int status = 0;
  for (int i = 0; i < seq.count; i++) {
    vdb_grid_info info[64];
    int count = 0;
    if (vdb_list_grids(seq.paths[i], info, 64, &count, &err)) {
      status = cli_fail("import", "%s", err.message);
      break;
    }
    printf("%s (frame %d): %d grid%s\n", seq.paths[i], seq.frames[i], count,
           count == 1 ? "" : "s");
    printf("  %-16s %-8s %-12s %-10s %-30s %s\n", "name", "type", "class", "voxel",
           "active bbox", "active voxels");
    for (int g = 0; g < count && g < 64; g++) {
      char box[64], voxels[32];
      snprintf(voxels, sizeof voxels, "%lld", info[g].active_voxels);
      if (info[g].active_voxels < 0)
        snprintf(box, sizeof box, "(not read)"), snprintf(voxels, sizeof voxels, "?");
      else if (info[g].bbox_min[0] > info[g].bbox_max[0])
        snprintf(box, sizeof box, "(empty)");
      else
        snprintf(box, sizeof box, "[%d,%d,%d]..[%d,%d,%d]", info[g].bbox_min[0],
                 info[g].bbox_min[1], info[g].bbox_min[2], info[g].bbox_max[0],
                 info[g].bbox_max[1], info[g].bbox_max[2]);
      printf("  %-16s %-8s %-12s %-10.6g %-30s %s\n", info[g].name, info[g].value_type,
             info[g].grid_class, info[g].voxel_size[0], box, voxels);
    }
  }
  vdb_sequence_destroy(&seq);
  return status;
}

/* The profile in docs/config.md's [fog] keys (render/fog_field.h's fog_profile), so that the
 * section loads in a scene config as it is: the coefficients go on over indented lines (a
 * config line holds at most 199 bytes; the plume's 64 numbers took 590), and what is only
 * information (the support, the integral) is a comment. */
static void write_profile(FILE *f, const char *section, const vdb_profile *p) {
  fprintf(f, "[%s]\n", section);
  if (p->kind == VDB_PROFILE_EXPONENTIAL) {
    if (p->scale_height > 0)
      fprintf(f, "profile = exponential\nfog_height = %.9g\nscale_height = %.9g\n", p->y_bottom,
              p->scale_height);
    else
      fprintf(f, "profile = slab\n");
  } else {
    fprintf(f, "profile = bspline\nprofile_degree = %d\nprofile_origin = %.9g\n"
               "profile_spacing = %.9g\nprofile_coefficients =",
            p->degree, p->origin, p->spacing);
    for (int k = 0; k < p->count; k++)
      fprintf(f, "%s %.9g", k > 0 && k % 8 == 0 ? "\n   " : "", p->values[k]);
    fprintf(f, "\n");
  }
  fprintf(f, "; the profile's support and its integral (f * thickness = column optical depth)\n");
  fprintf(f, "; profile_bottom = %.9g\n; profile_top = %.9g\n; thickness = %.9g\n\n",
          p->y_bottom, p->y_top, p->thickness);
}

/* [section]: where the fogmap lies (every frame's) and the profile's support. */
static void write_box(FILE *f, const char *section, const vdb_fogmap_place *place,
                      const vdb_profile *p) {
  fprintf(f, "[%s]\n; origin: world X Z of the outer corner of fogmap cell (0, 0); row = Z\n",
          section);
  fprintf(f, "origin = %.9g %.9g\ncell_size = %.9g\nfloor = %.9g\ntop = %.9g\n\n",
          place->origin_x, place->origin_z, place->cell_size, p->y_bottom, p->y_top);
}

static int write_sidecar(const char *path, const import_options *o, const vdb_sequence *seq,
                         const vdb_frame *frames, const vdb_fogmap_place *place,
                         const vdb_profile *profile, fog_error *err) {
  /* every profile written (the sequence's, or each frame's) and the fogmap's place */
  for (int i = profile ? seq->count - 1 : 0; i < seq->count; i++) {
    const vdb_profile *g = profile ? profile : &frames[i].profile;
    const bool exponential = g->kind == VDB_PROFILE_EXPONENTIAL;
    const double far = fmax(fmax(fabs(place->origin_x), fabs(place->origin_z)),
                            fmax(fmax(fabs(g->y_bottom), fabs(g->y_top)),
                                 exponential ? 0.0 : fabs(g->origin)));
    /* the profile's length as written: an exponential of no height is written as a slab */
    const double length = exponential ? (g->scale_height > 0 ? g->scale_height : place->cell_size)
                                      : g->spacing;
    const double smallest = fmin(place->cell_size, length);
    if (!(smallest >= sidecar_min_cell && place->cell_size <= SIDECAR_WORLD &&
          far <= SIDECAR_WORLD))
      return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                      "the placement gives cells of %.6g at (%.6g, %.6g), heights %.6g to "
                      "%.6g and a profile %s of %.6g: a scene config holds lengths of %g to %g "
                      "and positions within +-%g; change --scale, --cell or --offset",
                      place->cell_size, place->origin_x, place->origin_z, g->y_bottom, g->y_top,
                      exponential ? "scale height" : "knot spacing",
                      length, sidecar_min_cell,
                      (double)SIDECAR_WORLD, (double)SIDECAR_WORLD);
  }
  /* printed in memory, then written whole (sim/atomic_file.h: "NAME.tmp" beside it was
   * a name a user's file could have) */
  char *text = NULL;
  size_t text_size = 0;
  FILE *f = open_memstream(&text, &text_size);
  if (!f) return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%.400s: out of memory", path);
  fprintf(f, "; fogpipe import: K(x,y,z) = density_scale * f(x,z) * g(y) with max g = 1.\n"
             "; f: %s.####.exr (channel Y), the extinction per world unit where g = 1.\n"
             "; [box%s] and [fog%s] are scene config sections (docs/config.md): copied into\n"
             "; a scene as [box] and [fog], with 'fogmap = %s.%04d.exr' added to [fog],\n"
             "; they place and shape frame %d. [sequence] records this import (it is not\n"
             "; a scene section).\n\n",
          o->name, profile ? "" : ".####", profile ? "" : ".####", o->name, seq->frames[0],
          seq->frames[0]);
  fprintf(f, "[sequence]\nfiles = %s.%%04d.exr\nchannel = Y\n", o->name);
  fprintf(f, "first_frame = %d\nlast_frame = %d\nframe_count = %d\n", seq->frames[0],
          seq->frames[seq->count - 1], seq->count);
  fprintf(f, "frames =");
  for (int i = 0; i < seq->count; i++) fprintf(f, " %d", seq->frames[i]);
  fprintf(f, "\nmissing_frames =");
  for (int i = 0; i < seq->missing_count; i++) fprintf(f, " %d", seq->missing[i]);
  fprintf(f, "\nwidth = %d\nheight = %d\n", place->width, place->height);
  fprintf(f, "source = %s\ngrid = %s\nup = %s\nscale = %.9g\noffset = %.9g %.9g %.9g\n",
          o->inputs[0], o->grid ? o->grid : "density", o->up == VDB_UP_Y ? "y" : "z",
          o->scale > 0 ? o->scale : 1.0, o->offset[0], o->offset[1], o->offset[2]);
  fprintf(f, "mantaflow_config = %s\n", frames[0].config_path[0] ? frames[0].config_path : "none");
  fprintf(f, "profile_per = %s\n", profile ? "sequence" : "frame");
  fprintf(f, "; density x volume of each frame (the column integral's total), in frame order\nmass =");
  for (int i = 0; i < seq->count; i++) fprintf(f, " %.9g", frames[i].columns.mass);
  fprintf(f, "\n\n");
  if (profile) {
    /* one profile for the sequence: its support is the box's height */
    write_box(f, "box", place, profile);
    write_profile(f, "fog", profile);
  } else {
    /* A profile per frame, and the box's height per frame with it: a slab fills the box
     * floor to top, and the exponential profile is 1 from the floor up, so a box spanning
     * every frame's support would add fog below or above a frame's own. */
    fprintf(f, "; one box height and profile per frame: [box.####] and [fog.####]\n\n");
    for (int i = 0; i < seq->count; i++) {
      char section[64];
      snprintf(section, sizeof section, "box.%04d", seq->frames[i]);
      write_box(f, section, place, &frames[i].profile);
      snprintf(section, sizeof section, "fog.%04d", seq->frames[i]);
      write_profile(f, section, &frames[i].profile);
    }
  }
  if (ferror(f) | fclose(f)) {
    free(text);
    return fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%.400s: out of memory", path);
  }
  const int failed = atomic_file_write(path, text, text_size, err);
  free(text);
  return failed;
}

/* The report's 3D reference marched again on the GL (render/volume_march.h: the grid as a
 * 3D texture, hardware trilinear), the same rays and samples: per row, the largest
 * |T_GL - T_CPU| (the two references' agreement) and the GL time. Returns 1 (with why)
 * where no GL context can be made; the CPU report stands alone then. */
static int report_gl_march(const vdb_frame *full, const vdb_fogmap_place *place,
                           const vdb_profile *profile, const vdb_report_desc *desc,
                           const vdb_report_row *rows, int row_count, const double *reference,
                           double *max_dt, double *seconds, char *why, size_t why_size) {
  const int side = desc->rays_per_side, azimuths = desc->azimuths;
  const vdb_dense_grid *g = &full->grid;
  const vdb_world_map *w = &full->world;
  double lo[3], hi[3], y_mid, step;
  fog_error serr = {0};
  if (vdb_report_geometry(g, w, place, profile, desc, lo, hi, &y_mid, &step, &serr)) {
    snprintf(why, why_size, "%s", serr.message);
    return 1;
  }
  /* u_c = (p_a - base_a) / step_a - index_min_c for the world axis a fed by index axis c. */
  volume_grid_desc grid = {.dim = {g->dim[0], g->dim[1], g->dim[2]}, .values = g->values};
  for (int a = 0; a < 3; a++) {
    const int c = w->index_axis[a];
    grid.index_from_world[c][a] = 1.0 / w->step[a];
    grid.index_offset[c] = -w->base[a] / w->step[a] - g->index_min[c];
  }
  fog_error rerr = {0};
  gl_context *gl = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, &rerr);
  volume_march *march = gl ? volume_march_create(&grid, &rerr) : NULL;
  float *depth = malloc(sizeof(float) * (size_t)side * side);
  int status = !gl || !march || !depth;
  const double start = app_clock_seconds();
  for (int r = 0; r < row_count && !status; r++) {
    max_dt[r] = 0;
    for (int az = 0; az < azimuths && !status; az++) {
      volume_view_desc view = {.lo = {lo[0], lo[1], lo[2]}, .hi = {hi[0], hi[1], hi[2]},
                               .y_mid = y_mid, .side = side, .step = step};
      vdb_report_direction(rows[r].elevation_deg, az, azimuths, view.dir);
      status = volume_march_view(march, &view, depth, &rerr);
      const double *ref = reference + ((size_t)r * azimuths + az) * side * side;
      for (int k = 0; k < side * side && !status; k++)
        if (ref[k] >= 0 && depth[k] >= 0)
          max_dt[r] = fmax(max_dt[r], fabs(exp(-(double)depth[k]) - exp(-ref[k])));
    }
  }
  *seconds = app_clock_seconds() - start;
  if (status) snprintf(why, why_size, "%s", depth ? rerr.message : "out of memory");
  free(depth);
  volume_march_destroy(march);
  gl_context_destroy(gl);
  return status;
}

static int run_report(const import_options *o, const vdb_sequence *seq, const vdb_frame *frames,
                      const vdb_fogmap_place *place, const vdb_profile *seq_profile,
                      const char *temp_dir) {
  int index = seq->count - 1;
  while (index > 0 && frames[index].empty) index--; /* the last frame with fog */
  if (o->report_frame >= 0) {
    index = -1;
    for (int i = 0; i < seq->count; i++)
      if (seq->frames[i] == o->report_frame) index = i;
    if (index < 0) return cli_fail("import", "--report-frame %d: no such frame imported", o->report_frame);
    if (frames[index].empty)
      return cli_fail("import", "--report-frame %d: %s has an empty grid: no fog to report on",
                      o->report_frame, seq->paths[index]);
  }
  const vdb_profile *profile = seq_profile ? seq_profile : &frames[index].profile;
  fog_error err = {0};
  vdb_frame full;
  vdb_frame_desc desc = {.grid = o->grid, .up = o->up, .scale = o->scale,
                         .offset = {o->offset[0], o->offset[1], o->offset[2]},
                         .config = o->config, .place = place, .fixed_profile = profile,
                         .keep_grid = 1, .max_voxels = o->max_voxels};
  if (vdb_frame_load(seq->paths[index], &desc, &full, &err))
    return cli_fail("import", "frame %d: %s", seq->frames[index], err.message);
  vdb_report_row rows[report_rows];
  for (int r = 0; r < report_rows; r++) rows[r] = (vdb_report_row){.elevation_deg = report_elevations[r]};
  vdb_report_desc report = {.rays_per_side = o->report_rays ? o->report_rays : 48, .azimuths = 4};
  report.reference_depth =
      malloc(sizeof(double) * report_rows * report.azimuths * report.rays_per_side *
             report.rays_per_side);
  if (!report.reference_depth) {
    vdb_frame_destroy(&full);
    return cli_fail("import", "out of memory for the report's rays");
  }
  const double t0 = app_clock_seconds();
  int status = vdb_report_run(&full.grid, &full.world, &full.map, place, profile, &report, rows,
                              report_rows, &err);
  const double seconds = app_clock_seconds() - t0;
  if (status) {
    free(report.reference_depth);
    vdb_frame_destroy(&full);
    return cli_fail("import", "frame %d: %s", seq->frames[index], err.message);
  }
  double gl_max_dt[report_rows], gl_seconds = 0;
  char gl_why[600] = "";
  int gl_failed = report_gl_march(&full, place, profile, &report, rows, report_rows,
                                  report.reference_depth, gl_max_dt, &gl_seconds, gl_why,
                                  sizeof gl_why);
  free(report.reference_depth);
  printf("\n2.5D accuracy, frame %d (%s): transmittance of f*g against a trilinear ray march\n"
         "of the 3D grid, orthographic views, %d x %d rays x 4 azimuths per elevation,\n"
         "step 1/4 cell, rays with optical depth > 1e-4\n",
         seq->frames[index], seq->paths[index], report.rays_per_side, report.rays_per_side);
  printf("3D reference: CPU march in double %.2f s", seconds);
  if (gl_failed)
    printf("; GL 3D-texture march skipped (%s)\n", gl_why);
  else
    printf("; GL 3D-texture march of the same rays (hardware trilinear)\n"
           "%.2f s, max |T_GL - T_CPU| per elevation in the last column\n", gl_seconds);
  printf("%10s %8s %12s %12s %12s %16s %14s\n", "elevation", "rays", "mean |dT|", "max |dT|",
         "mean T_3D", "mean|dT|/(1-T)", "GL vs CPU 3D");
  chart_point points[2 * report_rows];
  for (int r = 0; r < report_rows; r++) {
    const double contrast = 1 - rows[r].mean_transmittance;
    char agreement[32] = "-";
    if (!gl_failed) snprintf(agreement, sizeof agreement, "%.1e", gl_max_dt[r]);
    printf("%9.0f° %8d %12.5f %12.5f %12.4f %16.3f %14s\n", rows[r].elevation_deg, rows[r].rays,
           rows[r].mean_abs_error, rows[r].max_abs_error, rows[r].mean_transmittance,
           contrast > 0 ? rows[r].mean_abs_error / contrast : 0.0, agreement);
    points[r] = (chart_point){"mean |T 2.5D - T 3D|", rows[r].elevation_deg, rows[r].mean_abs_error};
    points[report_rows + r] =
        (chart_point){"max |T 2.5D - T 3D|", rows[r].elevation_deg, rows[r].max_abs_error};
  }
  /* Straight down both integrate the same columns, but only where the fogmap's cells are
   * the grid's columns: resampled (--resolution, --cell) the 90 deg row is the resampling's */
  const vdb_columns *c = &full.columns;
  const double ox = (place->origin_x - c->origin_x) / c->cell_x,
               oz = (place->origin_z - c->origin_z) / c->cell_z;
  const bool native = fabs(place->cell_size - c->cell_x) <= 1e-6 * c->cell_x &&
                      fabs(place->cell_size - c->cell_z) <= 1e-6 * c->cell_z &&
                      fabs(ox - round(ox)) <= 1e-6 && fabs(oz - round(oz)) <= 1e-6;
  printf("(the last column compares the error with the fog's own contrast 1 - mean T_3D: near\n"
         " 0, f*g is enough for that view; a sizeable fraction means the vertical structure\n"
         " that f*g flattens shows, and the 3D grid should be rendered instead: a scene config\n"
         " with [fog] model = volume and vdb = this file draws it in 3D (docs/config.md).\n");
  if (native)
    printf(" Straight down (90 deg) the model is exact by construction.)\n");
  else
    printf(" Straight down (90 deg) the model is exact on the grid's own columns (%g x %g);\n"
           " this fogmap's cells (%g) resample them, so the 90 deg row measures the\n"
           " resampling, and the other rows include it.)\n",
           c->cell_x, c->cell_z, place->cell_size);
  vdb_frame_destroy(&full);
  char csv[4200], png[4200], error[600], title[256];
  snprintf(csv, sizeof csv, "%s/%s.report.csv", temp_dir, o->name);
  snprintf(png, sizeof png, "%s/%s.report.png", temp_dir, o->name);
  snprintf(title, sizeof title, "2.5D vs 3D transmittance error, frame %d", seq->frames[index]);
  chart_desc chart = {.title = title, .x_label = "view elevation (degrees)",
                      .y_label = "|transmittance error|", .width = 800, .height = 500};
  if (chart_write(&chart, points, 2 * report_rows, csv, png, error, (int)sizeof error))
    return cli_fail("import", "%s", error);
  return 0;
}

/* Missing frame numbers inside the range: an error, or with --skip-missing a warning.
 * -1 to go on, else the exit status. */
static int check_missing(const import_options *o, const vdb_sequence *seq) {
  if (!seq->missing_count) return -1;
  char list[400] = "";
  for (int i = 0; i < seq->missing_count && strlen(list) < 300; i++)
    snprintf(list + strlen(list), sizeof list - strlen(list), "%s%d", i ? ", " : "",
             seq->missing[i]);
  if (!o->skip_missing)
    return cli_fail("import", "%s: %d frame%s missing: %s%s (--skip-missing goes on without them)",
                    o->inputs[0], seq->missing_count, seq->missing_count == 1 ? "" : "s", list,
                    strlen(list) >= 300 ? ", ..." : "");
  fprintf(stderr, "fogpipe import: warning: %d frame%s missing: %s\n", seq->missing_count,
          seq->missing_count == 1 ? "" : "s", list);
  return -1;
}

/* Pass 1: reads, places and projects every frame (a frame's own profile is fitted too),
 * with the warnings a frame earns. 0 or the exit status; *loaded frames need destroying. */
static int load_frames(const import_options *o, const vdb_sequence *seq, vdb_frame *frames,
                       int *loaded) {
  fog_error err = {0};
  /* a sequence's empty frame (before the smoke, or after it) is a frame without fog; a
   * single file's is an error, and so is a sequence whose every frame is empty */
  vdb_frame_desc desc = {.grid = o->grid, .up = o->up, .scale = o->scale,
                         .offset = {o->offset[0], o->offset[1], o->offset[2]},
                         .config = o->config, .profile = o->profile, .max_voxels = o->max_voxels,
                         .empty_ok = seq->count > 1};
  /* each frame finds its config beside it, or none does (before any is read) */
  if (!o->config && vdb_sequence_check_placement(seq, &err))
    return cli_fail("import", "%s, or --config FILE or --config none for all", err.message);
  for (*loaded = 0; *loaded < seq->count; (*loaded)++) {
    const int k = *loaded;
    if (stop_signals_caught()) return IMPORT_INTERRUPTED;
    if (vdb_frame_load(seq->paths[k], &desc, &frames[k], &err))
      return cli_fail("import", "frame %d: %s", seq->frames[k], err.message);
    const vdb_frame *f = &frames[k];
    if (f->world.warning[0] && (k == 0 || strcmp(f->world.warning, frames[0].world.warning)))
      fprintf(stderr, "fogpipe import: warning: %s: %s\n", seq->paths[k], f->world.warning);
    if (f->negative_voxels)
      fprintf(stderr, "fogpipe import: warning: %s: %lld negative voxels clamped to 0\n",
              seq->paths[k], f->negative_voxels);
    if (k == 0 && !f->config_path[0] && o->up == VDB_UP_Z &&
        !(o->config && !strcmp(o->config, "none")))
      fprintf(stderr, "fogpipe import: note: no Mantaflow config beside %s: placement from the "
              "VDB transform alone (a Blender cache carries no domain placement: its domain's "
              "corner lands on the origin, and an adaptive domain's sub-box is lost)\n",
              seq->paths[0]);
    if (o->verbose)
      printf("frame %4d: %s: %lld active voxels, mass %.6g, %dx%d columns, %d layers\n",
             seq->frames[k], seq->paths[k], f->active_voxels, f->columns.mass,
             f->columns.width, f->columns.height, f->columns.layers);
  }
  /* an empty frame's own profile: its nearest frame's with fog (its fogmap is 0, and a
   * player blending it with a neighbour then keeps the neighbour's shape) */
  int with_fog = -1;
  for (int k = 0; k < seq->count; k++)
    if (!frames[k].empty) with_fog = k;
  if (with_fog < 0)
    return cli_fail("import", "%s: every frame's grid '%s' is empty (no active voxels)",
                    o->inputs[0], o->grid ? o->grid : "density");
  int empty = 0;
  char list[320] = "";
  for (int k = 0; k < seq->count; k++) {
    if (!frames[k].empty) continue;
    /* nearest by frame number (frames 1, 2 and 9 of a --skip-missing run: 2 takes 1's,
     * not 9's, which was as near in the list); a tie goes to the earlier frame */
    int nearest = -1;
    const long long at = seq->frames[k];
    for (int j = 0; j < seq->count; j++)
      if (!frames[j].empty &&
          (nearest < 0 || llabs(seq->frames[j] - at) < llabs(seq->frames[nearest] - at)))
        nearest = j;
    frames[k].profile = frames[nearest].profile;
    const size_t used = strlen(list);
    if (used < 300) snprintf(list + used, sizeof list - used, "%s%d", empty ? " " : "",
                             seq->frames[k]);
    else if (!strstr(list, "..."))
      snprintf(list + used, sizeof list - used, " ...");
    empty++;
  }
  if (empty)
    fprintf(stderr, "fogpipe import: note: no fog in %d frame%s (grid '%s' empty or all 0): "
            "%s\n", empty, empty == 1 ? "" : "s", o->grid ? o->grid : "density", list);
  return 0;
}

/* Frames NAME.####.exr in out that this import did not write: an earlier import's, of
 * other frames, placed and normalised by another NAME.ini. Named, not removed (importing a
 * sequence in parts into one folder is a way to work), as record warns of another
 * recording's frames. */
static void warn_other_frames(const import_options *o, const vdb_sequence *seq) {
  DIR *d = opendir(o->out);
  if (!d) return;
  recorder frames = {0}; /* the same NAME.####.exr naming as a recording's */
  snprintf(frames.name, sizeof frames.name, "%s", o->name);
  int others = 0, first = INT_MAX, last = INT_MIN;
  struct dirent *e;
  while ((e = readdir(d))) {
    const int frame = recorder_frame_number(&frames, e->d_name);
    if (frame < 0) continue;
    bool ours = false;
    for (int i = 0; i < seq->count && !ours; i++) ours = seq->frames[i] == frame;
    if (ours) continue;
    others++;
    first = frame < first ? frame : first, last = frame > last ? frame : last;
  }
  closedir(d);
  if (others)
    fprintf(stderr, "fogpipe import: warning: %s also holds %d frame%s of another import "
            "(%s.%04d.exr .. %s.%04d.exr), which %s.ini does not describe\n", o->out, others,
            others == 1 ? "" : "s", o->name, first, o->name, last, o->name);
  /* an earlier run's report, kept beside an import it does not describe */
  if (!o->report)
    for (int k = 0; k < 2; k++) {
      char path[PATH_MAX + 32];
      snprintf(path, sizeof path, "%s/%s.report.%s", o->out, o->name, k ? "png" : "csv");
      if (access(path, F_OK) == 0)
        fprintf(stderr, "fogpipe import: warning: %s is an earlier import's report, which "
                "does not describe this one (run with --report to write this one's)\n", path);
    }
}

/* Every file in temp_dir is complete: moves them into out. 0 or the exit status. */
static void print_summary(const import_options *o, const vdb_sequence *seq,
                          const vdb_frame *frames, const vdb_fogmap_place *place,
                          const vdb_profile *profile, double mass_min, double mass_max) {
  printf("imported %d frame%s (%d..%d) of '%s' from %s\n", seq->count, seq->count == 1 ? "" : "s",
         seq->frames[0], seq->frames[seq->count - 1], o->grid ? o->grid : "density", o->inputs[0]);
  printf("fogmap %dx%d cells of %.6g at origin (%.6g, %.6g); mass %.6g..%.6g\n", place->width,
         place->height, place->cell_size, place->origin_x, place->origin_z, mass_min, mass_max);
  const vdb_profile *g = profile ? profile : &frames[seq->count - 1].profile;
  printf("profile (%s%s): y in [%.6g, %.6g], thickness %.6g\n",
         g->kind == VDB_PROFILE_EXPONENTIAL ? "exponential" : "B-spline",
         profile ? "" : ", per frame; last frame shown", g->y_bottom, g->y_top, g->thickness);
  printf("wrote %s/%s.####.exr and %s/%s.ini\n", o->out, o->name, o->out, o->name);
}

int cmd_import(int argc, char **argv) {
  import_options o;
  int parsed = parse_options(argc, argv, &o);
  if (parsed) return parsed < 0 ? 0 : parsed;
  if (o.list) return list_grids(&o);
  char chart_error[256];
  if (o.report && !chart_can_draw(chart_error, sizeof chart_error)) /* before the import */
    return cli_fail("import", "--report: %s", chart_error);

  fog_error err = {0};
  vdb_sequence seq;
  if (vdb_sequence_find(o.inputs, o.input_count, o.first, o.last, &seq, &err))
    return cli_fail("import", "%s", err.message);
  int missing = check_missing(&o, &seq);
  if (missing >= 0) {
    vdb_sequence_destroy(&seq);
    return missing;
  }
  /* --report-frame among the frames found, before any is read (it was checked after every
   * frame had been imported) */
  bool report_frame_found = o.report_frame < 0;
  for (int i = 0; i < seq.count; i++) report_frame_found |= seq.frames[i] == o.report_frame;
  if (!report_frame_found) {
    const int first = seq.frames[0], last = seq.frames[seq.count - 1];
    vdb_sequence_destroy(&seq);
    return cli_usage_error("import", "--report-frame %d: no such frame among those imported "
                           "(%d..%d)", o.report_frame, first, last);
  }

  int status = 0, loaded = 0;
  out_folder made = {0}; /* the folders of --out this run made */
  char temp_dir[4200] = "";
  vdb_frame *frames = calloc((size_t)seq.count, sizeof *frames);
  const vdb_columns **cols = malloc((size_t)seq.count * sizeof *cols); /* frames[i].columns */
  fogmap map = {0};
  if (!frames || !cols) {
    free(frames), free(cols);
    vdb_sequence_destroy(&seq);
    return cli_fail("import", "out of memory for %d frames", seq.count);
  }
  for (int i = 0; i < seq.count; i++) cols[i] = &frames[i].columns;
  /* Ctrl-C or SIGTERM: the staging folder and the folders this run made go, --out stays as
   * it was (exit 130); held while the files move into place */
  stop_signals stop;
  stop_signals_clear();
  stop_signals_catch(&stop, false);
  if ((status = load_frames(&o, &seq, frames, &loaded))) goto done;
  vdb_fogmap_place place;
  /* one fogmap grid for the whole sequence: the union of the frames' footprints */
  if (vdb_fogmap_place_fit_columns(cols, seq.count, o.resolution, o.cell, &place, &err)) {
    status = cli_fail("import", "%s", err.message);
    goto done;
  }
  vdb_profile seq_profile;
  const vdb_profile *profile = NULL;
  if (!o.profile_per_frame) {
    if (vdb_profile_fit_columns(cols, seq.count, &o.profile, &seq_profile, &err)) {
      status = cli_fail("import", "%s: %s", o.inputs[0], err.message);
      goto done;
    }
    profile = &seq_profile;
  }
  /* The fog pass holds a fogmap with a cell of border each side in one texture: past 16384
   * texels (llvmpipe's limit and many GPUs') no render loads it. Said, not refused: a
   * GPU with a larger limit may. */
  if (place.width > 16382 || place.height > 16382)
    fprintf(stderr, "fogpipe import: warning: a %dx%d fogmap needs a %d-texel texture side to "
            "render; llvmpipe and many GPUs take at most 16384 (a coarser --cell or "
            "--resolution up to 16382 keeps it renderable)\n", place.width, place.height,
            (place.width > place.height ? place.width : place.height) + 2);
  /* Pass 2: resample and write into a temporary folder beside the results. */
  fog_error folder_err = {0};
  if (out_folder_make(&made, o.out, &folder_err)) {
    status = cli_fail("import", "--out: %s", folder_err.message);
    goto done;
  }
  snprintf(temp_dir, sizeof temp_dir, "%s/.%s.import.XXXXXX", o.out, o.name);
  if (!mkdtemp(temp_dir)) {
    status = cli_fail("import", "%s: cannot create a temporary folder: %s", o.out, strerror(errno));
    temp_dir[0] = 0;
    goto done;
  }
  if (fogmap_create(&map, place.width, place.height, &err)) {
    status = cli_fail("import", "%s", err.message);
    goto done;
  }
  double mass_min = INFINITY, mass_max = 0;
  for (int i = 0; i < seq.count; i++) {
    const vdb_profile *g = profile ? profile : &frames[i].profile;
    if (stop_signals_caught()) {
      status = IMPORT_INTERRUPTED;
      goto done;
    }
    if (vdb_columns_resample(&frames[i].columns, &place, g->thickness, &map, &err)) {
      status = cli_fail("import", "frame %d: %s: %s", seq.frames[i], seq.paths[i], err.message);
      goto done;
    }
    char path[4300];
    snprintf(path, sizeof path, "%s/%s.%04d.exr", temp_dir, o.name, seq.frames[i]);
    if (fogmap_save_exr(path, &map, &err)) {
      status = cli_fail("import", "frame %d: %s", seq.frames[i], err.message);
      goto done;
    }
    mass_min = fmin(mass_min, frames[i].columns.mass);
    mass_max = fmax(mass_max, frames[i].columns.mass);
  }
  char sidecar[4300];
  snprintf(sidecar, sizeof sidecar, "%s/%s.ini", temp_dir, o.name);
  if (write_sidecar(sidecar, &o, &seq, frames, &place, profile, &err)) {
    status = cli_fail("import", "%s", err.message);
    goto done;
  }
  if (o.report && (status = run_report(&o, &seq, frames, &place, profile, temp_dir))) goto done;
  if (stop_signals_caught()) {
    status = IMPORT_INTERRUPTED;
    goto done;
  }
  stop_signals_hold(&stop);
  status = staged_move_into_place("import", temp_dir, o.out);
  stop_signals_release(&stop);
  if (status) goto done;
  print_summary(&o, &seq, frames, &place, profile, mass_min, mass_max);
  warn_other_frames(&o, &seq);
done:
  if (status == IMPORT_INTERRUPTED)
    fprintf(stderr, "fogpipe import: interrupted: nothing written%s\n",
            made.any ? "" : " (the folder is as it was)");
  if (temp_dir[0]) staged_remove(temp_dir);
  if (status) out_folder_undo(&made); /* folders made for a failed import go too */
  stop_signals_restore(&stop);
  fogmap_destroy(&map);
  for (int i = 0; i < seq.count; i++) vdb_frame_destroy(&frames[i]);
  free(frames);
  free(cols);
  vdb_sequence_destroy(&seq);
  return status;
}
