#include <gtest/gtest.h>

#include <iostream>

#include "proxima/core/rng.h"
#include "proxima/trace/object_bvh.h"
#include "proxima/trace/ray_scene.h"
#include "trace/test_geometry.h"

namespace proxima {

// One object's BVH answers rays as Embree does on a scene holding only that object: the
// same nearest triangle and distance, from inside and outside, with t ranges.
TEST(ObjectBvh, NearestHitsAgreeWithEmbree) {
  Scene scene;
  const uint32_t mat = test::add_diffuse(scene, vec3(0.5f), 0.5f, 0.0f);
  Mesh mesh = test::sphere_mesh(vec3(0.2f, -0.1f, 0.3f), 1.0f, 24, 12);
  append_mesh(mesh, test::quad_mesh(vec3(-2, -2, -0.5f), vec3(4, 0, 0), vec3(0, 4, 0)));
  add_object(scene, mesh, "ball-on-floor", mat);
  const ObjectBvh bvh(scene, 0);
  ASSERT_FALSE(bvh.empty());
  RayScene rays(scene);
  Pcg32 rng(7);
  auto in = [&](float a) { return a * (2.0f * rng.next_float() - 1.0f); };
  int hits = 0, disagree = 0;
  for (int k = 0; k < 4000; ++k) {
    const vec3 o(in(2.5f), in(2.5f), in(2.5f));
    const vec3 d = glm::normalize(vec3(in(1.0f), in(1.0f), in(1.0f)) + vec3(1e-3f));
    const float t_max = k % 2 ? kInf : 1.5f;
    const Hit e = rays.intersect(Ray{o, d, 0.0f, t_max});
    const auto b = bvh.intersect(o, d, 0.0f, t_max);
    if (e.valid() != b.has_value()) {
      ++disagree;
      continue;
    }
    if (!b) continue;
    ++hits;
    // A ray through a shared edge may take either neighbour; the distance is the same.
    if (std::abs(b->t - e.t) > 1e-4f * std::max(1.0f, e.t)) ++disagree;
  }
  EXPECT_GT(hits, 500);
  std::cout << hits << " hits, " << disagree << " disagree\n";
  EXPECT_LE(disagree, 2) << "of " << hits;  // edge-grazing rays only
}

}  // namespace proxima
