#include "proxima/scene/animation.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace proxima {

mat4 animation_transform(const RigidAnimation& anim, float t) {
  if (anim.keys.empty()) return mat4(1.0f);
  const auto& keys = anim.keys;
  float t0 = keys.front().time, t1 = keys.back().time;
  if (anim.loop && t1 > t0) t = t0 + std::fmod(std::fmod(t - t0, t1 - t0) + (t1 - t0), t1 - t0);
  vec3 translation;
  quat rotation;
  if (t <= t0) {
    translation = keys.front().translation;
    rotation = keys.front().rotation;
  } else if (t >= t1) {
    translation = keys.back().translation;
    rotation = keys.back().rotation;
  } else {
    size_t i = 1;
    while (keys[i].time < t) ++i;
    const RigidKey& a = keys[i - 1];
    const RigidKey& b = keys[i];
    float w = b.time > a.time ? (t - a.time) / (b.time - a.time) : 1.0f;
    translation = glm::mix(a.translation, b.translation, w);
    rotation = glm::slerp(a.rotation, b.rotation, w);
  }
  // p' = pivot + R·(p − pivot) + translation
  mat4 m = glm::translate(mat4(1.0f), anim.pivot + translation) * glm::mat4_cast(rotation) *
           glm::translate(mat4(1.0f), -anim.pivot);
  return m;
}

}  // namespace proxima
