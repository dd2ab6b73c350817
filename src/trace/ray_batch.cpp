#include "proxima/trace/ray_batch.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"

namespace proxima {

namespace {

constexpr size_t kChunk = 4096;
// How many rays ahead a chunk's gather prefetches their origins and directions: enough to
// cover a memory access with the few nanoseconds each ray's copy takes.
constexpr size_t kPrefetchAhead = 16;

// Rays are traced in the order of a key: direction octant (3 bits) above the Morton code
// of the origin on a 16³ grid over the batch's origins (12 bits). Rays with the same key
// start close together and head the same way, so consecutive rays visit the same BVH nodes
// and triangles while they are in cache. Measured on 1M random rays inside living-room
// (one thread): the traversal ≈1.8× faster in this order than in input order; 32³ and 64³
// grids were no faster. The order changes no result: every ray is still its own
// rtcIntersect1.
constexpr int kGridBits = 4;
constexpr int kKeyBits = 3 + 3 * kGridBits;
constexpr int kRadixBits = (kKeyBits + 1) / 2;  // two counting-sort passes
// Rays per block of the parallel sort: fixed, so the order never depends on the threads.
constexpr size_t kSortBlock = size_t(1) << 16;

// The bits of v (< 2^kGridBits) spread to every third bit.
uint32_t spread3(uint32_t v) {
  uint32_t out = 0;
  for (int b = 0; b < kGridBits; ++b) out |= ((v >> b) & 1u) << (3 * b);
  return out;
}

RayBatchBuffer<uint32_t> sort_keys(std::span<const vec3> origins, std::span<const vec3> directions) {
  vec3 lo(kInf), hi(-kInf);
  for (const vec3& o : origins) {
    lo = glm::min(lo, o);
    hi = glm::max(hi, o);
  }
  const float cells = float(1 << kGridBits);
  const vec3 extent = hi - lo;
  const vec3 scale(extent.x > 0.0f ? cells / extent.x : 0.0f, extent.y > 0.0f ? cells / extent.y : 0.0f,
                   extent.z > 0.0f ? cells / extent.z : 0.0f);
  RayBatchBuffer<uint32_t> keys(origins.size());
  parallel_for(keys.size(), kSortBlock, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const vec3 cell = glm::min((origins[i] - lo) * scale, vec3(cells - 1.0f));
      const vec3& d = directions[i];
      const uint32_t octant = (d.x < 0.0f ? 1u : 0u) | (d.y < 0.0f ? 2u : 0u) | (d.z < 0.0f ? 4u : 0u);
      keys[i] = (octant << (3 * kGridBits)) | spread3(uint32_t(cell.x)) | (spread3(uint32_t(cell.y)) << 1) |
                (spread3(uint32_t(cell.z)) << 2);
    }
  });
  return keys;
}

// One stable counting-sort pass: `in` reordered into `out` by bits [shift, shift +
// kRadixBits) of keys[in[k]]. Parallel over fixed blocks (each counts, then places, its
// own elements), so the result does not depend on the thread count.
void radix_pass(const RayBatchBuffer<uint32_t>& keys, std::span<const uint32_t> in, std::span<uint32_t> out,
                int shift) {
  constexpr size_t kBuckets = size_t(1) << kRadixBits;
  constexpr uint32_t kMask = uint32_t(kBuckets - 1);
  const size_t blocks = (in.size() + kSortBlock - 1) / kSortBlock;
  std::vector<size_t> start(blocks * kBuckets);  // [block][bucket]
  parallel_for(in.size(), kSortBlock, [&](size_t begin, size_t end) {
    size_t* count = &start[begin / kSortBlock * kBuckets];
    for (size_t k = begin; k < end; ++k) ++count[(keys[in[k]] >> shift) & kMask];
  });
  size_t sum = 0;  // bucket by bucket, blocks in order within a bucket: stable
  for (size_t b = 0; b < kBuckets; ++b)
    for (size_t block = 0; block < blocks; ++block) {
      const size_t count = start[block * kBuckets + b];
      start[block * kBuckets + b] = sum;
      sum += count;
    }
  parallel_for(in.size(), kSortBlock, [&](size_t begin, size_t end) {
    size_t* next = &start[begin / kSortBlock * kBuckets];
    for (size_t k = begin; k < end; ++k) out[next[(keys[in[k]] >> shift) & kMask]++] = in[k];
  });
}

// Ray indices in the order of their keys (stable: ties keep their input order).
RayBatchBuffer<uint32_t> trace_order(std::span<const vec3> origins, std::span<const vec3> directions) {
  const RayBatchBuffer<uint32_t> keys = sort_keys(origins, directions);
  RayBatchBuffer<uint32_t> order(keys.size()), tmp(keys.size());
  parallel_for(tmp.size(), kSortBlock, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) tmp[i] = uint32_t(i);
  });
  radix_pass(keys, tmp, order, 0);
  radix_pass(keys, order, tmp, kRadixBits);
  return tmp;
}

