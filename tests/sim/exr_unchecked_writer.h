/* Writes a one-channel float EXR whatever its values hold, NaN and infinity included: the
 * bad-input tests need such files, and the product's image_write_exr refuses to make them.
 * Uncompressed, through OpenEXR Core directly (independent of sim/image_exr.c). */
#ifndef FOGPIPE_TESTS_SIM_EXR_UNCHECKED_WRITER_H
#define FOGPIPE_TESTS_SIM_EXR_UNCHECKED_WRITER_H

#include <openexr.h>

static inline int exr_write_unchecked(const char *path, const char *channel, int width,
                                      int height, const float *pixels) {
  exr_context_t ctxt = NULL;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  int part = 0;
  exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
  if (rv == EXR_ERR_SUCCESS) rv = exr_add_part(ctxt, "test", EXR_STORAGE_SCANLINE, &part);
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_initialize_required_attr_simple(ctxt, part, width, height, EXR_COMPRESSION_NONE);
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_add_channel(ctxt, part, channel, EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
  if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(ctxt);
  exr_encode_pipeline_t encode = EXR_ENCODE_PIPELINE_INITIALIZER;
  for (int y = 0; rv == EXR_ERR_SUCCESS && y < height; y++) { /* one line per chunk */
    exr_chunk_info_t chunk;
    rv = exr_write_scanline_chunk_info(ctxt, part, y, &chunk);
    if (rv == EXR_ERR_SUCCESS)
      rv = y ? exr_encoding_update(ctxt, part, &chunk, &encode)
             : exr_encoding_initialize(ctxt, part, &chunk, &encode);
    if (rv != EXR_ERR_SUCCESS) break;
    exr_coding_channel_info_t *info = &encode.channels[0];
    info->encode_from_ptr = (const uint8_t *)(pixels + (size_t)y * (size_t)width);
    info->user_pixel_stride = (int32_t)sizeof(float);
    info->user_line_stride = (int32_t)(sizeof(float) * (size_t)width);
    info->user_bytes_per_element = (int16_t)sizeof(float);
    info->user_data_type = EXR_PIXEL_FLOAT;
    if (!y) rv = exr_encoding_choose_default_routines(ctxt, part, &encode);
    if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_run(ctxt, part, &encode);
  }
  exr_encoding_destroy(ctxt, &encode);
  exr_result_t finish = exr_finish(&ctxt);
  return rv != EXR_ERR_SUCCESS || finish != EXR_ERR_SUCCESS;
}

#endif
