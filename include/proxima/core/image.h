// Image<T>: an owning, row-major, interleaved-channel pixel array. Its pixels are a
// LargeBuffer: whole images of 2 MiB and more sit on huge pages (core/large_buffer.h).
// Conventions (DESIGN.md): row 0 is the top row; pixel (x, y) has its center at (x + 0.5, y + 0.5).
#pragma once

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <span>

#include "proxima/core/large_buffer.h"

namespace proxima {

template <typename T>
class Image {
 public:
  Image() = default;
  Image(int width, int height, int channels, T fill = T{})
      : width_(width), height_(height), channels_(channels),
        data_(size_t(width) * size_t(height) * size_t(channels), fill) {
    assert(width >= 0 && height >= 0 && channels > 0);
  }

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  size_t pixel_count() const { return size_t(width_) * size_t(height_); }
  bool empty() const { return data_.empty(); }

  // Channel c of pixel (x, y); (0, 0) is the top-left pixel.
  T& at(int x, int y, int c = 0) { return data_[index(x, y, c)]; }
  const T& at(int x, int y, int c = 0) const { return data_[index(x, y, c)]; }

  // All channels of pixel (x, y).
  std::span<T> pixel(int x, int y) { return {&data_[index(x, y, 0)], size_t(channels_)}; }
  std::span<const T> pixel(int x, int y) const { return {&data_[index(x, y, 0)], size_t(channels_)}; }

  std::span<T> data() { return data_; }
  std::span<const T> data() const { return data_; }

  bool operator==(const Image& o) const = default;

 private:
  size_t index(int x, int y, int c) const {
    assert(x >= 0 && x < width_ && y >= 0 && y < height_ && c >= 0 && c < channels_);
    return (size_t(y) * size_t(width_) + size_t(x)) * size_t(channels_) + size_t(c);
  }

  int width_ = 0;
  int height_ = 0;
  int channels_ = 0;
  LargeBuffer<T> data_;
};

using ImageF = Image<float>;
using ImageU8 = Image<uint8_t>;
using ImageU32 = Image<uint32_t>;

}  // namespace proxima
