/* OpenEXR through the OpenEXR 3 Core C API (openexr.h).
 *
 * Reading: part 0, one channel (half or float) to float; scanline files, and tiled files
 * at their full-resolution level (0, 0); the image is the display window, the data window
 * placed in it (zero where there is no data). Writing: one scanline part, ZIP compression
 * (lossless, 16 scanlines per chunk; smooth fog compresses well and every EXR reader
 * supports it), channels sorted by name as EXR requires.
 *
 * Both directions use our own stream callbacks on a file descriptor we opened: the
 * library's own file handling would hide the errno (missing file, disk full) we must
 * report, and writes must go to an atomic_file temporary. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sim/image_io.h"

/* Our stream: a file descriptor and the last message the library reported. */
typedef struct exr_stream {
  int fd;
  int64_t size;
  atomic_file *out;  /* when writing */
  char last_message[256]; /* the library's last error message */
} exr_stream;

/* The stream of the read or write under way on this thread, for remember_error. The error
 * handler must not ask the context for its user data: OpenEXR Core calls the handler with
 * the context's lock held (e.g. from exr_write_header when a write fails), and
 * exr_get_user_data takes that lock again, so a full disk used to hang the process. */
static _Thread_local exr_stream *current_stream;

static void remember_error(exr_const_context_t ctxt, exr_result_t code, const char *msg) {
  exr_stream *stream = current_stream;
  if (stream) snprintf(stream->last_message, sizeof stream->last_message, "%s", msg ? msg : "");
}

