// Reflection depth image (thesis ch. 5 §5.3) from a one-sample-per-pixel ReflectionFrame.
#include "proxima/reflect/temporal_depth_image.h"

#include <cmath>
#include <stdexcept>

#include "proxima/scene/shading.h"

namespace proxima {

namespace {
vec3 pixel3(const ImageF& image, int x, int y) { return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)}; }
}  // namespace

vec3 key_mirror_direction(const ReflectionDepthImage& key, int x, int y) {
  const vec3 w = pixel3(key.position, x, y);
  return glm::normalize(reflect(w - key.camera.position, pixel3(key.normal, x, y)));
}

vec3 key_reflected_point(const ReflectionDepthImage& key, int x, int y) {
  return pixel3(key.position, x, y) + key_mirror_direction(key, x, y) * key.distance.at(x, y);
}

ReflectionDepthImage make_reflection_depth_image(const ReflectionFrame& frame, const TracedReflections& traced,
                                                 float max_distance) {
  if (frame.supersample != 1) throw std::logic_error("reflection depth image: frame must have supersample 1");
  if (traced.radiance.size() != frame.sample_count()) throw std::logic_error("reflection depth image: trace mismatch");
  const int w = frame.camera.width, h = frame.camera.height;
  ReflectionDepthImage key;
  key.camera = frame.camera;
  key.object = ImageU32(w, h, 1, kNoReflector);
  key.position = ImageF(w, h, 3, 0.0f);
  key.normal = ImageF(w, h, 3, 0.0f);
  key.depth = ImageF(w, h, 1, kInf);
  key.specular = ImageF(w, h, 1, 0.0f);
  key.radiance = ImageF(w, h, 3, 0.0f);
  key.distance = ImageF(w, h, 1, 0.0f);
  key.reflective_pixels = frame.sample_count();
  const vec3 forward = camera_forward(frame.camera);
  for (size_t i = 0; i < frame.sample_count(); ++i) {
    const int x = int(frame.pixel[i] % uint32_t(w)), y = int(frame.pixel[i] / uint32_t(w));
    key.object.at(x, y) = frame.reflector[i];
    key.depth.at(x, y) = glm::dot(frame.position[i] - frame.camera.position, forward);
    key.specular.at(x, y) = frame.specular[i];
    for (int c = 0; c < 3; ++c) {
      key.position.at(x, y, c) = frame.position[i][c];
      key.normal.at(x, y, c) = frame.normal[i][c];
      key.radiance.at(x, y, c) = traced.radiance[i][c];
    }
    double sum = 0.0;
    int finite = 0;
    for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r)
      if (std::isfinite(traced.hit_t[r])) {
        sum += traced.hit_t[r];
        ++finite;
      }
    key.distance.at(x, y) = finite ? std::min(float(sum / finite), max_distance) : max_distance;
  }
  return key;
}

}  // namespace proxima
