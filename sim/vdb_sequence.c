/* VDB sequences: files, directories, printf (%04d) and #### patterns, globs; frame
 * numbers from file names; missing frames inside the range. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <glob.h>
#include <inttypes.h>
#include <stdbool.h>
#include <stdint.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sim/vdb_import.h"

/* At most this many frames from the first to the last (2^20: 12 hours at 24 fps): the
 * missing frames are listed one by one, and a glob matching unrelated files numbered 1
 * and 2000000000 asked for an 8 GB list (and overflowed int computing its size). */
enum { max_span = VDB_SEQUENCE_MAX_SPAN };

/* The last run of digits in the file name (not the folders); -1 if none. */
static long frame_of(const char *path, int *digits_start, int *digits_len) {
  const char *base = strrchr(path, '/');
  base = base ? base + 1 : path;
  const char *end = NULL;
  for (const char *p = base; *p; p++)
    if (isdigit((unsigned char)*p)) end = p;
  if (!end) return -1;
  const char *start = end;
  while (start > base && isdigit((unsigned char)start[-1])) start--;
  if (digits_start) *digits_start = (int)(start - path);
  if (digits_len) *digits_len = (int)(end - start + 1);
  return strtol(start, NULL, 10);
}

/* The same file however spelt (device and inode), or the same string. */
static bool same_file(const char *a, const char *b) {
  struct stat sa, sb;
  if (!strcmp(a, b)) return true;
  return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

typedef struct entry {
  int frame;
  char *path;
} entry;

typedef struct entry_list {
  entry *items;
  int count, capacity;
  int last;             /* the range's last frame, -1: open */
  char too_large[4096]; /* a file whose frame number an int does not hold */
  char unnumbered[4096]; /* a name without digits among numbered ones (add_glob) */
} entry_list;

/* 0, 1 (out of memory) or 2: frame past INT_MAX in an open range (the path kept in
 * list->too_large; a closed range leaves it out, as every frame past its end). */
static int push(entry_list *list, long frame, const char *path) {
  if (frame > INT_MAX) {
    if (list->last >= 0) return 0;
    snprintf(list->too_large, sizeof list->too_large, "%s", path);
    return 2;
  }
  if (list->count == list->capacity) {
    int cap = list->capacity ? 2 * list->capacity : 64;
    entry *items = realloc(list->items, (size_t)cap * sizeof *items);
    if (!items) return 1;
    list->items = items;
    list->capacity = cap;
  }
  char *copy = strdup(path);
  if (!copy) return 1;
  list->items[list->count++] = (entry){.frame = (int)frame, .path = copy};
  return 0;
}

static int by_frame(const void *a, const void *b) {
  const entry *x = a, *y = b;
  if (x->frame != y->frame) return (x->frame > y->frame) - (x->frame < y->frame);
  return strcmp(x->path, y->path);
}

/* A printf pattern's one integer conversion (%d, %4d, %04d; width at most 3 digits): its
 * span in pattern. The pattern becomes snprintf's format with one int argument, so it is
 * one only if every other '%' is "%%": a name like "x%s%d.vdb" (or a second %d) is not a
 * pattern (it used to reach snprintf, which read a pointer that was never passed). */
static int find_conversion(const char *pattern, int *start, int *end) {
  int found = 0;
  for (const char *p = pattern; *p; p++) {
    if (*p != '%') continue;
    if (p[1] == '%') {
      p++;
      continue;
    }
    const char *q = p + 1;
    while (isdigit((unsigned char)*q) && q - p <= 3) q++;
    if (found || (*q != 'd' && *q != 'i' && *q != 'u')) return 0;
    *start = (int)(p - pattern);
    *end = (int)(q - pattern) + 1;
    found = 1;
    p = q;
  }
  return found;
}

/* fluid_data_####.vdb -> fluid_data_%04d.vdb (a '%' of the name becomes "%%"). */
bool vdb_pattern_hash_run(const char *pattern, size_t *start, size_t *length) {
  const char *slash = strrchr(pattern, '/'), *name = slash ? slash + 1 : pattern;
  const char *last = strrchr(name, '#');
  if (!last) return false;
  const char *first = last;
  while (first > name && first[-1] == '#') first--;
  *start = (size_t)(first - pattern), *length = (size_t)(last - first) + 1;
  return true;
}

static int hashes_to_printf(const char *in, char *out, size_t out_size) {
  size_t at, n;
  if (!vdb_pattern_hash_run(in, &at, &n)) return 0;
  const char *h = in + at;
  size_t used = 0;
  for (const char *p = in; *p && used + 2 < out_size; p++) {
    if (p == h) {
      int w = snprintf(out + used, out_size - used, "%%0%zud", n);
      if (w < 0 || (size_t)w >= out_size - used) return 0;
      used += (size_t)w;
      p += n - 1;
      continue;
    }
    if (*p == '%') out[used++] = '%';
    out[used++] = *p;
  }
  if (used + 2 >= out_size) return 0;
  out[used] = '\0';
  return 1;
}

/* 0, 1 (out of memory), 2 (push's), or 3: a name without digits among numbered ones (kept
 * in list->unnumbered): numbered by its place it became a frame of the sequence
 * (fog_preview.vdb beside fog_0000 and fog_0001 played as frame 2). Names are numbered by
 * place only where none has digits. */
static int add_glob(entry_list *list, const char *pattern, int *matched) {
  glob_t g;
  int status = glob(pattern, 0, NULL, &g);
  if (status == GLOB_NOMATCH) return 0;
  if (status != 0) return 1;
  size_t numbered = 0, first_unnumbered = g.gl_pathc;
  for (size_t i = 0; i < g.gl_pathc; i++) {
    if (frame_of(g.gl_pathv[i], NULL, NULL) >= 0) numbered++;
    else if (first_unnumbered == g.gl_pathc) first_unnumbered = i;
  }
  if (numbered > 0 && first_unnumbered < g.gl_pathc) {
    snprintf(list->unnumbered, sizeof list->unnumbered, "%s", g.gl_pathv[first_unnumbered]);
    globfree(&g);
    return 3;
  }
  for (size_t i = 0; i < g.gl_pathc; i++) {
    long f = frame_of(g.gl_pathv[i], NULL, NULL);
    const int pushed = push(list, f < 0 ? list->count : f, g.gl_pathv[i]);
    if (pushed) {
      globfree(&g);
      return pushed;
    }
    (*matched)++;
  }
  globfree(&g);
  return 0;
}

static int add_pattern(entry_list *list, const char *pattern, int first, int last,
                       int *matched) {
  int s, e;
  if (!find_conversion(pattern, &s, &e)) return 1;
  char path[4096];
  if (last >= 0 && first >= 0) {
    /* A closed range: try every frame (missing ones are found later). */
    for (int64_t f = first; f <= last; f++) {
      snprintf(path, sizeof path, pattern, (int)f);
      if (access(path, F_OK) == 0) {
        if (push(list, (int)f, path)) return 1;
        (*matched)++;
      }
    }
    return 0;
  }
  /* Open range: glob the digits, then keep the names the pattern reproduces. */
  char globbed[4096];
  /* where a matching name's digits start: the name's characters before them, which the
   * glob's escapes and the pattern's "%%" do not count one for one */
  size_t used = 0, digits_at = 0, name_at = 0;
  for (int i = 0; pattern[i] && used + 8 < sizeof globbed; i++) {
    if (i == s) {
      digits_at = name_at;
      memcpy(globbed + used, "[0-9]*", 6);
      used += 6;
      i = e - 1;
      continue;
    }
    if (strchr("*?[\\", pattern[i])) globbed[used++] = '\\'; /* a folder "take[1]" is itself */
    globbed[used++] = pattern[i];
    name_at++;
    if (pattern[i] == '%') i++; /* "%%" names one '%' */
  }
  globbed[used] = '\0';
  glob_t g;
  int status = glob(globbed, 0, NULL, &g);
  if (status == GLOB_NOMATCH) return 0;
  if (status != 0) return 1;
  for (size_t i = 0; i < g.gl_pathc; i++) {
    const char *name = g.gl_pathv[i];
    /* a glob character before the digits ("*_%04d.vdb") moves them: such a pattern never
     * reproduces a name (below), and the offset may even lie past the name's end */
    if (digits_at > strlen(name)) continue;
    long f = strtol(name + digits_at, NULL, 10);
    snprintf(path, sizeof path, pattern, (int)f);
    if (strcmp(path, name) != 0) continue;
    if (push(list, (int)f, name)) {
      globfree(&g);
      return 1;
    }
    (*matched)++;
  }
  globfree(&g);
  return 0;
}

int vdb_sequence_find(const char *const *inputs, int input_count, int first, int last,
                      vdb_sequence *out, fog_error *err) {
  *out = (vdb_sequence){0};
  entry_list list = {.last = last};
  if (first >= 0 && last >= 0 && (int64_t)last - first + 1 > max_span) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "frames %d..%d: more than %d frames", first, last,
             max_span);
    return 1;
  }
  for (int n = 0; n < input_count; n++) {
    const char *in = inputs[n];
    char pattern[4096];
    int matched = 0, status = 0, s, e;
    struct stat st;
    /* A path that exists is itself, even where its name holds '#', '%' or '*' (a folder
     * "take#2"); only a path that does not is read as a pattern. */
    const bool exists = stat(in, &st) == 0;
    if (exists && S_ISDIR(st.st_mode)) {
      /* the folder's name as it is: glob's own characters in it ("take[1]") escaped */
      size_t used = 0;
      for (const char *c = in; *c && used + 8 < sizeof pattern; c++) {
        if (strchr("*?[\\", *c)) pattern[used++] = '\\';
        pattern[used++] = *c;
      }
      snprintf(pattern + used, sizeof pattern - used, "/*.vdb");
      status = add_glob(&list, pattern, &matched);
    } else if (exists) {
      long f = frame_of(in, NULL, NULL);
      status = push(&list, f < 0 ? list.count : f, in);
      matched = 1;
    } else if (hashes_to_printf(in, pattern, sizeof pattern)) {
      status = add_pattern(&list, pattern, first, last, &matched);
    } else if (find_conversion(in, &s, &e)) {
      status = add_pattern(&list, in, first, last, &matched);
    } else if (strpbrk(in, "*?[")) {
      /* Wildcards in the file name only: one folder listed. In folder components they made
       * glob walk whole trees ("/ * / * / *" took minutes; found by the config fuzzer). */
      const char *slash = strrchr(in, '/');
      if (slash && strcspn(in, "*?[") < (size_t)(slash - in)) {
        fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                 "%s: wildcards go in the file name only (e.g. bake/fluid_*.vdb), not in "
                 "folder names",
                 in);
        goto fail;
      }
      status = add_glob(&list, in, &matched);
    } else {
      fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: no such file or directory", in);
      goto fail;
    }
    if (status == 2) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: its frame number is past %d", list.too_large,
               INT_MAX);
      goto fail;
    }
    if (status == 3) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
               "%s: no frame number in its name, beside numbered files in %s (a frame is the "
               "last run of digits in a name): move it out or number it",
               list.unnumbered, in);
      goto fail;
    }
    if (status) {
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: cannot list (out of memory?)", in);
      goto fail;
    }
    if (!matched) {
      if (last >= 0)
        fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: no files for frames %d..%d", in, first, last);
      else
        fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: no files match", in);
      goto fail;
    }
  }
  qsort(list.items, (size_t)list.count, sizeof *list.items, by_frame);
  /* Keep the range; drop a later duplicate of the same file (sorted by frame, then path,
   * so copies are neighbours; "d//f.vdb" and "./d/f.vdb" are one file too). Two files of
   * one frame number are an error: one would silently stand for both. A name without
   * digits is numbered by its place in the list, which can be a numbered file's frame:
   * that message says so. */
  int kept = 0;
  for (int i = 0; i < list.count; i++) {
    entry it = list.items[i];
    int in_range = (first < 0 || it.frame >= first) && (last < 0 || it.frame <= last);
    const entry *previous = kept > 0 ? &list.items[kept - 1] : NULL;
    int duplicate = previous && previous->frame == it.frame && same_file(previous->path, it.path);
    if (in_range && !duplicate && previous && previous->frame == it.frame) {
      const bool numbered = frame_of(previous->path, NULL, NULL) >= 0 &&
                            frame_of(it.path, NULL, NULL) >= 0;
      if (numbered)
        fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                 "frame %d twice: %s and %s (one file a frame number)", it.frame,
                 previous->path, it.path);
      else
        fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                 "frame %d twice: %s and %s (a name without digits takes its place in the "
                 "list as its frame: number every file, or import them apart)", it.frame,
                 previous->path, it.path);
      for (int j = i; j < list.count; j++) free(list.items[j].path);
      list.count = kept;
      goto fail;
    }
    if (in_range && !duplicate)
      list.items[kept++] = it;
    else
      free(it.path);
  }
  list.count = kept;
  if (kept == 0) {
    fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: no frames in the range %d..%d",
             input_count ? inputs[0] : "(no input)", first, last);
    goto fail;
  }
  out->count = kept;
  out->frames = malloc((size_t)kept * sizeof(int));
  out->paths = malloc((size_t)kept * sizeof(char *));
  const int64_t lo = first >= 0 ? first : list.items[0].frame;
  const int64_t hi = last >= 0 ? last : list.items[kept - 1].frame;
  if (hi - lo + 1 > max_span) {
    fog_fail(err, FOG_ERR_BAD_FILE,
             "%s: frame numbers %" PRId64 " to %" PRId64
             " span more than %d frames (a pattern "
             "or folder matching unrelated files?)",
             input_count ? inputs[0] : "(no input)", lo, hi, max_span);
    goto fail;
  }
  out->missing = malloc((size_t)(hi - lo + 1 > 0 ? hi - lo + 1 : 1) * sizeof(int));
  if (!out->frames || !out->paths || !out->missing) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory listing %d frames", kept);
    goto fail;
  }
  for (int i = 0; i < kept; i++) {
    out->frames[i] = list.items[i].frame;
    out->paths[i] = list.items[i].path;
  }
  int i = 0;
  for (int64_t f = lo; f <= hi; f++) {
    while (i < kept && out->frames[i] < f) i++;
    if (i >= kept || out->frames[i] != f) out->missing[out->missing_count++] = (int)f;
  }
  free(list.items);
  return 0;