static int64_t stream_read(exr_const_context_t ctxt, void *user, void *buffer, uint64_t size,
                           uint64_t offset, exr_stream_error_func_ptr_t error_cb) {
  exr_stream *stream = user;
  uint8_t *p = buffer;
  uint64_t done = 0;
  while (done < size) {
    ssize_t n = pread(stream->fd, p + done, size - done, (off_t)(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      error_cb(ctxt, EXR_ERR_READ_IO, "read failed: %s", strerror(errno));
      return -1;
    }
    if (n == 0) break; /* end of file: the library reports a short read */
    done += (uint64_t)n;
  }
  return (int64_t)done;
}

static int64_t stream_size(exr_const_context_t ctxt, void *user) { return ((exr_stream *)user)->size; }

static int64_t stream_write(exr_const_context_t ctxt, void *user, const void *buffer,
                            uint64_t size, uint64_t offset,
                            exr_stream_error_func_ptr_t error_cb) {
  exr_stream *stream = user;
  if (atomic_file_pwrite(stream->out, buffer, size, offset)) {
    error_cb(ctxt, EXR_ERR_WRITE_IO, "write failed: %s", strerror(stream->out->write_errno));
    return -1;
  }
  return (int64_t)size;
}

/* "the library's message" or, when it gave none, the generic text of the code. */
static const char *exr_reason(const exr_stream *stream, exr_result_t code) {
  return stream->last_message[0] ? stream->last_message : exr_get_default_error_message(code);
}

static void list_channels(const exr_attr_chlist_t *list, char *out, size_t size) {
  out[0] = '\0';
  for (int c = 0; c < list->num_channels; c++) {
    size_t used = strlen(out);
    if (used + 8 >= size) {
      snprintf(out + used, size - used, ", ...");
      break;
    }
    snprintf(out + used, size - used, "%s\"%s\"", c ? ", " : "", list->entries[c].name.str);
  }
}

/* Points the chosen channel of this chunk at its place in the output image (rows of
 * `width` floats) and every other channel at a scratch chunk that is thrown away.
 * (Leaving the other channels' pointers NULL, which the API documents as "skip", crashes
 * OpenEXR 3.1.5's unpack routines for half channels; decoding them costs little.) */
static void aim_channels(exr_decode_pipeline_t *decode, const char *name, float *chunk_origin,
                         int width, float *scratch) {
  for (int c = 0; c < decode->channel_count; c++) {
    exr_coding_channel_info_t *info = &decode->channels[c];
    int chosen = !strcmp(info->channel_name, name);
    info->decode_to_ptr = (uint8_t *)(chosen ? chunk_origin : scratch);
    info->user_pixel_stride = (int32_t)sizeof(float);
    info->user_line_stride =
        (int32_t)(sizeof(float) * (size_t)(chosen ? width : info->width));
    info->user_bytes_per_element = (int16_t)sizeof(float);
    info->user_data_type = EXR_PIXEL_FLOAT; /* half is converted by the library */
  }
}

/* Decodes one chunk (a scanline block or a tile) into the output image. */
static exr_result_t decode_chunk(exr_context_t ctxt, const exr_chunk_info_t *chunk,
                                 exr_decode_pipeline_t *decode, int *initialised,
                                 const char *name, float *origin, int width,
                                 float *scratch) {
  exr_result_t rv;
  if (!*initialised) {
    rv = exr_decoding_initialize(ctxt, 0, chunk, decode);
    if (rv != EXR_ERR_SUCCESS) return rv;
    *initialised = 1;
    aim_channels(decode, name, origin, width, scratch);
    rv = exr_decoding_choose_default_routines(ctxt, 0, decode);
  } else {
    rv = exr_decoding_update(ctxt, 0, chunk, decode);
    aim_channels(decode, name, origin, width, scratch);
  }
  if (rv != EXR_ERR_SUCCESS) return rv;
  return exr_decoding_run(ctxt, 0, decode);
}

/* Opens path for reading through our stream (the current one of this thread) and fills the
 * context initialiser; 1 with err set when the file cannot be opened. */
static int open_read_stream(const char *path, exr_stream *stream, exr_context_initializer_t *init,
                            fog_error *err) {
  *stream = (exr_stream){.fd = open(path, O_RDONLY | O_CLOEXEC)};
  if (stream->fd < 0)
    return fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: cannot open: %s", path, strerror(errno));
  current_stream = stream;
  struct stat st;
  stream->size = fstat(stream->fd, &st) == 0 ? (int64_t)st.st_size : -1;
  *init = (exr_context_initializer_t)EXR_DEFAULT_CONTEXT_INITIALIZER;
  init->error_handler_fn = remember_error;
  init->user_data = stream;
  init->read_fn = stream_read;
  init->size_fn = stream_size;
  return 0;
}

/* Part 0's layout: scanline or tiled, its data window and channels, a size a fogmap can
 * take. 0, or 1 with err. */
static int exr_read_layout(exr_context_t ctxt, const char *path, exr_stream *stream,
                           exr_storage_t *storage, exr_attr_box2i_t *window,
                           const exr_attr_chlist_t **list, int64_t *width, int64_t *height,
                           fog_error *err) {
  exr_result_t rv = exr_get_storage(ctxt, 0, storage);
  if (rv == EXR_ERR_SUCCESS) rv = exr_get_data_window(ctxt, 0, window);
  if (rv == EXR_ERR_SUCCESS) rv = exr_get_channels(ctxt, 0, list);
  if (rv != EXR_ERR_SUCCESS || !*list)
    return fog_fail(err, FOG_ERR_BAD_FILE, "%s: EXR header incomplete: %s", path,
                    exr_reason(stream, rv));
  if (*storage != EXR_STORAGE_SCANLINE && *storage != EXR_STORAGE_TILED)
    return fog_fail(err, FOG_ERR_BAD_FILE, "%s: deep EXR data; expected a scanline or tiled image",
                    path);
  *width = (int64_t)window->max.x - window->min.x + 1;
  *height = (int64_t)window->max.y - window->min.y + 1;
  if (*width <= 0 || *height <= 0)
    return fog_fail(err, FOG_ERR_BAD_FILE, "%s: EXR data window has zero size (%lldx%lld)", path,
                    (long long)*width, (long long)*height);
  if (*width > 1 << 20 || *height > 1 << 20 || *width * *height > (int64_t)1 << 28)
    return fog_fail(err, FOG_ERR_BAD_FILE, "%s: EXR size %lldx%lld is too large for a fogmap", path,
                    (long long)*width, (long long)*height);
  return 0;
}

/* The channel to load: the one named, or the only one; half or float, full resolution. */
static const exr_attr_chlist_entry_t *exr_pick_channel(const exr_attr_chlist_t *list,
                                                       int parts, const char *path,
                                                       const char *channel,
                                                       const char *channel_setting,
                                                       fog_error *err) {
  char names[256], where[80] = "";
  list_channels(list, names, sizeof names);
  /* a multi-part file: only its first part is read (a channel in another part was reported
   * missing with part 0's list alone) */
  if (parts > 1)
    snprintf(where, sizeof where, " in its first part (of %d; the others are not read)", parts);
  const exr_attr_chlist_entry_t *entry = NULL;
  if (list->num_channels == 0)
    return fog_fail(err, FOG_ERR_BAD_FILE, "%s: EXR has no channels", path), NULL;
  if (!channel) {
    char hint[128];
    if (list->num_channels != 1)
      return fog_fail(err, FOG_ERR_BAD_FILE, "%s: EXR has %d channels (%s)%s; name the one to "
                      "load%s", path, list->num_channels, names, where,
                      image_channel_setting_hint(channel_setting, hint, sizeof hint)),
             NULL;
    entry = &list->entries[0];
  } else {
    for (int c = 0; c < list->num_channels; c++)
      if (!strcmp(list->entries[c].name.str, channel)) entry = &list->entries[c];
    if (!entry)
      return fog_fail(err, FOG_ERR_NO_SUCH_CHANNEL, "%s: EXR has no channel \"%s\"; it has %s%s",
                      path, channel, names, where),
             NULL;
  }
  if (entry->pixel_type != EXR_PIXEL_HALF && entry->pixel_type != EXR_PIXEL_FLOAT)
    return fog_fail(err, FOG_ERR_BAD_FILE,
                    "%s: EXR channel \"%s\" holds 32-bit unsigned integers; expected "
                    "half or float",
                    path, entry->name.str),
           NULL;
  /* any channel subsampled, not only the one loaded: OpenEXR Core (3.1) decodes the others
   * wrongly beside it and reads past its buffer (a luminance/chroma file's Y came back
   * 1, 0.5, 0, ... for a constant 0.5) */
  for (int c = 0; c < list->num_channels; c++) {
    const exr_attr_chlist_entry_t *e = &list->entries[c];
    if (e->x_sampling != 1 || e->y_sampling != 1)
      return fog_fail(err, FOG_ERR_BAD_FILE,
                      "%s: EXR channel \"%s\" is subsampled (%d x %d), which this reader "
                      "cannot decode beside the others; expected one value per pixel in every "
                      "channel (save it without chroma subsampling)",
                      path, e->name.str, e->x_sampling, e->y_sampling),
             NULL;
  }
  return entry;
}

/* Decodes channel `name` of every chunk into out (width x height floats). The chunk layout:
 * scanline blocks of lines_per_chunk rows, or tiles of level (0, 0); tile (tx, ty) starts at
 * pixel (tx * tile_w, ty * tile_h) of the data window. *out_of_memory on a failed scratch. */
static exr_result_t exr_read_chunks(exr_context_t ctxt, exr_storage_t storage,
                                    const exr_attr_box2i_t *window, int64_t width,
                                    int64_t height, const char *name, float *out,
                                    int *out_of_memory) {
  exr_decode_pipeline_t decode = EXR_DECODE_PIPELINE_INITIALIZER;
  int initialised = 0;
  int32_t lines_per_chunk = 1;
  uint32_t tile_w = 0, tile_h = 0;
  exr_result_t rv;
  if (storage == EXR_STORAGE_SCANLINE) {
    rv = exr_get_scanlines_per_chunk(ctxt, 0, &lines_per_chunk);
    if (rv == EXR_ERR_SUCCESS && lines_per_chunk < 1) rv = EXR_ERR_INVALID_ATTR;
  } else {
    exr_tile_level_mode_t level_mode;
    exr_tile_round_mode_t round_mode;
    rv = exr_get_tile_descriptor(ctxt, 0, &tile_w, &tile_h, &level_mode, &round_mode);
    if (rv == EXR_ERR_SUCCESS && (tile_w == 0 || tile_h == 0)) rv = EXR_ERR_INVALID_ATTR;
  }
  if (rv != EXR_ERR_SUCCESS) return rv;
  /* The scratch chunk for the channels not loaded: one channel of one chunk, in floats
   * (each of them decodes into it, over the others), the chunk clipped to the image. Not
   * sized by exr_get_chunk_unpacked_size: that counts every channel of a whole tile at the
   * header's tile size, which one damaged byte made 3.6 GB for a 1x1 image. */
  int64_t chunk_w = storage == EXR_STORAGE_SCANLINE || tile_w > width ? width : tile_w;
  int64_t chunk_h = storage == EXR_STORAGE_SCANLINE
                        ? (lines_per_chunk < height ? lines_per_chunk : height)
                        : (tile_h < height ? tile_h : height);
  float *scratch = malloc((size_t)chunk_w * (size_t)chunk_h * sizeof(float));
  if (!scratch) {
    *out_of_memory = 1;
    return EXR_ERR_OUT_OF_MEMORY;
  }
  if (storage == EXR_STORAGE_SCANLINE) {
    for (int32_t y = window->min.y; rv == EXR_ERR_SUCCESS && y <= window->max.y;
         y += lines_per_chunk) {
      exr_chunk_info_t chunk;
      rv = exr_read_scanline_chunk_info(ctxt, 0, y, &chunk);
      if (rv != EXR_ERR_SUCCESS) break;
      float *origin = out + (size_t)(chunk.start_y - window->min.y) * (size_t)width;
      rv = decode_chunk(ctxt, &chunk, &decode, &initialised, name, origin, (int)width, scratch);
    }
  } else {
    int64_t tiles_x = (width + tile_w - 1) / tile_w;
    int64_t tiles_y = (height + tile_h - 1) / tile_h;
    for (int64_t ty = 0; rv == EXR_ERR_SUCCESS && ty < tiles_y; ty++)
      for (int64_t tx = 0; rv == EXR_ERR_SUCCESS && tx < tiles_x; tx++) {
        exr_chunk_info_t chunk;
        rv = exr_read_tile_chunk_info(ctxt, 0, (int)tx, (int)ty, 0, 0, &chunk);
        if (rv != EXR_ERR_SUCCESS) break;
        float *origin = out + (size_t)(ty * tile_h) * (size_t)width + (size_t)(tx * tile_w);
        rv = decode_chunk(ctxt, &chunk, &decode, &initialised, name, origin, (int)width,
                          scratch);
      }
  }
  if (initialised) exr_decoding_destroy(ctxt, &decode);
  free(scratch);
  return rv;
}

int exr_read_channel(const char *path, const char *channel, const char *channel_setting,
                     int *width_out, int *height_out, float **pixels, fog_error *err) {
  exr_stream stream;
  exr_context_initializer_t init;
  if (open_read_stream(path, &stream, &init, err)) return 1;
  exr_context_t ctxt = NULL;
  float *out = NULL;
  int status = 1;
  exr_result_t rv = exr_start_read(&ctxt, path, &init);
  if (rv != EXR_ERR_SUCCESS) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: not a readable EXR: %s", path, exr_reason(&stream, rv));
    goto done;
  }
  exr_storage_t storage;
  exr_attr_box2i_t window;
  const exr_attr_chlist_t *list = NULL;
  int64_t width = 0, height = 0;
  if (exr_read_layout(ctxt, path, &stream, &storage, &window, &list, &width, &height, err))
    goto done;
  int parts = 1;
  exr_get_count(ctxt, &parts);
  const exr_attr_chlist_entry_t *entry =
      exr_pick_channel(list, parts, path, channel, channel_setting, err);
  if (!entry) goto done;
  out = calloc((size_t)width * (size_t)height, sizeof *out);
  if (!out) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory for a %lldx%lld fogmap", path,
             (long long)width, (long long)height);
    goto done;
  }
  int out_of_memory = 0;
  rv = exr_read_chunks(ctxt, storage, &window, width, height, entry->name.str, out,
                       &out_of_memory);
  if (out_of_memory) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory for an EXR chunk", path);
    goto done;
  }
  exr_compression_t compression = EXR_COMPRESSION_NONE;
  int major = 0, minor = 0, patch = 0;
  exr_get_library_version(&major, &minor, &patch, NULL);
  /* OpenEXR Core before 3.2 (3.1 in Debian 12) cannot decode DWA; its last message blamed
   * the data, and a good file from a compositor read as damaged (a later library that
   * decodes DWA fails only on a damaged file, said as such below) */
  if (rv != EXR_ERR_SUCCESS && (major < 3 || (major == 3 && minor < 2)) &&
      exr_get_compression(ctxt, 0, &compression) == EXR_ERR_SUCCESS &&
      (compression == EXR_COMPRESSION_DWAA || compression == EXR_COMPRESSION_DWAB)) {
    fog_fail(err, FOG_ERR_UNSUPPORTED, "%s: %s compression, which this OpenEXR (%d.%d.%d) cannot "
             "decode: save the fogmap with ZIP, PIZ or no compression", path,
             compression == EXR_COMPRESSION_DWAA ? "DWAA" : "DWAB", major, minor, patch);
    goto done;
  }
  if (rv != EXR_ERR_SUCCESS) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: EXR pixel data unreadable (damaged or truncated?): %s",
             path, exr_reason(&stream, rv));
    goto done;
  }
  /* The image is the display window: the data window placed in it at its offset, zero
   * (no fog) where it holds no data, cropped where it reaches past (a file cropped to its
   * non-empty pixels was stretched over the whole fog box) */
  exr_attr_box2i_t display;
  if (exr_get_display_window(ctxt, 0, &display) == EXR_ERR_SUCCESS &&
      (display.min.x != window.min.x || display.min.y != window.min.y ||
       display.max.x != window.max.x || display.max.y != window.max.y)) {
    const int64_t dw = (int64_t)display.max.x - display.min.x + 1,
                  dh = (int64_t)display.max.y - display.min.y + 1;
    if (dw <= 0 || dh <= 0 || dw > 1 << 20 || dh > 1 << 20 || dw * dh > (int64_t)1 << 28) {
      fog_fail(err, FOG_ERR_BAD_FILE, "%s: EXR display window %lldx%lld: expected a size "
               "from 1x1 to a fogmap's largest", path, (long long)dw, (long long)dh);
      goto done;
    }
    float *placed = calloc((size_t)dw * (size_t)dh, sizeof *placed);
    if (!placed) {
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "%s: out of memory for a %lldx%lld fogmap", path,
               (long long)dw, (long long)dh);
      goto done;
    }
    for (int64_t y = 0; y < height; y++) {
      const int64_t py = (int64_t)window.min.y - display.min.y + y;
      if (py < 0 || py >= dh) continue;
      for (int64_t x = 0; x < width; x++) {
        const int64_t px = (int64_t)window.min.x - display.min.x + x;
        if (px >= 0 && px < dw) placed[py * dw + px] = out[y * width + x];
      }
    }
    free(out);
    out = placed, width = dw, height = dh;
  }
  *width_out = (int)width;
  *height_out = (int)height;
  *pixels = out;
  out = NULL;
  status = 0;
