// A smooth, non-repeating 32×32 wall texture for reflection tests: any misplaced
// reflection shows as a wrong color.
#pragma once

#include <cmath>

#include "proxima/scene/scene.h"

namespace proxima {

// Adds the "waves" texture and a white diffuse material using it; returns the material.
inline uint32_t add_waves_wall_material(Scene& s) {
  Texture tex;
  tex.name = "waves";
  tex.image = ImageF(32, 32, 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      tex.image.at(x, y, 0) = 0.5f + 0.4f * std::sin(0.39f * float(x));
      tex.image.at(x, y, 1) = 0.5f + 0.4f * std::cos(0.29f * float(y));
      tex.image.at(x, y, 2) = 0.5f + 0.3f * std::sin(0.2f * float(x + y));
    }
  s.textures.push_back(tex);
  Material wall;
  wall.diffuse = vec3(1.0f);
  wall.diffuse_texture = int(s.textures.size() - 1);
  return add_material(s, wall);
}

}  // namespace proxima
