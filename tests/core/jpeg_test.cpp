// read_image_linear on JPEG files (libjpeg-turbo): pixels, color spaces, and bad files.
#include "jpeg_test.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "proxima/core/camera.h"
#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/limits.h"
#include "test_util.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

// Largest difference, in 8-bit sRGB levels, between a decoded image and 8-bit sRGB source
// pixels of `source_channels` per pixel (1: gray, compared with R, G and B).
int max_level_error(const ImageF& img, const std::vector<uint8_t>& src, int source_channels) {
  int worst = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const size_t i = (size_t(y) * size_t(img.width()) + size_t(x)) * size_t(source_channels);
        const int want = src[i + size_t(source_channels == 1 ? 0 : c)];
        const int got = int(std::lround(linear_to_srgb(img.at(x, y, c)) * 255.0f));
        worst = std::max(worst, std::abs(got - want));
      }
  return worst;
}

TEST(Jpeg, RgbDecodesCloseToTheSource) {
  TempDir dir;
  const int w = 24, h = 16;
  const auto src = gradient_rgb(w, h);
  const std::string jpeg = encode_jpeg(src, w, h);  // quality 100, 4:4:4
  write_file(dir.path / "a.jpg", jpeg);
  const ImageF img = read_image_linear(dir.path / "a.jpg");
  ASSERT_EQ(img.width(), w);
  ASSERT_EQ(img.height(), h);
  ASSERT_EQ(img.channels(), 3);
  // Exactly libjpeg-turbo's 8-bit pixels, sRGB-decoded…
  const std::vector<uint8_t> direct = decode_jpeg_rgb(jpeg, w, h);
  for (size_t i = 0; i < direct.size(); ++i)
    ASSERT_EQ(img.data()[i], srgb_to_linear(direct[i] / 255.0f)) << "sample " << i;
  // …which are the source's within the loss left at quality 100 (YCbCr and DCT rounding:
  // measured 3 levels on this gradient; a wrong channel order or transfer is off by tens).
  EXPECT_LE(max_level_error(img, src, 3), 3);
  // Row 0 is the top row: green grows downwards, red to the right.
  EXPECT_GT(img.at(0, h - 1, 1), img.at(0, 0, 1));
  EXPECT_GT(img.at(w - 1, 0, 0), img.at(0, 0, 0));
  // Linear, not sRGB: mid-gray sRGB 120 of the blue channel is about 0.19 linear.
  EXPECT_NEAR(img.at(w / 2, h / 2, 2), srgb_to_linear(120.0f / 255.0f), 0.01f);
}

TEST(Jpeg, ChromaSubsampledDecodesCloseToTheSource) {
  TempDir dir;
  const int w = 32, h = 32;
  const auto src = gradient_rgb(w, h);
  for (int subsampling : {TJSAMP_422, TJSAMP_420}) {
    write_file(dir.path / "s.jpg", encode_jpeg(src, w, h, {.subsampling = subsampling, .quality = 90}));
    const ImageF img = read_image_linear(dir.path / "s.jpg");
    ASSERT_EQ(img.width(), w);
    EXPECT_LE(max_level_error(img, src, 3), 6) << "subsampling " << subsampling;
  }
}

// Progressive coding reorders the same quantized coefficients: the same pixels as baseline.
TEST(Jpeg, ProgressiveDecodesToTheSamePixelsAsBaseline) {
  TempDir dir;
  const int w = 40, h = 24;
  const auto src = gradient_rgb(w, h);
  write_file(dir.path / "base.jpg", encode_jpeg(src, w, h, {.quality = 85}));
  write_file(dir.path / "prog.jpg", encode_jpeg(src, w, h, {.quality = 85, .flags = TJFLAG_PROGRESSIVE}));
  const ImageF base = read_image_linear(dir.path / "base.jpg");
  const ImageF prog = read_image_linear(dir.path / "prog.jpg");
  ASSERT_EQ(prog.width(), w);
  EXPECT_TRUE(prog == base);
}