done:
  if (ctxt) exr_finish(&ctxt);
  current_stream = NULL;
  close(stream.fd);
  free(out);
  return status;
}

/* The library's ZIP compression, then the raw bytes wherever the stream did not come out
 * smaller. A reader takes a chunk exactly as long as its raw bytes for raw; OpenEXR Core
 * 3.1.5 (Debian 12's) kept a deflate stream of exactly that length, so such a chunk read
 * back as garbage (5e29 in a 6x6 wavelet band; fixed upstream in 3.2). */
static _Thread_local exr_result_t (*library_compress)(exr_encode_pipeline_t *encode);
static exr_result_t compress_or_keep_raw(exr_encode_pipeline_t *encode) {
  exr_result_t rv = library_compress(encode);
  if (rv == EXR_ERR_SUCCESS && encode->compressed_buffer != encode->packed_buffer &&
      encode->compressed_bytes >= encode->packed_bytes &&
      encode->compressed_alloc_size >= encode->packed_bytes) {
    memcpy(encode->compressed_buffer, encode->packed_buffer, encode->packed_bytes);
    encode->compressed_bytes = encode->packed_bytes;
  }
  return rv;
}

static int by_name(const void *a, const void *b) {
  return strcmp(((const image_channel *)a)->name, ((const image_channel *)b)->name);
}

