// View sets (view_set.h): reference viewpoints and seeded intermediate viewpoints.
#include "proxima/depthimage/view_set.h"

#include <cassert>
#include <cmath>

#include "proxima/core/error.h"
#include "proxima/core/rng.h"

namespace proxima {

ViewShape parse_view_shape(const std::string& name, const char* flag) {
  if (name == "segment") return ViewShape::Segment;
  if (name == "triangle") return ViewShape::Triangle;
  if (name == "rectangle") return ViewShape::Rectangle;
  fail_input(std::string(flag) + ": unknown view set '" + name + "' (segment, triangle, rectangle)");
}

const char* view_shape_name(ViewShape shape) {
  switch (shape) {
    case ViewShape::Segment: return "segment";
    case ViewShape::Triangle: return "triangle";
    case ViewShape::Rectangle: return "rectangle";
  }
  return "?";
}

ViewSet make_view_set(ViewShape shape, const Camera& base, float radius, float focus) {
  ViewSet set;
  set.shape = shape;
  set.base = base;
  set.target = base.position + focus * camera_forward(base);
  const vec3 c = base.position, r = radius * camera_right(base), u = radius * camera_up(base);
  switch (shape) {
    case ViewShape::Segment: set.corners = {c - r, c + r}; break;
    case ViewShape::Triangle: {
      const float s = std::sqrt(3.0f) / 2.0f;
      set.corners = {c + u, c - s * r - 0.5f * u, c + s * r - 0.5f * u};
      break;
    }
    case ViewShape::Rectangle: set.corners = {c - r - u, c + r - u, c + r + u, c - r + u}; break;
  }
  return set;
}

Camera view_camera(const ViewSet& set, vec3 position) {
  const Camera& b = set.base;
  return look_at(position, set.target, camera_up(b), b.vfov_deg, b.width, b.height, b.near, b.far);
}

Camera corner_camera(const ViewSet& set, size_t i) {
  assert(i < set.corners.size());
  return view_camera(set, set.corners[i]);
}

Camera centroid_camera(const ViewSet& set) {
  vec3 c(0.0f);
  for (vec3 p : set.corners) c += p;
  return view_camera(set, c / float(set.corners.size()));
}

std::vector<vec3> intermediate_viewpoints(const ViewSet& set, int k, uint64_t seed) {
  Pcg32 rng(derive_seed(seed, 0x56696577u));  // "View"
  std::vector<vec3> points;
  points.reserve(size_t(std::max(k, 0)));
  const std::vector<vec3>& v = set.corners;
  for (int i = 0; i < k; ++i) {
    const float a = rng.next_float(), b = rng.next_float();
    switch (set.shape) {
      case ViewShape::Segment: points.push_back(v[0] + a * (v[1] - v[0])); break;
      case ViewShape::Triangle: {
        // Uniform in the triangle: fold the unit square's upper half back.
        const bool fold = a + b > 1.0f;
        const float s = fold ? 1.0f - a : a, t = fold ? 1.0f - b : b;
        points.push_back(v[0] + s * (v[1] - v[0]) + t * (v[2] - v[0]));
        break;
      }
      case ViewShape::Rectangle: points.push_back(v[0] + a * (v[1] - v[0]) + b * (v[3] - v[0])); break;
    }
  }
  return points;
}

}  // namespace proxima
