/* fogpipe transform: wavelet-decompose a fogmap into its B-spline pyramid, or (with
 * --inverse) rebuild the fogmap from such a folder. The maths is in transform/ and
 * docs/transform.md; this file parses options, reads and writes files. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <OpenEXR/openexr.h>

#include "app/cli.h"
#include "app/staged_move.h"
#include "app/stop_signals.h"
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/out_folder.h"
#include "sim/sim.h"
#include "transform/transform.h"

static const char *const orientation_names[3] = {"x", "y", "xy"};

static const char *basis_word(transform_basis b) {
  return b == TRANSFORM_HAAR ? "haar" : b == TRANSFORM_LINEAR ? "linear" : "quadratic";
}

static int parse_basis(const char *s, transform_basis *b) {
  if (!strcmp(s, "haar")) *b = TRANSFORM_HAAR;
  else if (!strcmp(s, "linear")) *b = TRANSFORM_LINEAR;
  else if (!strcmp(s, "quadratic")) *b = TRANSFORM_QUADRATIC;
  else return 1;
  return 0;
}

/* --levels and the manifest's levels: at most 60 (a 2^60-wide map); the manifest took up
 * to 1000000, and checking 5 (L + 1) output names for it stalled --inverse for 25 s. */
enum { TRANSFORM_CLI_MAX_LEVELS = 60 };

/* A whole number 0..1000000 of a pyramid's sidecar file: non-zero when it is not one. */
static int parse_int(const char *s, int *out) {
  long v;
  if (!cli_parse_long(s, 0, 1000000, &v)) return 1;
  *out = (int)v;
  return 0;
}

/* ---- a signed EXR channel reader (fogmap_load rejects negative values, but detail
 * coefficients are signed): channel "Y" of a scanline EXR, half or float. ---- */

/* OpenEXR's errors said by this command's own messages, not printed a second time */
static void quiet_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg) {
  (void)ctxt, (void)code, (void)msg;
}

static int read_signed_exr(const char *path, int *w_out, int *h_out, float **pixels,
                           char *msg, size_t msg_size) {
  exr_context_t ctxt = NULL;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = quiet_exr_error; /* NULL is OpenEXR's own, which prints */
  exr_decode_pipeline_t decode = EXR_DECODE_PIPELINE_INITIALIZER;
  int initialised = 0, status = 1;
  float *out = NULL;
  if (exr_start_read(&ctxt, path, &init) != EXR_ERR_SUCCESS) {
    snprintf(msg, msg_size, "%s: missing or not a readable EXR", path);
    return 1;
  }
  exr_storage_t storage;
  exr_attr_box2i_t win;
  const exr_attr_chlist_t *list = NULL;
  if (exr_get_storage(ctxt, 0, &storage) || exr_get_data_window(ctxt, 0, &win) ||
      exr_get_channels(ctxt, 0, &list) || storage != EXR_STORAGE_SCANLINE || !list ||
      list->num_channels != 1 || strcmp(list->entries[0].name.str, "Y")) {
    snprintf(msg, msg_size, "%s: expected a scanline EXR with one channel \"Y\"", path);
    goto done;
  }
  int w = win.max.x - win.min.x + 1, h = win.max.y - win.min.y + 1;
  if (w <= 0 || h <= 0 || (int64_t)w * h > (int64_t)1 << 28) {
    snprintf(msg, msg_size, "%s: bad EXR size %dx%d", path, w, h);
    goto done;
  }
  out = malloc(sizeof(float) * (size_t)w * (size_t)h);
  int32_t lines = 1;
  exr_result_t rv = out ? exr_get_scanlines_per_chunk(ctxt, 0, &lines) : EXR_ERR_OUT_OF_MEMORY;
  for (int32_t y = win.min.y; rv == EXR_ERR_SUCCESS && y <= win.max.y; y += lines) {
    exr_chunk_info_t chunk;
    rv = exr_read_scanline_chunk_info(ctxt, 0, y, &chunk);
    if (rv != EXR_ERR_SUCCESS) break;
    rv = initialised ? exr_decoding_update(ctxt, 0, &chunk, &decode)
                     : exr_decoding_initialize(ctxt, 0, &chunk, &decode);
    if (rv != EXR_ERR_SUCCESS) break;
    exr_coding_channel_info_t *c = &decode.channels[0];
    c->decode_to_ptr = (uint8_t *)(out + (size_t)(chunk.start_y - win.min.y) * (size_t)w);
    c->user_pixel_stride = sizeof(float);
    c->user_line_stride = (int32_t)(sizeof(float) * (size_t)w);
    c->user_bytes_per_element = sizeof(float);
    c->user_data_type = EXR_PIXEL_FLOAT;
    if (!initialised) {
      rv = exr_decoding_choose_default_routines(ctxt, 0, &decode);
      initialised = 1;
      if (rv != EXR_ERR_SUCCESS) break;
    }
    rv = exr_decoding_run(ctxt, 0, &decode);
  }
  if (rv != EXR_ERR_SUCCESS) {
    snprintf(msg, msg_size, "%s: EXR decoding failed: %s", path, exr_get_default_error_message(rv));
    goto done;
  }
  /* A coefficient NaN or infinite would come out of the inverse as a hole or a wall of
   * fog (the final clamp makes NaN 0): a damaged file, refused naming the cell. */
  for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
    if (!isfinite(out[i])) {
      snprintf(msg, msg_size, "%s: value %g at x %zu, y %zu: expected finite coefficients",
               path, out[i], i % (size_t)w, i / (size_t)w);
      goto done;
    }
  *w_out = w, *h_out = h, *pixels = out;
  out = NULL;
  status = 0;
done:
  if (initialised) exr_decoding_destroy(ctxt, &decode);
  exr_finish(&ctxt);
  free(out);
  return status;
}

