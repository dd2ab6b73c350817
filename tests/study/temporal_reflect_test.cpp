// study/temporal_reflect.h on tiny paths: errors against full ray tracing per frame, the
// recomputed share, the error breakdown, determinism across thread counts, options by name.
#include "proxima/study/temporal_reflect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/load.h"
#include "test_util.h"
#include "study_test_util.h"

namespace proxima {

namespace {

// Six frames of room-reflector's first path at 48×32, compared with full ray tracing.
study::TemporalReflectOptions tiny_options() {
  study::TemporalReflectOptions o;
  o.width = 48;
  o.height = 32;
  o.path = "0";
  o.frames = 6;
  o.compare = true;
  return o;
}

const Scene& room() {
  static const Scene scene = load_scene("room-reflector");
  return scene;
}

const Table& per_frame(const Results& r) {
  for (const Table& t : r.tables)
    if (t.title == "Per frame") return t;
  throw std::runtime_error("no per-frame table");
}

double column(const Table& t, size_t row, const std::string& name) {
  for (size_t c = 0; c < t.columns.size(); ++c)
    if (t.columns[c] == name) return std::get<double>(t.rows.at(row).at(c));
  throw std::runtime_error("no column " + name);
}

}  // namespace

TEST(TemporalReflectStudy, EveryFrameCloseToFullRayTracing) {
  const Results r = study::run_temporal_reflect(room(), tiny_options(), {});
  const Table& t = per_frame(r);
  ASSERT_EQ(t.rows.size(), 6u);
  EXPECT_EQ(r.metrics.at("frames"), 6.0);
  int reuse = 0;
  for (size_t i = 0; i < t.rows.size(); ++i) {
    const bool key = column(t, i, "key") == 1.0;
    const double mae = column(t, i, "temporal_mae");  // 0–255, over the reflective pixels
    ASSERT_FALSE(std::isnan(mae)) << "frame " << i;
    EXPECT_LT(mae, 3.0) << "frame " << i;
    if (key) {
      EXPECT_EQ(column(t, i, "recompute_pct"), 100.0) << "frame " << i;
    } else {
      ++reuse;
      EXPECT_GE(column(t, i, "recompute_pct"), 0.0) << "frame " << i;
      EXPECT_LT(column(t, i, "recompute_pct"), 100.0) << "frame " << i;
    }
  }
  EXPECT_EQ(column(t, 0, "key"), 1.0);
  EXPECT_GE(reuse, 1);  // the path's frames do reuse a key frame
  EXPECT_EQ(r.metrics.at("keyframes"), double(6 - reuse));
  EXPECT_GT(r.metrics.at("recompute_pct_avg"), 0.0);
  EXPECT_LT(r.metrics.at("recompute_pct_avg"), 100.0);
  // The warp follows the reflected points; direct reprojection treats them as painted on.
  EXPECT_LE(r.metrics.at("temporal_mae_avg"), r.metrics.at("direct_mae_avg"));
}

TEST(TemporalReflectStudy, BreakdownContributionsAddUpToTheMae) {
  study::TemporalReflectOptions o = tiny_options();
  o.breakdown = true;
  o.reference_rays = 16;
  o.lobe_seed_cell = 0.01f;
  const Results r = study::run_temporal_reflect(room(), o, {});
  double sum = 0.0;
  int classes = 0;
  for (const auto& [name, value] : r.metrics)
    if (name.rfind("breakdown_", 0) == 0) sum += value, ++classes;
  EXPECT_EQ(classes, 14);
  EXPECT_GT(r.metrics.at("temporal_mae_avg"), 0.0);
  EXPECT_NEAR(sum, r.metrics.at("temporal_mae_avg"), 1e-6 * (1.0 + sum));
  EXPECT_TRUE(r.metrics.count("seed_noise_mae_avg"));
  EXPECT_TRUE(r.metrics.count("hq_temporal_mae_avg"));
}

TEST(TemporalReflectStudy, EdgeRuleRecomputeIsCountedApart) {
  study::TemporalReflectOptions o = tiny_options();
  o.edge_contrast = 0.02f;
  o.edge_rule = "recompute";
  const Results r = study::run_temporal_reflect(room(), o, {});
  EXPECT_EQ(r.metrics.at("edge_rule_recompute"), 1.0);
  EXPECT_GE(r.metrics.at("edge_pct_avg"), 0.0);
  EXPECT_LE(r.metrics.at("edge_pct_avg"), r.metrics.at("recompute_pct_avg"));
}

// One key frame (the threshold never fires, the cost rule is off): later frames have two
// previous offset buffers for the extrapolated start.
TEST(TemporalReflectStudy, MatchExtrapolateKeepsOneKeyFrame) {
  study::TemporalReflectOptions o = tiny_options();
  o.threshold = 1.0f;
  o.keyframe_cost = 0.0f;
  const Results plain = study::run_temporal_reflect(room(), o, {});
  o.match_extrapolate = true;
  const Results m = study::run_temporal_reflect(room(), o, {});
  EXPECT_EQ(plain.metrics.at("match_extrapolate"), 0.0);
  EXPECT_EQ(m.metrics.at("match_extrapolate"), 1.0);
  EXPECT_EQ(m.metrics.at("keyframes"), 1.0);
  EXPECT_GT(plain.metrics.at("match_steps_per_pixel_avg"), 0.0);
  EXPECT_GT(m.metrics.at("match_steps_per_pixel_avg"), 0.0);
}

TEST(TemporalReflectStudy, SameMetricsAndImagesForOneAndTwoThreads) {
  TempDir dir;
  Results runs[2];
  for (int threads : {1, 2}) {
    ThreadLimit limit(threads);
    runs[threads - 1] =
        study::run_temporal_reflect(room(), tiny_options(), {dir.path / std::to_string(threads)});
  }
  EXPECT_GT(expect_same_metrics(runs[0], runs[1]), 20u);
  EXPECT_EQ(runs[0].images.size(), 6u);
  expect_same_images(runs[0], runs[1], dir.path / "1", dir.path / "2");
}

TEST(TemporalReflectStudy, BadOptionsNameTheFlag) {
  auto message = [](const study::TemporalReflectOptions& o) -> std::string {
    try {
      study::run_temporal_reflect(room(), o, {});
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  study::TemporalReflectOptions o = tiny_options();
  o.path.clear();
  EXPECT_NE(message(o).find("--path"), std::string::npos);
  o = tiny_options();
  o.path = "nope";
  EXPECT_NE(message(o).find("--path"), std::string::npos);
  o = tiny_options();
  o.height = kMaxImageSide + 1;
  EXPECT_NE(message(o).find("--height"), std::string::npos);
  o = tiny_options();
  o.edge_rule = "blend";
  EXPECT_NE(message(o).find("--edge-rule"), std::string::npos);
  o = tiny_options();
  o.compare = false;
  o.breakdown = true;
  EXPECT_NE(message(o).find("--breakdown"), std::string::npos);
}

}  // namespace proxima
