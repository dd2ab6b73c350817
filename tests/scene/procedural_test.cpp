// Procedural meshes: exact triangle counts, closedness, orientation, normals, and the
// teapot data's internal consistency (shared patch edges, symmetry).
#include "proxima/scene/procedural.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <tuple>
#include <utility>
#include <vector>

namespace proxima {
namespace {

// Vertex ids after welding by exact position.
std::vector<uint32_t> weld(const Mesh& m) {
  std::map<std::tuple<float, float, float>, uint32_t> ids;
  std::vector<uint32_t> out;
  out.reserve(m.positions.size());
  for (const vec3& p : m.positions) {
    auto it = ids.emplace(std::make_tuple(p.x, p.y, p.z), uint32_t(ids.size())).first;
    out.push_back(it->second);
  }
  return out;
}

struct EdgeStats {
  size_t boundary = 0;          // undirected edges used by one triangle
  size_t shared = 0;            // … by two
  size_t over_shared = 0;       // … by more than two
  size_t repeated_directed = 0; // directed edges used twice (inconsistent orientation)
  size_t degenerate = 0;        // triangles with two welded vertices equal
};

EdgeStats edge_stats(const Mesh& m) {
  std::vector<uint32_t> id = weld(m);
  std::map<std::pair<uint32_t, uint32_t>, int> undirected, directed;
  EdgeStats s;
  for (const uvec3& t : m.triangles) {
    uint32_t v[3] = {id[t.x], id[t.y], id[t.z]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      ++s.degenerate;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      uint32_t a = v[k], b = v[(k + 1) % 3];
      ++directed[{a, b}];
      ++undirected[{std::min(a, b), std::max(a, b)}];
    }
  }
  for (const auto& [e, n] : undirected) {
    if (n == 1) ++s.boundary;
    if (n == 2) ++s.shared;
    if (n > 2) ++s.over_shared;
  }
  for (const auto& [e, n] : directed) {
    if (n > 1) ++s.repeated_directed;
  }
  return s;
}

// Closed and consistently oriented: every edge has exactly two triangles, traversed in
// opposite directions.
void expect_watertight(const Mesh& m) {
  EdgeStats s = edge_stats(m);
  EXPECT_EQ(s.boundary, 0u);
  EXPECT_EQ(s.over_shared, 0u);
  EXPECT_EQ(s.repeated_directed, 0u);
  EXPECT_EQ(s.degenerate, 0u);
  EXPECT_GT(s.shared, 0u);
}

// Σ p0 · (p1 × p2) / 6: the enclosed volume, positive when the triangles face outward.
double signed_volume(const Mesh& m) {
  double v = 0.0;
  for (const uvec3& t : m.triangles) {
    dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
    v += glm::dot(a, glm::cross(b, c));
  }
  return v / 6.0;
}

// Attributes are complete, normals unit, uvs in [0, 1], indices in range; the vertex
// normals agree with the winding (positive dot with the face normal) on at least
// `min_agree` of the non-degenerate triangles.
void expect_well_formed(const Mesh& m, double min_agree = 1.0) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  for (size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_TRUE(is_finite(m.positions[i]));
    EXPECT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-5f) << "vertex " << i;
    EXPECT_GE(m.uvs[i].x, 0.0f);
    EXPECT_LE(m.uvs[i].x, 1.0f);
    EXPECT_GE(m.uvs[i].y, 0.0f);
    EXPECT_LE(m.uvs[i].y, 1.0f);
  }
  size_t agree = 0, counted = 0;
  for (const uvec3& t : m.triangles) {
    ASSERT_LT(t.x, m.positions.size());
    ASSERT_LT(t.y, m.positions.size());
    ASSERT_LT(t.z, m.positions.size());
    vec3 face = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    if (glm::length(face) == 0.0f) continue;
    ++counted;
    vec3 n = m.normals[t.x] + m.normals[t.y] + m.normals[t.z];
    if (glm::dot(face, n) > 0.0f) ++agree;
  }
  ASSERT_GT(counted, 0u);
  EXPECT_GE(double(agree), min_agree * double(counted)) << agree << " of " << counted;
}

