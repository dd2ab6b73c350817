#include "proxima/trace/ray_batch.h"

#include <cmath>
#include <string>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"

namespace proxima {

namespace {

constexpr size_t kChunk = 4096;

// First row of a that is not finite (or, for directions, zero); a.size() if none.
size_t first_bad_row(std::span<const vec3> a, bool nonzero) {
  for (size_t i = 0; i < a.size(); ++i) {
    const vec3 v = a[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return i;
    if (nonzero && v.x == 0.0f && v.y == 0.0f && v.z == 0.0f) return i;
  }
  return a.size();
}

}  // namespace

RayBatchHits cast_ray_batch(const Scene& scene, const RayScene& rays, std::span<const vec3> origins,
                            std::span<const vec3> directions, float tmin, float tmax) {
  if (origins.size() != directions.size())
    fail_input("rays: " + std::to_string(origins.size()) + " origins but " + std::to_string(directions.size()) +
               " directions");
  if (!(tmin >= 0.0f) || !std::isfinite(tmin) || !(tmax >= tmin))
    fail_input("rays: need 0 ≤ tmin ≤ tmax (tmin finite)");
  if (const size_t i = first_bad_row(origins, false); i < origins.size())
    fail_input("rays: origin " + std::to_string(i) + " is not finite");
  if (const size_t i = first_bad_row(directions, true); i < directions.size())
    fail_input("rays: direction " + std::to_string(i) + " is zero or not finite");

  const size_t n = origins.size();
  RayBatchHits out;
  out.t.resize(n);
  out.triangle.resize(n);
  out.object.resize(n);
  out.normal.resize(n);
  out.uv.resize(n);
  parallel_for(n, kChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const Hit h = rays.intersect(Ray{origins[i], directions[i], tmin, tmax});
      out.t[i] = h.t;
      out.triangle[i] = h.triangle;
      out.object[i] = h.valid() ? scene.triangle_object[h.triangle] : kNoTriangle;
      out.normal[i] = h.valid() ? triangle_normal(scene, h.triangle) : vec3(0.0f);
      out.uv[i] = h.valid() ? vec2(h.u, h.v) : vec2(0.0f);
    }
  });
  return out;
}

}  // namespace proxima
