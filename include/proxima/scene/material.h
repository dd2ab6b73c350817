// Materials and textures (DESIGN.md): diffuse linear RGB with an optional texture,
// specular s in [0, 1] (0 = diffuse, 1 = perfect reflector), gloss g in [0, 1]
// (0 = mirror, 1 = widest lobe), emission. The shading model is in docs/shading.md.
#pragma once

#include <string>

#include "proxima/core/image.h"
#include "proxima/core/math.h"

namespace proxima {

struct Material {
  std::string name;
  vec3 diffuse{0.8f};
  int diffuse_texture = -1;  // index into Scene::textures, or −1
  float specular = 0.0f;     // s
  float gloss = 0.0f;        // g
  vec3 emission{0.0f};

  bool reflective() const { return specular > 0.0f; }
};

struct Texture {
  std::string name;  // file it came from, or a generator name
  ImageF image;      // linear RGB, 3 channels; row 0 is v = 1 (top of the picture)
};

// Bilinear lookup with repeat wrapping; uv (0,0) is the bottom-left of the picture.
vec3 sample_texture(const Texture& texture, vec2 uv);

}  // namespace proxima
