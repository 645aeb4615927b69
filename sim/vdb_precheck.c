/* vdb_precheck_file: a cheap structural check of an OpenVDB file, in plain C, before
 * OpenVDB opens it.
 *
 * Why: OpenVDB 10 trusts every length and count in a file. io::File::open reads strings
 * (util/Name.h readString: std::string(size, ' ') of a uint32 size from the file),
 * metadata values and counts, and allocates and fills them before it could notice that
 * the file is far shorter: one flipped bit in a 50 KB bake made it take 6-19 GB and up to
 * a minute. A count read past the end of the stream is worse still: the read fails, the
 * variable keeps whatever it held, and the loop goes on.
 *
 * This walks the same bytes in the same order as OpenVDB 10 reads them (each step names
 * the OpenVDB function it mirrors), checks every length, count and offset against the
 * bytes actually there, and fails with a message saying what is wrong. For the trees of
 * plain value types (float, double, int32/64, vec3i/s/d) it also walks every node: masks,
 * the mask-compression flags and the size of each zip or blosc chunk, which OpenVDB
 * allocates as read (fuzzing found 16 TB requests, a raw chunk longer than its buffer
 * overflowing it, a blosc header trusted past its chunk; tests/fuzz/regressions/vdb/). It
 * reads masks and chunk headers only (pread through a 16 KB window; the compressed bytes
 * are skipped, never decoded): about 0.5 ms for a Blender bake frame of 50-90 KB. Bool,
 * mask and point grids and, in io::Stream files without grid offsets, the grids after
 * such a grid keep the header checks only; files of a format before 222 (OpenVDB 3.0)
 * are refused. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <blosc.h>
#include <zlib.h>

#include "sim/image_io.h"
#include "sim/vdb_import.h"

/* openvdb/version.h */
#define VDB_MAGIC 0x56444220u
#define VERSION_GRID_INSTANCING 216
#define VERSION_BOOST_UUID 218
#define VERSION_SELECTIVE_COMPRESSION 220
#define VERSION_FLOAT_FRUSTUM_BBOX 221
#define VERSION_NODE_MASK_COMPRESSION 222

typedef struct vdb_in {
  int fd;
  const char *path;
  fog_error *err;
  uint64_t size;        /* of the file */
  uint64_t pos;         /* the stream position OpenVDB would be at */
  uint64_t end;         /* reads must end by here: the file's end or the current block's */
  const char *within;   /* what ends at `end`, for messages: "the file", ... */
  char section[160];    /* "header" or "grid 'density'", for messages */
  /* The bytes at [cache_pos, cache_pos + cache_len): a tree is read in thousands of small
   * pieces (masks, chunk sizes). */
  unsigned char cache[16384];
  uint64_t cache_pos;
  size_t cache_len;
} vdb_in;