// One ray's answer, kept in trace order until it is written back in input order.
struct TracedRay {
  float t;
  uint32_t triangle;
  vec2 uv;
  vec3 normal;
  uint32_t object;
};
static_assert(sizeof(TracedRay) == 32);

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

LargeBuffer<TriangleHitRecord> triangle_hit_records(const Scene& scene) {
  LargeBuffer<TriangleHitRecord> records(scene.triangles.size());
  parallel_for(records.size(), kChunk * 4, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      records[i] = {triangle_normal(scene, uint32_t(i)), scene.triangle_object[i]};
  });
  return records;
}

RayBatchHits cast_ray_batch(std::span<const TriangleHitRecord> records, const RayScene& rays,
                            std::span<const vec3> origins, std::span<const vec3> directions, float tmin,
                            float tmax) {
  if (origins.size() != directions.size())
    fail_input("rays: " + std::to_string(origins.size()) + " origins but " +
               std::to_string(directions.size()) + " directions");
  if (!(tmin >= 0.0f) || !std::isfinite(tmin) || !(tmax >= tmin))
    fail_input("rays: need 0 ≤ tmin ≤ tmax (tmin finite)");
  if (const size_t i = first_bad_row(origins, false); i < origins.size())
    fail_input("rays: origin " + std::to_string(i) + " is not finite");
  if (const size_t i = first_bad_row(directions, true); i < directions.size())
    fail_input("rays: direction " + std::to_string(i) + " is zero or not finite");
  if (origins.size() > std::numeric_limits<uint32_t>::max())
    fail_input("rays: " + std::to_string(origins.size()) + " rays in one batch; at most 2^32 − 1");

  const size_t n = origins.size();
  RayBatchHits out;
  out.t.resize(n);
  out.triangle.resize(n);
  out.object.resize(n);
  out.normal.resize(n);
  out.uv.resize(n);
  const RayBatchBuffer<uint32_t> order = trace_order(origins, directions);
  std::atomic<bool> foreign_triangle{false};
  // Rays in trace order: each chunk gathers its rays, traces them and stores the answers
  // in trace order (sequential writes); the records are prefetched right after each hit so
  // they arrive while the next rays are traced.
  RayBatchBuffer<TracedRay> traced(n);
  RayBatchBuffer<uint32_t> rank(n);  // position of ray i in the trace order
  parallel_for(n, kChunk, [&](size_t begin, size_t end) {
    std::vector<Ray> chunk(end - begin);
    for (size_t k = begin; k < end; ++k) {
      if (k + kPrefetchAhead < end) {
        __builtin_prefetch(&origins[order[k + kPrefetchAhead]]);
        __builtin_prefetch(&directions[order[k + kPrefetchAhead]]);
      }
      chunk[k - begin] = Ray{origins[order[k]], directions[order[k]], tmin, tmax};
    }
    std::vector<Hit> hits(chunk.size());
    for (size_t j = 0; j < chunk.size(); ++j) {
      hits[j] = rays.intersect(chunk[j]);
      if (hits[j].valid() && hits[j].triangle >= records.size()) {
        foreign_triangle.store(true, std::memory_order_relaxed);
        hits[j] = Hit{};
      }
      if (hits[j].valid()) __builtin_prefetch(&records[hits[j].triangle]);
    }
    for (size_t j = 0; j < hits.size(); ++j) {
      const Hit& h = hits[j];
      const TriangleHitRecord record =
          h.valid() ? records[h.triangle] : TriangleHitRecord{vec3(0.0f), kNoTriangle};
      traced[begin + j] = TracedRay{h.t, h.triangle, vec2(h.u, h.v), record.normal, record.object};
      rank[order[begin + j]] = uint32_t(begin + j);
    }
  });
  // Back to input order: sequential writes into the results, reads from the trace order
  // prefetched ahead.
  parallel_for(n, kChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (i + kPrefetchAhead < end) __builtin_prefetch(&traced[rank[i + kPrefetchAhead]]);
      const TracedRay& r = traced[rank[i]];
      out.t[i] = r.t;
      out.triangle[i] = r.triangle;
      out.uv[i] = r.uv;  // 0 on a miss
      out.normal[i] = r.normal;
      out.object[i] = r.object;
    }
  });
  if (foreign_triangle.load())
    throw std::logic_error("cast_ray_batch: a hit triangle has no record (records of another scene)");
  return out;
}

RayBatchHits cast_ray_batch(const Scene& scene, const RayScene& rays, std::span<const vec3> origins,
                            std::span<const vec3> directions, float tmin, float tmax) {
  return cast_ray_batch(triangle_hit_records(scene), rays, origins, directions, tmin, tmax);
}

}  // namespace proxima
