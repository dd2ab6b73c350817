#include "proxima/core/image_io.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "proxima/core/error.h"
#include "proxima/core/math.h"
#include "test_util.h"

namespace proxima {
namespace {

TEST(ImageIo, PngRoundTripThroughSrgb) {
  TempDir dir;
  ImageF img(5, 3, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = float(x + y * 5 + c) / 20.0f;
  write_png_linear(dir.path / "a.png", img);
  ImageF back = read_image_linear(dir.path / "a.png");
  ASSERT_EQ(back.width(), 5);
  ASSERT_EQ(back.height(), 3);
  for (size_t i = 0; i < img.data().size(); ++i) EXPECT_NEAR(back.data()[i], img.data()[i], 0.01f);
  // Row 0 is the top row: the brightest pixel is bottom right.
  EXPECT_GT(back.at(4, 2, 0), back.at(4, 0, 0));
}

TEST(ImageIo, ExrRoundTripIsExactIncludingInfinity) {
  TempDir dir;
  for (int channels : {1, 2, 3, 4}) {
    ImageF img(7, 4, channels);
    for (size_t i = 0; i < img.data().size(); ++i) img.data()[i] = float(i) * 0.37f - 3.0f;
    img.at(2, 1, 0) = kInf;
    auto path = dir.path / ("d" + std::to_string(channels) + ".exr");
    write_exr(path, img);
    ImageF back = read_exr(path);
    ASSERT_EQ(back.channels(), channels);
    EXPECT_TRUE(back == img);
  }
}

TEST(ImageIo, MissingDirectoryFailsWithoutLeavingFiles) {
  TempDir dir;
  ImageF img(2, 2, 3, 0.5f);
  EXPECT_THROW(write_png_linear(dir.path / "nope" / "a.png", img), InputError);
  EXPECT_THROW(read_image_linear(dir.path / "missing.png"), InputError);
  EXPECT_THROW(read_exr(dir.path / "missing.exr"), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path));
}

TEST(ImageIo, SrgbTransferInverts) {
  for (float v = 0.0f; v <= 1.0f; v += 0.01f) EXPECT_NEAR(srgb_to_linear(linear_to_srgb(v)), v, 1e-5f);
}

// An EXR whose pixel data fails to decode is freed once: tinyexr frees the half-decoded
// image itself, so read_exr must not free it again.
TEST(ImageIo, TruncatedExrFailsWithoutDoubleFree) {
  TempDir dir;
  ImageF img(64, 64, 3);
  for (size_t i = 0; i < img.data().size(); ++i) img.data()[i] = float(i % 97) / 7.0f;
  write_exr(dir.path / "full.exr", img);
  std::ifstream in(dir.path / "full.exr", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  for (size_t keep : {bytes.size() - 1, bytes.size() / 2, size_t(400)}) {
    std::ofstream(dir.path / "cut.exr", std::ios::binary) << bytes.substr(0, keep);
    EXPECT_THROW(read_exr(dir.path / "cut.exr"), InputError) << keep;
  }
}

// A PNG whose first IDAT chunk is empty makes stb_image call memcpy(NULL, …, 0), fatal
// under UBSan (make asan) unless image_io.cpp is built without that check: a plain decode
// error.
TEST(ImageIo, PngWithEmptyIdatChunkIsAnInputError) {
  TempDir dir;
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string("\0\0\0\x0dIHDR\0\0\0\x01\0\0\0\x01\x08\x02\0\0\0\0\0\0\0", 25);  // 1×1 RGB
  png += std::string("\0\0\0\0IDAT\0\0\0\0", 12);                                           // empty
  png += std::string("\0\0\0\0IEND\0\0\0\0", 12);
  std::ofstream(dir.path / "empty_idat.png", std::ios::binary) << png;
  EXPECT_THROW(read_image_linear(dir.path / "empty_idat.png"), InputError);
}

// A PNG declaring a 1 GiB IDAT chunk in a tiny file would make stb_image allocate 2 GiB
// before noticing the data is missing.
TEST(ImageIo, PngChunkLongerThanTheFileIsRejectedBeforeAllocating) {
  TempDir dir;
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string("\0\0\0\x0dIHDR\0\0\0\x01\0\0\0\x01\x08\x02\0\0\0\0\0\0\0", 25);  // 1×1 RGB
  png += std::string("\x40\0\0\0IDAT", 8) + "short";                                          // 1 GiB claimed
  std::ofstream(dir.path / "liar.png", std::ios::binary) << png;
  try {
    read_image_linear(dir.path / "liar.png");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("liar.png: cannot read image: PNG chunk of 1073741824 bytes runs past"),
              std::string::npos)
        << e.what();
  }
  // …also when the file ends right after the chunk's 8-byte header.
  std::ofstream(dir.path / "cut.png", std::ios::binary) << png.substr(0, png.size() - 5);
  EXPECT_THROW(read_image_linear(dir.path / "cut.png"), InputError);
  ImageF ok(3, 2, 3, 0.25f);
  write_png_linear(dir.path / "ok.png", ok);  // real files (several chunks) still read
  EXPECT_EQ(read_image_linear(dir.path / "ok.png").width(), 3);
}

}  // namespace
}  // namespace proxima
