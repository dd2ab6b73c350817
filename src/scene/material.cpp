#include "proxima/scene/material.h"

#include <cmath>

namespace proxima {

vec3 sample_texture(const Texture& texture, vec2 uv) {
  const ImageF& img = texture.image;
  if (img.empty()) return vec3(1.0f);
  // Texel centers at (i + 0.5) / size; v = 0 is the bottom row (row height − 1).
  // Repeat-wrap into [0, 1] first so the float → int conversions below stay in range for
  // huge uvs; non-finite ones (overflowing interpolation) read texel (0, 0).
  vec2 w = uv - glm::floor(uv);
  if (!(w.x >= 0.0f && w.x <= 1.0f)) w.x = 0.0f;
  if (!(w.y >= 0.0f && w.y <= 1.0f)) w.y = 0.0f;
  float x = w.x * float(img.width()) - 0.5f;
  float y = (1.0f - w.y) * float(img.height()) - 0.5f;
  float fx = std::floor(x), fy = std::floor(y);
  float tx = x - fx, ty = y - fy;
  auto wrap = [](int i, int n) { int m = i % n; return m < 0 ? m + n : m; };
  int x0 = wrap(int(fx), img.width()), x1 = wrap(int(fx) + 1, img.width());
  int y0 = wrap(int(fy), img.height()), y1 = wrap(int(fy) + 1, img.height());
  auto texel = [&](int xi, int yi) {
    return vec3(img.at(xi, yi, 0), img.at(xi, yi, 1), img.at(xi, yi, 2));
  };
  return glm::mix(glm::mix(texel(x0, y0), texel(x1, y0), tx), glm::mix(texel(x0, y1), texel(x1, y1), tx),
                  ty);
}

}  // namespace proxima