int image_write_exr(const char *path, int width, int height, const image_channel *channels,
                    int channel_count, fog_error *err) {
  return image_write_exr_with(path, width, height, channels, channel_count, NULL, err);
}

int image_write_exr_with(const char *path, int width, int height, const image_channel *channels,
                         int channel_count, const image_exr_header *header, fog_error *err) {
  const image_exr_header none = {0};
  if (!header) header = &none;
  if (width <= 0 || height <= 0)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: image size %dx%d: both must be positive",
                    path, width, height);
  if (channel_count <= 0 || channel_count > 64)
    return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: an EXR needs 1 to 64 channels, not %d",
                    path, channel_count);
  image_channel sorted[64];
  for (int c = 0; c < channel_count; c++) {
    sorted[c] = channels[c];
    if (!sorted[c].name || !sorted[c].name[0] || strlen(sorted[c].name) > 31 ||
        !sorted[c].pixels)
      return fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                      "%s: channel %d needs a name (1 to 31 characters) and pixels", path, c);
  }
  /* EXR requires channels sorted by name (the channel list attribute is sorted). */
  qsort(sorted, (size_t)channel_count, sizeof sorted[0], by_name);
  for (int c = 1; c < channel_count; c++)
    if (!strcmp(sorted[c - 1].name, sorted[c].name))
      return fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "%s: channel \"%s\" given twice", path,
                      sorted[c].name);

  for (int c = 0; c < channel_count; c++)
    if (image_check_finite(path, sorted[c].name, sorted[c].pixels, width, height, 1,
                           sorted[c].as_half ? 65504.0f : FLT_MAX, err))
      return 1;

  atomic_file file;
  if (atomic_file_open(&file, path, err)) return 1;
  exr_stream stream = {.fd = file.fd, .out = &file};
  current_stream = &stream;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = remember_error;
  init.user_data = &stream;
  init.write_fn = stream_write;
  exr_context_t ctxt = NULL;
  exr_encode_pipeline_t encode = EXR_ENCODE_PIPELINE_INITIALIZER;
  int initialised = 0;
  int part = 0;
  const char *stage = "starting the file";
  exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
  if (rv == EXR_ERR_SUCCESS) rv = exr_add_part(ctxt, "fogpipe", EXR_STORAGE_SCANLINE, &part);
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_initialize_required_attr_simple(ctxt, part, width, height, EXR_COMPRESSION_ZIP);
  /* pLinear 0: scene-linear light is perceived logarithmically (the hint B44 and DWA
   * compression act on when a compositor saves the file again), as OpenEXR's own default */
  for (int c = 0; rv == EXR_ERR_SUCCESS && c < channel_count; c++)
    rv = exr_add_channel(ctxt, part, sorted[c].name,
                         sorted[c].as_half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT,
                         EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
  for (int k = 0; rv == EXR_ERR_SUCCESS && k < header->string_count; k++)
    rv = exr_attr_set_string(ctxt, part, header->strings[k].name, header->strings[k].value);
  for (int k = 0; rv == EXR_ERR_SUCCESS && k < header->matrix_count; k++) {
    exr_attr_m44f_t m;
    memcpy(m.m, header->matrices[k].m, sizeof m.m);
    rv = exr_attr_set_m44f(ctxt, part, header->matrices[k].name, &m);
  }
  if (rv == EXR_ERR_SUCCESS) {
    stage = "writing the header";
    rv = exr_write_header(ctxt);
  }
  int32_t lines_per_chunk = 1;
  if (rv == EXR_ERR_SUCCESS) rv = exr_get_scanlines_per_chunk(ctxt, part, &lines_per_chunk);
  if (rv == EXR_ERR_SUCCESS) stage = "writing pixels";
  for (int y = 0; rv == EXR_ERR_SUCCESS && y < height; y += lines_per_chunk) {
    exr_chunk_info_t chunk;
    rv = exr_write_scanline_chunk_info(ctxt, part, y, &chunk);
    if (rv != EXR_ERR_SUCCESS) break;
    rv = initialised ? exr_encoding_update(ctxt, part, &chunk, &encode)
                     : exr_encoding_initialize(ctxt, part, &chunk, &encode);
    if (rv != EXR_ERR_SUCCESS) break;
    /* The encoder's channels are in file (sorted) order, as is `sorted`; match by name
     * anyway rather than rely on that. */
    for (int c = 0; c < encode.channel_count; c++) {
      exr_coding_channel_info_t *info = &encode.channels[c];
      const image_channel *source = NULL;
      for (int s = 0; s < channel_count; s++)
        if (!strcmp(sorted[s].name, info->channel_name)) source = &sorted[s];
      info->encode_from_ptr =
          (const uint8_t *)(source->pixels + (size_t)chunk.start_y * (size_t)width);
      info->user_pixel_stride = (int32_t)sizeof(float);
      info->user_line_stride = (int32_t)(sizeof(float) * (size_t)width);
      info->user_bytes_per_element = (int16_t)sizeof(float);
      info->user_data_type = EXR_PIXEL_FLOAT; /* float -> half done by the library */
    }
    if (!initialised) {
      initialised = 1;
      rv = exr_encoding_choose_default_routines(ctxt, part, &encode);
      if (rv != EXR_ERR_SUCCESS) break;
      if (encode.compress_fn) {
        library_compress = encode.compress_fn; /* the same routine for every ZIP part */
        encode.compress_fn = compress_or_keep_raw;
      }
    }
    rv = exr_encoding_run(ctxt, part, &encode);
  }
  if (initialised) exr_encoding_destroy(ctxt, &encode);
  if (rv == EXR_ERR_SUCCESS) stage = "finishing (writing the chunk table)";
  /* exr_finish writes the chunk offset table; its failure (a full disk) matters too. */
  exr_result_t finish = ctxt ? exr_finish(&ctxt) : EXR_ERR_SUCCESS;
  current_stream = NULL;
  if (rv == EXR_ERR_SUCCESS) rv = finish;
  if (rv != EXR_ERR_SUCCESS || file.write_errno) {
    if (file.write_errno)
      fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: write failed while %s: %s", path, stage,
               strerror(file.write_errno));
    else
      fog_fail(err, FOG_ERR_FILE_ACCESS, "%s: EXR writing failed while %s: %s", path, stage,
               exr_reason(&stream, rv));
    atomic_file_abandon(&file);
    return 1;
  }
  return atomic_file_commit(&file, err);
}

