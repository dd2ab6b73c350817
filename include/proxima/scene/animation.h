// Rigid per-object animation: translation and rotation (about a pivot) as functions of
// time, given by key frames and interpolated linearly (translation) and by slerp (rotation).
#pragma once

#include <vector>

#include "proxima/core/math.h"

namespace proxima {

struct RigidKey {
  float time = 0.0f;  // seconds
  vec3 translation{0.0f};
  quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
};

struct RigidAnimation {
  vec3 pivot{0.0f};            // rotation center in rest-pose world space
  std::vector<RigidKey> keys;  // sorted by time; empty = static
  bool loop = false;           // wrap time into [first key, last key]

  bool animated() const { return !keys.empty(); }
};

// World transform of the object at time t (identity for a static object). Before the first
// key or after the last, the end key holds (unless loop).
mat4 animation_transform(const RigidAnimation& anim, float t);

}  // namespace proxima