/* ---- forward ---- */

static int write_exr(const char *dir, const char *name, int w, int h, const float *v) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  image_channel y = {.name = "Y", .pixels = v, .as_half = 0};
  fog_error err;
  if (image_write_exr(path, w, h, &y, 1, &err)) return cli_fail("transform", "%s", err.message);
  return 0;
}

static int write_manifest(const char *dir, transform_plan *plan, const char *input,
                          const double *energy) {
  const transform_desc *d = transform_plan_desc(plan);
  char path[4096];
  snprintf(path, sizeof path, "%s/transform.ini", dir);
  char *text = NULL;
  size_t text_size = 0;
  FILE *f = open_memstream(&text, &text_size); /* written whole below */
  if (!f) return cli_fail("transform", "%s: out of memory", path);
  /* the input's name in a comment line: a control character in it (a line break) would
   * end the comment and make a manifest the reader refuses */
  fprintf(f, "# fogpipe transform of ");
  for (const char *c = input; *c; c++) fputc((unsigned char)*c < 0x20 || *c == 0x7f ? '?' : *c, f);
  fprintf(f, " (docs/transform.md)\n[transform]\n");
  fprintf(f, "basis = %s\ndegree = %d\nlevels = %d\nmode = %s\ndecomposition = %s\n",
          basis_word(d->basis), transform_basis_degree(d->basis), d->levels,
          d->boundary == TRANSFORM_PERIODIC ? "periodic" : "symmetric",
          d->decomposition == TRANSFORM_STANDARD ? "standard" : "nonstandard");
  fprintf(f, "width = %d\nheight = %d\n", d->width, d->height);
  for (int l = 0; l <= d->levels; l++) {
    int w, h, gw, gh;
    transform_level_size(plan, l, &w, &h);
    transform_grid_size(plan, l, &gw, &gh);
    double s = ldexp(1.0, d->levels - l);
    double first = transform_basis_degree(d->basis) == 1 ? 0.0 : 0.5 * (s - 1.0);
    fprintf(f, "\n[level %d]\nwidth = %d\nheight = %d\nspacing = %.17g\n"
            "# fine-sample position of stored coefficient (0,0) (EXRs hold no ghosts)\n"
            "origin = %.17g\n", l, w, h, s, first);
    if (l > 0)
      fprintf(f, "energy_x = %.17g\nenergy_y = %.17g\nenergy_xy = %.17g\n", energy[3 * l],
              energy[3 * l + 1], energy[3 * l + 2]);
  }
  if (ferror(f) | fclose(f)) {
    free(text);
    return cli_fail("transform", "%s: out of memory", path);
  }
  fog_error err = {0};
  const int failed = atomic_file_write(path, text, text_size, &err);
  free(text);
  return failed ? cli_fail("transform", "%s", err.message) : 0;
}