TEST(Jpeg, GrayDecodesToEqualChannels) {
  TempDir dir;
  const int w = 16, h = 16;
  std::vector<uint8_t> src;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) src.push_back(uint8_t(20 + 10 * x + 3 * y));
  write_file(dir.path / "g.jpg", encode_jpeg(src, w, h, {.pixel_format = TJPF_GRAY, .subsampling = TJSAMP_GRAY}));
  const ImageF img = read_image_linear(dir.path / "g.jpg");
  ASSERT_EQ(img.channels(), 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      EXPECT_EQ(img.at(x, y, 0), img.at(x, y, 1));
      EXPECT_EQ(img.at(x, y, 0), img.at(x, y, 2));
    }
  EXPECT_LE(max_level_error(img, src, 1), 2);
}

// CMYK files are stored inverted (Adobe's convention, which libjpeg-turbo follows): with
// K = 255 (no black ink) the stored C, M, Y bytes are R, G, B; K scales them.
TEST(Jpeg, CmykDecodesByLibjpegTurbosRule) {
  TempDir dir;
  const int w = 16, h = 16;
  std::vector<uint8_t> src, expected;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t c = uint8_t(60 + 8 * x), m = uint8_t(200 - 6 * y), ye = 140, k = y < h / 2 ? 255 : 128;
      for (uint8_t v : {c, m, ye, k}) src.push_back(v);
      for (uint8_t v : {c, m, ye}) expected.push_back(uint8_t((v * k + 127) / 255));
    }
  write_file(dir.path / "cmyk.jpg", encode_jpeg(src, w, h, {.pixel_format = TJPF_CMYK}));
  const ImageF img = read_image_linear(dir.path / "cmyk.jpg");
  ASSERT_EQ(img.width(), w);
  EXPECT_LE(max_level_error(img, expected, 3), 3);
}

TEST(Jpeg, FourChannelsHaveOpaqueAlpha) {
  TempDir dir;
  const auto src = gradient_rgb(8, 8);
  write_file(dir.path / "a.jpg", encode_jpeg(src, 8, 8));
  const ImageF img = read_image_linear(dir.path / "a.jpg", 4);
  ASSERT_EQ(img.channels(), 4);
  const ImageF rgb = read_image_linear(dir.path / "a.jpg", 3);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      EXPECT_EQ(img.at(x, y, 3), 1.0f);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, y, c), rgb.at(x, y, c));
    }
}

TEST(Jpeg, FormatIsChosenByContentNotByExtension) {
  TempDir dir;
  const auto src = gradient_rgb(8, 4);
  write_file(dir.path / "really_a_jpeg.png", encode_jpeg(src, 8, 4));
  EXPECT_LE(max_level_error(read_image_linear(dir.path / "really_a_jpeg.png"), src, 3), 2);
  write_png_linear(dir.path / "really_a_png.jpg", ImageF(3, 2, 3, 0.25f));
  const ImageF png = read_image_linear(dir.path / "really_a_png.jpg");
  EXPECT_EQ(png.width(), 3);
  EXPECT_NEAR(png.at(1, 1, 0), 0.25f, 0.01f);
}

TEST(Jpeg, NonImageNamedJpgIsAnInputErrorNamingTheFile) {
  TempDir dir;
  write_file(dir.path / "notes.jpg", "these are not pixels\n");
  const std::string error = error_of([&] { read_image_linear(dir.path / "notes.jpg"); });
  EXPECT_NE(error.find("notes.jpg: cannot read image: not a PNG or JPEG file"), std::string::npos) << error;
  write_file(dir.path / "empty.jpg", "");
  EXPECT_NE(error_of([&] { read_image_linear(dir.path / "empty.jpg"); }).find("empty.jpg"), std::string::npos);
}

// libjpeg only warns about a file that ends early and fills the rest with gray; proxima
// stops on the warning.
TEST(Jpeg, TruncatedFileIsAnInputErrorNamingTheFile) {
  TempDir dir;
  const int w = 64, h = 48;
  for (int flags : {0, TJFLAG_PROGRESSIVE}) {
    const std::string full = encode_jpeg(gradient_rgb(w, h), w, h, {.quality = 90, .flags = flags});
    write_file(dir.path / "full.jpg", full);
    ASSERT_EQ(read_image_linear(dir.path / "full.jpg").width(), w);
    const size_t header_end = jpeg_sof_offset(full) + 20;
    for (size_t keep : {full.size() - 2, full.size() - 40, full.size() / 2, header_end, size_t(3)}) {
      write_file(dir.path / "cut.jpg", full.substr(0, keep));
      const std::string error = error_of([&] { read_image_linear(dir.path / "cut.jpg"); });
      EXPECT_NE(error.find("cut.jpg: cannot read JPEG: "), std::string::npos)
          << "flags " << flags << ", kept " << keep << " of " << full.size() << " bytes: '" << error << "'";
    }
  }
}

