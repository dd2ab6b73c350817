// Reflection depth image (thesis ch. 5 §5.3) from a one-sample-per-pixel ReflectionFrame.
#include "proxima/reflect/temporal_depth_image.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "proxima/core/image_rgb.h"
#include "proxima/scene/shading.h"

namespace proxima {

vec3 key_mirror_direction(const ReflectionDepthImage& key, int x, int y) {
  const vec3 w = rgb_at(key.position, x, y);
  return glm::normalize(reflect(w - key.camera.position, rgb_at(key.normal, x, y)));
}

vec3 key_reflected_point(const ReflectionDepthImage& key, int x, int y) {
  return rgb_at(key.position, x, y) + key_mirror_direction(key, x, y) * key.distance.at(x, y);
}

namespace {

constexpr int kSpreadStep[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};

// One neighbour's term of mirror_spread: angles from |a − b| of unit vectors (2 sin(θ/2)),
// accurate for the tiny pixel angles. `spread` < 0: no neighbour yet.
float spread_with(float spread, vec3 view, vec3 mirror, vec3 neighbour_view, vec3 neighbour_mirror) {
  const float view_angle = glm::length(neighbour_view - view);
  const float mirror_angle = glm::length(neighbour_mirror - mirror);
  return view_angle > 0.0f ? std::max(spread, mirror_angle / view_angle) : spread;
}

vec3 key_view_direction(const ReflectionDepthImage& key, int x, int y) {
  return glm::normalize(rgb_at(key.position, x, y) - key.camera.position);
}

}  // namespace

float mirror_spread(const ReflectionDepthImage& key, int x, int y) {
  const int w = key.object.width(), h = key.object.height();
  const uint32_t object = key.object.at(x, y);
  const vec3 view = key_view_direction(key, x, y);
  const vec3 mirror = key_mirror_direction(key, x, y);
  float spread = -1.0f;
  for (const auto& d : kSpreadStep) {
    const int nx = x + d[0], ny = y + d[1];
    if (nx < 0 || ny < 0 || nx >= w || ny >= h || key.object.at(nx, ny) != object) continue;
    spread = spread_with(spread, view, mirror, key_view_direction(key, nx, ny), key_mirror_direction(key, nx, ny));
  }
  return spread < 0.0f ? kInf : spread;
}

namespace {

// s.spread and R of every reflective pixel (key.pixels sorted), as mirror_spread and
// key_reflected_point give them — the same operations on the same values — with each
// pixel's view and mirror directions computed once, not once per neighbour that reads them.
// A pixel's neighbours above and below are found by cursors that only move forward.
void spread_and_reflected(ReflectionDepthImage& key) {
  const int w = key.object.width();
  const std::vector<uint32_t>& pixels = key.pixels;
  const size_t n = pixels.size();
  static thread_local std::vector<vec3> view, mirror;  // per reflective pixel, kept between key frames
  view.resize(n), mirror.resize(n);
  for (size_t j = 0; j < n; ++j) {
    const int x = int(pixels[j] % uint32_t(w)), y = int(pixels[j] / uint32_t(w));
    view[j] = key_view_direction(key, x, y);
    mirror[j] = key_mirror_direction(key, x, y);
  }
  const uint32_t* object = key.object.data().data();
  const uint32_t row = uint32_t(w);
  size_t up = 0, down = 0;  // first index with pixel ≥ p − w, ≥ p + w
  for (size_t j = 0; j < n; ++j) {
    const uint32_t p = pixels[j];
    const uint32_t x = p % row;
    while (up < n && pixels[up] < p - std::min(p, row)) ++up;
    while (down < n && pixels[down] < p + row) ++down;
    // The 4-neighbours in mirror_spread's order: left, right, above, below; each on the same reflector.
    const size_t none = n;
    const size_t neighbour[4] = {x > 0 && j > 0 && pixels[j - 1] == p - 1 ? j - 1 : none,
                                 x + 1 < row && j + 1 < n && pixels[j + 1] == p + 1 ? j + 1 : none,
                                 p >= row && up < n && pixels[up] == p - row ? up : none,
                                 down < n && pixels[down] == p + row ? down : none};
    float spread = -1.0f;
    for (const size_t k : neighbour)
      if (k != none && object[pixels[k]] == object[p]) spread = spread_with(spread, view[j], mirror[j], view[k], mirror[k]);
    key.spread.data()[p] = spread < 0.0f ? kInf : spread;
    key.reflected[j] = vec3(key.position.data()[3 * size_t(p)], key.position.data()[3 * size_t(p) + 1],
                            key.position.data()[3 * size_t(p) + 2]) +
                       mirror[j] * key.distance.data()[p];
  }
}

}  // namespace

ReflectionDepthImage make_reflection_depth_image(const ReflectionFrame& frame, const TracedReflections& traced,
                                                 float max_distance) {
  ReflectionDepthImage key;
  make_reflection_depth_image_into(frame, traced, max_distance, key);
  return key;
}

void make_reflection_depth_image_into(const ReflectionFrame& frame, const TracedReflections& traced,
                                      float max_distance, ReflectionDepthImage& key) {
  if (frame.supersample != 1) throw std::logic_error("reflection depth image: frame must have supersample 1");
  if (traced.radiance.size() != frame.sample_count()) throw std::logic_error("reflection depth image: trace mismatch");
  const int w = frame.camera.width, h = frame.camera.height;
  if (key.object.width() == w && key.object.height() == h) {
    // Back to the empty image: only the earlier key frame's reflective pixels hold values.
    for (const uint32_t i : key.pixels) {
      const int x = int(i % uint32_t(w)), y = int(i / uint32_t(w));
      key.object.at(x, y) = kNoReflector;
      key.depth.at(x, y) = kInf;
      key.specular.at(x, y) = key.distance.at(x, y) = key.spread.at(x, y) = key.lobe.at(x, y) = 0.0f;
      for (int c = 0; c < 3; ++c) key.position.at(x, y, c) = key.normal.at(x, y, c) = key.radiance.at(x, y, c) = 0.0f;
    }
  } else {
    key.object = ImageU32(w, h, 1, kNoReflector);
    key.position = ImageF(w, h, 3, 0.0f);
    key.normal = ImageF(w, h, 3, 0.0f);
    key.depth = ImageF(w, h, 1, kInf);
    key.specular = ImageF(w, h, 1, 0.0f);
    key.radiance = ImageF(w, h, 3, 0.0f);
    key.distance = ImageF(w, h, 1, 0.0f);
    key.spread = ImageF(w, h, 1, 0.0f);
    key.lobe = ImageF(w, h, 1, 0.0f);
  }
  key.reflected.clear();
  static std::atomic<uint64_t> builds{0};
  key.serial = ++builds;
  key.camera = frame.camera;
  key.reflective_pixels = frame.sample_count();
  const vec3 forward = camera_forward(frame.camera);
  for (size_t i = 0; i < frame.sample_count(); ++i) {
    const int x = int(frame.pixel[i] % uint32_t(w)), y = int(frame.pixel[i] / uint32_t(w));
    key.object.at(x, y) = frame.reflector[i];
    key.depth.at(x, y) = glm::dot(frame.position[i] - frame.camera.position, forward);
    key.specular.at(x, y) = frame.specular[i];
    key.lobe.at(x, y) = glossy_lobe_half_angle(frame.gloss[i]);
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
  // Row-major: the samples' pixels sorted (one sample per pixel), not a scan of the image.
  key.pixels.assign(frame.pixel.begin(), frame.pixel.end());
  const bool sorted = std::is_sorted(key.pixels.begin(), key.pixels.end());
  if (!sorted) std::sort(key.pixels.begin(), key.pixels.end());
  key.reflected.resize(key.pixels.size());
  if (sorted) {
    spread_and_reflected(key);
  } else {  // not from prepare_reflection_frame: pixel by pixel
    for (size_t j = 0; j < key.pixels.size(); ++j) {
      const int x = int(key.pixels[j] % uint32_t(w)), y = int(key.pixels[j] / uint32_t(w));
      key.spread.at(x, y) = mirror_spread(key, x, y);
      key.reflected[j] = key_reflected_point(key, x, y);
    }
  }
}

}  // namespace proxima
