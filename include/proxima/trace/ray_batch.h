// Batched closest-hit queries in structure-of-arrays form: origins and directions in, one
// array per hit attribute out — the layout of numpy arrays (the Python module's
// RayScene.cast) and of Open3D's RaycastingScene.cast_rays.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "proxima/core/large_buffer.h"
#include "proxima/core/math.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

// LargeBufferAllocator whose containers leave new elements uninitialized (resize does not
// zero them): a batch writes every element of its results in parallel, and zero-filling
// them first would be one more pass over the whole output, on one thread.
template <typename T>
struct UninitializedAllocator : LargeBufferAllocator<T> {
  template <typename U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() noexcept = default;
  template <typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0)
      ::new (static_cast<void*>(p)) U;
    else
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <typename T>
using RayBatchBuffer = std::vector<T, UninitializedAllocator<T>>;

// Per ray; index i is ray i. Misses: t = +inf, triangle and object = kNoTriangle
// (0xFFFFFFFF), normal and uv = 0.
struct RayBatchHits {
  RayBatchBuffer<float> t;            // distance along the ray in units of its direction
  RayBatchBuffer<uint32_t> triangle;  // triangle id (index into Scene::triangles)
  RayBatchBuffer<uint32_t> object;    // object id (index into Scene::objects)
  RayBatchBuffer<vec3> normal;        // unit geometric normal, right-hand rule over the vertex order
  RayBatchBuffer<vec2> uv;            // barycentrics (u, v): p = (1−u−v)·p0 + u·p1 + v·p2
};

// What a hit reports besides t and (u, v), packed in one 16-byte record per triangle: a
// hit then reads one cache line instead of the triangle's indices, its three vertices and
// its object (random rays hit triangles in random order, so each of those is a miss).
struct TriangleHitRecord {
  vec3 normal;      // triangle_normal(scene, triangle)
  uint32_t object;  // scene.triangle_object[triangle]
};
static_assert(sizeof(TriangleHitRecord) == 16);

// The records of every triangle of `scene`, index = triangle id (parallel; 16 bytes per
// triangle). Valid as long as the scene's geometry and object assignment stay unchanged.
LargeBuffer<TriangleHitRecord> triangle_hit_records(const Scene& scene);

// Closest hit of each ray origins[i] + t·directions[i], t in [tmin, tmax], on `rays` built
// from the scene `records` were made from (triangle_hit_records; make them once and reuse
// them over batches). The rays are traced in a coherent order (sorted by direction octant,
// then origin cell) over fixed chunks in parallel, each ray on its own (rtcIntersect1), and
// the normals and object ids read from the records: each ray's result is bit for bit that
// of RayScene::intersect, for any thread count and any order of the input. Throws
// InputError when the spans differ in size, a value is not finite (directions may not be
// zero), tmin/tmax are not 0 ≤ tmin ≤ tmax (tmax may be +inf) or there are 2^32 rays or
// more; std::logic_error when a hit triangle has no record (records of another scene).
RayBatchHits cast_ray_batch(std::span<const TriangleHitRecord> records, const RayScene& rays,
                            std::span<const vec3> origins, std::span<const vec3> directions,
                            float tmin = 0.0f, float tmax = kInf);

// The same for one batch: makes the scene's records first (one pass over its triangles).
RayBatchHits cast_ray_batch(const Scene& scene, const RayScene& rays, std::span<const vec3> origins,
                            std::span<const vec3> directions, float tmin = 0.0f, float tmax = kInf);

}  // namespace proxima
