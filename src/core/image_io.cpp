#include "proxima/core/image_io.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_FAILURE_USERMSG
// stb decodes PNG only: the least decoder code facing untrusted files. stb's JPEG decoder
// (Debian's 2022-09 stb) writes past its Huffman size table on a malformed DHT
// segment; JPEG goes through libjpeg-turbo's TurboJPEG API instead.
#define STBI_ONLY_PNG
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <tinyexr.h>
#include <turbojpeg.h>

#include "proxima/core/atomic_file.h"
#include "proxima/core/error.h"
#include "proxima/core/limits.h"

namespace proxima {

namespace fs = std::filesystem;

float srgb_to_linear(float s) {
  return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float l) {
  return l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

namespace {

uint8_t to_byte(float v) {
  if (!(v > 0.0f)) return 0;  // also maps NaN to 0
  return uint8_t(std::lround(std::min(v, 1.0f) * 255.0f));
}

// Devices and FIFOs would block or never end; only regular files are images.
void check_regular_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail_missing_file(path.string() + ": no such file");
  if (!fs::is_regular_file(path, ec)) fail_input(path.string() + ": not a regular file");
}

// stb_image grows its buffer to a chunk's declared length before reading it, so a
// 100-byte PNG declaring a 1 GiB IDAT chunk allocates 2 GiB. Chunks
// must fit in the file.
void check_png_chunks(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char sig[8] = {};
  if (!in.read(sig, 8) || std::memcmp(sig, "\x89PNG\r\n\x1a\n", 8) != 0) return;  // not a PNG
  std::error_code ec;
  const uint64_t size = fs::file_size(path, ec);
  if (ec) return;  // stb reports the unreadable file
  uint64_t pos = 8;
  unsigned char header[8];
  while (pos + 8 <= size && in.read(reinterpret_cast<char*>(header), 8)) {  // stb reads any whole header
    const uint64_t length = uint64_t(header[0]) << 24 | uint64_t(header[1]) << 16 | uint64_t(header[2]) << 8 | header[3];
    if (pos + 12 + length > size)
      fail_input(path.string() + ": cannot read image: PNG chunk of " + std::to_string(length) +
                 " bytes runs past the end of the file");
    if (std::memcmp(header + 4, "IEND", 4) == 0) return;
    pos += 12 + length;
    in.seekg(std::streamoff(pos));
  }
}

void check_channels(const fs::path& path, int channels, int lo, int hi) {
  if (channels < lo || channels > hi)
    fail_input(path.string() + ": cannot store an image with " + std::to_string(channels) + " channels");
}

enum class ImageKind { kPng, kJpeg, kUnknown };

// By content, not by extension: a texture named .png may hold a JPEG and vice versa.
ImageKind image_kind(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[8] = {};
  in.read(reinterpret_cast<char*>(magic), 8);
  const auto got = size_t(in.gcount());
  if (got >= 3 && magic[0] == 0xFF && magic[1] == 0xD8 && magic[2] == 0xFF) return ImageKind::kJpeg;  // SOI, then a marker
  if (got == 8 && std::memcmp(magic, "\x89PNG\r\n\x1a\n", 8) == 0) return ImageKind::kPng;
  return ImageKind::kUnknown;
}

// 8-bit sRGB samples, `in_channels` per pixel (3, or 4 with a linear alpha), → linear floats
// with `channels` channels (3 or 4; a missing alpha is 1).
ImageF srgb8_to_linear(const unsigned char* src, int w, int h, int in_channels, int channels) {
  static const auto lut = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgb_to_linear(float(i) / 255.0f);
    return t;
  }();
  ImageF img(w, h, channels);
  auto dst = img.data();
  const size_t n = img.pixel_count();
  for (size_t p = 0; p < n; ++p) {
    const unsigned char* s = src + p * size_t(in_channels);
    float* d = dst.data() + p * size_t(channels);
    for (int c = 0; c < 3; ++c) d[c] = lut[s[c]];
    if (channels == 4) d[3] = in_channels == 4 ? float(s[3]) / 255.0f : 1.0f;
  }
  return img;
}

// JPEG through TurboJPEG. Warnings (a truncated file, corrupt entropy data) are errors:
// libjpeg would otherwise fill the missing part with gray and succeed. Progressive files
// are limited to 500 scans (TJFLAG_LIMITSCANS), the known way to make a small file decode
// for minutes.
ImageF read_jpeg_linear(const fs::path& path, int channels) {
  std::error_code ec;
  const uint64_t size = fs::file_size(path, ec);
  if (ec) fail_input(path.string() + ": cannot read image: " + ec.message());
  // The whole file is held in memory while decoding: one larger than the memory limit is
  // refused before it is read.
  if (size > limits().max_memory_mb << 20)
    fail_input(path.string() + ": cannot read image: file of " + std::to_string(size >> 20) +
               " MiB exceeds the memory limit (--max-memory-mb, PROXIMA_MAX_MEMORY_MB)");
  std::vector<unsigned char> bytes(size);
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
    fail_input(path.string() + ": cannot read image: read error");

  const std::unique_ptr<void, int (*)(tjhandle)> tj(tjInitDecompress(), tjDestroy);
  if (!tj) fail_input(path.string() + ": cannot read JPEG: " + tjGetErrorStr2(nullptr));
  auto fail = [&] { fail_input(path.string() + ": cannot read JPEG: " + tjGetErrorStr2(tj.get())); };
  int w = 0, h = 0, subsamp = 0, colorspace = 0;
  if (tjDecompressHeader3(tj.get(), bytes.data(), (unsigned long)size, &w, &h, &subsamp, &colorspace) != 0) fail();
  if (w <= 0 || h <= 0) fail_input(path.string() + ": cannot read JPEG: empty image");
  // The header's size is checked before decoding. The budget counts the float image plus one
  // float's worth per pixel for the 8-bit decode buffer (≤ 4 B) and libjpeg's progressive
  // coefficient arrays (≤ 8 B, freed before the float image is made).
  check_image_budget(path.string(), uint64_t(w), uint64_t(h), uint64_t(channels) + 1);

  // CMYK files (Adobe's, inverted as libjpeg-turbo stores them) are decoded as CMYK and
  // converted here: TurboJPEG has no CMYK → RGB conversion. Gray and YCbCr decode to RGB.
  const bool cmyk = colorspace == TJCS_CMYK || colorspace == TJCS_YCCK;
  const int format = cmyk ? TJPF_CMYK : TJPF_RGB;
  const int pixel_size = cmyk ? 4 : 3;
  std::vector<unsigned char> pixels(size_t(w) * size_t(h) * size_t(pixel_size));
  if (tjDecompress2(tj.get(), bytes.data(), (unsigned long)size, pixels.data(), w, 0, h, format,
                    TJFLAG_STOPONWARNING | TJFLAG_LIMITSCANS) != 0)
    fail();
  if (cmyk) {
    // libjpeg-turbo's own rule (cmyk.h): R = C·K / 255, in place, RGB packed into the front.
    const size_t n = size_t(w) * size_t(h);
    for (size_t p = 0; p < n; ++p) {
      const unsigned char* s = pixels.data() + 4 * p;
      const unsigned k = s[3];
      unsigned char rgb[3];
      for (int c = 0; c < 3; ++c) rgb[c] = (unsigned char)((unsigned(s[c]) * k + 127) / 255);
      std::memcpy(pixels.data() + 3 * p, rgb, 3);
    }
  }
  return srgb8_to_linear(pixels.data(), w, h, 3, channels);
}

}  // namespace