static int read_manifest(const char *dir, transform_desc *desc, char *msg, size_t msg_size);

/* The folder's file of level l, kind k (0 approx, 1 deconstructed, 2..4 detail x, y, xy)
 * into path. */
static void level_file(const char *dir, int l, int k, char *path, size_t size) {
  if (k == 0) snprintf(path, size, "%s/approx_%d.exr", dir, l);
  else if (k == 1) snprintf(path, size, "%s/deconstructed_%d.exr", dir, l);
  else snprintf(path, size, "%s/detail_%d_%s.exr", dir, l, orientation_names[k - 2]);
}

/* The files of levels J+1 .. earlier_levels that an earlier, deeper transform into DIR left
 * (its transform.ini said so): beside a transform.ini of J levels they would be read as
 * this one's. Only that transform's own names, and never the input (`in` may be one). */
static void remove_deeper_levels(const char *dir, int levels, int earlier_levels,
                                 const char *in) {
  int removed = 0;
  char path[4400];
  for (int l = levels + 1; l <= earlier_levels; l++)
    for (int k = 0; k < 5; k++) {
      level_file(dir, l, k, path, sizeof path);
      if (!cli_same_file(path, in)) removed += unlink(path) == 0;
    }
  if (removed)
    printf("removed %d file%s of an earlier transform with more levels than %d\n", removed,
           removed == 1 ? "" : "s", levels);
}

