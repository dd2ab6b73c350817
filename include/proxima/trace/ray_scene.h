// RayScene: the Embree 3 BVH of a Scene and its ray queries. Embree stays behind this
// header. Hits report the global triangle id, distance t along the ray and Embree's
// barycentrics (u, v): p = (1−u−v)·p0 + u·p1 + v·p2.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "proxima/core/math.h"
#include "proxima/scene/scene.h"

namespace proxima {

struct Hit {
  uint32_t triangle = kNoTriangle;
  float t = kInf;  // in units of the ray's dir
  float u = 0.0f;
  float v = 0.0f;

  bool valid() const { return triangle != kNoTriangle; }
};

class RayScene {
 public:
  // Builds the BVH over the scene's triangles (rest pose or already posed): Embree's
  // high-quality SAH build, robust (watertight) triangle tests. Embree failures (e.g. out
  // of memory) throw std::runtime_error.
  explicit RayScene(const Scene& scene);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Moves the vertices to those of `posed` (same topology as the scene built from) and
  // refits the BVH. The first update rebuilds once into a refittable two-level BVH; later
  // ones only refit (≈25 ms for 1M triangles). A different vertex or triangle count throws
  // std::logic_error.
  void update(const Scene& posed);

  // Closest hit in [ray.tmin, ray.tmax].
  Hit intersect(const Ray& ray) const;
  // True if anything is hit in [ray.tmin, ray.tmax].
  bool occluded(const Ray& ray) const;

  // Batched, parallel over fixed chunks of rays; results are bit-identical to the
  // single-ray calls. hits.size() == rays.size() (else std::logic_error).
  void intersect(std::span<const Ray> rays, std::span<Hit> hits) const;
  void occluded(std::span<const Ray> rays, std::span<uint8_t> blocked) const;

  double build_ms() const;  // time of the last build or refit

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace proxima