Bounds3 bounds(const Mesh& m) {
  Bounds3 b;
  for (const vec3& p : m.positions) b.extend(p);
  return b;
}

TEST(ProceduralSphere, TriangleCount) {
  EXPECT_EQ(make_sphere(1.0f, 3, 2).triangles.size(), 2u * 3u * 1u);
  EXPECT_EQ(make_sphere(1.0f, 16, 8).triangles.size(), 2u * 16u * 7u);
  EXPECT_EQ(make_sphere(0.4f, 64, 32).triangles.size(), 2u * 64u * 31u);
}

TEST(ProceduralSphere, ClosedOutwardWithAnalyticVolume) {
  const float r = 0.4f;
  Mesh m = make_sphere(r, 64, 32);
  expect_watertight(m);
  expect_well_formed(m);
  double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  double v = signed_volume(m);
  EXPECT_GT(v, 0.0);
  EXPECT_LT(v, exact);  // inscribed polyhedron
  EXPECT_NEAR(v, exact, 0.01 * exact);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_NEAR(glm::length(m.positions[i]), r, 1e-6f);
    EXPECT_LT(glm::length(m.normals[i] - m.positions[i] / r), 1e-5f);
  }
}

// Every vertex on the implicit surface Σ|p_i/r_i|^(2/e) = 1, normals along its gradient
// (checked by finite differences), closed and outward; e = 1 is the ellipsoid.
TEST(ProceduralSuperellipsoid, OnTheSurfaceWithGradientNormals) {
  const vec3 r{1.5f, 0.32f, 0.68f};
  for (float e : {1.0f, 0.55f, 0.3f}) {
    SCOPED_TRACE(e);
    Mesh m = make_superellipsoid(r, e, 48, 24);
    EXPECT_EQ(m.triangles.size(), 2u * 48u * 23u);
    expect_watertight(m);
    expect_well_formed(m);
    EXPECT_GT(signed_volume(m), 0.0);
    auto f = [&](dvec3 p) {
      double sum = 0.0;
      for (int c = 0; c < 3; ++c) sum += std::pow(std::abs(p[c] / double(r[c])), 2.0 / double(e));
      return sum;
    };
    for (size_t i = 0; i < m.positions.size(); ++i) {
      dvec3 p(m.positions[i]);
      EXPECT_NEAR(f(p), 1.0, 1e-4) << "vertex " << i;
      // Finite-difference gradient (skipped at the axis extremes, where it has a kink for e < 1).
      const double h = 1e-5;
      dvec3 g;
      for (int c = 0; c < 3; ++c) {
        dvec3 d(0.0);
        d[c] = h;
        g[c] = (f(p + d) - f(p - d)) / (2.0 * h);
      }
      if (glm::length(g) < 1e-3) continue;
      EXPECT_GT(glm::dot(glm::normalize(g), dvec3(m.normals[i])), 0.999) << "vertex " << i;
    }
  }
  Mesh ellipsoid = make_superellipsoid(vec3(1.0f), 1.0f, 32, 16);
  Mesh sphere = make_sphere(1.0f, 32, 16);
  for (size_t i = 0; i < sphere.positions.size(); ++i)
    EXPECT_LT(glm::length(ellipsoid.positions[i] - sphere.positions[i]), 1e-6f);
}

TEST(ProceduralCylinder, TriangleCounts) {
  EXPECT_EQ(make_cylinder(1.0f, 2.0f, 64, 16, false).triangles.size(), 2u * 64u * 16u);
  EXPECT_EQ(make_cylinder(1.0f, 2.0f, 64, 16, true).triangles.size(), 2u * 64u * 16u + 2u * 64u);
  EXPECT_EQ(make_cylinder(1.0f, 2.0f, 3, 1, true).triangles.size(), 6u + 6u);
}

