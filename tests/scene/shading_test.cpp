#include "proxima/scene/shading.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace proxima {
namespace {

TEST(Shading, ReflectMirrorsAboutNormal) {
  vec3 r = reflect(vec3(1.0f, -1.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(r, vec3(1.0f, 1.0f, 0.0f));
  // The side of the normal does not matter.
  EXPECT_EQ(reflect(vec3(1.0f, -1.0f, 0.0f), vec3(0.0f, -1.0f, 0.0f)), r);
}

TEST(Shading, GlossyHalfAngleIsLinearUpTo30Degrees) {
  EXPECT_EQ(glossy_lobe_half_angle(0.0f), 0.0f);
  EXPECT_NEAR(glossy_lobe_half_angle(0.5f), glm::radians(15.0f), 1e-7f);
  EXPECT_NEAR(glossy_lobe_half_angle(1.0f), glm::radians(30.0f), 1e-7f);
  EXPECT_NEAR(glossy_lobe_half_angle(7.0f), glm::radians(30.0f), 1e-7f);  // clamped
}

TEST(Shading, SampleConeStaysInsideAndIsUniformInSolidAngle) {
  Pcg32 rng(7);
  for (vec3 axis : {vec3(0, 0, 1), vec3(0, 0, -1), glm::normalize(vec3(1, -2, 0.3f))}) {
    float alpha = glm::radians(20.0f);
    double mean_cos = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      vec3 d = sample_cone(axis, alpha, rng.next_float(), rng.next_float());
      EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
      float c = glm::dot(d, axis);
      EXPECT_GE(c, std::cos(alpha) - 1e-5f);
      mean_cos += c;
    }
    // Uniform in solid angle: cos θ is uniform on [cos α, 1]; 5 standard errors.
    double width = 1.0 - std::cos(alpha);
    EXPECT_NEAR(mean_cos / n, 1.0 - 0.5 * width, 5.0 * width / std::sqrt(12.0 * n));
  }
  EXPECT_EQ(sample_cone(vec3(0, 1, 0), 0.0f, 0.3f, 0.7f), vec3(0, 1, 0));
}

TEST(Shading, LobeDirectionNeverPointsBelowTheSurface) {
  vec3 n(0, 1, 0);
  vec3 grazing = glm::normalize(vec3(1.0f, 0.05f, 0.0f));
  Pcg32 rng(3);
  for (int i = 0; i < 1000; ++i) {
    vec3 d = glossy_lobe_direction(grazing, n, glm::radians(30.0f), vec2(rng.next_float(), rng.next_float()));
    EXPECT_GE(glm::dot(d, n), 0.0f);
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
  }
}

// m² samples: one per cell of the m×m grid; otherwise one per x stratum and per y stratum.
void expect_stratified(int count) {
  std::vector<vec2> s(static_cast<size_t>(count));
  Pcg32 rng(11);
  stratified_samples_2d(s, rng);
  int m = int(std::lround(std::sqrt(count)));
  bool grid = m * m == count;
  std::vector<int> cells(size_t(count), 0), xs(size_t(count), 0), ys(size_t(count), 0);
  for (vec2 p : s) {
    ASSERT_TRUE(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f);
    if (grid) {
      ++cells[size_t(int(p.y * float(m)) * m + int(p.x * float(m)))];
    } else {
      ++xs[size_t(p.x * float(count))];
      ++ys[size_t(p.y * float(count))];
    }
  }
  auto once = [](const std::vector<int>& v) {
    return std::all_of(v.begin(), v.end(), [](int c) { return c == 1; });
  };
  if (grid) {
    EXPECT_TRUE(once(cells)) << count;
  } else {
    EXPECT_TRUE(once(xs)) << count;
    EXPECT_TRUE(once(ys)) << count;
  }
}

TEST(Shading, StratifiedSamplesCoverEveryStratum) {
  expect_stratified(1);
  expect_stratified(16);
  expect_stratified(49);
  expect_stratified(7);
  expect_stratified(12);
}

TEST(Shading, PointLightInverseSquareAndCosine) {
  PointLight light{vec3(0, 2, 0), vec3(8, 4, 2)};
  EXPECT_EQ(point_light_irradiance(light, vec3(0), vec3(0, 1, 0)), vec3(2, 1, 0.5f));
  // 45° incidence at distance √8: I·cos45°/8.
  vec3 e = point_light_irradiance(light, vec3(2, 0, 0), vec3(0, 1, 0));
  EXPECT_NEAR(e.x, 8.0f * std::sqrt(0.5f) / 8.0f, 1e-6f);
  EXPECT_EQ(point_light_irradiance(light, vec3(0), vec3(0, -1, 0)), vec3(0));  // behind
  EXPECT_EQ(point_light_irradiance(light, light.position, vec3(0, 1, 0)), vec3(0));
}

// Closed form: irradiance under the corner of a parallel a×b rectangle at height h
// (configuration factor of a differential area to a parallel rectangle), E = π·L·F.
double corner_irradiance(double a, double b, double h, double radiance) {
  double x = a / h, y = b / h;
  double f = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
              y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
             (2.0 * M_PI);
  return M_PI * radiance * f;
}

TEST(Shading, AreaLightSamplesConvergeToClosedForm) {
  // Light facing down (normal −Y) at height 1.5 over [0, 2] × [0, 1] in x, z.
  AreaLight light{vec3(0, 1.5f, 0), vec3(2, 0, 0), vec3(0, 0, 1), vec3(3.0f)};
  ASSERT_NEAR(light.normal().y, -1.0f, 1e-6f);
  const int n = 64;
  Pcg32 rng(5);
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      vec2 ab = stratum_sample(i, j, n, rng.next_float(), rng.next_float());
      sum += area_light_sample_irradiance(light, light.point(ab.x, ab.y), vec3(0), vec3(0, 1, 0)).x;
    }
  EXPECT_NEAR(sum / (n * n), corner_irradiance(2.0, 1.0, 1.5, 3.0),
              1e-3 * corner_irradiance(2.0, 1.0, 1.5, 3.0));
  // One-sided: a point above the light receives nothing.
  EXPECT_EQ(area_light_sample_irradiance(light, light.point(0.5f, 0.5f), vec3(1, 3, 0.5f), vec3(0, -1, 0)),
            vec3(0));
}

TEST(Shading, CombineFollowsTheDocumentedFormula) {
  ShadingTerms t;
  t.emission = vec3(0.1f, 0, 0);
  t.ambient = vec3(0.2f);
  t.albedo = vec3(0.5f, 1.0f, 0.0f);
  t.specular = 0.25f;
  t.direct_irradiance = vec3(kPi);
  t.reflected = vec3(4.0f);
  vec3 l = combine_shading(t);
  EXPECT_NEAR(l.x, 0.1f + 0.75f * 0.5f * (0.2f + 1.0f) + 1.0f, 1e-6f);
  EXPECT_NEAR(l.y, 0.75f * 1.0f * (0.2f + 1.0f) + 1.0f, 1e-6f);
  EXPECT_NEAR(l.z, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace proxima