TEST(Jpeg, HeaderDeclaring60000SquareIsRefusedBeforeDecoding) {
  TempDir dir;
  const std::string small = encode_jpeg(gradient_rgb(16, 16), 16, 16);
  write_file(dir.path / "huge.jpg", with_declared_size(small, 60000, 60000));
  const std::string error = error_of([&] { read_image_linear(dir.path / "huge.jpg"); });
  // The side check of check_image_budget, from the header: nothing was decoded.
  EXPECT_NE(error.find("huge.jpg: image of 60000x60000 pixels exceeds the maximum side " +
                       std::to_string(kMaxImageSide)),
            std::string::npos)
      << error;
}

TEST(Jpeg, HeaderOverTheMemoryLimitIsRefusedBeforeDecoding) {
  TempDir dir;
  const Limits saved = limits();
  set_limits({.max_triangles = saved.max_triangles, .max_memory_mb = 16});
  const std::string small = encode_jpeg(gradient_rgb(16, 16), 16, 16);
  write_file(dir.path / "big.jpg", with_declared_size(small, 4000, 3000));
  const std::string error = error_of([&] { read_image_linear(dir.path / "big.jpg"); });
  set_limits(saved);
  // 4000 × 3000 pixels × (3 + 1) floats: 183 MiB.
  EXPECT_NE(error.find("big.jpg: image of 4000x3000 pixels needs about 183 MiB, more than the limit of 16 MiB"),
            std::string::npos)
      << error;
}

// stb's JPEG decoder writes past its Huffman table on this 19-byte file
// (a DHT segment whose counts sum above 256). With its leading fill byte it is not a JPEG
// to the content check; without it libjpeg-turbo reads it and refuses it.
TEST(Jpeg, MalformedHuffmanTableIsAnInputError) {
  TempDir dir;
  const std::string dht("\xff\xff\xd8\xff\xff\xff\xc4\x00\x20\x00\xff\xff\xff\x05\xf0\x24\xff\x01\x00", 19);
  write_file(dir.path / "dht.jpg", dht);
  EXPECT_NE(error_of([&] { read_image_linear(dir.path / "dht.jpg"); }).find("dht.jpg: "), std::string::npos);
  write_file(dir.path / "dht2.jpg", dht.substr(1));
  EXPECT_NE(error_of([&] { read_image_linear(dir.path / "dht2.jpg"); }).find("dht2.jpg: cannot read JPEG: "),
            std::string::npos);
}

// Random byte changes after the SOI marker: each file decodes to its declared size with
// values in [0, 1], or is an InputError; nothing else (a crash, another exception).
TEST(Jpeg, CorruptedFilesDecodeOrFailCleanly) {
  TempDir dir;
  const int w = 32, h = 16;
  const std::string full = encode_jpeg(gradient_rgb(w, h), w, h, {.subsampling = TJSAMP_420, .quality = 80});
  std::mt19937 rng(7);
  int errors = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::string bytes = full;
    const int changes = 1 + int(rng() % 4);
    for (int k = 0; k < changes; ++k) bytes[3 + rng() % (bytes.size() - 3)] = char(rng());
    write_file(dir.path / "bad.jpg", bytes);
    try {
      const ImageF img = read_image_linear(dir.path / "bad.jpg");
      ASSERT_GT(img.width(), 0);
      ASSERT_EQ(img.data().size(), size_t(img.width()) * size_t(img.height()) * 3);
      for (float v : img.data()) ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
    } catch (const InputError& e) {
      ++errors;
      ASSERT_NE(std::string(e.what()).find("bad.jpg: "), std::string::npos) << e.what();
    }
  }
  // Both outcomes occur, so the loop tests both paths.
  EXPECT_GT(errors, 0);
  EXPECT_LT(errors, 300);
}

}  // namespace
}  // namespace proxima