TEST(ProceduralCylinder, CappedIsClosedWithAnalyticVolume) {
  const float r = 0.5f, h = 2.0f;
  Mesh m = make_cylinder(r, h, 96, 4, true);
  expect_watertight(m);
  expect_well_formed(m);
  double exact = std::numbers::pi * r * r * h;
  double v = signed_volume(m);
  EXPECT_LT(v, exact);
  EXPECT_NEAR(v, exact, 0.005 * exact);
  Bounds3 b = bounds(m);
  EXPECT_EQ(b.min.y, 0.0f);
  EXPECT_EQ(b.max.y, h);
}

TEST(ProceduralCylinder, UncappedHasTwoOpenRims) {
  Mesh m = make_cylinder(1.0f, 1.0f, 32, 3, false);
  EdgeStats s = edge_stats(m);
  EXPECT_EQ(s.boundary, 2u * 32u);
  EXPECT_EQ(s.repeated_directed, 0u);
  expect_well_formed(m);
  for (const vec3& n : m.normals) EXPECT_EQ(n.y, 0.0f);
}

TEST(ProceduralTorus, ClosedWithAnalyticVolume) {
  const float R = 1.0f, r = 0.25f;
  Mesh m = make_torus(R, r, 96, 48);
  EXPECT_EQ(m.triangles.size(), 2u * 96u * 48u);
  expect_watertight(m);
  expect_well_formed(m);
  double exact = 2.0 * std::numbers::pi * std::numbers::pi * R * r * r;
  EXPECT_NEAR(signed_volume(m), exact, 0.01 * exact);
  Bounds3 b = bounds(m);
  EXPECT_NEAR(b.max.x, R + r, 1e-6f);
  EXPECT_NEAR(b.max.y, r, 1e-6f);
  EXPECT_NEAR(b.min.y, -r, 1e-6f);
}

TEST(ProceduralBox, ClosedExactVolumeAndBounds) {
  for (int sub : {1, 3}) {
    const vec3 size{0.5f, 1.0f, 2.0f};
    Mesh m = make_box(size, sub);
    EXPECT_EQ(m.triangles.size(), 12u * size_t(sub * sub));
    expect_watertight(m);
    expect_well_formed(m);
    EXPECT_NEAR(signed_volume(m), 1.0, 1e-6);
    Bounds3 b = bounds(m);
    EXPECT_EQ(b.min, -0.5f * size);
    EXPECT_EQ(b.max, 0.5f * size);
    // Flat faces: every vertex normal is one of the six axis directions and points out.
    for (size_t i = 0; i < m.positions.size(); ++i) {
      vec3 n = m.normals[i];
      EXPECT_EQ(std::abs(n.x) + std::abs(n.y) + std::abs(n.z), 1.0f);
      EXPECT_FLOAT_EQ(glm::dot(n, m.positions[i]), glm::dot(glm::abs(n), 0.5f * size));
    }
  }
}

TEST(ProceduralPlane, FacesUpWithExactArea) {
  Mesh m = make_plane(2.0f, 3.0f, 4, 5);
  EXPECT_EQ(m.triangles.size(), 2u * 4u * 5u);
  expect_well_formed(m);
  double area = 0.0;
  for (const uvec3& t : m.triangles) {
    vec3 c = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    EXPECT_GT(c.y, 0.0f);
    area += 0.5 * glm::length(c);
  }
  EXPECT_NEAR(area, 6.0, 1e-5);
  Bounds3 b = bounds(m);
  EXPECT_EQ(b.min, vec3(-1.0f, 0.0f, -1.5f));
  EXPECT_EQ(b.max, vec3(1.0f, 0.0f, 1.5f));
  EdgeStats s = edge_stats(m);
  EXPECT_EQ(s.boundary, 2u * (4u + 5u));
}

