#include <gtest/gtest.h>

#include "proxima/reflect/reflection_clustering.h"

namespace proxima {

TEST(ClusterClustering, SeparateObjectsWithEqualNormalsGetSeparateClusters) {
  // Two flat reflectors facing up (a table top and the floor), 50 pixels each.
  std::vector<vec3> normals(100, vec3(0.0f, 1.0f, 0.0f));
  std::vector<uint32_t> reflectors(100, 3);
  for (size_t i = 50; i < 100; ++i) reflectors[i] = 7;
  ReflectionClusters c = cluster_reflections(normals, reflectors);
  ASSERT_EQ(c.count(), 2u);
  EXPECT_NE(c.cluster_of[0], c.cluster_of[99]);
  EXPECT_EQ(c.reflector[c.cluster_of[0]], 3u);
  EXPECT_EQ(c.reflector[c.cluster_of[99]], 7u);
  EXPECT_EQ(c.cluster(c.cluster_of[0]).size(), 50u);
}

TEST(ClusterClustering, FlatSurfaceWithNoisyNormalsIsOneCluster) {
  // Axis-aligned walls with float noise in their normals stay in one bin each.
  std::vector<vec3> normals;
  std::vector<uint32_t> reflectors;
  for (int i = 0; i < 200; ++i) {
    float e = 1e-6f * float(i % 7 - 3);
    normals.push_back(glm::normalize(vec3(e, 1.0f, -e)));
    reflectors.push_back(0);
    normals.push_back(glm::normalize(vec3(1.0f, e, e)));
    reflectors.push_back(1);
  }
  ReflectionClusters c = cluster_reflections(normals, reflectors);
  EXPECT_EQ(c.count(), 2u);
}

TEST(ClusterClustering, CurvedReflectorSplitsByNormalAndBinsScaleWithShare) {
  // A sphere's visible hemisphere on one reflector: at most 13 × 8 clusters, more than one.
  std::vector<vec3> normals;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      float th = 6.2831853f * float(i) / 40.0f, ph = 1.5707963f * float(j) / 40.0f;
      normals.push_back(vec3(std::sin(ph) * std::cos(th), std::cos(ph), std::sin(ph) * std::sin(th)));
    }
  std::vector<uint32_t> one(normals.size(), 0);
  ReflectionClusters full = cluster_reflections(normals, one);
  EXPECT_GT(full.count(), 10u);
  EXPECT_LE(full.count(), 13u * 8u);
  // The same sphere as a 1% share beside a large flat reflector gets fewer bins.
  std::vector<vec3> n2 = normals;
  std::vector<uint32_t> r2(normals.size(), 0);
  for (int i = 0; i < 160000; ++i) {
    n2.push_back(vec3(0.0f, 1.0f, 0.0f));
    r2.push_back(1);
  }
  ReflectionClusters small = cluster_reflections(n2, r2);
  EXPECT_LT(small.count() - 1, full.count());
}

TEST(ClusterClustering, EmptyInput) {
  ReflectionClusters c = cluster_reflections({}, {});
  EXPECT_EQ(c.count(), 0u);
  EXPECT_EQ(c.offsets.size(), 1u);
}

}  // namespace proxima
