// cast_ray_batch: the structure-of-arrays batch equals the single-ray queries bit for bit,
// for any thread count, and rejects bad input with InputError.
#include "proxima/trace/ray_batch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
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
    b.origins.push_back(vec3(rng.next_float() * 1.8f - 0.9f, rng.next_float() * 1.8f + 0.1f, rng.next_float() * 1.8f - 0.9f));
    b.directions.push_back(vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f + 1e-3f));
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

TEST(RayBatch, RejectsBadInput) {
  const Scene scene = make_builtin_scene("cornell");
  const RayScene rays(scene);
  const std::vector<vec3> one = {vec3(0, 1, 0)}, down = {vec3(0, -1, 0)}, two = {vec3(0, -1, 0), vec3(0, 1, 0)};
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
