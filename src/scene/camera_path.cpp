#include "proxima/scene/camera_path.h"

#include <algorithm>

namespace proxima {
namespace {

// Uniform Catmull-Rom through p1 → p2 at w in [0, 1].
template <typename T>
T catmull_rom(const T& p0, const T& p1, const T& p2, const T& p3, float w) {
  float w2 = w * w, w3 = w2 * w;
  return 0.5f * ((2.0f * p1) + (-p0 + p2) * w + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * w2 +
                 (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * w3);
}

}  // namespace

Camera camera_at_time(const CameraPath& path, float t, int width, int height, float near, float far) {
  const auto& k = path.keys;
  CameraKey key = k.front();
  if (k.size() > 1 && t > k.front().time) {
    if (t >= k.back().time) {
      key = k.back();
    } else {
      size_t i = 1;
      while (k[i].time < t) ++i;
      size_t i0 = i >= 2 ? i - 2 : 0, i1 = i - 1, i2 = i, i3 = std::min(i + 1, k.size() - 1);
      float span = k[i2].time - k[i1].time;
      float w = span > 0.0f ? (t - k[i1].time) / span : 1.0f;
      key.time = t;
      key.position = catmull_rom(k[i0].position, k[i1].position, k[i2].position, k[i3].position, w);
      key.target = catmull_rom(k[i0].target, k[i1].target, k[i2].target, k[i3].target, w);
      key.vfov_deg = k[i1].vfov_deg + (k[i2].vfov_deg - k[i1].vfov_deg) * w;
      // Valid keys can still interpolate to a view look_at cannot take (the target passing
      // through the position, looking straight along up) or overflow for huge coordinates;
      // such a frame takes the view of the nearer key.
      const CameraKey& nearer = w < 0.5f ? k[i1] : k[i2];
      if (!is_finite(key.position)) key.position = nearer.position;
      const vec3 dir = key.target - key.position;
      if (!is_finite(dir) || !(glm::length(glm::cross(glm::normalize(dir), path.up)) > 1e-6f * glm::length(path.up)))
        key.target = key.position + (nearer.target - nearer.position);
    }
  }
  return look_at(key.position, key.target, path.up, key.vfov_deg, width, height, near, far);
}

float frame_time(const CameraPath& path, int frame) {
  float t0 = path.keys.front().time, t1 = path.keys.back().time;
  if (path.frames <= 1) return t0;
  return t0 + float(frame) * (t1 - t0) / float(path.frames - 1);
}

}  // namespace proxima
