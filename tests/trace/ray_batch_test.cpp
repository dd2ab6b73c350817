// cast_ray_batch: the structure-of-arrays batch equals the single-ray queries bit for bit,
// for any thread count and whatever the order or composition of the batch (it traces rays
// in its own coherent order), and rejects bad input with InputError.
#include "proxima/trace/ray_batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/scene/builtin_scenes.h"

namespace proxima {
namespace {

struct Batch {
  std::vector<vec3> origins, directions;
};

// Rays from inside the Cornell box in random directions (most hit, those through the open
// side miss).
Batch random_rays(size_t n, uint64_t seed) {
  Pcg32 rng(seed);
  Batch b;
  for (size_t i = 0; i < n; ++i) {
    b.origins.push_back(
        vec3(rng.next_float() * 1.8f - 0.9f, rng.next_float() * 1.8f + 0.1f, rng.next_float() * 1.8f - 0.9f));
    b.directions.push_back(
        vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f + 1e-3f));
  }
  return b;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(RayBatch, EqualsTheSingleRayQueries) {
  const Scene scene = make_builtin_scene("cornell");
  const RayScene rays(scene);
  const Batch b = random_rays(20000, 3);
  const RayBatchHits h = cast_ray_batch(scene, rays, b.origins, b.directions);
  ASSERT_EQ(h.t.size(), b.origins.size());
  size_t hits = 0;
  for (size_t i = 0; i < b.origins.size(); ++i) {
    const Hit s = rays.intersect(Ray{b.origins[i], b.directions[i], 0.0f, kInf});
    ASSERT_EQ(h.triangle[i], s.triangle) << i;
    ASSERT_TRUE(same_bits(h.t[i], s.t)) << i;
    if (s.valid()) {
      ++hits;
      EXPECT_EQ(h.object[i], scene.triangle_object[s.triangle]);
      EXPECT_EQ(h.normal[i], triangle_normal(scene, s.triangle));
      EXPECT_EQ(h.uv[i], vec2(s.u, s.v));
    } else {
      EXPECT_EQ(h.object[i], kNoTriangle);
      EXPECT_EQ(h.normal[i], vec3(0.0f));
      EXPECT_EQ(h.uv[i], vec2(0.0f));
    }
  }
  EXPECT_GT(hits, b.origins.size() / 2);
  EXPECT_LT(hits, b.origins.size());
}

TEST(RayBatch, SameBitsForAnyThreadCount) {
  const Scene scene = make_builtin_scene("cornell");
  const RayScene rays(scene);
  const Batch b = random_rays(50000, 5);
  const RayBatchHits all = cast_ray_batch(scene, rays, b.origins, b.directions, 0.0f, 2.0f);
  ThreadLimit one(1);
  const RayBatchHits single = cast_ray_batch(scene, rays, b.origins, b.directions, 0.0f, 2.0f);
  EXPECT_TRUE(all.triangle == single.triangle);
  EXPECT_EQ(std::memcmp(all.t.data(), single.t.data(), all.t.size() * sizeof(float)), 0);
}

// Each ray of h equals the single-ray query of the same ray: ids, t, uv bit for bit, the
// normal and object those of the hit triangle. Returns the number of hits.
size_t expect_single_ray_results(const Scene& scene, const RayScene& rays, const Batch& b,
                                 const RayBatchHits& h) {
  size_t hits = 0;
  for (size_t i = 0; i < b.origins.size(); ++i) {
    const Hit s = rays.intersect(Ray{b.origins[i], b.directions[i], 0.0f, kInf});
    EXPECT_EQ(h.triangle[i], s.triangle) << i;
    EXPECT_TRUE(same_bits(h.t[i], s.t)) << i;
    EXPECT_TRUE(same_bits(h.uv[i].x, s.u) && same_bits(h.uv[i].y, s.v)) << i;
    if (!s.valid()) continue;
    ++hits;
    EXPECT_EQ(h.object[i], scene.triangle_object[s.triangle]) << i;
    EXPECT_EQ(h.normal[i], triangle_normal(scene, s.triangle)) << i;
  }
  return hits;
}

TEST(RayBatch, LargeSceneMixedCoherentAndRandomRays) {
  // living-room (≈290k triangles): random rays from inside the room, then a pinhole fan
  // from one point (one origin cell, few octants), interleaved with them.
  const Scene scene = make_builtin_scene("living-room");
  const RayScene rays(scene);
  vec3 lo(kInf), hi(-kInf);
  for (const vec3& p : scene.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const vec3 pad = 0.1f * (hi - lo), center = 0.5f * (lo + hi);
  Pcg32 rng(11);
  Batch b;
  for (int i = 0; i < 6000; ++i) {
    const vec3 u(rng.next_float(), rng.next_float(), rng.next_float());
    b.origins.push_back(lo + pad + u * (hi - lo - 2.0f * pad));
    b.directions.push_back(
        vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f + 1e-3f));
    b.origins.push_back(center);
    b.directions.push_back(vec3(float(i % 80) / 80.0f - 0.5f, float(i / 80) / 75.0f - 0.5f, -1.0f));
  }
  const auto records = triangle_hit_records(scene);
  const RayBatchHits h = cast_ray_batch(records, rays, b.origins, b.directions);
  const size_t hits = expect_single_ray_results(scene, rays, b, h);
  EXPECT_GT(hits, b.origins.size() / 2);
}

TEST(RayBatch, ResultsDoNotDependOnTheBatchOrderOrComposition) {
  const Scene scene = make_builtin_scene("cornell");
  const RayScene rays(scene);
  const Batch b = random_rays(30000, 7);
  const RayBatchHits whole = cast_ray_batch(scene, rays, b.origins, b.directions);
  // Reversed: the same rays in the opposite order.
  Batch reversed = b;
  std::reverse(reversed.origins.begin(), reversed.origins.end());
  std::reverse(reversed.directions.begin(), reversed.directions.end());
  const RayBatchHits back = cast_ray_batch(scene, rays, reversed.origins, reversed.directions);
  // A part of the batch alone (other origin bounds, so other sort keys).
  const size_t part = 777;
  const RayBatchHits first =
      cast_ray_batch(scene, rays, std::span(b.origins).first(part), std::span(b.directions).first(part));
  for (size_t i = 0; i < b.origins.size(); ++i) {
    const size_t r = b.origins.size() - 1 - i;
    ASSERT_EQ(whole.triangle[i], back.triangle[r]) << i;
    ASSERT_TRUE(same_bits(whole.t[i], back.t[r])) << i;
    ASSERT_EQ(whole.normal[i], back.normal[r]) << i;
    ASSERT_EQ(whole.uv[i], back.uv[r]) << i;
    if (i < part) {
      ASSERT_EQ(whole.triangle[i], first.triangle[i]) << i;
      ASSERT_TRUE(same_bits(whole.t[i], first.t[i])) << i;
    }
  }
}

TEST(RayBatch, HitRecordsAreTheTrianglesNormalAndObject) {
  const Scene scene = make_builtin_scene("cornell");
  const auto records = triangle_hit_records(scene);
  ASSERT_EQ(records.size(), scene.triangles.size());
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    EXPECT_EQ(records[t].normal, triangle_normal(scene, t)) << t;
    EXPECT_EQ(records[t].object, scene.triangle_object[t]) << t;
  }
}

TEST(RayBatch, RecordsOfAnotherSceneAreRefused) {
  // The records of a scene with fewer triangles than the one traced: a hit triangle has no
  // record, which must not read past them.
  const Scene scene = make_builtin_scene("cornell");
  const RayScene rays(scene);
  const std::vector<TriangleHitRecord> too_few(1);
  const Batch b = random_rays(1000, 9);
  EXPECT_THROW(cast_ray_batch(too_few, rays, b.origins, b.directions), std::logic_error);
}

TEST(RayBatch, RejectsBadInput) {
  const Scene scene = make_builtin_scene("cornell");
  const RayScene rays(scene);
  const std::vector<vec3> one = {vec3(0, 1, 0)}, down = {vec3(0, -1, 0)},
                          two = {vec3(0, -1, 0), vec3(0, 1, 0)};
  const std::vector<vec3> nan = {vec3(0, NAN, 0)}, zero = {vec3(0.0f)}, inf = {vec3(kInf, 0, 0)};
  EXPECT_THROW(cast_ray_batch(scene, rays, one, two), InputError);
  EXPECT_THROW(cast_ray_batch(scene, rays, nan, down), InputError);
  EXPECT_THROW(cast_ray_batch(scene, rays, one, zero), InputError);
  EXPECT_THROW(cast_ray_batch(scene, rays, one, inf), InputError);
  EXPECT_THROW(cast_ray_batch(scene, rays, one, down, -1.0f), InputError);
  EXPECT_THROW(cast_ray_batch(scene, rays, one, down, 2.0f, 1.0f), InputError);
  EXPECT_TRUE(cast_ray_batch(scene, rays, {}, {}).t.empty());
  const RayBatchHits h = cast_ray_batch(scene, rays, one, down);
  EXPECT_NEAR(h.t[0], 1.0f, 1e-5f);  // the floor, y = 0
}

}  // namespace
}  // namespace proxima