TEST(ProceduralTeapot, TriangleCountDropsPoleDegenerates) {
  for (int n : {1, 4, 10}) {
    Mesh m = make_teapot(n);
    EXPECT_EQ(m.triangles.size(), size_t(64 * n * n - 8 * n)) << "n = " << n;
    EXPECT_EQ(edge_stats(m).degenerate, 0u) << "n = " << n;
  }
}

TEST(ProceduralTeapot, RestsOnGroundWithHeightOneSpoutTowardPlusX) {
  Mesh m = make_teapot(8);
  expect_well_formed(m, 0.99);
  Bounds3 b = bounds(m);
  EXPECT_NEAR(b.min.y, 0.0f, 1e-6f);
  EXPECT_NEAR(b.max.y, 1.0f, 1e-6f);
  // Body radius 2, spout tip near x = 3.4, handle out to x ≈ −2.9 (Newell units, height 3.15).
  EXPECT_NEAR(b.max.z, 2.0f / 3.15f, 1e-3f);
  EXPECT_NEAR(b.min.z, -2.0f / 3.15f, 1e-3f);
  EXPECT_GT(b.max.x, 3.2f / 3.15f);
  EXPECT_LT(b.min.x, -2.8f / 3.15f);
  EXPECT_GT(b.max.x, -b.min.x);
  EXPECT_GT(signed_volume(m), 0.0);
}

// Adjacent patches share their edges, so after welding the only open edges are the five
// rims the data leaves open: the pot's opening and the lid's edge (4n edges each), and
// both ends of the handle and of the spout (2n each). A mistyped shared control point
// would open more.
TEST(ProceduralTeapot, PatchesMeetExactlyAndAreConsistentlyOriented) {
  for (int n : {3, 8}) {
    EdgeStats s = edge_stats(make_teapot(n));
    EXPECT_EQ(s.boundary, size_t(16 * n)) << "n = " << n;
    EXPECT_EQ(s.over_shared, 0u);
    EXPECT_EQ(s.repeated_directed, 0u);
  }
}

// Newell's data is mirror-symmetric about the plane through spout and handle (z = 0 here),
// and pot, lid and bottom are symmetric under quarter turns about the axis. A mistyped
// control point breaks one of these.
TEST(ProceduralTeapot, DataIsSymmetric) {
  Mesh m = make_teapot(6);
  std::vector<vec3> sorted = m.positions;
  auto less = [](vec3 a, vec3 b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
  std::sort(sorted.begin(), sorted.end(), less);
  auto has = [&](vec3 q) {
    auto it = std::lower_bound(sorted.begin(), sorted.end(), vec3(q.x - 2e-6f, -kInf, -kInf), less);
    for (; it != sorted.end() && it->x <= q.x + 2e-6f; ++it) {
      if (glm::length(*it - q) <= 2e-6f) return true;
    }
    return false;
  };
  size_t mirrored = 0, turned = 0, turn_exempt = 0;
  for (const vec3& p : m.positions) {
    if (has({p.x, p.y, -p.z})) ++mirrored;
    // Handle and spout (|z| < 0.66 / 3.15, |x| > 1.5 / 3.15) have no quarter-turn partner.
    if (has({p.z, p.y, -p.x})) {
      ++turned;
    } else if (std::abs(p.z) < 0.21f && std::abs(p.x) > 0.47f) {
      ++turn_exempt;
    }
  }
  EXPECT_EQ(mirrored, m.positions.size());
  EXPECT_EQ(turned + turn_exempt, m.positions.size());
  EXPECT_GT(turned, m.positions.size() / 2);
}

TEST(ProceduralTeapot, Deterministic) {
  Mesh a = make_teapot(5), b = make_teapot(5);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(),
                           a.positions.size() * sizeof(vec3)));
  EXPECT_EQ(a.triangles, b.triangles);
}

}  // namespace
}  // namespace proxima
