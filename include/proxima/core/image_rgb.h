// The first three channels of an ImageF pixel as a vec3 (color, normal, radiance images).
#pragma once

#include "proxima/core/image.h"
#include "proxima/core/math.h"

namespace proxima {

inline vec3 rgb_at(const ImageF& image, int x, int y) {
  return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

}  // namespace proxima
