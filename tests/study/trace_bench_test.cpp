// study/trace_bench.h: the Embree speed figures as a library call. Only what cannot depend
// on the machine's speed is asserted: the metrics exist and are positive, the ray counts.
#include "proxima/study/trace_bench.h"

#include <gtest/gtest.h>

#include "proxima/scene/builtin_scenes.h"
#include "test_util.h"

namespace proxima {
namespace {

TEST(TraceBenchStudy, NamedMetricsAtOneAndAllThreads) {
  const Scene scene = make_builtin_scene("room-reflector");
  study::TraceBenchOptions o;
  o.width = 48;
  o.height = 32;
  o.threads = 2;
  o.reps = 1;
  const Results r = study::run_trace_bench(scene, o, {});
  for (const char* m : {"bvh_build_ms", "primary_mrays_s", "bvh_build_ms_1t", "primary_mrays_s_1t"}) {
    ASSERT_TRUE(r.metrics.count(m)) << m;
    EXPECT_GT(r.metrics.at(m), 0.0) << m;
  }
  EXPECT_EQ(r.metrics.at("triangles"), double(scene.triangles.size()));
  // The reflector shows in the default view: some primary rays reflect, never more than one per pixel.
  const double reflected = r.metrics.at("reflection_rays");
  EXPECT_GT(reflected, 0.0);
  EXPECT_LE(reflected, 48.0 * 32.0);
  EXPECT_GT(r.metrics.at("reflection_mrays_s"), 0.0);
  ASSERT_EQ(r.tables.size(), 1u);
  EXPECT_EQ(r.tables[0].title, "bench trace: room-reflector, 48x32, median of 1");
  ASSERT_EQ(r.tables[0].rows.size(), 2u);
  EXPECT_EQ(std::get<double>(r.tables[0].rows[0][0]), 1.0);
  EXPECT_EQ(std::get<double>(r.tables[0].rows[1][0]), 2.0);
  EXPECT_TRUE(r.images.empty());
}

TEST(TraceBenchStudy, OneThreadOnlyAndNoReflectors) {
  // The cornell box with every material made diffuse: no reflection rays, their rate 0.
  Scene scene = make_builtin_scene("cornell");
  for (Material& m : scene.materials) m.specular = 0.0f;
  study::TraceBenchOptions o;
  o.width = 16;
  o.height = 16;
  o.threads = 1;
  o.reps = 1;
  const Results r = study::run_trace_bench(scene, o, {});
  EXPECT_EQ(r.tables.at(0).rows.size(), 1u);
  EXPECT_FALSE(r.metrics.count("primary_mrays_s_1t"));
  EXPECT_EQ(r.metrics.at("reflection_rays"), 0.0);
  EXPECT_EQ(r.metrics.at("reflection_mrays_s"), 0.0);
}

TEST(TraceBenchStudy, ValidateNamesTheFlag) {
  study::TraceBenchOptions o;
  EXPECT_EQ(error_of([&] { study::validate(o); }), "");
  o.reps = 0;
  EXPECT_EQ(error_of([&] { study::validate(o); }), "--reps: must be in 1..1000");
  o.reps = 1001;
  EXPECT_EQ(error_of([&] { study::validate(o); }), "--reps: must be in 1..1000");
}

}  // namespace
}  // namespace proxima