void write_png(const fs::path& path, const ImageU8& image) {
  check_channels(path, image.channels(), 1, 4);
  if (image.empty()) fail_input(path.string() + ": cannot write an empty image");
  write_atomically(path, [&](const fs::path& tmp) {
    int ok = stbi_write_png(tmp.c_str(), image.width(), image.height(), image.channels(),
                            image.data().data(), image.width() * image.channels());
    if (!ok) fail_input(path.string() + ": cannot write PNG");
  });
}

void write_png_linear(const fs::path& path, const ImageF& linear) {
  int c = linear.channels();
  check_channels(path, c, 1, 4);
  ImageU8 out(linear.width(), linear.height(), c);
  auto src = linear.data();
  auto dst = out.data();
  bool has_alpha = c == 4;
  for (size_t i = 0; i < src.size(); ++i) {
    bool alpha = has_alpha && (i % 4 == 3);
    dst[i] = to_byte(alpha ? src[i] : linear_to_srgb(src[i]));
  }
  write_png(path, out);
}

ImageF read_image_linear(const fs::path& path, int channels) {
  check_channels(path, channels, 3, 4);
  check_regular_file(path);
  switch (image_kind(path)) {
    case ImageKind::kJpeg: return read_jpeg_linear(path, channels);
    case ImageKind::kPng: break;
    case ImageKind::kUnknown: fail_input(path.string() + ": cannot read image: not a PNG or JPEG file");
  }
  check_png_chunks(path);
  int w = 0, h = 0, n = 0;
  // The header's size is checked before decoding: a small PNG can claim gigapixels.
  if (!stbi_info(path.c_str(), &w, &h, &n))
    fail_input(path.string() + ": cannot read image: " + stbi_failure_reason());
  check_image_budget(path.string(), uint64_t(w), uint64_t(h), uint64_t(channels));
  stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &n, channels);
  if (!pixels) fail_input(path.string() + ": cannot read image: " + stbi_failure_reason());
  const std::unique_ptr<stbi_uc, void (*)(void*)> owned(pixels, stbi_image_free);
  return srgb8_to_linear(pixels, w, h, channels, channels);
}

