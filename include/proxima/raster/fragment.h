// Fragment: one pixel center covered by one triangle, as the rasterizer hands it to a
// fragment test (a callable `bool(const Fragment&)`: true keeps the fragment, false
// discards it). Tests are template parameters, inlined into the per-tile loop.
#pragma once

#include <cstdint>

namespace proxima {

struct Fragment {
  int x, y;           // pixel; its center (x + 0.5, y + 0.5) is inside the triangle
  uint32_t triangle;  // id into Scene::triangles
  float depth;        // −z_cam at the pixel center, perspective-correct, > 0
  float u, v;         // perspective-correct barycentrics, Embree convention:
                      // p = (1−u−v)·p0 + u·p1 + v·p2 (only filled when
                      // RasterOptions::fragment_barycentrics is set; 0 otherwise)
};

// The default test: keeps every fragment.
struct AcceptAllFragments {
  bool operator()(const Fragment&) const { return true; }
};

}  // namespace proxima
