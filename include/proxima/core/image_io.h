// Reading and writing images: PNG (8-bit sRGB, via stb), JPEG (read only, via libjpeg-turbo)
// and EXR (32-bit float, via tinyexr).
// Every writer writes to a temporary file beside the target and renames it, so a failed
// write never leaves a half-written file. Failures throw InputError naming the file.
#pragma once

#include <filesystem>

#include "proxima/core/image.h"

namespace proxima {

// Linear float RGB(A) in [0, 1] → sRGB 8-bit PNG. 1, 3 or 4 channels; alpha stays linear.
void write_png_linear(const std::filesystem::path& path, const ImageF& linear);

// 8-bit PNG as stored (no color conversion). 1, 2, 3 or 4 channels.
void write_png(const std::filesystem::path& path, const ImageU8& image);

// PNG (8 or 16 bit) or JPEG (baseline or progressive; YCbCr, gray, CMYK/YCCK) → linear float
// RGB (sRGB decoded) with `channels` channels (3 or 4; alpha is 1 where the file has none).
// The format is chosen by the file's first bytes, not its extension. The size in the header
// is checked (kMaxImageSide, the memory limit) before decoding. A JPEG that libjpeg only
// warns about (truncated, corrupt data) is an error, not a partly gray picture.
ImageF read_image_linear(const std::filesystem::path& path, int channels = 3);

// Float image (1..4 channels) → 32-bit float EXR. Channel names: Y, or R G B (A).
void write_exr(const std::filesystem::path& path, const ImageF& image);

// Reads an EXR back as float (1..4 channels as stored).
ImageF read_exr(const std::filesystem::path& path);

// sRGB transfer functions on one channel value.
float srgb_to_linear(float s);
float linear_to_srgb(float l);

}  // namespace proxima