void write_exr(const fs::path& path, const ImageF& image) {
  int c = image.channels();
  check_channels(path, c, 1, 4);
  if (image.empty()) fail_input(path.string() + ": cannot write an empty image");
  // tinyexr wants planar channels, named in alphabetical order (A, B, G, R).
  static const char* kNames1[] = {"Y"};
  static const char* kNames3[] = {"B", "G", "R"};
  static const char* kNames4[] = {"A", "B", "G", "R"};
  static const char* kNames2[] = {"U", "V"};  // 2-channel buffers (e.g. barycentrics)
  const char** names = c == 1 ? kNames1 : c == 2 ? kNames2 : c == 3 ? kNames3 : kNames4;
  // Source channel of each stored (alphabetical) channel.
  int source[4];
  if (c == 1) source[0] = 0;
  if (c == 2) { source[0] = 0; source[1] = 1; }
  if (c == 3) { source[0] = 2; source[1] = 1; source[2] = 0; }
  if (c == 4) { source[0] = 3; source[1] = 2; source[2] = 1; source[3] = 0; }

  size_t n = image.pixel_count();
  std::vector<std::vector<float>> planes(static_cast<size_t>(c), std::vector<float>(n));
  auto src = image.data();
  for (int k = 0; k < c; ++k)
    for (size_t i = 0; i < n; ++i) planes[size_t(k)][i] = src[i * size_t(c) + size_t(source[k])];
  std::vector<float*> plane_ptrs;
  for (auto& p : planes) plane_ptrs.push_back(p.data());

  EXRHeader header;
  InitEXRHeader(&header);
  EXRImage exr;
  InitEXRImage(&exr);
  exr.num_channels = c;
  exr.images = reinterpret_cast<unsigned char**>(plane_ptrs.data());
  exr.width = image.width();
  exr.height = image.height();
  std::vector<EXRChannelInfo> infos(static_cast<size_t>(c));
  std::vector<int> types(size_t(c), TINYEXR_PIXELTYPE_FLOAT);
  for (int k = 0; k < c; ++k) {
    std::snprintf(infos[size_t(k)].name, sizeof(infos[size_t(k)].name), "%s", names[k]);
  }
  header.num_channels = c;
  header.channels = infos.data();
  header.pixel_types = types.data();
  header.requested_pixel_types = types.data();
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;

  write_atomically(path, [&](const fs::path& tmp) {
    const char* err = nullptr;
    int ret = SaveEXRImageToFile(&exr, &header, tmp.c_str(), &err);
    if (ret != TINYEXR_SUCCESS) {
      std::string msg = err ? err : "unknown error";
      if (err) FreeEXRErrorMessage(err);
      fail_input(path.string() + ": cannot write EXR: " + msg);
    }
  });
}