/* One attribute of part 0's header: string (text, size) or M44f (matrix). */
typedef struct header_query {
  const char *name;
  char *text;
  size_t size;
  float *matrix;
} header_query;

static int read_header_attribute(const char *path, const header_query *q, fog_error *err) {
  exr_stream stream;
  exr_context_initializer_t init;
  if (open_read_stream(path, &stream, &init, err)) return 1;
  exr_context_t ctxt = NULL;
  int status = 1;
  exr_result_t rv = exr_start_read(&ctxt, path, &init);
  if (rv != EXR_ERR_SUCCESS) {
    fog_fail(err, FOG_ERR_BAD_FILE, "%s: not a readable EXR: %s", path, exr_reason(&stream, rv));
  } else if (q->matrix) {
    exr_attr_m44f_t value;
    if (exr_attr_get_m44f(ctxt, 0, q->name, &value) != EXR_ERR_SUCCESS) {
      fog_fail(err, FOG_ERR_BAD_FILE, "%s: no 4x4 matrix attribute \"%s\" in the EXR header", path,
               q->name);
    } else {
      memcpy(q->matrix, value.m, sizeof value.m);
      status = 0;
    }
  } else {
    int32_t length = 0;
    const char *text = NULL;
    rv = exr_attr_get_string(ctxt, 0, q->name, &length, &text);
    if (rv != EXR_ERR_SUCCESS || !text) {
      fog_fail(err, FOG_ERR_BAD_FILE, "%s: no string attribute \"%s\" in the EXR header", path,
               q->name);
    } else {
      snprintf(q->text, q->size, "%.*s", (int)length, text);
      status = 0;
    }
  }
  if (ctxt) exr_finish(&ctxt);
  current_stream = NULL;
  close(stream.fd);
  return status;
}

int image_read_exr_channel(const char *path, const char *channel, int *width, int *height,
                           float **pixels, fog_error *err) {
  return exr_read_channel(path, channel, NULL, width, height, pixels, err);
}

int image_read_exr_string(const char *path, const char *name, char *value, size_t size,
                          fog_error *err) {
  return read_header_attribute(path, &(header_query){.name = name, .text = value, .size = size},
                               err);
}

int image_read_exr_matrix(const char *path, const char *name, float m[16], fog_error *err) {
  return read_header_attribute(path, &(header_query){.name = name, .matrix = m}, err);
}