static int damaged(vdb_in *in, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static int damaged(vdb_in *in, const char *format, ...) {
  char detail[400];
  va_list args;
  va_start(args, format);
  vsnprintf(detail, sizeof detail, format, args);
  va_end(args);
  return fog_fail(in->err, FOG_ERR_BAD_FILE, "%s: cannot read: damaged OpenVDB %s: %s", in->path,
                  in->section, detail);
}

/* n more bytes must lie before in->end; what describes them ("the grid count (4 bytes)"). */
static int need(vdb_in *in, uint64_t n, const char *what) {
  const uint64_t left = in->end > in->pos ? in->end - in->pos : 0;
  if (n <= left) return 0;
  return damaged(in, "%s exceeds the %" PRIu64 " bytes left in %s (at byte %" PRIu64
                 " of the file's %" PRIu64 ")", what, left, in->within, in->pos, in->size);
}

static int skip(vdb_in *in, uint64_t n, const char *what) {
  if (need(in, n, what)) return 1;
  in->pos += n;
  return 0;
}

static int get(vdb_in *in, void *dst, size_t n, const char *what) {
  if (need(in, n, what)) return 1;
  if (in->pos < in->cache_pos || in->pos + n > in->cache_pos + in->cache_len) {
    ssize_t got;
    if (n > sizeof in->cache) {
      got = pread(in->fd, dst, n, (off_t)in->pos);
    } else {
      got = pread(in->fd, in->cache, sizeof in->cache, (off_t)in->pos);
      in->cache_pos = in->pos;
      in->cache_len = got > 0 ? (size_t)got : 0;
    }
    if (got < (ssize_t)n)
      return fog_fail(in->err, FOG_ERR_FILE_ACCESS, "%s: cannot read: %s", in->path,
                      got < 0 ? strerror(errno) : "the file shrank while being read");
    if (n > sizeof in->cache) {
      in->pos += n;
      return 0;
    }
  }
  memcpy(dst, in->cache + (in->pos - in->cache_pos), n);
  in->pos += n;
  return 0;
}

/* OpenVDB writes host-endian; every platform it ships on is little-endian. */
static uint64_t le(const unsigned char *b, int n) {
  uint64_t v = 0;
  for (int i = n - 1; i >= 0; i--) v = v << 8 | b[i];
  return v;
}

static int get_u32(vdb_in *in, uint32_t *v, const char *what) {
  unsigned char b[4];
  if (get(in, b, 4, what)) return 1;
  *v = (uint32_t)le(b, 4);
  return 0;
}

static int get_i64(vdb_in *in, int64_t *v, const char *what) {
  unsigned char b[8];
  if (get(in, b, 8, what)) return 1;
  *v = (int64_t)le(b, 8);
  return 0;
}

/* Non-printable bytes (damage, or the grid name's "\x1e" suffix separator) as '?'. */
static void printable(char *s) {
  for (; *s; s++)
    if ((unsigned char)*s < 0x20 || (unsigned char)*s > 0x7e) *s = '?';
}

/* util/Name.h readString: a uint32 length, then the bytes. Keeps the first cap-1 bytes in
 * out (NUL-terminated) and the true length in *len, so "float\0" is not "float". */
static int get_string(vdb_in *in, char *out, size_t cap, uint32_t *len, const char *what) {
  char phrase[224];
  snprintf(phrase, sizeof phrase, "%s length (4 bytes)", what);
  if (get_u32(in, len, phrase)) return 1;
  snprintf(phrase, sizeof phrase, "%s length %" PRIu32, what, *len);
  if (need(in, *len, phrase)) return 1;
  const size_t keep = *len < cap ? *len : cap - 1;
  if (get(in, out, keep, what)) return 1;
  out[keep] = '\0';
  in->pos += *len - keep;
  return 0;
}

static int same_name(const char *s, uint32_t len, const char *name) {
  return len == strlen(name) && !strcmp(s, name);
}

/* The UUID as boost::uuids' operator>> reads it (Archive::readHeader's `is >> mUuid`):
 * 32 hex digits with '-' after the 4th, 6th, 8th and 10th byte, whitespace skipped before
 * each character. On anything else the stream fails and OpenVDB silently sees no grids. */
static int read_uuid(vdb_in *in) {
  const uint64_t start = in->pos;
  for (int i = 0; i < 16; i++)
    for (int k = 0; k < (i == 3 || i == 5 || i == 7 || i == 9 ? 3 : 2); k++) {
      unsigned char c = 0;
      do {
        if (get(in, &c, 1, "the UUID (36 characters)")) return 1;
      } while (c == ' ' || (c >= '\t' && c <= '\r'));
      const int hex = (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
      if (k < 2 ? !hex : c != '-')
        return damaged(in, "the UUID at byte %" PRIu64 " is not 32 hex digits and 4 hyphens "
                       "(byte %" PRIu64 " is 0x%02x)", start, in->pos - 1, c);
    }
  return 0;
}

/* io::Archive::readHeader. */
static int read_header(vdb_in *in, uint32_t *version, int *has_offsets) {
  unsigned char magic[8];
  if (get(in, magic, 8, "the magic number (8 bytes)")) return 1;
  if (le(magic, 8) != VDB_MAGIC)
    return damaged(in, "the magic number is 0x%016" PRIx64 ", not 0x%016" PRIx64,
                   le(magic, 8), (uint64_t)VDB_MAGIC);
  uint32_t v, n;
  if (get_u32(in, &v, "the file format version (4 bytes)")) return 1;
  /* newer than OpenVDB 10 (224): OpenVDB only warns and reads it as its own */
  if (v < 211) {  /* separate major, minor, patch numbers (uint32 arithmetic, as OpenVDB) */
    if (get_u32(in, &n, "the file format minor version (4 bytes)")) return 1;
    v = 100 * v + 10 * n;
    if (get_u32(in, &n, "the file format patch version (4 bytes)")) return 1;
    v += n;
  }
  /* Older formats (OpenVDB before 3.0, 2014) store transforms, topology and values in
   * other layouts, each with lengths OpenVDB trusts (fuzzing flipped the version of a
   * current file to 218 and OpenVDB read a 1.8 GB transform name): refused, not checked. */
  if (v < VERSION_NODE_MASK_COMPRESSION)
    return fog_fail(in->err, FOG_ERR_BAD_FILE,
                    "%s: cannot read: OpenVDB file format %" PRIu32
                    " is older than "
                    "222 (OpenVDB 3.0, 2014), the oldest fogpipe checks before OpenVDB reads "
                    "it; re-save the file with a current OpenVDB (or it is damaged)",
                    in->path, v);
  if (v >= 211 && skip(in, 8, "the library version (8 bytes)")) return 1;
  *has_offsets = 1;
  if (v >= 212) {
    unsigned char flag = 0;
    if (get(in, &flag, 1, "the grid offsets flag (1 byte)")) return 1;
    *has_offsets = flag != 0;
  }
  if (v >= VERSION_SELECTIVE_COMPRESSION && v < VERSION_NODE_MASK_COMPRESSION &&
      skip(in, 1, "the compression flag (1 byte)"))
    return 1;
  *version = v;
  if (v >= VERSION_BOOST_UUID) return read_uuid(in);
  return skip(in, 16, "the UUID (16 bytes)");
}

/* A blosc chunk (io::DelayedLoadMetadata::readValue): OpenVDB reserves the uncompressed
 * size that the chunk's 16-byte header claims (bytes 4-7), so that must be no more than
 * the table it holds, or 128 bytes (compression::bloscCompress pads smaller tables). */
static int check_blosc(vdb_in *in, uint32_t bytes, uint64_t table_bytes, const char *what) {
  char phrase[224];
  if (table_bytes < 128) table_bytes = 128;
  if (bytes < 16)
    return damaged(in, "%s is a %" PRIu32 "-byte blosc chunk, shorter than its header", what,
                   bytes);
  snprintf(phrase, sizeof phrase, "%s's blosc chunk of %" PRIu32 " bytes", what, bytes);
  if (need(in, bytes, phrase)) return 1;
  unsigned char header[16];
  const uint64_t chunk = in->pos;
  if (get(in, header, 16, phrase)) return 1;
  if (le(header + 4, 4) > table_bytes)
    return damaged(in, "%s's blosc chunk claims %" PRIu64 " bytes uncompressed, more than "
                   "%" PRIu64, what, le(header + 4, 4), table_bytes);
  /* blosc_decompress is not told the chunk's size: it reads as far as the header says */
  if (le(header + 12, 4) > bytes)
    return damaged(in, "%s's blosc chunk of %" PRIu32 " bytes claims %" PRIu64 " compressed",
                   what, bytes, le(header + 12, 4));
  in->pos = chunk + bytes;
  return 0;
}

/* io::DelayedLoadMetadata::readValue ("__delayedload", Mantaflow writes one per grid):
 * a leaf count, a per-leaf int8 mask table and an optional int64 compressed-size table,
 * each either raw or a blosc chunk; OpenVDB allocates count entries of each. */
static int read_delayed_load(vdb_in *in, uint32_t size, const char *what) {
  if (size == 0) return 0;
  char phrase[224];
  snprintf(phrase, sizeof phrase, "the size %" PRIu32 " of %s", size, what);
  if (need(in, size, phrase)) return 1;
  const uint64_t saved_end = in->end, value_end = in->pos + size;
  const char *saved_within = in->within;
  in->end = value_end;
  in->within = "its metadata value";
  uint32_t count, bytes;
  int bad = get_u32(in, &count, "the delayed-load leaf count (4 bytes)");
  /* every leaf stores at least its 64-byte value mask (LeafNode::readTopology, 8^3 leaves
   * in every registered tree type), so a file holds at most size/64 leaves */
  if (!bad && count > in->size / 64)
    bad = damaged(in, "the leaf count %" PRIu32 " of %s exceeds the %" PRIu64 " leaves the "
                  "file's %" PRIu64 " bytes can hold", count, what, in->size / 64, in->size);
  if (!bad) bad = get_u32(in, &bytes, "the delayed-load mask size (4 bytes)");
  if (!bad) bad = bytes ? check_blosc(in, bytes, count, "the delayed-load mask")
                        : skip(in, count, "the delayed-load mask table");
  if (!bad) bad = get_u32(in, &bytes, "the delayed-load size table's size (4 bytes)");
  if (!bad && bytes != UINT32_MAX)  /* UINT32_MAX: no compressed sizes stored */
    bad = bytes ? check_blosc(in, bytes, 8ull * count, "the delayed-load size table")
                : skip(in, 8ull * count, "the delayed-load size table");
  in->end = saved_end;
  in->within = saved_within;
  in->pos = value_end;  /* OpenVDB skips any bytes it does not know */
  return bad;
}

/* Metadata::read after MetaMap::readMeta found the type: a uint32 size, then the value.
 * The types openvdb::initialize registers read exactly sizeof(T) (TypedMetadata::readValue
 * ignores the size; another size would leave the stream out of step). Strings and
 * unknown types allocate the size and read it. */
static int read_meta_value(vdb_in *in, const char *type, uint32_t type_len, const char *what) {
  static const struct { const char *name; uint32_t bytes; } fixed[] = {
      {"bool", 1},    {"int32", 4},    {"int64", 8},   {"float", 4},   {"double", 8},
      {"vec2i", 8},   {"vec2s", 8},    {"vec2d", 16},  {"vec3i", 12},  {"vec3s", 12},
      {"vec3d", 24},  {"vec4i", 16},   {"vec4s", 16},  {"vec4d", 32},  {"mat4s", 64},
      {"mat4d", 128}, {"ptidx32", 4},  {"ptidx64", 8},
  };
  char phrase[224];
  uint32_t size;
  snprintf(phrase, sizeof phrase, "the size of %s (4 bytes)", what);
  if (get_u32(in, &size, phrase)) return 1;
  for (size_t t = 0; t < sizeof fixed / sizeof fixed[0]; t++)
    if (same_name(type, type_len, fixed[t].name)) {
      if (size != fixed[t].bytes)
        return damaged(in, "%s (%s) has size %" PRIu32 ", not %" PRIu32, what, type, size,
                       fixed[t].bytes);
      if (!strcmp(fixed[t].name, "bool")) { /* read into a bool: 0 or 1 */
        unsigned char b;
        if (get(in, &b, 1, what)) return 1;
        if (b > 1) return damaged(in, "%s (bool) is %u, not 0 or 1", what, b);
        in->pos--;
      }
      snprintf(phrase, sizeof phrase, "the value of %s (%" PRIu32 " bytes)", what, size);
      return skip(in, size, phrase);
    }
  if (same_name(type, type_len, "__delayedload")) return read_delayed_load(in, size, what);
  snprintf(phrase, sizeof phrase, "the size %" PRIu32 " of %s", size, what);
  return skip(in, size, phrase);
}

/* MetaMap::readMeta: a uint32 count, then per item readString (name), readString (type
 * name) and Metadata::read. */
static int read_metamap(vdb_in *in, const char *owner, int *half) {
  char phrase[224];
  uint32_t count;
  snprintf(phrase, sizeof phrase, "the %s count (4 bytes)", owner);
  if (get_u32(in, &count, phrase)) return 1;
  /* every item holds at least three uint32s: name length, type name length, size */
  snprintf(phrase, sizeof phrase, "the %s count %" PRIu32 " (12 bytes or more each)", owner,
           count);
  if (need(in, 12ull * count, phrase)) return 1;
  for (uint32_t i = 0; i < count; i++) {
    char name[64], type[32], what[128];
    uint32_t name_len, type_len;
    snprintf(what, sizeof what, "%s item %" PRIu32 "'s name", owner, i + 1);
    if (get_string(in, name, sizeof name, &name_len, what)) return 1;
    printable(name);
    snprintf(what, sizeof what, "%s '%s' type name", owner, name);
    if (get_string(in, type, sizeof type, &type_len, what)) return 1;
    printable(type);
    snprintf(what, sizeof what, "%s '%s'", owner, name);
    /* GridBase::saveFloatAsHalf: whether the tree's values are stored as 16-bit floats */
    const uint64_t value_at = in->pos + 4;
    if (read_meta_value(in, type, type_len, what)) return 1;
    /* OpenVDB writes it as a bool; read as another type, Metadata::asBool of an unknown
     * type is "has bytes", of a number "non-zero": refused rather than mirrored (fuzzing
     * found a "vec3" here: OpenVDB read halves where this walk expected floats, and
     * leaked a node). */
    if (same_name(name, name_len, "is_saved_as_half_float") && !same_name(type, type_len, "bool"))
      return damaged(in, "%s has type '%s', not bool", what, type);
    if (half && same_name(name, name_len, "is_saved_as_half_float")) {
      const uint64_t after = in->pos;
      unsigned char b;
      in->pos = value_at;
      if (get(in, &b, 1, what)) return 1;
      in->pos = after;
      *half = b != 0;
    }
  }
  return 0;
}

/* math::Transform::read: readString (the map's type name), then MapBase::read of that
 * map (math/Maps.h), each a fixed number of Vec3d/Mat4d except the frustum, which holds
 * a second map. (Files before format 219 stored old transforms; read_header refuses them.) */
static int read_map(vdb_in *in, uint32_t version, int depth) {
  static const struct { const char *name; uint32_t bytes; } maps[] = {
      {"AffineMap", 128},          {"UnitaryMap", 128},        /* a Mat4d */
      {"ScaleMap", 120},           {"UniformScaleMap", 120},   /* 5 Vec3d */
      {"ScaleTranslateMap", 144},  {"UniformScaleTranslateMap", 144},  /* 6 Vec3d */
      {"TranslationMap", 24},
  };
  char type[40], phrase[96];
  uint32_t len;
  if (get_string(in, type, sizeof type, &len,
                 depth ? "the frustum's second map type name" : "the transform type name"))
    return 1;
  printable(type);
  for (size_t m = 0; m < sizeof maps / sizeof maps[0]; m++)
    if (same_name(type, len, maps[m].name)) {
      snprintf(phrase, sizeof phrase, "the %s (%" PRIu32 " bytes)", type, maps[m].bytes);
      return skip(in, maps[m].bytes, phrase);
    }
  if (same_name(type, len, "NonlinearFrustumMap") && depth < 4) {
    /* NonlinearFrustumMap::read: a BBoxd (a CoordBBox before 221), taper, depth */
    if (skip(in, (version >= VERSION_FLOAT_FRUSTUM_BBOX ? 48 : 24) + 16,
             "the frustum map (64 bytes)"))
      return 1;
    return read_map(in, version, depth + 1);
  }
  return damaged(in, "unknown transform type '%s' (%" PRIu32 " bytes)", type, len);
}

/* A tree type as its name says ("Tree_float_5_4_3"): the value type's size in the file,
 * in full and as a 16-bit float (0: not a floating-point type, never stored as half), and
 * the log2 sizes of its nodes below the root (levels = 3: two internal nodes, the leaf).
 * walk: 1 for the value types whose nodes are plain LeafNode/InternalNode (bool, mask and
 * point grids store their leaves differently: their trees are not walked). Unknown types
 * get the smallest sizes (OpenVDB refuses to read unregistered grid types anyway). */
typedef struct tree_type {
  uint64_t value_bytes, half_bytes;
  int levels, log2[3];
  int walk;
} tree_type;

static tree_type tree_layout(const char *type) {
  static const struct { const char *name; uint32_t bytes, half_bytes; int walk; } values[] = {
      {"bool", 1, 0, 0},        {"mask", 1, 0, 0},       {"float", 4, 2, 1},
      {"double", 8, 2, 1},      {"int32", 4, 0, 1},      {"int64", 8, 0, 1},
      {"vec3i", 12, 0, 1},      {"vec3s", 12, 6, 1},     {"vec3d", 24, 6, 1},
      {"ptidx32", 4, 0, 0},     {"ptidx64", 8, 0, 0},    {"ptdataidx32", 4, 0, 0},
      {"ptdataidx64", 8, 0, 0},
  };
  tree_type t = {.value_bytes = 1};
  if (strncmp(type, "Tree_", 5) != 0) return t;
  const char *v = type + 5, *u = strchr(v, '_');
  if (!u) return t;
  for (size_t k = 0; k < sizeof values / sizeof values[0]; k++)
    if (strlen(values[k].name) == (size_t)(u - v) && !strncmp(v, values[k].name, u - v)) {
      t.value_bytes = values[k].bytes;
      t.half_bytes = values[k].half_bytes;
      t.walk = values[k].walk;
    }
  for (const char *p = u; *p == '_' && t.levels < 3;) {
    char *next;
    const long log2 = strtol(p + 1, &next, 10);
    if (next == p + 1 || log2 < 1 || log2 > 10) break;
    t.log2[t.levels++] = (int)log2;
    p = next;
  }
  if (t.levels < 1) t.log2[0] = 0;
  /* Walked: exactly root, internal, internal, leaf ("_5_4_3"), nodes of 2^6 to 2^18
   * values, nothing after the numbers. */
  int walk = t.walk && t.levels == 3;
  for (int l = 0; l < 3 && walk; l++) walk = t.log2[l] >= 2 && t.log2[l] <= 6;
  if (walk) {
    const char *p = u;
    for (int l = 0; l < 3; l++) {
      char *next;
      (void)strtol(p + 1, &next, 10);
      p = next;
    }
    walk = *p == '\0';
  }
  t.walk = walk;
  return t;
}

/* The least bytes a root child takes in the file: its Coord (12 bytes) and an InternalNode
 * whose readTopology starts with two masks of 2^(3*log2) bits. */
static uint64_t root_child_bytes(const tree_type *t) {
  return t->levels >= 1 && t->log2[0] >= 1 ? 12 + 2 * ((1ull << (3 * t->log2[0])) / 8) : 12;
}

/* A walk of one tree's nodes, as Tree::readTopology and Tree::readBuffers read them. */
typedef struct root_child {
  int32_t origin[3];
  size_t first_leaf, leaf_count; /* its leaves, in walk.leaf_on */
  size_t order;                  /* in the file */
} root_child;

typedef struct tree_walk {
  tree_type type;
  int half;                      /* GridBase::saveFloatAsHalf */
  uint32_t compression;          /* io::readGridCompression: ZIP 1, ACTIVE_MASK 2, BLOSC 4 */
  unsigned char *child_mask[2];  /* the internal nodes being read, per level */
  unsigned char *value_mask;
  unsigned char *leaf_masks;     /* each leaf's value mask, in the order read */
  size_t leaves, leaf_capacity;
  root_child *children;
  size_t child_count;
} tree_walk;

enum { COMPRESS_ZIP = 1, COMPRESS_ACTIVE_MASK = 2, COMPRESS_BLOSC = 4 };

static uint64_t mask_bytes(int log2) { return (1ull << (3 * log2)) / 8; }

static uint32_t count_on(const unsigned char *mask, uint64_t bytes) {
  uint32_t n = 0;
  for (uint64_t i = 0; i < bytes; i++) n += (uint32_t)__builtin_popcount(mask[i]);
  return n;
}

/* A topology chunk of `size` compressed bytes, at in->pos, decoded as OpenVDB decodes it:
 * unzipFromStream (zlib's uncompress) and bloscDecompress (blosc_decompress_ctx) throw
 * unless the chunk gives exactly `bytes` bytes, and RootNode::readTopology then loses the
 * internal node it was reading (~0.5 MB per damaged file; tests/fuzz/lsan.supp), so such a
 * chunk is refused here. OpenVDB never writes a chunk longer than the compressor's bound
 * (it stores the bytes raw instead), which bounds the memory this takes. */
static int decode_chunk(vdb_in *in, int blosc, uint64_t size, uint64_t bytes, const char *what) {
  const uint64_t bound = blosc ? bytes + BLOSC_MAX_OVERHEAD : compressBound((uLong)bytes);
  const char *kind = blosc ? "blosc" : "zip";
  if (size > bound)
    return damaged(in, "the %s chunk of %s is %" PRIu64 " bytes, more than %s's bound of %"
                   PRIu64 " for %" PRIu64 " bytes (at byte %" PRIu64 ")", kind, what, size,
                   kind, bound, bytes, in->pos - 8);
  unsigned char *packed = malloc(size ? size : 1), *unpacked = malloc(bytes ? bytes : 1);
  if (!packed || !unpacked) {
    free(packed);
    free(unpacked);
    return fog_fail(in->err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory checking the file",
                    in->path);
  }
  const uint64_t chunk = in->pos;
  char phrase[384]; /* the longest `what` (223 bytes) and the words around it */
  snprintf(phrase, sizeof phrase, "the %s chunk of %" PRIu64 " bytes of %s", kind, size, what);
  int bad = get(in, packed, size, phrase);
  long long got = -1;
  if (!bad && blosc) {
    got = blosc_decompress_ctx(packed, unpacked, bytes, 1);
  } else if (!bad) {
    uLongf length = (uLongf)bytes;
    got = uncompress(unpacked, &length, packed, (uLong)size) == Z_OK ? (long long)length : -1;
  }
  if (!bad && got < 0)
    bad = damaged(in, "the %s chunk of %" PRIu64 " bytes of %s (at byte %" PRIu64 ") does "
                  "not decode to the %" PRIu64 " bytes expected", kind, size, what, chunk - 8,
                  bytes);
  else if (!bad && got != (long long)bytes)
    bad = damaged(in, "the %s chunk of %" PRIu64 " bytes of %s (at byte %" PRIu64 ") decodes "
                  "to %lld bytes where %" PRIu64 " are expected", kind, size, what, chunk - 8,
                  got, bytes);
  free(packed);
  free(unpacked);
  return bad;
}

/* io::readData's chunk (io/Compression.h) of `bytes` bytes as `compression` stores it:
 * blosc or zip (bloscFromStream, unzipFromStream: an int64 size, then that many bytes,
 * which OpenVDB allocates first; <= 0: -size raw bytes, which must be exactly `bytes`),
 * or raw. A blosc chunk's 16-byte header must claim `bytes` uncompressed and at most the
 * chunk's own size compressed: blosc_decompress_ctx is not told the chunk's size and
 * trusts the header. With `decode` (the topology's chunks) the chunk is decoded too. */
static int read_chunk(vdb_in *in, uint32_t compression, uint64_t bytes, int decode,
                      const char *what) {
  char phrase[384]; /* the longest `what` (223 bytes) and the words around it */
  if (!(compression & (COMPRESS_BLOSC | COMPRESS_ZIP))) {
    snprintf(phrase, sizeof phrase, "%s (%" PRIu64 " bytes)", what, bytes);
    return skip(in, bytes, phrase);
  }
  const char *kind = compression & COMPRESS_BLOSC ? "blosc" : "zip";
  int64_t size;
  snprintf(phrase, sizeof phrase, "the size of the %s chunk of %s (8 bytes)", kind, what);
  if (get_i64(in, &size, phrase)) return 1;
  if (size <= 0) {
    const uint64_t raw = (uint64_t)0 - (uint64_t)size;
    if (raw != bytes)
      return damaged(in, "%s are a raw chunk of %" PRIu64 " bytes where %" PRIu64 " are "
                     "expected (at byte %" PRIu64 ")", what, raw, bytes, in->pos - 8);
    snprintf(phrase, sizeof phrase, "%s (a raw chunk of %" PRIu64 " bytes)", what, raw);
    return skip(in, raw, phrase);
  }
  snprintf(phrase, sizeof phrase, "the %s chunk of %" PRId64 " bytes of %s", kind, size, what);
  if (need(in, (uint64_t)size, phrase)) return 1;
  if (compression & COMPRESS_BLOSC) {
    const uint64_t chunk = in->pos;
    unsigned char header[16];
    if (size < 16)
      return damaged(in, "%s are a %" PRId64 "-byte blosc chunk, shorter than its header", what,
                     size);
    if (get(in, header, 16, phrase)) return 1;
    if (le(header + 4, 4) != bytes || le(header + 12, 4) > (uint64_t)size)
      return damaged(in, "the blosc chunk of %" PRId64 " bytes of %s (at byte %" PRIu64 ") "
                     "claims %" PRIu64 " bytes compressed and %" PRIu64 " uncompressed; "
                     "expected at most %" PRId64 " and exactly %" PRIu64, size, what, chunk - 8,
                     le(header + 12, 4), le(header + 4, 4), size, bytes);
    in->pos = chunk;
  }
  if (decode) return decode_chunk(in, compression & COMPRESS_BLOSC, (uint64_t)size, bytes, what);
  in->pos += (uint64_t)size;
  return 0;
}

/* io::readCompressedValues: a node's values (count of them, active of which are on):
 * the mask-compression flag byte, up to two inactive values, a selection mask, then the
 * values (only the active ones when the grid is mask-compressed and the flag says so), as
 * 16-bit floats when the grid saves floats as half (HalfReader: nothing at all for no
 * values). */
static int read_values(vdb_in *in, const tree_walk *w, uint64_t count, uint32_t active,
                       uint64_t selection_bytes, int decode, const char *what) {
  char phrase[224];
  unsigned char flag;
  snprintf(phrase, sizeof phrase, "%s's compression flag (1 byte)", what);
  if (get(in, &flag, 1, phrase)) return 1;
  const int8_t metadata = (int8_t)flag;
  /* NO_MASK_AND_ONE_INACTIVE_VAL, MASK_AND_ONE_INACTIVE_VAL, MASK_AND_TWO_INACTIVE_VALS */
  const int inactive = metadata == 2 || metadata == 4 ? 1 : metadata == 5 ? 2 : 0;
  snprintf(phrase, sizeof phrase, "%s's inactive values (%d x %" PRIu64 " bytes)", what, inactive,
           w->type.value_bytes);
  if (skip(in, inactive * w->type.value_bytes, phrase)) return 1;
  if (metadata == 3 || metadata == 4 || metadata == 5) {
    snprintf(phrase, sizeof phrase, "%s's selection mask (%" PRIu64 " bytes)", what,
             selection_bytes);
    if (skip(in, selection_bytes, phrase)) return 1;
  }
  if ((w->compression & COMPRESS_ACTIVE_MASK) && metadata != 6 /* NO_MASK_AND_ALL_VALS */)
    count = active;
  const int as_half = w->half && w->type.half_bytes;
  if (as_half && count < 1) return 0;
  snprintf(phrase, sizeof phrase, "the %" PRIu64 " values of %s", count, what);
  return read_chunk(in, w->compression,
                    count * (as_half ? w->type.half_bytes : w->type.value_bytes), decode, phrase);
}

/* InternalNode::readTopology (level 0: the root's children, 1: theirs): child mask, value
 * mask, every value (readCompressedValues), then each child's topology in mask order; a
 * LeafNode::readTopology is its value mask. */
static int read_internal(vdb_in *in, tree_walk *w, int level) {
  const uint64_t bytes = mask_bytes(w->type.log2[level]);
  char what[96];
  snprintf(what, sizeof what, "a level-%d internal node", 2 - level);
  char phrase[160];
  snprintf(phrase, sizeof phrase, "%s's child mask (%" PRIu64 " bytes)", what, bytes);
  if (get(in, w->child_mask[level], bytes, phrase)) return 1;
  snprintf(phrase, sizeof phrase, "%s's value mask (%" PRIu64 " bytes)", what, bytes);
  if (get(in, w->value_mask, bytes, phrase)) return 1;
  const uint32_t active = count_on(w->value_mask, bytes);
  if (read_values(in, w, 8 * bytes, active, bytes, 1, what)) return 1;
  const unsigned char *children = w->child_mask[level];
  const uint64_t leaf_bytes = mask_bytes(w->type.log2[2]);
  for (uint64_t i = 0; i < 8 * bytes; i++) {
    if (!(children[i / 8] >> (i % 8) & 1)) continue;
    if (level == 0) {
      if (read_internal(in, w, 1)) return 1;
      continue;
    }
    if (w->leaves == w->leaf_capacity) {
      const size_t capacity = w->leaf_capacity ? 2 * w->leaf_capacity : 1024;
      unsigned char *grown = realloc(w->leaf_masks, capacity * leaf_bytes);
      if (!grown)
        return fog_fail(in->err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory checking the file",
                        in->path);
      w->leaf_masks = grown;
      w->leaf_capacity = capacity;
    }
    if (get(in, w->leaf_masks + w->leaves * leaf_bytes, leaf_bytes, "a leaf's value mask"))
      return 1;
    w->leaves++;
  }
  return 0;
}

/* std::map<Coord, NodeStruct>'s order (Coord::operator<: x, then y, then z), and the file
 * order among equal origins. */
static int by_origin(const void *a, const void *b) {
  const root_child *x = a, *y = b;
  for (int i = 0; i < 3; i++)
    if (x->origin[i] != y->origin[i]) return x->origin[i] < y->origin[i] ? -1 : 1;
  return (x->order > y->order) - (x->order < y->order);
}

/* The rest of RootNode::readTopology (tiles: Coord, value, active flag; children: Coord
 * and the node), which must end at the grid's block offset, then Tree::readBuffers:
 * RootNode visits its children in its std::map's order (two at one origin are refused
 * below), each InternalNode its children in mask order, and each
 * LeafNode::readBuffers passes its value mask and reads its 8^3 values. */
static int walk_tree(vdb_in *in, tree_walk *w, uint32_t tiles, uint32_t children,
                     uint64_t block_pos, uint64_t end_pos) {
  char phrase[160];
  /* a tile's active flag is read into a bool: a byte other than 0 or 1 is undefined */
  for (uint32_t t = 0; t < tiles; t++) {
    unsigned char active;
    snprintf(phrase, sizeof phrase, "root tile %" PRIu32 " (%" PRIu64 " bytes)", t + 1,
             13 + w->type.value_bytes);
    if (skip(in, 12 + w->type.value_bytes, phrase) || get(in, &active, 1, phrase)) return 1;
    if (active > 1)
      return damaged(in, "root tile %" PRIu32 "'s active flag is %u, not 0 or 1 (at byte %"
                     PRIu64 ")", t + 1, active, in->pos - 1);
  }
  int bad = 0;
  uint64_t largest = 0;
  for (int l = 0; l < 3; l++)
    if (mask_bytes(w->type.log2[l]) > largest) largest = mask_bytes(w->type.log2[l]);
  w->child_mask[0] = malloc(mask_bytes(w->type.log2[0]));
  w->child_mask[1] = malloc(mask_bytes(w->type.log2[1]));
  w->value_mask = malloc(largest);
  w->children = malloc(((size_t)children + 1) * sizeof *w->children);
  if (!w->child_mask[0] || !w->child_mask[1] || !w->value_mask || !w->children)
    bad = fog_fail(in->err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory checking the file", in->path);
  for (uint32_t c = 0; !bad && c < children; c++) {
    unsigned char b[12];
    bad = get(in, b, 12, "a root child's origin (12 bytes)");
    if (bad) break;
    root_child *child = &w->children[w->child_count++];
    for (int a = 0; a < 3; a++) child->origin[a] = (int32_t)le(b + 4 * a, 4);
    child->first_leaf = w->leaves;
    child->order = c;
    bad = read_internal(in, w, 0);
    child->leaf_count = w->leaves - child->first_leaf;
  }
  /* File::readGrid reads the buffers right after the topology (Archive::readGrid), other
   * paths seek to the block offset first; OpenVDB writes the one right after the other. */
  if (!bad && block_pos != UINT64_MAX && in->pos != block_pos)
    bad = damaged(in, "the tree's topology ends at byte %" PRIu64 ", not at its buffers' "
                  "offset %" PRIu64, in->pos, block_pos);
  if (!bad) {
    qsort(w->children, w->child_count, sizeof *w->children, by_origin);
    in->end = end_pos;
    in->within = block_pos != UINT64_MAX ? "the grid's buffers" : "the file";
    const uint64_t leaf_bytes = mask_bytes(w->type.log2[2]);
    for (size_t c = 0; !bad && c < w->child_count; c++) {
      const root_child *child = &w->children[c];
      /* OpenVDB writes a std::map: one child per origin. Reading a second one, it assigns
       * over the first's NodeStruct without deleting that node (a leak fuzzing found). */
      if (c + 1 < w->child_count && !memcmp(child->origin, w->children[c + 1].origin,
                                            sizeof child->origin)) {
        bad = damaged(in, "two root children at (%" PRId32 ", %" PRId32 ", %" PRId32 ")",
                      child->origin[0], child->origin[1], child->origin[2]);
        break;
      }
      /* The leaf's value mask is stored again before its values; io::File's stream is
       * seekable, so OpenVDB seeks over that copy and keeps the topology's mask, which
       * says how many values a mask-compressed leaf stores. */
      for (size_t l = 0; !bad && l < child->leaf_count; l++) {
        const unsigned char *mask = w->leaf_masks + (child->first_leaf + l) * leaf_bytes;
        bad = skip(in, leaf_bytes, "a leaf's value mask");
        if (!bad)
          bad = read_values(in, w, 8 * leaf_bytes, count_on(mask, leaf_bytes), leaf_bytes, 0,
                            "a leaf");
      }
    }
  }
  free(w->child_mask[0]);
  free(w->child_mask[1]);
  free(w->value_mask);
  free(w->leaf_masks);
  free(w->children);
  return bad;
}

/* io::Archive::readGrid (and File::readGridPartial): readGridCompression, the grid's
 * MetaMap, the transform, then (not for instances) Tree::readTopology: TreeBase's buffer
 * count, then RootNode::readTopology: background, tile count, child count, which it loops
 * over without checking the stream (a damaged count loops billions of times past the
 * end, allocating a node per child). For the plain value types and with block offsets
 * (every io::File), the whole tree is walked, topology and buffers (walk_tree): OpenVDB
 * allocates each compressed chunk's size as read, and a damaged chunk also leaks the
 * node being read (RootNode::readTopology is not exception-safe). */
static int read_grid(vdb_in *in, uint32_t version, const char *type, int instance,
                     uint64_t block_pos, uint64_t end_pos, int *walked) {
  uint32_t compression = 0;
  if (version >= VERSION_NODE_MASK_COMPRESSION &&
      get_u32(in, &compression, "the grid's compression flags (4 bytes)"))
    return 1;
  /* GridBase::saveFloatAsHalf reads the grid's own metadata item (MetaMap::readMeta
   * replaces what the descriptor's "_HalfFloat" set): without one, full floats */
  int half = 0;
  if (read_metamap(in, "grid metadata", &half)) return 1;
  if (read_map(in, version, 0)) return 1;
  if (instance) {
    if (walked) *walked = 1;
    return 0;
  }
  const tree_type t = tree_layout(type);
  const uint64_t value_bytes = t.value_bytes, child_bytes = root_child_bytes(&t);
  char phrase[224];
  snprintf(phrase, sizeof phrase, "the tree's buffer count and background (%" PRIu64 " bytes)",
           4 + value_bytes);
  if (skip(in, 4 + value_bytes, phrase)) return 1;
  uint32_t tiles, children;
  if (get_u32(in, &tiles, "the root's tile count (4 bytes)") ||
      get_u32(in, &children, "the root's child count (4 bytes)"))
    return 1;
  /* a tile: Coord, value, active flag; a child: Coord and at least its node's masks */
  snprintf(phrase, sizeof phrase, "the topology of the root's %" PRIu32 " tiles and %" PRIu32
           " child nodes (%" PRIu64 " bytes or more)", tiles, children,
           tiles * (13 + value_bytes) + children * child_bytes);
  if (need(in, tiles * (13 + value_bytes) + children * child_bytes, phrase)) return 1;
  if (!t.walk || version < VERSION_NODE_MASK_COMPRESSION) return 0;
  tree_walk w = {.type = t, .half = half, .compression = compression};
  if (walk_tree(in, &w, tiles, children, block_pos, end_pos)) return 1;
  if (walked) *walked = 1;
  return 0;
}

/* io::File::readGridDescriptors: readGridCount, then per grid GridDescriptor::read
 * (readString unique name, readString grid type, readString instance parent name from
 * version 216, int64 grid, block and end offsets) and a seek to the end offset, where the
 * next descriptor starts. Each grid's own block is checked as OpenVDB will read it. */
static int read_descriptors(vdb_in *in, uint32_t version, int has_offsets) {
  unsigned char b[4];
  if (get(in, b, 4, "the grid count (4 bytes)")) return 1;
  const int32_t count = (int32_t)le(b, 4);
  if (count < 0) return damaged(in, "the grid count %" PRId32 " is negative", count);
  char phrase[224];
  snprintf(phrase, sizeof phrase, "the grid count %" PRId32 " (36 bytes or more per grid "
           "descriptor)", count);
  if (need(in, 36ull * (uint32_t)count, phrase)) return 1;
  for (int32_t i = 0; i < count; i++) {
    char name[96], type[64], parent[8], what[64];
    uint32_t name_len, type_len, parent_len = 0;
    snprintf(what, sizeof what, "grid descriptor %" PRId32 "'s name", i + 1);
    if (get_string(in, name, sizeof name, &name_len, what)) return 1;
    printable(name);
    snprintf(what, sizeof what, "grid descriptor %" PRId32 "'s type name", i + 1);
    if (get_string(in, type, sizeof type, &type_len, what)) return 1;
    printable(type);
    /* "_HalfFloat" marks 16-bit storage of buffers; the tree type is what precedes it */
    if (type_len >= 10 && type_len < sizeof type && !strcmp(type + type_len - 10, "_HalfFloat"))
      type[type_len - 10] = '\0';
    snprintf(what, sizeof what, "grid descriptor %" PRId32 "'s instance parent name", i + 1);
    if (version >= VERSION_GRID_INSTANCING &&
        get_string(in, parent, sizeof parent, &parent_len, what))
      return 1;
    int64_t grid_pos, block_pos, end_pos;
    snprintf(what, sizeof what, "grid descriptor %" PRId32 "'s offsets (24 bytes)", i + 1);
    if (need(in, 24, what) || get_i64(in, &grid_pos, what) || get_i64(in, &block_pos, what) ||
        get_i64(in, &end_pos, what))
      return 1;
    const int instance = parent_len > 0;
    const int64_t size = (int64_t)in->size, here = (int64_t)in->pos;
    if (!has_offsets) {
      /* io::Stream output: each grid follows its descriptor inline, buffers right after
       * the topology; the next descriptor follows the grid, found only by walking the
       * whole tree (where a grid is not walked, the grids after it are not checked). */
      snprintf(in->section, sizeof in->section, "grid '%s'", name);
      int walked = 0;
      if (read_grid(in, version, type, instance, UINT64_MAX, in->size, &walked))
        return 1;
      if (!walked) return 0;
      snprintf(in->section, sizeof in->section, "header");
      in->end = in->size;
      in->within = "the file";
      continue;
    }
    /* io::Archive::writeGrid puts the grid right after its descriptor and the blocks
     * (buffers) after the topology; writeGridInstance leaves the block offset 0 */
    if (end_pos > size)
      return damaged(in, "grid '%s' ends at byte %" PRId64 ", beyond the end of the file "
                     "(%" PRIu64 " bytes; truncated?)", name, end_pos, in->size);
    if (grid_pos != here || end_pos < grid_pos ||
        (!instance && (block_pos < grid_pos || block_pos > end_pos)))
      return damaged(in, "grid '%s' has offsets %" PRId64 ", %" PRId64 ", %" PRId64 " (grid, "
                     "blocks, end); expected %" PRId64 " <= blocks <= end <= %" PRIu64,
                     name, grid_pos, block_pos, end_pos, here, in->size);
    snprintf(in->section, sizeof in->section, "grid '%s'", name);
    in->end = (uint64_t)(instance ? end_pos : block_pos);
    in->within = instance ? "the grid" : "the grid's metadata and topology";
    if (read_grid(in, version, type, instance, (uint64_t)block_pos, (uint64_t)end_pos, NULL))
      return 1;
    snprintf(in->section, sizeof in->section, "header");
    in->end = in->size;
    in->within = "the file";
    in->pos = (uint64_t)end_pos;  /* GridDescriptor::seekToEnd */
  }
  return 0;
}

int vdb_precheck_file(const char *path, fog_error *err) {
  vdb_in in = {.path = path, .err = err, .within = "the file", .section = "header"};
  in.fd = open(path, O_RDONLY);
  if (in.fd < 0)
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot open: %s", path, strerror(errno));
  struct stat st;
  if (fstat(in.fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    close(in.fd);
    return fog_fail(err, FOG_ERR_BAD_FILE, "%s: not a regular file", path);
  }
  in.size = in.end = (uint64_t)st.st_size;
  uint32_t version = 0;
  int has_offsets = 1;
  /* io::File::open: the header, the file's MetaMap, the grid descriptors */
  const int bad = read_header(&in, &version, &has_offsets) ||
                  read_metamap(&in, "file metadata", NULL) ||
                  read_descriptors(&in, version, has_offsets);
  close(in.fd);
  return bad;
}