static int run_forward(const char *in, const char *channel, const char *dir,
                       transform_desc desc) {
  /* the input must not be one of the files this writes (transform P/approx_0.exr --out P) */
  for (int l = 0; l <= desc.levels && l <= 60; l++)
    for (int k = 0; k < 5; k++) {
      char output[4400];
      level_file(dir, l, k, output, sizeof output);
      if (cli_output_not_input("transform", "--out", output, in, "the input fogmap")) return 2;
    }
  fogmap map;
  fog_error serr;
  if (fogmap_load(in, &(fogmap_load_desc){.channel = channel, .channel_setting = "--channel"},
                  &map, &serr))
    return cli_fail("transform", "%s", serr.message);
  desc.width = map.width, desc.height = map.height;
  transform_plan *plan = NULL;
  fog_error terr;
  int status = 1;
  size_t n = (size_t)map.width * map.height;
  float *coef = NULL, *approx[64] = {0}, *detail[64] = {0}, *band = NULL;
  double *energy = NULL;
  char staging[4200] = "";
  out_folder made = {0}; /* the folders of DIR this run made */
  /* Ctrl-C or SIGTERM: the staging folder goes and DIR stays as it was (exit 130); they
   * are held while the files move into place */
  stop_signals stop;
  stop_signals_clear();
  stop_signals_catch(&stop, false);
  if (desc.levels > 60) {
    cli_fail("transform", "%s: %d levels is too many", in, desc.levels);
    goto done;
  }
  if (!(plan = transform_plan_create(&desc, &terr))) {
    cli_fail("transform", "%s: %s", in, terr.message);
    goto done;
  }
  int J = desc.levels;
  coef = transform_alloc_floats(n);
  band = malloc(n * sizeof *band);
  energy = calloc(3 * (size_t)(J + 1), sizeof *energy);
  int ok = coef && band && energy;
  for (int l = 0; ok && l <= J; l++) {
    int w, h;
    transform_level_size(plan, l, &w, &h);
    approx[l] = transform_alloc_floats((size_t)w * h);
    detail[l] = transform_alloc_floats((size_t)w * h);
    ok = approx[l] && detail[l];
  }
  if (!ok) {
    cli_fail("transform", "%s: out of memory", in);
    goto done;
  }
  transform_forward(plan, map.density, coef);
  transform_pyramid(plan, coef, approx);
  /* A_J is the fogmap: its copy, not the reconstruction (which rounds 0 to -1e-9, a value
   * no fogmap holds). The coarser A_l stay the transform's own, signed (docs/transform.md) */
  memcpy(approx[J], map.density, sizeof(float) * n);
  transform_details(plan, coef, detail);
  transform_detail_energy(plan, coef, energy);
  /* an earlier transform into DIR, whose deeper levels go once this one is written */
  transform_desc earlier;
  char earlier_msg[256];
  const int earlier_levels =
      read_manifest(dir, &earlier, earlier_msg, sizeof earlier_msg) ? -1 : earlier.levels;
  /* only now touch DIR (and its parents, as import and record make theirs) */
  fog_error ferr = {0};
  if (out_folder_make(&made, dir, &ferr)) {
    cli_fail("transform", "%s", ferr.message);
    goto done;
  }
  /* every file into a staging folder in DIR, then moved in all or none: a run that fails
   * part-way leaves an earlier transform in DIR whole, not a mix under its manifest */
  snprintf(staging, sizeof staging, "%s/.transform.XXXXXX", dir);
  if (!mkdtemp(staging)) {
    cli_fail("transform", "%s: cannot make a staging folder in it: %s", dir, strerror(errno));
    staging[0] = '\0';
    goto done;
  }
  char name[64];
  for (int l = 0; l <= J; l++) {
    int w, h;
    transform_level_size(plan, l, &w, &h);
    if (stop_signals_caught()) goto interrupted;
    snprintf(name, sizeof name, "approx_%d.exr", l);
    if (write_exr(staging, name, w, h, approx[l])) goto done;
    if (l == 0) continue;
    snprintf(name, sizeof name, "deconstructed_%d.exr", l);
    if (write_exr(staging, name, w, h, detail[l])) goto done;
    for (int o = 0; o < 3; o++) {
      int x, y, bw, bh;
      transform_band_rect(plan, l, (transform_orientation)o, &x, &y, &bw, &bh);
      for (int j = 0; j < bh; j++)
        memcpy(band + (size_t)j * bw, coef + (size_t)(y + j) * map.width + x,
               sizeof(float) * (size_t)bw);
      snprintf(name, sizeof name, "detail_%d_%s.exr", l, orientation_names[o]);
      if (write_exr(staging, name, bw, bh, band)) goto done;
    }
  }
  if (write_manifest(staging, plan, in, energy)) goto done;
  if (stop_signals_caught()) goto interrupted;
  stop_signals_hold(&stop);
  if (!staged_move_into_place("transform", staging, dir)) {
    remove_deeper_levels(dir, J, earlier_levels, in);
    status = 0;
  }
  stop_signals_release(&stop);
  goto done;
interrupted:
  fprintf(stderr, "fogpipe transform: interrupted: nothing written%s\n",
          made.any ? "" : " (the folder is as it was)");
  status = 130;
done:
  if (staging[0]) staged_remove(staging);
  if (status) out_folder_undo(&made); /* folders made for a failed run go too */
  stop_signals_restore(&stop);
  for (int l = 0; l < 64; l++) free(approx[l]), free(detail[l]);
  free(coef), free(band), free(energy);
  transform_plan_destroy(plan);
  fogmap_destroy(&map);
  return status;
}

/* ---- inverse ---- */