fail:
  for (int i = 0; i < list.count; i++) free(list.items[i].path);
  free(list.items);
  free(out->frames);
  free(out->paths);
  free(out->missing);
  *out = (vdb_sequence){0};
  return 1;
}

void vdb_sequence_destroy(vdb_sequence *sequence) {
  for (int i = 0; i < sequence->count; i++) free(sequence->paths[i]);
  free(sequence->paths);
  free(sequence->frames);
  free(sequence->missing);
  *sequence = (vdb_sequence){0};
}

int vdb_config_path_beside(const char *vdb_path, char *out, size_t out_size) {
  int ds = 0, dl = 0;
  if (frame_of(vdb_path, &ds, &dl) < 0) return 1;
  const char *slash = strrchr(vdb_path, '/');
  int dir_len = slash ? (int)(slash - vdb_path) : 0;
  int w = snprintf(out, out_size, "%.*s%s../config/config_%.*s.uni", dir_len, vdb_path,
                   dir_len ? "/" : "", dl, vdb_path + ds);
  if (w <= 0 || (size_t)w >= out_size) return 1;
  return access(out, R_OK) == 0 ? 0 : 1;
}

int vdb_sequence_check_placement(const vdb_sequence *seq, fog_error *err) {
  char first_config[4096], config[4096];
  const bool first = seq->count > 0 &&
                     !vdb_config_path_beside(seq->paths[0], first_config, sizeof first_config);
  for (int i = 1; i < seq->count; i++) {
    const bool has = !vdb_config_path_beside(seq->paths[i], config, sizeof config);
    if (has == first) continue;
    const int with = has ? i : 0, without = has ? 0 : i;
    return fog_fail(err, FOG_ERR_BAD_FILE,
                    "frame %d: %.300s has no Mantaflow config beside it, but frame %d's "
                    "%.300s has (%.300s): the frames would be placed two ways; give every "
                    "frame its config",
                    seq->frames[without], seq->paths[without], seq->frames[with],
                    seq->paths[with], has ? config : first_config);
  }
  return 0;
}

int vdb_sequence_check_gaps(const vdb_sequence *seq, const char *pattern, fog_error *err) {
  if (!seq->missing_count) return 0;
  return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                  "%.300s: %d frame%s missing inside %d..%d (the first: %d)", pattern,
                  seq->missing_count, seq->missing_count == 1 ? "" : "s", seq->frames[0],
                  seq->frames[seq->count - 1], seq->missing[0]);
}
