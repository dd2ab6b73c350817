// Soft-shadow errors (shadow_error.h). Paper: Xie Naiwen, PhD thesis, ch. 3 §3.4.2
// (../shared/papers/004_d1af2812aec5f9c7.txt, lines 936–950): visibility error = wrong
// visibility decisions per pixel, intensity error = their signed sum's magnitude, both
// 0..255; error images green where too bright, red where too dark.
#include "proxima/shadows/shadow_error.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstdlib>

namespace proxima {

ShadowError compare_visibility(const LightVisibility& approx, const LightVisibility& truth, const Receivers& receivers) {
  assert(approx.width == truth.width && approx.height == truth.height && approx.samples == truth.samples);
  ShadowError e;
  e.image = ImageF(approx.width, approx.height, 3, 0.0f);
  const double scale = 255.0 / double(std::max(1, truth.samples));
  double intensity_sum = 0.0, visibility_sum = 0.0;
  size_t pixels = 0;
  for (int y = 0; y < approx.height; ++y)
    for (int x = 0; x < approx.width; ++x) {
      if (!receivers.mask.at(x, y)) continue;
      const size_t base = (size_t(y) * size_t(approx.width) + size_t(x)) * size_t(approx.words);
      int wrong = 0;
      for (int k = 0; k < approx.words; ++k)
        wrong += std::popcount(approx.bits[base + size_t(k)] ^ truth.bits[base + size_t(k)]);
      const int diff = approx.lit_count(x, y) - truth.lit_count(x, y);
      const double vis = scale * wrong, inten = scale * std::abs(diff);
      visibility_sum += vis;
      intensity_sum += inten;
      e.visibility_max = std::max(e.visibility_max, vis);
      e.intensity_max = std::max(e.intensity_max, inten);
      ++pixels;
      const float shade = float(std::min(1.0, 4.0 * inten / 255.0));
      e.image.at(x, y, diff > 0 ? 1 : 0) = diff != 0 ? shade : 0.0f;
    }
  if (pixels > 0) {
    e.intensity_mean = intensity_sum / double(pixels);
    e.visibility_mean = visibility_sum / double(pixels);
  }
  return e;
}

ImageF shadow_image(const LightVisibility& v, const Receivers& receivers) {
  ImageF out(v.width, v.height, 3, 0.0f);
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x) {
      if (!receivers.mask.at(x, y)) {
        out.at(x, y, 2) = 0.08f;
        continue;
      }
      const float lit = float(v.lit_count(x, y)) / float(std::max(1, v.samples));
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = lit;
    }
  return out;
}

}  // namespace proxima