static int read_manifest(const char *dir, transform_desc *desc, char *msg, size_t msg_size) {
  char path[4096], word[64];
  /* lines of any length: the comment names the input, whose path may be long (a 512-byte
   * buffer split it and read its rest as a key line: the folder could not be inverted) */
  char *line = NULL;
  size_t line_size = 0;
  snprintf(path, sizeof path, "%s/transform.ini", dir);
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(msg, msg_size, "%s: cannot open: %s (not a fogpipe transform folder?)", path,
             strerror(errno));
    return 1;
  }
  /* [transform]'s keys as write_manifest writes them: each at most once; the first four
   * required. The [level N] sections are notes for a reader (not read). */
  static const char *const keys[] = {"basis", "levels", "width", "height", "mode",
                                     "decomposition", "degree"};
  enum { KEY_COUNT = 7, REQUIRED = 15 };
  int have = 0, lineno = 0, in_transform = 0, status = 0, degree = -1;
  bool in_section = false;
  *desc = (transform_desc){0};
  while (!status && getline(&line, &line_size, f) >= 0) {
    lineno++;
    char *s = line;
    while (*s == ' ' || *s == '\t') s++;
    if (*s == '#' || *s == ';' || *s == '\n' || *s == '\r' || !*s) continue;
    if (*s == '[') {
      in_transform = !strncmp(s, "[transform]", 11);
      in_section = true;
      continue;
    }
    if (!in_section) {
      snprintf(msg, msg_size, "%s:%d: expected a comment or '[transform]' first", path, lineno);
      status = 1;
      break;
    }
    if (!in_transform) continue;
    char key[64];
    if (sscanf(s, "%63[a-z_] = %63s", key, word) != 2) {
      snprintf(msg, msg_size, "%s:%d: expected key = value", path, lineno);
      status = 1;
      break;
    }
    int k = 0;
    while (k < KEY_COUNT && strcmp(key, keys[k])) k++;
    if (k == KEY_COUNT || (have >> k) & 1) {
      snprintf(msg, msg_size, "%s:%d: [transform] %s: %s", path, lineno, key,
               k == KEY_COUNT ? "unknown key" : "given twice");
      status = 1;
      break;
    }
    have |= 1 << k;
    int bad = 0;
    if (k == 0) bad = parse_basis(word, &desc->basis);
    else if (k == 1)
      bad = parse_int(word, &desc->levels) || desc->levels > TRANSFORM_CLI_MAX_LEVELS;
    else if (k == 2) bad = parse_int(word, &desc->width);
    else if (k == 3) bad = parse_int(word, &desc->height);
    else if (k == 4) {
      bad = strcmp(word, "symmetric") && strcmp(word, "periodic");
      desc->boundary = strcmp(word, "periodic") ? TRANSFORM_SYMMETRIC : TRANSFORM_PERIODIC;
    } else if (k == 5) {
      bad = strcmp(word, "standard") && strcmp(word, "nonstandard");
      desc->decomposition =
          strcmp(word, "standard") ? TRANSFORM_NONSTANDARD : TRANSFORM_STANDARD;
    } else {
      bad = parse_int(word, &degree);
    }
    if (bad) {
      snprintf(msg, msg_size, "%s:%d: bad value \"%s\" for %s", path, lineno, word, key);
      status = 1;
    }
  }
  free(line);
  fclose(f);
  if (!status && (have & REQUIRED) != REQUIRED) {
    snprintf(msg, msg_size,
             "%s: [transform] needs basis, levels, width and height (missing:%s%s%s%s)", path,
             have & 1 ? "" : " basis", have & 2 ? "" : " levels", have & 4 ? "" : " width",
             have & 8 ? "" : " height");
    status = 1;
  } else if (!status && (int64_t)desc->width * desc->height > (int64_t)1 << 28) {
    /* what read_signed_exr takes: the plan and the map were made from the manifest's size
     * before any band was read (width = 1000000, height = 20000: 80 GB cleared) */
    snprintf(msg, msg_size, "%s: [transform] width x height %d x %d is more than a fogmap's "
             "%lld cells", path, desc->width, desc->height, (long long)1 << 28);
    status = 1;
  } else if (!status && degree >= 0 && degree != transform_basis_degree(desc->basis)) {
    snprintf(msg, msg_size, "%s: [transform] degree = %d contradicts basis = %s (degree %d)", path,
             degree, basis_word(desc->basis), transform_basis_degree(desc->basis));
    status = 1;
  }
  return status;
}

static int read_into(const char *dir, const char *name, int w, int h, float *dst,
                     size_t stride) {
  char path[4096], msg[8448];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  int rw, rh;
  float *v;
  if (read_signed_exr(path, &rw, &rh, &v, msg, sizeof msg)) return cli_fail("transform", "%s", msg);
  if (rw != w || rh != h) {
    free(v);
    return cli_fail("transform", "%s: size %dx%d, transform.ini says %dx%d", path, rw, rh, w, h);
  }
  for (int j = 0; j < h; j++) memcpy(dst + (size_t)j * stride, v + (size_t)j * w, sizeof(float) * w);
  free(v);
  return 0;
}

