// Batched closest-hit queries in structure-of-arrays form: origins and directions in, one
// array per hit attribute out — the layout of numpy arrays (the Python module's
// RayScene.cast) and of Open3D's RaycastingScene.cast_rays.
#pragma once

#include <cstdint>
#include <span>

#include "proxima/core/large_buffer.h"
#include "proxima/core/math.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

// Per ray; index i is ray i. Misses: t = +inf, triangle and object = kNoTriangle
// (0xFFFFFFFF), normal and uv = 0.
struct RayBatchHits {
  LargeBuffer<float> t;             // distance along the ray in units of its direction
  LargeBuffer<uint32_t> triangle;   // triangle id (index into Scene::triangles)
  LargeBuffer<uint32_t> object;     // object id (index into Scene::objects)
  LargeBuffer<vec3> normal;         // unit geometric normal, right-hand rule over the vertex order
  LargeBuffer<vec2> uv;             // barycentrics (u, v): p = (1−u−v)·p0 + u·p1 + v·p2
};

// Closest hit of each ray origins[i] + t·directions[i], t in [tmin, tmax], on `rays` built
// from `scene`. Parallel over fixed chunks; each ray's result is bit for bit that of
// RayScene::intersect, for any thread count. Throws InputError when the spans differ in
// size, a value is not finite (directions may not be zero), or tmin/tmax are not
// 0 ≤ tmin ≤ tmax (tmax may be +inf).
RayBatchHits cast_ray_batch(const Scene& scene, const RayScene& rays, std::span<const vec3> origins,
                            std::span<const vec3> directions, float tmin = 0.0f, float tmax = kInf);

}  // namespace proxima
