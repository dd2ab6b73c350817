// View sets: corner layout, intermediate viewpoints inside the region and seeded.
#include "proxima/depthimage/view_set.h"

#include <gtest/gtest.h>

#include "proxima/core/error.h"

namespace proxima {
namespace {

const Camera kBase = look_at(vec3(0, 1, 5), vec3(0, 1, 0), vec3(0, 1, 0), 45.0f, 64, 64);

TEST(ViewSet, CornersLieAroundTheBaseInItsImagePlane) {
  for (ViewShape shape : {ViewShape::Segment, ViewShape::Triangle, ViewShape::Rectangle}) {
    const ViewSet set = make_view_set(shape, kBase, 0.5f, 5.0f);
    const size_t want = shape == ViewShape::Segment ? 2 : shape == ViewShape::Triangle ? 3 : 4;
    ASSERT_EQ(set.corners.size(), want);
    vec3 sum(0.0f);
    for (vec3 c : set.corners) {
      sum += c;
      EXPECT_NEAR(c.z, 5.0f, 1e-5f);  // the base looks down −Z: corners in z = 5
    }
    const Camera centroid = centroid_camera(set);
    EXPECT_NEAR(glm::length(sum / float(want) - kBase.position), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(camera_forward(centroid) - camera_forward(kBase)), 0.0f, 1e-5f);
    // Every corner camera looks at the target.
    const auto p = project(corner_camera(set, 1), set.target);
    ASSERT_TRUE(p.has_value());
    EXPECT_NEAR(p->pixel.x, 32.0f, 1e-3f);
    EXPECT_NEAR(p->pixel.y, 32.0f, 1e-3f);
  }
}

TEST(ViewSet, IntermediateViewpointsFillTheTriangleAndAreSeeded) {
  const ViewSet set = make_view_set(ViewShape::Triangle, kBase, 1.0f, 5.0f);
  const auto a = intermediate_viewpoints(set, 2000, 7);
  EXPECT_EQ(a, intermediate_viewpoints(set, 2000, 7));
  EXPECT_NE(a, intermediate_viewpoints(set, 2000, 8));
  const vec3 v0 = set.corners[0], v1 = set.corners[1], v2 = set.corners[2];
  const vec3 n = glm::cross(v1 - v0, v2 - v0);
  int near_corner[3] = {0, 0, 0};
  for (vec3 p : a) {
    // Inside: same side of every edge.
    EXPECT_GE(glm::dot(glm::cross(v1 - v0, p - v0), n), -1e-5f);
    EXPECT_GE(glm::dot(glm::cross(v2 - v1, p - v1), n), -1e-5f);
    EXPECT_GE(glm::dot(glm::cross(v0 - v2, p - v2), n), -1e-5f);
    for (int k = 0; k < 3; ++k) near_corner[k] += glm::length(p - set.corners[size_t(k)]) < 0.6f;
  }
  // Uniform: the three corner regions get similar shares (each ~12 % of the points).
  for (int k = 0; k < 3; ++k) EXPECT_GT(near_corner[k], 120) << k;
}

TEST(ViewSet, ParseRejectsUnknownNamesNamingTheFlag) {
  EXPECT_EQ(parse_view_shape("rectangle", "--views"), ViewShape::Rectangle);
  try {
    parse_view_shape("hexagon", "--views");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--views"), std::string::npos);
  }
}

}  // namespace
}  // namespace proxima
