// study/raster_bench.h: the rasterizer's agreement with Embree and its timing rows as a
// library call. The agreement is exact arithmetic, so it is asserted; times only exist.
#include "proxima/study/raster_bench.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "proxima/scene/builtin_scenes.h"
#include "test_util.h"

namespace proxima {
namespace {

TEST(RasterBenchStudy, AgreesWithEmbreeOnEveryBuiltinCamera) {
  const Scene scene = make_builtin_scene("cornell");
  study::RasterBenchStudyOptions o;
  o.width = 64;
  o.height = 64;
  o.threads = 2;
  o.reps = 1;
  const Results r = study::run_raster_bench(scene, o, {});
  // Issue 3's acceptance figure: ≥ 99.9% with a pixel center on the edge two triangles share
  // counting for either, and no disagreement that is not a tie.
  EXPECT_GE(r.metrics.at("id_agreement_with_ties_pct"), 99.9);
  EXPECT_GE(r.metrics.at("id_agreement_with_ties_pct"), r.metrics.at("id_agreement_pct"));
  EXPECT_EQ(r.metrics.at("id_disagreements_other"), 0.0);
  ASSERT_EQ(r.tables.size(), 2u);
  const Table& agree = r.tables[0];
  size_t cameras = 0;
  for (const BuiltinSceneInfo& info : builtin_scenes()) cameras += make_builtin_scene(info.name).cameras.size();
  EXPECT_EQ(agree.rows.size(), cameras);
  double min_pct = 100.0;
  for (const auto& row : agree.rows) min_pct = std::min(min_pct, std::get<double>(row[2]));
  EXPECT_EQ(r.metrics.at("id_agreement_pct"), min_pct);

  // Timing rows at 1 and 2 threads, all threads last; llvmpipe is the command's (not run here).
  const Table& speed = r.tables[1];
  EXPECT_EQ(speed.title, "raster cornell, 64x64, median of 1");
  EXPECT_EQ(speed.columns, (std::vector<std::string>{"threads", "depth_id_ms", "gbuffer_ms", "tris_per_s"}));
  ASSERT_EQ(speed.rows.size(), 2u);
  EXPECT_EQ(std::get<double>(speed.rows[0][0]), 1.0);
  EXPECT_EQ(std::get<double>(speed.rows[1][0]), 2.0);
  for (const char* m : {"raster_ms_depth_id", "raster_ms_depth_id_1t", "tris_per_s", "tris_per_s_1t"})
    EXPECT_GT(r.metrics.at(m), 0.0) << m;
  EXPECT_FALSE(r.metrics.count("llvmpipe_ms_depth_id"));
}

TEST(RasterBenchStudy, SkipAgreementTimesOnly) {
  const Scene scene = make_builtin_scene("cornell");
  study::RasterBenchStudyOptions o;
  o.width = 32;
  o.height = 32;
  o.threads = 1;
  o.reps = 1;
  o.skip_agreement = true;
  const Results r = study::run_raster_bench(scene, o, {});
  EXPECT_FALSE(r.metrics.count("id_agreement_pct"));
  ASSERT_EQ(r.tables.size(), 1u);
  EXPECT_EQ(r.tables[0].rows.size(), 1u);  // one thread: one row, no _1t metrics
  EXPECT_FALSE(r.metrics.count("raster_ms_depth_id_1t"));
  EXPECT_GT(r.metrics.at("raster_ms_depth_id"), 0.0);
}

TEST(RasterBenchStudy, ValidateNamesTheFlag) {
  study::RasterBenchStudyOptions o;
  EXPECT_EQ(error_of([&] { study::validate(o); }), "");
  o.reps = 0;
  EXPECT_EQ(error_of([&] { study::validate(o); }), "--reps: must be in 1..1000");
  const Scene scene = make_builtin_scene("cornell");
  o.reps = 1;
  o.camera.path = "nope";
  EXPECT_NE(error_of([&] { study::run_raster_bench(scene, o, {}); }).find("--path"), std::string::npos);
}

}  // namespace
}  // namespace proxima
