// Writes the synthetic seeds of tests/fuzz/corpus/: small PNGs, EXRs and VDBs in the layouts
// the readers handle (and a few they refuse), and command lines for fuzz_options. Not a
// fuzzer; run once, by hand, when a reader learns a new layout:
//   build-fuzz/fuzz_make_seeds tests/fuzz/corpus
// The real files of the corpora (configs/, tests/bad_input/, ../shared/data/vdb/) are
// copied by hand; docs/reliability.md lists them.
#include <openexr.h>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <spng.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "sim/vdb_import.h"

namespace {

std::string root;

void fail(const std::string &what) {
  std::fprintf(stderr, "fuzz_make_seeds: %s\n", what.c_str());
  std::exit(1);
}

void write_bytes(const std::string &path, const void *prefix, size_t prefix_size,
                 const void *data, size_t size) {
  FILE *f = std::fopen(path.c_str(), "wb");
  if (!f || std::fwrite(prefix, 1, prefix_size, f) != prefix_size ||
      (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0)
    fail("cannot write " + path);
  std::printf("%s (%zu bytes)\n", path.c_str(), prefix_size + size);
}

// ---- PNG (fuzz_fogmap_png: byte 0 picks the channel, then the file) ----

void png(const char *name, unsigned char channel_byte, uint32_t w, uint32_t h, uint8_t color,
         uint8_t depth, const std::vector<uint8_t> &samples, bool interlaced = false) {
  spng_ctx *ctx = spng_ctx_new(SPNG_CTX_ENCODER);
  spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
  spng_ihdr ihdr = {};
  ihdr.width = w, ihdr.height = h, ihdr.bit_depth = depth, ihdr.color_type = color;
  ihdr.interlace_method = interlaced ? 1 : 0;
  int e = spng_set_ihdr(ctx, &ihdr);
  if (!e && color == SPNG_COLOR_TYPE_INDEXED) {
    spng_plte plte = {};
    plte.n_entries = 4;
    for (int i = 0; i < 4; i++)
      plte.entries[i] = {uint8_t(60 * i), uint8_t(255 - 60 * i), uint8_t(20 * i), 255};
    e = spng_set_plte(ctx, &plte);
    spng_trns trns = {};
    trns.n_type3_entries = 2;
    trns.type3_alpha[0] = 0, trns.type3_alpha[1] = 128;
    if (!e) e = spng_set_trns(ctx, &trns);
  }
  if (!e) e = spng_encode_image(ctx, samples.data(), samples.size(), SPNG_FMT_PNG,
                                SPNG_ENCODE_FINALIZE);
  size_t size = 0;
  void *buffer = e ? nullptr : spng_get_png_buffer(ctx, &size, &e);
  spng_ctx_free(ctx);
  if (e || !buffer) fail(std::string(name) + ": " + spng_strerror(e));
  write_bytes(root + "/fogmap_png/" + name, &channel_byte, 1, buffer, size);
  std::free(buffer);
}

void pngs() {
  std::vector<uint8_t> grey8 = {0, 40, 80, 120, 160, 200, 240, 255, 7, 9, 11, 13};
  png("grey8_4x3.png", 0, 4, 3, SPNG_COLOR_TYPE_GRAYSCALE, 8, grey8);
  std::vector<uint8_t> grey16;  // host-endian uint16 samples (SPNG_FMT_PNG)
  for (uint16_t v : {0, 1000, 65535, 30000, 2, 40000}) {
    grey16.push_back(uint8_t(v)), grey16.push_back(uint8_t(v >> 8));
  }
  png("grey16_3x2.png", 1, 3, 2, SPNG_COLOR_TYPE_GRAYSCALE, 16, grey16);
  png("grey8_interlaced_4x3.png", 0, 4, 3, SPNG_COLOR_TYPE_GRAYSCALE, 8, grey8, true);
  png("grey_alpha8_2x2.png", 5, 2, 2, SPNG_COLOR_TYPE_GRAYSCALE_ALPHA, 8,
      {10, 255, 20, 128, 30, 0, 40, 64});
  png("rgb8_2x2.png", 2, 2, 2, SPNG_COLOR_TYPE_TRUECOLOR, 8,
      {255, 0, 0, 0, 255, 0, 0, 0, 255, 9, 99, 199});
  std::vector<uint8_t> rgba16;
  for (int i = 0; i < 2 * 2 * 4; i++) {
    rgba16.push_back(uint8_t(i * 17));
    rgba16.push_back(uint8_t(i));
  }
  png("rgba16_2x2.png", 4, 2, 2, SPNG_COLOR_TYPE_TRUECOLOR_ALPHA, 16, rgba16);
  png("indexed8_3x2.png", 3, 3, 2, SPNG_COLOR_TYPE_INDEXED, 8, {0, 1, 2, 3, 2, 1});
  png("grey1_8x2.png", 0, 8, 2, SPNG_COLOR_TYPE_GRAYSCALE, 1, {0xa5, 0x5a});  // refused
  png("indexed2_4x1.png", 5, 4, 1, SPNG_COLOR_TYPE_INDEXED, 2, {0x1b});
}

// ---- EXR (fuzz_fogmap_exr: byte 0 picks the channel, then the file) ----

struct exr_channel_spec {
  const char *name;
  exr_pixel_type_t type;
};

// A w x h image, scanline or tiled (tile_w x tile_h, one level), channels sorted by name.
void exr(const char *name, unsigned char channel_byte, int w, int h,
         std::vector<exr_channel_spec> channels, exr_compression_t compression, int tile_w = 0,
         int tile_h = 0) {
  const std::string path = root + "/fogmap_exr/.body.tmp";
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  exr_context_t ctxt = nullptr;
  int part = 0;
  const bool tiled = tile_w > 0;
  exr_result_t rv = exr_start_write(&ctxt, path.c_str(), EXR_WRITE_FILE_DIRECTLY, &init);
  if (!rv) rv = exr_add_part(ctxt, "seed", tiled ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE,
                             &part);
  if (!rv) rv = exr_initialize_required_attr_simple(ctxt, part, w, h, compression);
  for (const auto &c : channels)
    if (!rv) rv = exr_add_channel(ctxt, part, c.name, c.type, EXR_PERCEPTUALLY_LINEAR, 1, 1);
  if (!rv && tiled)
    rv = exr_set_tile_descriptor(ctxt, part, uint32_t(tile_w), uint32_t(tile_h),
                                 EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
  if (!rv) rv = exr_write_header(ctxt);
  // Pixel (x, y) of channel c: a small ramp, distinct per channel.
  std::vector<float> image(size_t(w) * h * channels.size());
  for (size_t c = 0; c < channels.size(); c++)
    for (int i = 0; i < w * h; i++) image[c * w * h + i] = 0.25f * float(c + 1) + 0.01f * float(i);
  exr_encode_pipeline_t encode = {};  // EXR_ENCODE_PIPELINE_INITIALIZER, without the warning
  bool initialised = false;
  std::vector<exr_chunk_info_t> chunks;
  int32_t lines = 1;
  if (!rv && !tiled) rv = exr_get_scanlines_per_chunk(ctxt, part, &lines);
  if (!tiled)
    for (int y = 0; !rv && y < h; y += lines) {
      exr_chunk_info_t chunk;
      rv = exr_write_scanline_chunk_info(ctxt, part, y, &chunk);
      chunks.push_back(chunk);
    }
  else
    for (int ty = 0; !rv && ty * tile_h < h; ty++)
      for (int tx = 0; !rv && tx * tile_w < w; tx++) {
        exr_chunk_info_t chunk;
        rv = exr_write_tile_chunk_info(ctxt, part, tx, ty, 0, 0, &chunk);
        chunks.push_back(chunk);
      }
  for (const exr_chunk_info_t &chunk : chunks) {
    if (rv) break;
    rv = initialised ? exr_encoding_update(ctxt, part, &chunk, &encode)
                     : exr_encoding_initialize(ctxt, part, &chunk, &encode);
    if (rv) break;
    for (int c = 0; c < encode.channel_count; c++) {
      exr_coding_channel_info_t *info = &encode.channels[c];
      size_t source = 0;
      for (size_t s = 0; s < channels.size(); s++)
        if (!std::strcmp(channels[s].name, info->channel_name)) source = s;
      // OpenEXR 3.1 Core gives a tile's start_x/start_y as tile indices, a scanline
      // chunk's start_y as a row.
      const size_t x0 = tiled ? size_t(chunk.start_x) * tile_w : 0;
      const size_t y0 = tiled ? size_t(chunk.start_y) * tile_h : size_t(chunk.start_y);
      info->encode_from_ptr =
          reinterpret_cast<const uint8_t *>(&image[source * w * h + y0 * w + x0]);
      info->user_pixel_stride = sizeof(float);
      info->user_line_stride = int32_t(sizeof(float) * size_t(w));
      info->user_bytes_per_element = sizeof(float);
      info->user_data_type = EXR_PIXEL_FLOAT;
    }
    if (!initialised) {
      initialised = true;
      rv = exr_encoding_choose_default_routines(ctxt, part, &encode);
      if (rv) break;
    }
    rv = exr_encoding_run(ctxt, part, &encode);
  }
  if (initialised) exr_encoding_destroy(ctxt, &encode);
  exr_result_t finish = ctxt ? exr_finish(&ctxt) : EXR_ERR_SUCCESS;
  if (rv || finish)
    fail(std::string(name) + ": " + exr_get_default_error_message(rv ? rv : finish));
  FILE *f = std::fopen(path.c_str(), "rb");
  std::vector<unsigned char> body;
  for (int ch; f && (ch = std::fgetc(f)) != EOF;) body.push_back(uint8_t(ch));
  if (f) std::fclose(f);
  std::remove(path.c_str());
  write_bytes(root + "/fogmap_exr/" + name, &channel_byte, 1, body.data(), body.size());
}

void exrs() {
  exr("y_float_none_5x3.exr", 0, 5, 3, {{"Y", EXR_PIXEL_FLOAT}}, EXR_COMPRESSION_NONE);
  exr("y_half_zip_4x20.exr", 1, 4, 20, {{"Y", EXR_PIXEL_HALF}}, EXR_COMPRESSION_ZIP);
  exr("rgb_half_rle_3x3.exr", 2, 3, 3,
      {{"B", EXR_PIXEL_HALF}, {"G", EXR_PIXEL_HALF}, {"R", EXR_PIXEL_HALF}},
      EXR_COMPRESSION_RLE);
  exr("rgba_float_zips_2x2.exr", 5, 2, 2,
      {{"A", EXR_PIXEL_FLOAT}, {"B", EXR_PIXEL_FLOAT}, {"G", EXR_PIXEL_FLOAT},
       {"R", EXR_PIXEL_FLOAT}},
      EXR_COMPRESSION_ZIPS);
  exr("density_piz_8x8.exr", 6, 8, 8, {{"density", EXR_PIXEL_HALF}}, EXR_COMPRESSION_PIZ);
  exr("y_pxr24_4x4.exr", 1, 4, 4, {{"Y", EXR_PIXEL_FLOAT}}, EXR_COMPRESSION_PXR24);
  exr("y_b44_4x4.exr", 1, 4, 4, {{"Y", EXR_PIXEL_HALF}}, EXR_COMPRESSION_B44);
  exr("y_uint_2x2.exr", 1, 2, 2, {{"Y", EXR_PIXEL_UINT}}, EXR_COMPRESSION_NONE);  // refused
  exr("y_tiled_none_6x5.exr", 1, 6, 5, {{"Y", EXR_PIXEL_FLOAT}}, EXR_COMPRESSION_NONE, 4, 4);
  exr("ry_tiled_zip_9x7.exr", 2, 9, 7, {{"R", EXR_PIXEL_HALF}, {"Y", EXR_PIXEL_FLOAT}},
      EXR_COMPRESSION_ZIP, 4, 3);
}

// ---- VDB (fuzz_vdb: the file as it is) ----

void vdb_dense(const char *name, int nx, int ny, int nz, int pattern, vdb_write_desc desc) {
  std::vector<float> values(size_t(nx) * ny * nz);
  for (size_t i = 0; i < values.size(); i++)
    values[i] = pattern == 0   ? 0.5f                                   // constant
                : pattern == 1 ? float(i % 7) * 0.125f                  // sparse ramp
                               : (i % 5 == 0 ? -0.25f : float(i % 3));  // negatives
  vdb_dense_grid grid = {};
  grid.dim[0] = nx, grid.dim[1] = ny, grid.dim[2] = nz;
  grid.index_min[0] = -2, grid.index_min[1] = 0, grid.index_min[2] = 3;
  for (int a = 0; a < 3; a++) grid.voxel_size[a] = 0.25, grid.translation[a] = 0.5 * a;
  grid.values = values.data();
  fog_error err;
  const std::string path = root + "/vdb/" + name;
  if (vdb_write_dense(path.c_str(), &grid, &desc, &err)) fail(err.message);
  std::printf("%s\n", path.c_str());
}

template <typename GridT>
void vdb_typed(const char *name, typename GridT::ValueType value, bool second_grid) {
  typename GridT::Ptr grid = GridT::create();
  grid->setName("density");
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
  auto acc = grid->getAccessor();
  for (int i = 0; i < 3; i++) acc.setValueOn(openvdb::Coord(i, 1, 2), value);
  openvdb::GridPtrVec grids{grid};
  if (second_grid) {
    openvdb::FloatGrid::Ptr t = openvdb::FloatGrid::create();
    t->setName("temperature");
    t->tree().setValueOn(openvdb::Coord(0, 0, 0), 2.0f);
    grids.push_back(t);
  }
  const std::string path = root + "/vdb/" + name;
  openvdb::io::File file(path);
  file.setCompression(openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK);
  file.write(grids);
  file.close();
  std::printf("%s\n", path.c_str());
}

// Three grids (float, vec3s, float as half) as io::Stream writes them: no grid offsets,
// each grid inline after its descriptor.
void vdb_stream(const char *name) {
  openvdb::FloatGrid::Ptr density = openvdb::FloatGrid::create();
  density->setName("density");
  for (int i = 0; i < 20; i++) density->tree().setValueOn(openvdb::Coord(i, i % 3, -i), 0.5f + i);
  openvdb::Vec3SGrid::Ptr velocity = openvdb::Vec3SGrid::create();
  velocity->setName("velocity");
  velocity->tree().setValueOn(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1, 2, 3));
  openvdb::FloatGrid::Ptr half = openvdb::FloatGrid::create();
  half->setName("half");
  half->setSaveFloatAsHalf(true);
  half->tree().setValueOn(openvdb::Coord(100, 0, 0), 2.0f);
  const std::string path = root + "/vdb/" + name;
  std::ofstream os(path, std::ios::binary);
  openvdb::io::Stream(os).write(openvdb::GridPtrVec{density, velocity, half});
  if (!os.good()) fail("cannot write " + path);
  std::printf("%s\n", path.c_str());
}

void vdbs() {
  openvdb::initialize();
  vdb_dense("ramp_zip_4x4x4.vdb", 4, 4, 4, 1, {nullptr, 0, 0, VDB_COMPRESSION_ZIP});
  vdb_dense("ramp_zip_half_5x3x2.vdb", 5, 3, 2, 1, {nullptr, 1, 0, VDB_COMPRESSION_ZIP});
  vdb_dense("negative_blosc_3x3x3.vdb", 3, 3, 3, 2, {nullptr, 0, 0, VDB_COMPRESSION_BLOSC});
  vdb_dense("tiles_blosc_16x8x8.vdb", 16, 8, 8, 0, {nullptr, 0, 1, VDB_COMPRESSION_BLOSC});
  vdb_dense("smoke_grid_zip_2x2x2.vdb", 2, 2, 2, 1, {"smoke", 0, 0, VDB_COMPRESSION_ZIP});
  // (No uncompressed seeds: OpenVDB writes a 4x4x4 grid uncompressed in 318 KB, its
  // internal nodes in full, and the largest seed sets libFuzzer's input size.)
  // A double grid (read like a float grid). (regressions/vdb/double_grid_past_float_range.vdb
  // is this file with the value 1e300, which float cannot hold.)
  vdb_typed<openvdb::DoubleGrid>("double_zip.vdb", 0.75, false);
  // A vector grid named density (refused: not scalar), beside a float grid.
  vdb_typed<openvdb::Vec3SGrid>("vec3_density_zip.vdb", openvdb::Vec3s(1, 2, 3), true);
  vdb_stream("stream_three_grids.vdb");
}

// ---- command lines (fuzz_options: byte 0 even = import, odd = design; NUL-separated) ----

void command(const char *name, unsigned char parser, std::vector<std::string> args) {
  std::string body;
  for (const auto &a : args) body += a, body += '\0';
  write_bytes(root + "/options/" + name, &parser, 1, body.data(), body.size());
}

void commands() {
  command("import_full", 0,
          {"data/fluid_data_####.vdb", "--out", "out", "--grid", "density", "--frames", "1-48",
           "--skip-missing", "--max-voxels", "1e6", "--up", "y", "--scale", "2.5", "--offset",
           "1,-2,3.5", "--config", "none", "--resolution", "256", "--name", "fog",
           "--profile", "exponential", "--profile-knots", "16", "--profile-degree", "0",
           "--profile-per", "frame", "--report", "--report-frame", "12", "--report-rays", "64",
           "--verbose"});
  command("import_list", 0, {"a.vdb", "b_%04d.vdb", "dir", "--list", "--frames", "7"});
  command("import_cell", 0, {"x.vdb", "--out", "o", "--cell", "0.125", "--profile", "bspline"});
  command("import_help", 0, {"--help"});
  command("import_bad", 0, {"--frames", "5-2", "--up", "x", "--name", "a/b"});
  command("design_values", 1,
          {"--size", "256x128", "--blob", "10,20,3.5,0.5", "--velocity", "1e3,-2", "--seed",
           "2147483647", "--octaves", "30", "--out", "x.PNG", "--blobs", "256", "--gain", "nan"});
  command("design_bad", 1, {"0x10", "1,2,", "inf", "-0", "99999999999999999999", "a.exr"});
}

}  // namespace

int main(int argc, char **argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_seeds CORPUS_DIR (tests/fuzz/corpus)\n");
    return 2;
  }
  root = argv[1];
  for (const char *d : {"fogmap_png", "fogmap_exr", "vdb", "options"})
    if (std::system(("mkdir -p '" + root + "/" + d + "'").c_str()) != 0) fail("mkdir");
  pngs();
  exrs();
  vdbs();
  commands();
  return 0;
}