/* stop: caught by the caller (Ctrl-C or SIGTERM while reading and inverting: nothing
 * written, exit 130; held while the map is written, so that it is whole) */
static int run_inverse(const char *dir, const char *out, int threads, stop_signals *stop) {
  transform_desc desc;
  char msg[8448];
  if (read_manifest(dir, &desc, msg, sizeof msg)) return cli_fail("transform", "%s", msg);
  /* --out must not replace a file of the folder it reads (approx_0.exr: the next inverse
   * would fail; any other: the folder would no longer be its transform.ini's) */
  for (int l = 0; l <= desc.levels; l++)
    for (int k = 0; k < 5; k++) {
      char input[4400];
      level_file(dir, l, k, input, sizeof input);
      if (cli_output_not_input("transform", "--out", out, input, "a file of the --inverse folder"))
        return 2;
    }
  desc.threads = threads;
  transform_plan *plan;
  fog_error terr;
  if (!(plan = transform_plan_create(&desc, &terr)))
    return cli_fail("transform", "%s/transform.ini: %s", dir, terr.message);
  size_t W = (size_t)desc.width;
  fogmap map = {0};
  fog_error serr;
  int status = 1;
  if (fogmap_create(&map, desc.width, desc.height, &serr)) {
    cli_fail("transform", "%s", serr.message);
    goto done;
  }
  int w0, h0;
  transform_level_size(plan, 0, &w0, &h0);
  if (read_into(dir, "approx_0.exr", w0, h0, map.density, W)) goto done;
  for (int l = 1; l <= desc.levels; l++)
    for (int o = 0; o < 3; o++) {
      int x, y, bw, bh;
      char name[64];
      transform_band_rect(plan, l, (transform_orientation)o, &x, &y, &bw, &bh);
      snprintf(name, sizeof name, "detail_%d_%s.exr", l, orientation_names[o]);
      if (read_into(dir, name, bw, bh, map.density + (size_t)y * W + x, W)) goto done;
    }
  transform_inverse(plan, map.density, map.density);
  /* densities are never negative, nor above what fogmap_load takes: float rounding just
   * past either bound (a peak of 1e12 came back as 1.0000003e12) is clamped */
  for (size_t i = 0; i < W * (size_t)desc.height; i++) {
    if (!(map.density[i] > 0.0f)) map.density[i] = 0.0f;
    if (map.density[i] > FOGMAP_MAX_DENSITY) map.density[i] = FOGMAP_MAX_DENSITY;
  }
  if (stop_signals_caught()) {
    fprintf(stderr, "fogpipe transform: interrupted: nothing written\n");
    status = 130;
    goto done;
  }
  stop_signals_hold(stop);
  const int failed = fogmap_save_exr(out, &map, &serr);
  stop_signals_release(stop); /* one held now only sets the flag: the file is whole */
  if (failed) {
    cli_fail("transform", "%s", serr.message);
    goto done;
  }
  status = 0;
done:
  fogmap_destroy(&map);
  transform_plan_destroy(plan);
  return status;
}

