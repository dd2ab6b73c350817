// JPEG files for the tests, made with libjpeg-turbo's encoder (tjCompress2), so no binary
// file is committed.
#pragma once

#include <turbojpeg.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace proxima {

struct JpegOptions {
  int pixel_format = TJPF_RGB;  // of `pixels`: TJPF_RGB, TJPF_GRAY or TJPF_CMYK
  int subsampling = TJSAMP_444;
  int quality = 100;
  int flags = 0;  // e.g. TJFLAG_PROGRESSIVE
};

// `pixels`: width·height pixels of tjPixelSize[pixel_format] bytes, row 0 at the top.
inline std::string encode_jpeg(const std::vector<uint8_t>& pixels, int width, int height,
                               const JpegOptions& o = {}) {
  tjhandle tj = tjInitCompress();
  unsigned char* buf = nullptr;
  unsigned long size = 0;
  const int rc = tjCompress2(tj, pixels.data(), width, 0, height, o.pixel_format, &buf, &size,
                             o.subsampling, o.quality, o.flags);
  const std::string error = rc != 0 ? tjGetErrorStr2(tj) : "";
  std::string bytes = rc == 0 ? std::string(reinterpret_cast<const char*>(buf), size) : "";
  tjFree(buf);
  tjDestroy(tj);
  if (rc != 0) throw std::runtime_error("tjCompress2: " + error);
  return bytes;
}

// libjpeg-turbo's own 8-bit RGB decode of a JPEG (a second path to the same pixels).
inline std::vector<uint8_t> decode_jpeg_rgb(const std::string& jpeg, int width, int height) {
  std::vector<uint8_t> px(size_t(width) * size_t(height) * 3);
  tjhandle tj = tjInitDecompress();
  const int rc = tjDecompress2(tj, reinterpret_cast<const unsigned char*>(jpeg.data()), jpeg.size(), px.data(),
                               width, 0, height, TJPF_RGB, 0);
  tjDestroy(tj);
  if (rc != 0) throw std::runtime_error("tjDecompress2 failed");
  return px;
}

// A smooth RGB test picture: red grows to the right, green downwards, blue is constant.
inline std::vector<uint8_t> gradient_rgb(int width, int height) {
  std::vector<uint8_t> px;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      px.push_back(uint8_t(40 + 160 * x / (width - 1)));
      px.push_back(uint8_t(30 + 180 * y / (height - 1)));
      px.push_back(120);
    }
  return px;
}

// Offset of the frame header (SOF0..SOF2 marker) in a JPEG, or npos: walks the marker
// segments that precede it (each FF xx, then a 2-byte big-endian length).
inline size_t jpeg_sof_offset(const std::string& jpeg) {
  size_t i = 2;  // after SOI
  while (i + 4 <= jpeg.size() && uint8_t(jpeg[i]) == 0xFF) {
    const uint8_t marker = uint8_t(jpeg[i + 1]);
    if (marker >= 0xC0 && marker <= 0xC2) return i;
    i += 2 + (size_t(uint8_t(jpeg[i + 2])) << 8 | uint8_t(jpeg[i + 3]));
  }
  return std::string::npos;
}

// The same JPEG with the frame header declaring width × height (entropy data unchanged).
inline std::string with_declared_size(std::string jpeg, int width, int height) {
  const size_t sof = jpeg_sof_offset(jpeg);
  if (sof == std::string::npos) throw std::runtime_error("no SOF marker");
  // FF Cn, length (2), precision (1), height (2), width (2).
  jpeg[sof + 5] = char(height >> 8), jpeg[sof + 6] = char(height & 0xFF);
  jpeg[sof + 7] = char(width >> 8), jpeg[sof + 8] = char(width & 0xFF);
  return jpeg;
}

}  // namespace proxima
