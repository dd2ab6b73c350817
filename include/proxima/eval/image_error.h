// Image error against a reference, the way the papers report it: per-channel mean and max
// absolute difference on the 0–255 scale of the displayed (sRGB 8-bit) image, plus PSNR.
// Both images are linear RGB; each value is clamped to [0, 1], sRGB-encoded and scaled to
// 0–255 (without rounding) before differencing, so errors match what a viewer sees.
#pragma once

#include <cstddef>

#include "proxima/core/image.h"

namespace proxima {

struct ImageError {
  size_t pixels = 0;           // pixels compared (mask true)
  double mae[3] = {0, 0, 0};   // mean |a − r| per channel, 0–255
  double max_abs[3] = {0, 0, 0};
  double mae_avg = 0.0;        // mean of the three channels
  double psnr_db = 0.0;        // 10·log10(255² / MSE) over all compared values; +inf if equal
};

// Compares approx with reference (both ≥ 3 channels, same size) over the pixels where
// mask (1 channel, same size, nonzero = compare) is set, or over all pixels if mask is null.
// No compared pixel → pixels = 0 and all errors 0.
ImageError compare_images(const ImageF& approx, const ImageF& reference, const ImageU8* mask = nullptr);

// Per-pixel error on the same 0–255 display scale: mean over the three channels of
// |a − r|; 0 where the mask is unset. 1 channel.
ImageF error_image(const ImageF& approx, const ImageF& reference, const ImageU8* mask = nullptr);

// Error heat map (1-channel error in 0–255 units → linear RGB, 3 channels): a perceptual
// black → purple → orange → yellow ramp (inferno-like) from 0 to `max_error`, saturating
// above it; one `max_error` for all methods of a comparison keeps them on one scale.
// Masked-out pixels (mask 0) are drawn mid grey.
ImageF error_heatmap(const ImageF& error, float max_error, const ImageU8* mask = nullptr);

// The one error heat-map scale of every command, study and report (0–255 display units):
// errors at or above it saturate to yellow.
inline constexpr float kErrorHeatmapMax = 32.0f;

// A horizontal legend bar for error_heatmap: width × height, 0 on the left, max on the right.
ImageF heatmap_legend(int width, int height);

}  // namespace proxima