int cmd_transform(int argc, char **argv) {
  const char *out = NULL, *inverse = NULL, *channel = NULL;
  transform_desc desc = {.levels = -1};
  /* in the enums' order: transform_basis, transform_boundary */
  static const char *const bases[] = {"linear", "haar", "quadratic", NULL};
  static const char *const modes[] = {"symmetric", "periodic", NULL};
  int basis = -1, mode = -1; /* -1: not given (linear, symmetric) */
  bool standard = false;
  const cli_option options[] = {
      {.kind = CLI_CHOICE, .name = "--basis", .value = "haar|linear|quadratic", .target = &basis,
       .choices = bases, .help = "B-spline degree 0, 1 (CDF 5/3), 2 (bior3.3);\ndefault linear"},
      {.kind = CLI_INT, .name = "--levels", .value = "J", .target = &desc.levels, .min = 0,
       .max = TRANSFORM_CLI_MAX_LEVELS,
       .help = "decomposition levels (required; too many for\n"
               "the size is an error naming the largest J)"},
      {.kind = CLI_CHOICE, .name = "--mode", .value = "symmetric|periodic", .target = &mode,
       .choices = modes,
       .help = "boundary extension; default symmetric\n(periodic needs sizes divisible by 2^J)"},
      {.kind = CLI_FLAG, .name = "--standard", .target = &standard,
       .help = "standard decomposition (default: non-standard)"},
      {.kind = CLI_TEXT, .name = "--channel", .value = "NAME", .target = &channel,
       .help = "the channel of a multi-channel IN: an EXR\n"
               "channel (R, Y, density, ...) or R, G, B, A of a\n"
               "PNG; default: IN must have one channel"},
      {.kind = CLI_INT, .name = "--threads", .value = "1|2", .target = &desc.threads, .min = 1,
       .max = 2, .help = "default 1"},
      {.kind = CLI_TEXT, .name = "--out", .value = "DIR|FILE", .target = &out,
       .required = true, .help = "output folder (forward) or EXR file (--inverse)"},
      {.kind = CLI_TEXT, .name = "--inverse", .value = "DIR", .target = &inverse,
       .help = "reconstruct from DIR"},
  };
  const cli_spec spec = {
      .command = "transform",
      .usage = "IN --levels J --out DIR [options]\n"
               "       fogpipe transform --inverse DIR --out FILE",
      .about = "Decomposes the fogmap IN (PNG or EXR) in a B-spline wavelet basis\n"
               "(Mallat's algorithm, unnormalised lifting; docs/transform.md) and writes to DIR:\n"
               "  approx_L.exr            approximation pyramid A_L, L = 0 (coarsest) .. J\n"
               "  detail_L_{x,y,xy}.exr   detail band L (1 = coarsest .. J), by orientation\n"
               "  deconstructed_L.exr     band L pushed through the synthesis filters once: a\n"
               "                          scaling grid at level L (A_L = refine(A_L-1) + it)\n"
               "  transform.ini           basis, levels, mode, sizes, grid origins, energies\n"
               "With --inverse, reads such a folder and writes the reconstructed fogmap EXR.",
      .operand = "IN", .min_operands = 0, .max_operands = 1,
      CLI_OPTIONS(options)};
  const char *in = NULL;
  int parsed = cli_parse_one(&spec, argc, argv, &in);
  if (parsed) return parsed == CLI_HELP ? 0 : parsed;
  if (inverse && (basis >= 0 || mode >= 0 || standard || desc.levels >= 0))
    return cli_usage_error("transform", "--inverse reads the basis, levels, mode and "
                           "decomposition from its folder's transform.ini; --basis, --levels, "
                           "--mode and --standard are for a forward transform");
  desc.basis = basis >= 0 ? (transform_basis)basis : TRANSFORM_LINEAR;
  desc.boundary = mode >= 0 ? (transform_boundary)mode : TRANSFORM_SYMMETRIC;
  desc.decomposition = standard ? TRANSFORM_STANDARD : TRANSFORM_NONSTANDARD;
  if (inverse) {
    if (in) return cli_usage_error("transform", "--inverse takes no input fogmap (%s)", in);
    if (channel) return cli_usage_error("transform", "--inverse reads its folder's own channels; "
                                 "--channel is for a forward transform");
    if (!cli_ends_with(out, ".exr")) /* what it writes, whatever the name says */
      return cli_usage_error("transform", "--out '%s': --inverse writes an EXR file: expected "
                             "a name ending in .exr", out);
    if (cli_output_file("transform", "--out", out) ||
        cli_output_in_folder("transform", "--out", out))
      return 2;
    stop_signals stop;
    stop_signals_clear();
    stop_signals_catch(&stop, true);
    const int status = run_inverse(inverse, out, desc.threads, &stop);
    stop_signals_restore(&stop);
    return status;
  }
  if (!in) return cli_usage_error("transform", "no input fogmap given");
  if (desc.levels < 0) return cli_usage_error("transform", "--levels is required");
  return run_forward(in, channel, out, desc);
}
