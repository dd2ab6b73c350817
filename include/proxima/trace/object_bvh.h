// ObjectBvh: a bounding volume hierarchy over one object's triangles for exact ray queries
// against that object alone (the cluster method's own-reflector test). Small and built per
// frame from the posed scene; the whole-scene queries stay with Embree (trace/ray_scene.h).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "proxima/core/math.h"
#include "proxima/scene/scene.h"

namespace proxima {

struct ObjectHit {
  float t = kInf;
  uint32_t triangle = kNoTriangle;  // scene triangle id
  float u = 0.0f, v = 0.0f;         // barycentrics as triangle_point takes them
};

class ObjectBvh {
 public:
  ObjectBvh() = default;
  // Over the triangles of scene.objects[object], with the scene's (posed) positions.
  ObjectBvh(const Scene& scene, uint32_t object);

  bool empty() const { return nodes_.empty(); }
  const Bounds3& bounds() const { return nodes_.front().box; }

  // The nearest hit with t in (t_min, t_max) on either face of a triangle; none when the
  // ray meets none there. The same ray gives the same hit for any thread.
  std::optional<ObjectHit> intersect(vec3 origin, vec3 dir, float t_min, float t_max) const;

 private:
  struct Node {
    Bounds3 box;
    uint32_t first = 0;  // leaf: first entry in the triangle arrays; inner: left child (right = first + 1)
    uint32_t count = 0;  // leaf: triangle count; inner: 0
  };
  std::vector<Node> nodes_;
  std::vector<uint32_t> triangle_;  // scene triangle ids in leaf order
  std::vector<vec3> a_, e1_, e2_;   // their first vertex and two edges
};

}  // namespace proxima
