// Shared by the env-map tests: the error of a method's shading over the reflector pixels.
#pragma once

#include <cmath>

#include "proxima/reflect/envmap_reflection.h"

namespace proxima::envmap_test {

// Mean |a − b| over the pixels where `pixels` has a reflector (linear, channels averaged).
inline double reflector_mae(const ImageF& a, const ImageF& b, const ReflectorPixels& pixels) {
  double sum = 0.0;
  size_t n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      if (pixels.triangle.at(x, y) == kNoTriangle) continue;
      for (int c = 0; c < 3; ++c) sum += std::abs(double(a.at(x, y, c)) - double(b.at(x, y, c))) / 3.0;
      ++n;
    }
  return n ? sum / double(n) : 0.0;
}

}  // namespace proxima::envmap_test
