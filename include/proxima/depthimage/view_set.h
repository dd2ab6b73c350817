// View sets: the reference viewpoints V_0 … V_{n−1} a scene is sampled from (thesis ch. 2,
// §2.2.2): the two ends of a segment (Figure 11), the three corners of a triangle
// (Figure 8) or the four corners of a rectangle (an area light, §3.3), plus the
// intermediate viewpoints inside that region from which output frames are rendered.
// Every camera of a set looks at one common target with the same up, field of view,
// resolution and clip range, so the images differ only by the viewpoint.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "proxima/core/camera.h"

namespace proxima {

enum class ViewShape { Segment, Triangle, Rectangle };

// "segment" | "triangle" | "rectangle"; throws InputError naming `flag` otherwise.
ViewShape parse_view_shape(const std::string& name, const char* flag);
const char* view_shape_name(ViewShape shape);

struct ViewSet {
  ViewShape shape = ViewShape::Triangle;
  std::vector<vec3> corners;  // V_0 … V_{n−1}: 2, 3 or 4 (rectangle: c0, c1, c2, c3 in order around)
  vec3 target{0.0f};          // every camera looks here
  Camera base;                // up (camera_up), vfov, width, height, near, far of every camera
};

// A view set centred on `base` (its position is the centroid): corners at distance
// `radius` from it in the plane spanned by the camera's right and up vectors —
// segment: ±right; triangle: equilateral, V_0 at the top; rectangle: ±right ± up.
// All cameras look at base.position + focus·forward.
ViewSet make_view_set(ViewShape shape, const Camera& base, float radius, float focus);

// Camera at viewpoint `position` looking at the set's target.
Camera view_camera(const ViewSet& set, vec3 position);

// Camera i of the set (V_i).
Camera corner_camera(const ViewSet& set, size_t i);

// Camera at the centroid of the corners (depth peeling's single viewpoint).
Camera centroid_camera(const ViewSet& set);

// k uniformly distributed viewpoints inside the set's region (on the segment, in the
// triangle, in the rectangle), from a PCG32 stream seeded with `seed`; the same seed gives
// the same points.
std::vector<vec3> intermediate_viewpoints(const ViewSet& set, int k, uint64_t seed);

}  // namespace proxima
