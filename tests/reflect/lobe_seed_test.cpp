// Glossy lobe rays seeded by the surface point (ReflectionOptions::lobe_seed_cell):
// a point draws the same lobe samples from any view, so a reflection reused from another
// frame carries the noise the reference has there; determinism for any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include "proxima/core/parallel.h"
#include "proxima/reflect/cluster_reflection.h"
#include "proxima/scene/scene.h"
#include "reflect_test_scenes.h"

namespace proxima {

namespace {

using reflect_test::add_diffuse;
using reflect_test::add_quad;

// A glossy 4 × 4 m floor (y = 0) in front of a lit wall.
Scene glossy_floor() {
  Scene s;
  s.name = "glossy-floor";
  const uint32_t floor_mat = add_diffuse(s, vec3(0.4f), 0.8f);
  s.materials[floor_mat].gloss = 0.3f;
  add_quad(s, vec3(-2, 0, -2), vec3(0, 0, 4), vec3(4, 0, 0), floor_mat, "floor");
  add_quad(s, vec3(-4, -1, -2), vec3(8, 0, 0), vec3(0, 6, 0), add_diffuse(s, vec3(0.8f, 0.5f, 0.2f)), "wall");
  s.point_lights.push_back({vec3(0.0f, 3.0f, 1.0f), vec3(12.0f)});
  return s;
}

Camera camera_at(vec3 eye) { return look_at(eye, vec3(0.0f, 0.0f, -0.3f), vec3(0, 1, 0), 50.0f, 64, 64, 0.01f, 100.0f); }

constexpr float kCell = 0.004f;  // × the scene diagonal

ReflectionFrame frame_at(const Scene& scene, vec3 eye, float cell) {
  ReflectionOptions o;
  o.supersample = 1;
  o.glossy_rays = 4;
  o.lobe_seed_cell = cell;
  return prepare_reflection_frame(scene, camera_at(eye), o);
}

// Angle of each lobe ray of sample i from the sample's mirror direction: a function of its
// lobe sample alone (the cone angle), whatever the view.
std::vector<float> lobe_angles(const ReflectionFrame& f, size_t i) {
  const vec3 mirror = reflect(glm::normalize(f.position[i] - f.camera.position), f.normal[i]);
  std::vector<float> out;
  for (uint32_t r = f.first_ray[i]; r < f.first_ray[i + 1]; ++r)
    out.push_back(std::acos(std::clamp(glm::dot(f.direction[r], mirror), -1.0f, 1.0f)));
  return out;
}

// Of the sample pairs (one per frame) whose points share a seed cell, the fraction whose
// lobe angles all agree.
double same_lobe_fraction(const ReflectionFrame& a, const ReflectionFrame& b, size_t* pairs) {
  const float cell = kCell * a.scene_diagonal;
  auto key = [&](vec3 p) {
    return std::make_tuple(int64_t(std::floor(p.x / cell)), int64_t(std::floor(p.y / cell)),
                           int64_t(std::floor(p.z / cell)));
  };
  std::map<std::tuple<int64_t, int64_t, int64_t>, size_t> in_a;
  for (size_t i = 0; i < a.sample_count(); ++i) in_a[key(a.position[i])] = i;
  size_t n = 0, same = 0;
  for (size_t j = 0; j < b.sample_count(); ++j) {
    const auto it = in_a.find(key(b.position[j]));
    if (it == in_a.end()) continue;
    ++n;
    const std::vector<float> x = lobe_angles(a, it->second), y = lobe_angles(b, j);
    bool equal = x.size() == y.size();
    for (size_t k = 0; equal && k < x.size(); ++k) equal = std::abs(x[k] - y[k]) < 1e-3f;
    same += equal;
  }
  *pairs = n;
  return n ? double(same) / double(n) : 0.0;
}

}  // namespace

TEST(LobeSeed, SameSurfacePointDrawsTheSameLobeSamplesFromAnotherView) {
  const Scene scene = glossy_floor();
  const vec3 eye(0.0f, 1.5f, 3.0f), moved = eye + vec3(0.1f, 0.04f, -0.05f);
  size_t pairs = 0;
  const double surface = same_lobe_fraction(frame_at(scene, eye, kCell), frame_at(scene, moved, kCell), &pairs);
  ASSERT_GT(pairs, 500u);
  // Rays that the lobe would send below the floor are mirrored back (glossy_lobe_direction),
  // which changes their angle from the mirror direction; at this view that is rare.
  EXPECT_GE(surface, 0.95) << pairs;
  // Per-pixel streams: the point moved to another pixel, mostly another stream.
  const double pixel = same_lobe_fraction(frame_at(scene, eye, 0.0f), frame_at(scene, moved, 0.0f), &pairs);
  EXPECT_LE(pixel, 0.5) << pairs;
}

TEST(LobeSeed, SurfaceSeededRaysAreIdenticalForAnyThreadCount) {
  const Scene scene = glossy_floor();
  auto rays = [&](int threads) {
    ThreadLimit limit(threads);
    return frame_at(scene, vec3(0.3f, 1.2f, 2.5f), kCell).direction;
  };
  const std::vector<vec3> one = rays(1), two = rays(2);
  ASSERT_EQ(one.size(), two.size());
  ASSERT_GT(one.size(), 1000u);
  for (size_t i = 0; i < one.size(); ++i) ASSERT_EQ(one[i], two[i]) << i;
}

TEST(LobeSeed, NegativeCellIsAnInputError) {
  const Scene scene = glossy_floor();
  EXPECT_ANY_THROW(frame_at(scene, vec3(0.0f, 1.5f, 3.0f), -1.0f));
}

}  // namespace proxima