ImageF read_exr(const fs::path& path) {
  check_regular_file(path);
  EXRVersion version;
  if (ParseEXRVersionFromFile(&version, path.c_str()) != TINYEXR_SUCCESS)
    fail_input(path.string() + ": not an EXR file");
  // tinyexr's C structs own memory; free them on every exit, including throws.
  EXRHeader header;
  InitEXRHeader(&header);
  EXRImage exr;
  InitEXRImage(&exr);
  struct Release {
    EXRHeader& h;
    EXRImage& i;
    ~Release() {
      FreeEXRImage(&i);
      FreeEXRHeader(&h);
    }
  } release{header, exr};
  auto fail = [&](const char* err, const char* fallback) {
    std::string msg = err ? err : fallback;
    if (err) FreeEXRErrorMessage(err);
    fail_input(path.string() + ": cannot read EXR: " + msg);
  };
  const char* err = nullptr;
  if (ParseEXRHeaderFromFile(&header, &version, path.c_str(), &err) != TINYEXR_SUCCESS) fail(err, "bad header");
  // The header's size is checked before decoding: a small file can claim gigapixels.
  const EXRBox2i& dw = header.data_window;
  const int64_t w = int64_t(dw.max_x) - dw.min_x + 1, h = int64_t(dw.max_y) - dw.min_y + 1;
  if (w <= 0 || h <= 0) fail(nullptr, "empty data window");
  check_image_budget(path.string(), uint64_t(w), uint64_t(h), uint64_t(std::max(header.num_channels, 1)));
  for (int k = 0; k < header.num_channels; ++k) header.requested_pixel_types[k] = TINYEXR_PIXELTYPE_FLOAT;
  if (LoadEXRImageFromFile(&exr, &header, path.c_str(), &err) != TINYEXR_SUCCESS) {
    InitEXRImage(&exr);  // tinyexr frees a half-decoded image itself but leaves its pointers set
    fail(err, "bad data");
  }
  int c = exr.num_channels;
  if (c < 1 || c > 4 || !exr.images)
    fail_input(path.string() + ": unsupported EXR layout (tiled or " + std::to_string(c) + " channels)");
  // Stored alphabetically; put R G B A (or U V / Y) back in interleaved order.
  auto rank = [](const std::string& name) {
    static const char* order[] = {"R", "G", "B", "A", "U", "V", "Y"};
    for (int i = 0; i < 7; ++i)
      if (name == order[i]) return i;
    return 7;
  };
  std::vector<int> perm(static_cast<size_t>(c));
  for (int k = 0; k < c; ++k) perm[size_t(k)] = k;
  std::sort(perm.begin(), perm.end(), [&](int a, int b) {
    return rank(header.channels[a].name) < rank(header.channels[b].name);
  });
  ImageF img(exr.width, exr.height, c);
  auto dst = img.data();
  size_t n = img.pixel_count();
  for (int k = 0; k < c; ++k) {
    const float* plane = reinterpret_cast<const float*>(exr.images[perm[size_t(k)]]);
    for (size_t i = 0; i < n; ++i) dst[i * size_t(c) + size_t(k)] = plane[i];
  }
  return img;
}

}  // namespace proxima
